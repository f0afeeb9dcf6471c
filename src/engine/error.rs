//! How a simulated step fails: its constraints, a shooting solve that does not converge or
//! whose trials fail, or an invariant the converged step breaks (spec §4, §5, §10).
use crate::control::shooting::SolveError;
use crate::kinematics::GeometryError;
use crate::model::InputError;

/// A step that could not be simulated. `phase` names where: `stance`, `double_support`,
/// `swing1`, `swing2`, `swing3`, `swing` (the swing's invariants) or `figure` (a pose of the
/// converged walk).
#[derive(Debug, thiserror::Error)]
pub enum SimulationError {
    /// The step's constraints cannot be planned for the gait (KLAW 1989 §3).
    #[error(transparent)]
    Plan(#[from] InputError),
    /// A shooting solve ended without meeting its end conditions.
    #[error(
        "step {step}, {phase}: shooting did not converge: residual {residual:.3e} after {iterations} trial integrations"
    )]
    NotConverged {
        /// The step's index, from 0.
        step: usize,
        /// The phase that failed (see [`SimulationError`]).
        phase: &'static str,
        /// The max-norm of the end-condition residual at the last point.
        residual: f64,
        /// The trial integrations spent, finite-difference trials included.
        iterations: usize,
    },
    /// A shooting solve returned no point: bad options, or its first trial integration failed.
    #[error("step {step}, {phase}: integration failed: {source}")]
    Integration {
        /// The step's index, from 0.
        step: usize,
        /// The phase that failed (see [`SimulationError`]).
        phase: &'static str,
        /// Why the solve returned no point.
        source: SolveError,
    },
    /// The step breaks an invariant.
    #[error("step {step}, {phase}: {source}")]
    Invariant {
        /// The step's index, from 0.
        step: usize,
        /// The phase that failed (see [`SimulationError`]).
        phase: &'static str,
        /// The invariant broken.
        source: Invariant,
    },
}

/// An invariant a simulated step breaks.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum Invariant {
    /// The virtual stance leg cannot take its pose (the hind leg through double support, the
    /// stance leg's heel-off).
    #[error(transparent)]
    Geometry(#[from] GeometryError),
    /// The hip goes below its heel-strike height, by `depth` (m).
    #[error("the hip drops {depth:.3e} m below its heel-strike height")]
    HipDrops {
        /// How far below (in m).
        depth: f64,
    },
    /// The toe's mid-swing clearance (m) is not positive.
    #[error("the toe touches the ground in mid swing (clearance {clearance:.3e} m)")]
    ToeTouches {
        /// The least clearance in mid swing (in m).
        clearance: f64,
    },
    /// A point of the swing foot goes `depth` (m) under the ground at `at` (fraction of the
    /// swing).
    #[error("the swing foot goes {depth:.3e} m under the ground at {:.0} % of the swing", 100.0 * at)]
    FootUnderGround {
        /// How far under (in m).
        depth: f64,
        /// Where in the swing (fraction of the swing, 0 to 1).
        at: f64,
    },
}

impl SimulationError {
    /// Whether the step failed with the stance hip under its heel-strike height, which a larger
    /// heel-strike impulse can mend \[ours\]: the part of the new leg's axial velocity the impulse
    /// leaves is absorbed in the loading response, and in slow walks and at the start of a walk
    /// the servo can let the hip sink up to 0.3 mm under y_hs doing so.
    pub fn is_loading_failure(&self) -> bool {
        matches!(
            self,
            SimulationError::Invariant {
                phase: "stance",
                source: Invariant::HipDrops { .. },
                ..
            }
        )
    }

    /// A failure that less pelvic list can mend \[ours\]: the swing's (its shooting, or its foot
    /// under the ground: the list lowers the swing hip by (l0/2) sin L at mid-step), or the
    /// stance hip under its heel-strike height (the list raises the stance hip joint by the
    /// same above the pelvis centre at mid-stance, past the straight leg's reach in slow walks
    /// of tall bodies: docs/coverage.md), or the flat foot out of the straight leg's reach as
    /// the hip passes over it (the same raised hip joint).
    pub fn is_list_failure(&self) -> bool {
        match self {
            SimulationError::NotConverged { phase, .. }
            | SimulationError::Integration { phase, .. } => phase.starts_with("swing"),
            SimulationError::Invariant { phase, source, .. } => {
                *phase == "swing"
                    || matches!(
                        source,
                        Invariant::HipDrops { .. }
                            | Invariant::Geometry(GeometryError::FlatFootOutOfReach { .. })
                    )
            }
            SimulationError::Plan(_) => false,
        }
    }

    /// The rolling hind foot out of the hip's reach in double support with the toe-off knee
    /// flexion it must reach: a straighter knee reaches further.
    pub fn is_toe_off_failure(&self) -> bool {
        matches!(
            self,
            SimulationError::Invariant {
                phase: "double_support",
                source: Invariant::Geometry(GeometryError::RollingFootOutOfReach { .. }),
                ..
            }
        )
    }

    /// The flat stance foot out of the straight leg's reach as the hip passes over it: a bounce
    /// too high for the leg, which a larger reach margin mends where the reach cuts the bounce.
    pub fn is_reach_failure(&self) -> bool {
        matches!(
            self,
            SimulationError::Invariant {
                source: Invariant::Geometry(GeometryError::FlatFootOutOfReach { .. }),
                ..
            }
        )
    }
}
