//! Lower-limb angles from the ankles' trajectories relative to the pelvis (Pronost, Dumont,
//! Nicolas & Multon, "Combining morphological interpolation and biomechanical inverse kinematics
//! to simulate bipedal locomotion"): the 11-rotation chain and its forward kinematics
//! ([`chain`]), the primary and secondary tasks ([`tasks`], data in [`model`]), Torczon's
//! multi-directional search ([`mds`]), the closed-loop solve ([`solve`]) and the whole figure
//! posed from its result ([`figure`]). `docs/ik.md` has the method, its decisions and its
//! measurements.
pub mod chain;
pub mod error;
pub mod figure;
pub mod mds;
pub mod model;
pub mod parameters;
pub mod solve;
pub mod tasks;

pub use chain::{Angles, Ankles, Chain};
pub use error::IkError;
pub use model::{IkModel, Weights};
pub use parameters::{IkParameters, Optimizer};
pub use solve::{Ik, Solution};
