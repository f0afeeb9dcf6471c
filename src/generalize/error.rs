//! What can go wrong in reading, generalizing and posing walk data.
use crate::model::Shown;

/// An error of the walk data, its generalization or its pose: each names the quantity and the
/// limit it broke.
#[derive(Debug, thiserror::Error)]
pub enum GeneralizeError {
    /// Walk data (a file or a value) that breaks the layout of docs/generalize.md.
    #[error("walk data: {field}: {reason}")]
    Invalid {
        /// The field, sequence or column.
        field: String,
        /// The rule broken.
        reason: String,
    },
    /// A step too long for the body: at heel strike the leading leg, its knee flexed by μ1,
    /// cannot reach the hip over the step (eq. 10 has no real root), or a leg of the posed step
    /// would stretch or a foot go under the floor.
    #[error(
        "step length {} m is too long for this body (leg length {} m): {reason}; the longest \
         step this prototype generalizes to on it is {} m",
        Shown(*step_length), Shown(*leg_length), Shown(*limit)
    )]
    TooLong {
        /// The step length asked for (m).
        step_length: f64,
        /// The body's leg length, thigh + shank (m).
        leg_length: f64,
        /// The longest step length that works (m).
        limit: f64,
        /// What fails at the step length asked for.
        reason: String,
    },
    /// A step too short for the body: a leg of the posed step would stretch or a foot go under
    /// the floor.
    #[error(
        "step length {} m is too short for this body (leg length {} m): {reason}; the shortest \
         step this prototype generalizes to on it is {} m",
        Shown(*step_length), Shown(*leg_length), Shown(*limit)
    )]
    TooShort {
        /// The step length asked for (m).
        step_length: f64,
        /// The body's leg length, thigh + shank (m).
        leg_length: f64,
        /// The shortest step length that works (m).
        limit: f64,
        /// What fails at the step length asked for.
        reason: String,
    },
    /// A leg whose hip joint is farther from its ankle than thigh + shank.
    #[error(
        "the {side} leg would be stretched at t = {t:.3} of step {step}: hip to ankle {} m, \
         longer than the leg ({} m)",
        Shown(*distance), Shown(*length)
    )]
    Stretched {
        /// `right` or `left`.
        side: &'static str,
        /// The step (0-based).
        step: usize,
        /// Normalized time in the step.
        t: f64,
        /// Hip joint to ankle (m).
        distance: f64,
        /// thigh + shank (m).
        length: f64,
    },
    /// A step whose legs reach only with the hip lowered from the walk data's H by more than
    /// the parameters allow.
    #[error(
        "the legs reach the hip only with it {} m below the walk data's (at most {} m allowed)",
        Shown(*drop), Shown(*max)
    )]
    HipDrop {
        /// The most the hip would come down (m).
        drop: f64,
        /// The parameters' bound (m).
        max: f64,
    },
    /// A point under the floor by more than the tolerance.
    #[error(
        "the {point} would be {} m below the floor at t = {t:.3} of step {step} (at most {} m \
         allowed)",
        Shown(*depth), Shown(*tolerance)
    )]
    BelowFloor {
        /// Which point, e.g. `right toe tip`.
        point: String,
        /// The step (0-based).
        step: usize,
        /// Normalized time in the step.
        t: f64,
        /// How far below (m).
        depth: f64,
        /// The tolerance (m).
        tolerance: f64,
    },
    /// A swing foot point on the floor away from where it left it or will strike.
    #[error(
        "the {point} would slide {} m on the floor at t = {t:.3} of step {step} (at most {} m \
         allowed): the walk data's swing foot meets the floor before its heel strike or after \
         its toe-off at this step length",
        Shown(*distance), Shown(*max)
    )]
    Slides {
        /// Which point, e.g. `left heel`.
        point: String,
        /// The step (0-based).
        step: usize,
        /// Normalized time in the step.
        t: f64,
        /// How far from its contact (m).
        distance: f64,
        /// The parameters' bound (m).
        max: f64,
    },
    /// A measured walk whose clip does not hold a whole step (docs/generalize.md).
    #[error("measured walk: {0}")]
    Measured(String),
    /// A measured walk with too few frames over its step.
    #[error(
        "measured walk: {frames} frames between the heel strikes at {t0:.4} s and {t1:.4} s: at \
         least {min} are needed"
    )]
    TooFewFrames {
        /// The frames found.
        frames: usize,
        /// The least allowed.
        min: usize,
        /// The step's heel strikes (s).
        t0: f64,
        /// The closing heel strike (s).
        t1: f64,
    },
    /// A measured segment whose length varies beyond the tolerance.
    #[error(
        "measured walk: inconsistent {segment} length: {} m {at}, the median is {} m; they may \
         differ by at most {}%",
        Shown(*length), Shown(*median), Shown(*tolerance_pct)
    )]
    InconsistentLength {
        /// The segment, e.g. `right thigh (hip–knee)`.
        segment: String,
        /// Where: `at frame 12 (t = 0.4 s)` or `on the left side`.
        at: String,
        /// The length found (m).
        length: f64,
        /// The median it is compared with (m).
        median: f64,
        /// The tolerance (% of the median).
        tolerance_pct: f64,
    },
}

impl GeneralizeError {
    /// An [`GeneralizeError::Invalid`] of `field`.
    pub fn invalid(field: impl Into<String>, reason: impl Into<String>) -> Self {
        GeneralizeError::Invalid {
            field: field.into(),
            reason: reason.into(),
        }
    }
}
