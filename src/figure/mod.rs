//! The whole figure around the dynamic model (KLAW 1989 §4.2, spec §7): the figure's landmarks
//! at one instant and the exported skeleton with its clinical joint angles.
pub mod landmarks;
pub mod skeleton;

pub use landmarks::*;
