//! Why a poulaine, its model or its database cannot be made or used.
use std::path::PathBuf;

use crate::ik::IkError;
use crate::model::InputError;

/// A poulaine failure.
#[derive(Debug, thiserror::Error)]
pub enum PoulaineError {
    /// A value or a setting out of range.
    #[error(transparent)]
    Input(#[from] InputError),
    /// Too few samples for the curve model.
    #[error("a poulaine needs at least {min} samples over its cycle, not {samples}")]
    TooFewSamples {
        /// The samples given.
        samples: usize,
        /// The least.
        min: usize,
    },
    /// A file that is not a poulaine, a model or a database.
    #[error("{path}: {reason}")]
    Malformed {
        /// The file.
        path: PathBuf,
        /// What is wrong, where.
        reason: String,
    },
    /// The characteristic points do not come in the cycle's order.
    #[error(
        "the {leg} ankle's characteristic points are out of order: {reason} (expected over the \
         cycle: highest, most forward, under the pelvis in support, most backward)"
    )]
    Order {
        /// `right` or `left`.
        leg: &'static str,
        /// Which.
        reason: String,
    },
    /// The tangents' least-squares fit failed (argmin's message).
    #[error("the tangent fit of the {leg} ankle failed: {reason}")]
    Fit {
        /// `right` or `left`.
        leg: &'static str,
        /// argmin's message.
        reason: String,
    },
    /// The inverse kinematics of a database walk failed.
    #[error(transparent)]
    Ik(#[from] IkError),
}
