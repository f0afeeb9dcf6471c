//! Poulaines (Pronost et al. §3–4): the ankles' trajectories relative to the pelvis over a gait
//! cycle, as sampled ([`trajectory`]).
pub mod error;
pub mod trajectory;

pub use error::PoulaineError;
pub use trajectory::Trajectory;
