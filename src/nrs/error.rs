//! How a non-rhythmic step, a turnaround or a start or stop cannot be made: an illegal goal (§4),
//! an input out of range, or the walking step it is built on.
use crate::engine::SimulationError;
use crate::figure::FigureError;
use crate::model::InputError;

/// Why a step's goal cannot be stepped to.
#[derive(Debug, thiserror::Error)]
pub enum GoalReason {
    /// The goal lies in the illegal region of Figure 2: the foot would cross the stance leg.
    #[error(
        "it lies {angle_deg:.1}° from the stance foot's direction towards the stance side, in \
         the illegal region (crossing the stance leg): forward steps go up to 90°, lateral ones \
         from 90° to {lateral_deg:.0}° on the stepping leg's side, backward ones from there to 180°"
    )]
    Illegal {
        /// The goal's angle from the stance foot's direction (deg, + towards the stepping side).
        angle_deg: f64,
        /// Where the lateral region ends (90° + ν, deg).
        lateral_deg: f64,
    },
    /// The stepping foot would land on the stance foot.
    #[error(
        "the feet would overlap: the goal is {distance:.3} m from the stance ankle, at least \
         {min:.3} m is needed"
    )]
    Overlap {
        /// The goal's distance from the stance ankle (m).
        distance: f64,
        /// The smallest distance at which the feet do not overlap (m).
        min: f64,
    },
    /// A forward or backward step shorter than the engine's shortest walking step.
    #[error(
        "a {kind} step of {length:.3} m is shorter than the walking engine's minimum step length \
         {min:.3} m (attribute step_length_min); step sideways or take a longer step"
    )]
    TooShort {
        /// `forward` or `backward`.
        kind: &'static str,
        /// The step's length along the stance foot (m).
        length: f64,
        /// The engine's shortest step (m).
        min: f64,
    },
    /// A leg would have to stretch beyond its length.
    #[error(
        "the {leg} leg cannot reach: hip to ankle {distance:.3} m at t = {t:.3} of the step, \
         the leg is {length:.3} m long"
    )]
    Unreachable {
        /// `left` or `right`.
        leg: &'static str,
        /// The hip-to-ankle distance asked for (m).
        distance: f64,
        /// The leg's length l3 + l4 (m).
        length: f64,
        /// The normalized time of the worst instant.
        t: f64,
    },
}

/// A non-rhythmic step or turnaround that cannot be made.
#[derive(Debug, thiserror::Error)]
pub enum NrsError {
    /// The goal cannot be stepped to.
    #[error("step of the {side} foot to ({x:.3}, {z:.3}): {reason}", x = position[0], z = position[1])]
    Goal {
        /// The goal's floor point (x, z) (m).
        position: [f64; 2],
        /// The stepping leg: `left` or `right`.
        side: &'static str,
        /// Why.
        reason: GoalReason,
    },
    /// A value out of its range (a duration, swhf, a turn angle).
    #[error(transparent)]
    Input(#[from] InputError),
    /// The walking step the NRS borrows its hip height and timing from could not be simulated.
    #[error(
        "the walking step of {step_length:.3} m in {duration:.3} s that the step is built on: \
         {source}"
    )]
    Walking {
        /// Its step length (m).
        step_length: f64,
        /// Its duration (s).
        duration: f64,
        /// Why it failed.
        source: SimulationError,
    },
    /// A walk of a scenario that could not be simulated.
    #[error(transparent)]
    Walk(#[from] SimulationError),
    /// A pose of the figure that cannot be drawn.
    #[error(transparent)]
    Figure(#[from] FigureError),
}
