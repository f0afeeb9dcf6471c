//! The high level of the control hierarchy (KLAW 1989 §3): the gait's parameters completed by
//! the normalizing formula (eq. 1), and the step constraints (timings, eq. 2; step-symmetry
//! final conditions, eq. 3).
pub mod constraints;
pub mod gait;
pub mod timing;

pub use constraints::StepConstraints;
pub use gait::{Gait, GaitRequest};
pub use timing::Timing;
