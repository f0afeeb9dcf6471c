//! The poulaine fit's tolerances and search grids, in one place.

/// Tolerances and grids of [`mod@crate::poulaine::fit`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitParameters {
    /// The shape fit's alternation of projection and tangents stops when a round lowers the
    /// samples' RMS distance from the shape by less than this fraction of it…
    pub shape_tolerance: f64,
    /// … or after this many rounds (its convergence is linear: the tangents and the parameters
    /// trade the same path against each other).
    pub shape_rounds: usize,
    /// The nearest-point search's grid over one knot segment, in the shape fit's projection.
    pub segment_grid: usize,
    /// The nearest-point search's grid over the whole cycle, in `Model::shape_error`.
    pub cycle_grid: usize,
    /// Golden-section steps refining a nearest point between its grid neighbours (each keeps
    /// 0.618 of the bracket).
    pub golden_steps: usize,
    /// The fewest samples strictly inside a knot segment for the shape fit to move their
    /// parameters; in a segment with fewer, they keep their phases (free parameters on so few
    /// samples let the cubic wind through them: 8-sample curves reached 10⁸ m between their
    /// samples).
    pub min_inside: usize,
}

impl FitParameters {
    /// The values klaw uses (docs/ik.md, "Poulaines and the database").
    pub const DEFAULT: Self = FitParameters {
        shape_tolerance: 1e-3,
        shape_rounds: 200,
        segment_grid: 64,
        cycle_grid: 2000,
        golden_steps: 40,
        min_inside: 4,
    };
}

impl Default for FitParameters {
    fn default() -> Self {
        Self::DEFAULT
    }
}
