//! klaw: goal-directed, dynamically simulated human walking after Bruderlin & Calvert,
//! "Goal-directed, dynamic animation of human walking" (SIGGRAPH 1989).
pub mod animate;
pub mod attributes;
pub mod body;
pub mod control;
pub mod error;
pub mod kinematics;
pub mod memory;
pub mod ode;

pub use attributes::{AttributeTable, Attributes};
pub use body::Body;
pub use error::{Error, Result};
pub mod params;
pub mod plan;
pub use params::{Gait, GaitRequest};
pub use plan::{StepConstraints, Timing};
pub mod dynamics;
pub mod export;
pub mod figure;
pub mod io;
pub mod plot;
pub mod plot_cycle;
pub mod plot_sweep;
pub mod report;
pub mod roots;
pub mod skeleton;
pub mod stream;
pub mod sweep;
pub mod sweep_io;
pub mod trig;
pub mod walk;
pub mod work;
