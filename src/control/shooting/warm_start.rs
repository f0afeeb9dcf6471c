//! Warm starts of the shooting solves (KLAW 1989 §4.1 \[ours\]): what a solve remembers for the
//! next step's solve of the same phase, how a solve starts, and the extrapolation of the
//! remembered solutions along the step sequence.
use nalgebra::{Matrix2, Vector2};

/// Relative step used when a warm start carries no usable slope or Jacobian.
pub(super) const FALLBACK_REL_STEP: f64 = 1e-4;

/// What a 1-D solve remembers for the next step's warm start.
#[derive(Clone, Copy, Debug)]
pub struct Memory1 {
    /// The returned point.
    pub(crate) x: f64,
    /// The last secant slope estimate `dr/dx` (NaN if none was formed).
    pub slope: f64,
    /// The points returned by the two solves before this one (NaN if none).
    pub(crate) earlier: [f64; 2],
    /// The step ratio λ to extrapolate with (`extrapolate`; NaN: from `earlier`).
    pub(crate) ratio: f64,
}

/// What a 2-D solve remembers: the solution and the last Broyden Jacobian.
#[derive(Clone, Copy, Debug)]
pub struct Memory2 {
    /// The returned point.
    pub(crate) x: Vector2<f64>,
    /// The last Jacobian estimate (NaN entries if none was formed).
    pub jacobian: Matrix2<f64>,
    /// The points returned by the two solves before this one (NaN if none).
    pub(crate) earlier: [Vector2<f64>; 2],
    /// The step ratio λ to extrapolate with (`extrapolate`; NaN: from `earlier`).
    pub(crate) ratio: f64,
}

/// The next solution predicted from the last three of a sequence converging geometrically:
/// x + λ (x − x₋₁), λ the ratio of the last two differences (least squares over the components,
/// each relative to its own size) unless `ratio` gives it, clipped to [−0.5, 0.5]; `x` itself
/// when the history is incomplete. Successive steps of a walk approach the limit cycle with one
/// ratio for all its unknowns (the step map's dominant eigenvalue, small and negative).
pub(super) fn extrapolate<const D: usize>(
    x: [f64; D],
    earlier: [[f64; D]; 2],
    ratio: f64,
) -> [f64; D] {
    let lambda = if ratio.is_finite() {
        ratio
    } else {
        step_ratio(x, earlier)
    };
    if !(lambda.is_finite() && earlier[0].iter().all(|v| v.is_finite())) {
        return x;
    }
    let lambda = lambda.clamp(-0.5, 0.5);
    let mut out = x;
    for i in 0..D {
        out[i] += lambda * (x[i] - earlier[0][i]);
    }
    out
}

/// The ratio λ of the last two differences of a sequence ending x₋₂, x₋₁, x (`earlier` =
/// [x₋₁, x₋₂]): least squares over the components, each relative to its own size; NaN when the
/// history is incomplete or constant.
pub fn step_ratio<const D: usize>(x: [f64; D], earlier: [[f64; D]; 2]) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for i in 0..D {
        let (d1, d0) = (x[i] - earlier[0][i], earlier[0][i] - earlier[1][i]);
        let w = 1.0 / x[i].abs().max(1e-12).powi(2);
        num += w * d1 * d0;
        den += w * d0 * d0;
    }
    if den > 0.0 { num / den } else { f64::NAN }
}

/// How a 1-D solve starts.
#[derive(Clone, Copy, Debug)]
pub enum Start1 {
    /// From `x0`, with `dx` the scale of the unknown (the first trial is `x0 + dx`).
    Cold {
        /// The first guess.
        x0: f64,
        /// The scale of the unknown: the second trial's step.
        dx: f64,
    },
    /// From the previous solve's memory: a Newton-like step with the remembered slope.
    Warm(Memory1),
}

/// How a 2-D solve starts.
#[derive(Clone, Copy, Debug)]
pub enum Start2 {
    /// From `x0` with a forward-difference Jacobian, step `h[i]` for unknown `i`.
    Cold {
        /// The first guess.
        x0: Vector2<f64>,
        /// The finite-difference steps, one per unknown.
        h: Vector2<f64>,
    },
    /// From the previous solve's memory: its point and Jacobian, no finite-difference trials.
    Warm(Memory2),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extrapolation_predicts_a_geometric_sequence() {
        // x_n = 3 + (-0.13)^n (1, -2): the next point from the last three, exactly
        let x = |n: i32| {
            let c = (-0.13f64).powi(n);
            [3.0 + c, 5.0 - 2.0 * c]
        };
        let p = extrapolate(x(2), [x(1), x(0)], f64::NAN);
        assert!((p[0] - x(3)[0]).abs() < 1e-12 && (p[1] - x(3)[1]).abs() < 1e-12);
        // no history, or no change: the last point
        assert_eq!(
            extrapolate([1.0], [[f64::NAN], [f64::NAN]], f64::NAN),
            [1.0]
        );
        assert_eq!(extrapolate([1.0], [[1.0], [1.0]], f64::NAN), [1.0]);
        // a ratio beyond ±0.5 is clipped
        assert_eq!(extrapolate([4.0], [[2.0], [1.0]], f64::NAN), [5.0]);
        // a given ratio (another sequence's with the same λ) replaces a history that is not
        // geometric yet, and needs only the last difference
        let y = |n: i32| 7.0 - 4.0 * (-0.13f64).powi(n);
        assert!((step_ratio(x(2), [x(1), x(0)]) + 0.13).abs() < 1e-12);
        let p = extrapolate([y(2)], [[y(1)], [f64::NAN]], -0.13);
        assert!((p[0] - y(3)).abs() < 1e-12);
        assert!(step_ratio([1.0], [[1.0], [1.0]]).is_nan());
    }
}
