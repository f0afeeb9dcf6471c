//! How the figure of a simulated walk cannot be built at an instant.
use crate::kinematics::GeometryError;

/// A frame of the figure that cannot be built: the stance leg's pose, or the segment frames
/// of the skeleton from the landmarks (spec §7).
#[derive(Debug, thiserror::Error)]
pub enum FigureError {
    /// The stance leg of step `step` cannot take its pose.
    #[error("step {step}, figure: {source}")]
    Pose {
        /// The step's index, from 0.
        step: usize,
        /// Why the pose cannot be taken.
        source: GeometryError,
    },
    /// A landmark coordinate or angle, named `name`, is NaN or infinite.
    #[error("{name} is {value}: a finite number is required")]
    NotFinite {
        /// The coordinate's or angle's name.
        name: String,
        /// Its value: NaN or ±infinity.
        value: f64,
    },
    /// A segment of the skeleton at time `time` (s), named `what`, has (nearly) zero length.
    #[error("frame at t = {time} s: {what} has zero length")]
    ZeroLength {
        /// The frame's time (in s).
        time: f64,
        /// The segment's name.
        what: String,
    },
    /// A direction that must be across a segment (the knee axis, the heel–ankle line) is along
    /// it.
    #[error("frame at t = {time} s: {what} is parallel to the segment")]
    Parallel {
        /// The frame's time (in s).
        time: f64,
        /// The direction's name.
        what: String,
    },
}

/// A result of the figure's constructions.
pub type Result<T, E = FigureError> = std::result::Result<T, E>;
