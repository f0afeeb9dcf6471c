//! The input of a non-rhythmic step and of a turnaround (Ko & Badler 1993 §4): the goal
//! parameters (where the stepping foot goes, which leg; how far, which way a turn goes) and the
//! attribute parameters (how: swing height, gaze, foot angles; dynamic or stationary turn).
//!
//! World frame as in [`crate::figure`]: x forward of the figure's first heading, y up, z to the
//! right; a floor point is (x, z); a heading is an angle about +y, + turning to the left (the
//! sense of `pelvis_rotation`), so heading ψ points along (cos ψ, 0, −sin ψ).
use serde::Serialize;

pub use crate::kinematics::pelvis::Side;

/// The three foot angles that shape an NRS⁻'s foot-angle trajectories (§5.1, Figure 3), rad,
/// the foot's pitch with the heel up +: θ_TOM^SW, θ_HSM+^SW, θ_HSM+^ST.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct FootAngles {
    /// θ_TOM^SW: the swing foot's pitch at toe-off (its largest heel rise on the ground).
    pub toe_off_swing: f64,
    /// θ_HSM+^SW: the swing foot's pitch when it lands (negative: heel first, toes up).
    pub strike_swing: f64,
    /// θ_HSM+^ST: the stance foot's pitch at the end of the step (positive: heel raised).
    pub strike_stance: f64,
}

/// An NRS⁻ (a forward, backward or lateral step), eq. 1:
/// `(footpos, footdir, left_or_right, swhf, eye_gaze_dir, θ_foot)`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct StepSpecs {
    /// footpos: where the stepping foot's ankle stands when the foot is flat, a floor point
    /// (x, z) of the world (m).
    pub foot_position: [f64; 2],
    /// footdir: the stepping foot's heading at the end (rad, + left).
    pub foot_direction: f64,
    /// left_or_right: the stepping leg.
    pub side: Side,
    /// swhf: the swing ankle's peak rise over its take-off-to-landing line, in units of 5 cm
    /// (eq. 3); 0 drags the foot.
    pub swing_height_factor: f64,
    /// eye_gaze_dir: the gaze heading at the end (rad); `None`: the pelvis's final facing.
    pub gaze_direction: Option<f64>,
    /// θ_foot; `None`: the defaults of `models/nrs.toml` for the step's type.
    pub foot_angles: Option<FootAngles>,
}

/// The two kinds of turnaround (§6): the second step's foot lands 2λ ahead of the first
/// (dynamic: a walk may follow) or beside it (stationary: another turn or a task may follow).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum TurnKind {
    /// The second foot lands ahead: ready to walk on.
    Dynamic,
    /// The second foot lands beside the first: feet side by side.
    Stationary,
}

/// A turnaround, eq. 2: `(angle, left_or_right, type)`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TurnSpecs {
    /// The turn (rad, > 0); more than the largest turn of `models/nrs.toml` is split into equal
    /// turnarounds.
    pub angle: f64,
    /// The direction of the turn; its leg steps first.
    pub side: Side,
    /// Dynamic or stationary.
    pub kind: TurnKind,
}

/// The type of an NRS⁻, from where its goal lies around the stance heel (§4, Figure 2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum StepType {
    /// A step ahead of the stance foot.
    Forward,
    /// A step behind it.
    Backward,
    /// A step to the stepping leg's side.
    Lateral,
}

impl StepType {
    /// The type's name in messages and files.
    pub fn name(self) -> &'static str {
        match self {
            StepType::Forward => "forward",
            StepType::Backward => "backward",
            StepType::Lateral => "lateral",
        }
    }
}
