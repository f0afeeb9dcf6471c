//! The inverse kinematics' tolerances and limits, in one place.

/// The minimiser of the secondary tasks.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Optimizer {
    /// Torczon's multi-directional search ([`crate::ik::mds`]), the paper's choice.
    MultiDirectional,
    /// argmin's Nelder–Mead, for comparison (`docs/ik.md`).
    NelderMead,
}

/// Tolerances and limits of [`crate::ik::solve`].
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct IkParameters {
    /// The closed loop's bound on the ankles' error at every frame, largest coordinate (m).
    pub tolerance: f64,
    /// λ of the damped pseudo-inverse (m).
    pub damping: f64,
    /// Primary-task corrections per frame before the frame fails.
    pub max_corrections: usize,
    /// The largest primary step J⁺ ΔX (eq. 2), as the norm of its angles (rad); a longer one is
    /// shortened to it along its direction \[ours\]. Near the straight knee's singularity the
    /// damped pseudo-inverse's gain reaches 1 / (2λ) = 500 rad/m, and a centimetre of error
    /// turned the whole chain by radians in one step (docs/ik.md).
    pub max_step: f64,
    /// The first frame: rounds of primary and secondary steps from the rest posture.
    pub start_rounds: usize,
    /// The secondary minimiser.
    pub optimizer: Optimizer,
    /// The minimiser's initial simplex: the rest posture's step plus h along each null-space
    /// direction (rad).
    pub simplex: f64,
    /// The minimiser stops at a simplex this small (rad; for Nelder–Mead: the costs' standard
    /// deviation, in z's units).
    pub simplex_tolerance: f64,
    /// The minimiser's iterations per frame.
    pub max_iterations: u64,
    /// Δt_ref (s) of the postural terms' scale Δt_ref / Δt ([`crate::ik::tasks`]).
    pub reference_step: f64,
    /// The farthest an ankle target may lie from its hip, as a fraction of the leg's length
    /// l3 + l4: a database's poulaine is clamped to it (Pronost et al. §4's "the ankle can
    /// follow the reconstructed curve"); 0.999 keeps the knee ≥ 5° bent, off the chain's
    /// singular straight leg.
    pub reach: f64,
    /// A periodic trajectory is solved once through before the kept pass (the warm-up), so that
    /// its first frame follows from its last.
    pub warm_up: bool,
}

impl Default for IkParameters {
    fn default() -> Self {
        IkParameters {
            tolerance: 1e-5,
            damping: 1e-3,
            max_corrections: 50,
            max_step: 0.25,
            start_rounds: 30,
            optimizer: Optimizer::MultiDirectional,
            simplex: 1e-2,
            simplex_tolerance: 1e-6,
            max_iterations: 400,
            reference_step: 1.0 / 60.0,
            reach: 0.999,
            warm_up: true,
        }
    }
}
