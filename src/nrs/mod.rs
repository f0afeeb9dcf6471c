//! Non-rhythmic stepping (Ko & Badler, "Intermittent non-rhythmic human stepping and
//! locomotion", 1993): single forward, backward and lateral steps (NRS⁻) and turnarounds on the
//! spot, each precomputed by an `initialize` from the figure's state and its specs and then
//! posed at any normalized time t ∈ [0, 1] by `advance` in constant time. The centre site's
//! height reuses the hip height trajectory the walking engine computes for the walking step of
//! the same length (eq. 4, eq. 5).
pub(crate) mod build;
pub mod curves;
pub mod error;
pub mod handover;
pub mod parameters;
pub mod pose;
pub(crate) mod range;
pub mod region;
pub(crate) mod segment;
pub mod specs;
pub mod state;
pub mod step;
pub mod turn;
pub mod walking;

pub use error::{GoalReason, NrsError};
pub use parameters::NrsParameters;
pub use specs::{FootAngles, Side, StepSpecs, StepType, TurnKind, TurnSpecs};
pub use state::WalkerState;
pub use step::NrsStep;
pub use turn::Turnaround;
