//! Stance control (KLAW 1989 §4.2, spec §4): the forces of the telescopic stance model — the leg
//! torque step τ1, the upper-body balance torque, the leg axis force with its position actuator
//! pa tracking the hip height reference — the telescopic / locked subphases, one trial
//! integration of a step's stance, and the table of its hip that the swing hangs from (spec §5).
//!
//! - `setup`: what one step's stance keeps between shooting trials ([`StanceSetup`]);
//! - `reference`: the hip height reference, the spec §4 bounce up to mid-stance and the
//!   virtual leg's from there (spec §7, `TerminalStance`);
//! - `forces`: the forces, the right-hand side and the events ([`StanceForces`]);
//! - `run`: one trial integration and its dense record ([`StanceRun`]);
//! - `hip_path`: the hip's acceleration tabulated for the swing ([`HipPath`]).
use nalgebra::SVector;

mod forces;
mod hip_path;
mod reference;
mod run;
mod setup;

pub use forces::{StanceForces, THETA1_ABORT};
pub use hip_path::{HIP_PATH_STEP, HipPath, OFFSET_DIFFERENCE_STEP};
pub use reference::ReferenceShape;
pub(crate) use reference::TerminalStance;
pub use run::StanceRun;
pub use setup::StanceSetup;

/// State (w, θ1, θ2, ẇ, θ̇1, θ̇2).
pub type StanceState = SVector<f64, 6>;
