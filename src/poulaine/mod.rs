//! Poulaines (Pronost et al. §3–4): the ankles' trajectories relative to the pelvis over a gait
//! cycle, as sampled ([`trajectory`]), their curve model ([`curve`]) fitted to the samples
//! ([`mod@fit`]), the database of modelled poulaines, its selection and corrections ([`database`]),
//! the synthetic database of klaw's walks ([`build`]), and how well the inverse kinematics
//! recovers a walk's angles from its poulaine ([`validate`]).
pub mod build;
pub mod curve;
pub mod database;
pub mod error;
pub mod fit;
pub mod parameters;
pub mod trajectory;
pub mod validate;

pub use database::{Axes, Database, Entry, Query};
pub use error::PoulaineError;
pub use fit::{FitError, Model, fit, fit_with};
pub use parameters::FitParameters;
pub use trajectory::Trajectory;
