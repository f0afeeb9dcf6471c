//! The engine: the step loop that walks a body step after step (KLAW 1989 Figure 1) with its
//! parameters, the poses of a simulated step at any instant, the per-step measures and report,
//! and the actuators' work.
pub mod error;
pub(crate) mod measure;
pub mod parameters;
pub mod pose;
pub mod report;
pub(crate) mod startup;
pub mod step;
pub(crate) mod trials;
pub mod walker;
pub mod work;

pub use error::{Invariant, SimulationError};
