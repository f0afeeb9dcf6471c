//! klaw: goal-directed, dynamically simulated human walking after Bruderlin & Calvert,
//! "Goal-directed, dynamic animation of human walking" (SIGGRAPH 1989).
pub mod analysis;
pub mod control;
pub mod dynamics;
pub mod engine;
pub mod error;
pub mod export;
pub mod figure;
pub mod input;
pub mod kinematics;
pub mod memory;
pub mod model;
pub mod numerics;
pub mod plan;
pub mod plot;
pub mod sweep;

pub use error::{Error, Result};
pub use model::attributes::{AttributeTable, Attributes};
pub use model::body::Body;
pub use plan::{Gait, GaitRequest, StepConstraints, Timing};
