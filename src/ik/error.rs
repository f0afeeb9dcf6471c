//! Why the inverse kinematics cannot follow its targets.
use crate::model::InputError;

/// An inverse-kinematics failure.
#[derive(Debug, thiserror::Error)]
pub enum IkError {
    /// Targets or settings that cannot be used.
    #[error(transparent)]
    Input(#[from] InputError),
    /// The closed loop left the ankles farther than the tolerance from their targets.
    #[error(
        "the inverse kinematics did not converge at frame {frame} (t = {time:.3} s): the ankles \
         are {residual:.2e} m from their targets after {corrections} corrections (tolerance \
         {tolerance:.1e} m); a target beyond the leg's reach?"
    )]
    NotConverged {
        /// The frame (from 0).
        frame: usize,
        /// Its time (s).
        time: f64,
        /// The largest coordinate of the ankles' error (m).
        residual: f64,
        /// The corrections tried.
        corrections: usize,
        /// The bound (m).
        tolerance: f64,
    },
    /// The secondary minimiser failed (argmin's error, as text).
    #[error("the secondary-task minimiser failed at frame {frame}: {reason}")]
    Minimiser {
        /// The frame (from 0).
        frame: usize,
        /// argmin's message.
        reason: String,
    },
}
