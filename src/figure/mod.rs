//! The whole figure around the dynamic model (KLAW 1989 §4.2, spec §7): the figure's landmarks
//! at one instant, its placement on the floor of the world, the segment frames of the exported
//! skeleton, the Euler sequences of its joints and its clinical joint angles.
pub mod clinical;
pub mod error;
pub(crate) mod euler;
pub mod landmarks;
pub mod placement;
pub mod skeleton;

pub use error::FigureError;
pub use landmarks::*;
pub use placement::Placement;
