//! Scenarios: a list of actions — stand, walk, step, turn, pause — run one after the other by
//! one figure on the floor (issue 15), with the walks of the dynamic engine and the
//! non-rhythmic steps and turnarounds of [`crate::nrs`] handing over to each other at matching
//! poses and pelvis velocities (starts from standing and stops into standing are inserted where
//! a walk begins or ends).
pub mod contacts;
mod fields;
pub mod file;
pub mod file_error;
mod run;

use serde::Serialize;

pub use contacts::Contact;
pub use run::run;

use crate::figure::Landmarks;
use crate::model::attributes::Attributes;
use crate::model::body::Body;
use crate::nrs::parameters::NrsParameters;
use crate::nrs::specs::{FootAngles, Side, TurnKind};
use crate::plan::GaitRequest;

pub use file::{parse_scenario, parse_scenario_with, read_scenario, read_scenario_with};
pub use file_error::ScenarioFileError;

/// Where a step's foot goes.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub enum Goal {
    /// The stepping foot's displacement in the figure's facing frame (the pelvis's heading when
    /// the step begins): `forward` and `left` (m), and the change of the foot's heading `turn`
    /// (rad, + left).
    Relative {
        /// Metres forward (negative: backward).
        forward: f64,
        /// Metres to the left (negative: to the right).
        left: f64,
        /// Change of the foot's heading (rad, + left).
        turn: f64,
    },
    /// A world floor point (x, z) for the flat foot's ankle, and the foot's world heading (rad).
    World {
        /// (x, z), m.
        position: [f64; 2],
        /// Heading, rad, + left.
        direction: f64,
    },
}

/// One action of a scenario.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Action {
    /// Quiet standing (feet side by side, the walk's step width apart) for `seconds`; as the
    /// first action it also places the figure: its ankles' midpoint at the floor point `at`
    /// (x, z) and facing heading `facing` (rad). Later in a scenario `at` and `facing` must be
    /// `None`.
    Stand {
        /// Duration (s), ≥ 0.
        seconds: f64,
        /// The floor point (x, z) under the ankles' midpoint (m); first action only.
        at: Option<[f64; 2]>,
        /// The heading (rad, + left); first action only.
        facing: Option<f64>,
    },
    /// A walk of the dynamic engine in the direction the figure faces: one gait per step (each
    /// completed by the normalizing formula). A start from standing and a stop into standing
    /// are added around it when the actions around it are not walks.
    Walk {
        /// The gait of every step; its length is the number of steps.
        gaits: Vec<GaitRequest>,
    },
    /// A non-rhythmic step (an NRS⁻: forward, backward or lateral by where the goal lies).
    Step {
        /// The stepping leg.
        side: Side,
        /// Where the foot goes.
        goal: Goal,
        /// The step's duration (s); `None`: that of the walking step of the same length.
        duration: Option<f64>,
        /// swhf (eq. 3); `None`: the default of `models/nrs.toml`.
        swing_height_factor: Option<f64>,
        /// The gaze's heading at the end of the step relative to the pelvis's facing at its
        /// start (rad, + left); `None`: looking where the pelvis faces at the end.
        gaze: Option<f64>,
        /// θ_foot; `None`: the defaults of the step's type.
        foot_angles: Option<FootAngles>,
    },
    /// A turnaround on the spot (split into equal turns of at most the largest turn).
    Turn {
        /// The turn (rad, > 0).
        angle: f64,
        /// Its direction.
        side: Side,
        /// Dynamic or stationary.
        kind: TurnKind,
        /// δ, the duration of the turn's first step (s); the turnaround takes 2.5 δ. `None`: the
        /// default of `models/nrs.toml`.
        step_duration: Option<f64>,
    },
    /// Hold the current pose for `seconds`.
    Pause {
        /// Duration (s), ≥ 0.
        seconds: f64,
    },
}

impl Action {
    /// The action's name in files and messages.
    pub fn name(&self) -> &'static str {
        match self {
            Action::Stand { .. } => "stand",
            Action::Walk { .. } => "walk",
            Action::Step { .. } => "step",
            Action::Turn { .. } => "turn",
            Action::Pause { .. } => "pause",
        }
    }
}

/// A scenario: one body with its attributes and NRS constants, and its actions in order.
#[derive(Clone, Debug)]
pub struct Scenario {
    /// The figure's body.
    pub body: Body,
    /// Its locomotion attributes (the walks' and the steps').
    pub attrs: Attributes,
    /// The constants of its steps, turns, starts and stops (`models/nrs.toml`'s by default,
    /// `--nrs-model`).
    pub nrs: NrsParameters,
    /// The actions, in order.
    pub actions: Vec<Action>,
}

/// A footprint: where and when a foot came to rest on the floor.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Footprint {
    /// Index of the footprint in the scenario, from 0 (the standing feet first).
    pub index: usize,
    /// The foot.
    pub side: Side,
    /// The flat foot's ankle, a floor point (x, z) (m).
    pub ankle: [f64; 2],
    /// The foot's heading (rad, + left).
    pub direction: f64,
    /// When the foot landed (s; 0 for the standing feet).
    pub time: f64,
    /// The index of the action that placed it (the scenario's, from 0).
    pub action: usize,
}

/// Where one action of the scenario lies in time.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Span {
    /// The action's index in the scenario, from 0; inserted starts and stops carry the index of
    /// their walk.
    pub action: usize,
    /// What ran: `stand`, `walk`, `start`, `stop`, `step`, `turn`, `pause`.
    pub kind: &'static str,
    /// Start and end time (s).
    pub t_start: f64,
    /// End time (s).
    pub t_end: f64,
}

/// A scenario's motion: the figure's frames (world frame), its footprints and the actions'
/// time spans.
#[derive(Clone, Debug)]
pub struct Motion {
    /// The frames at the scenario's frame rate, times strictly increasing from 0.
    pub frames: Vec<Landmarks>,
    /// Every footprint, in the order they were placed.
    pub footprints: Vec<Footprint>,
    /// The actions as they ran.
    pub spans: Vec<Span>,
    /// Every foot strike and foot off, in time order.
    pub contacts: Vec<Contact>,
}

/// A scenario that cannot be run: the action that fails, by its index from 0, and why.
#[derive(Debug, thiserror::Error)]
#[error("action {index} ({name}): {source}")]
pub struct ScenarioError {
    /// The action's index in the scenario, from 0.
    pub index: usize,
    /// The action's name (`walk`, `step`, …).
    pub name: &'static str,
    /// Why it fails (boxed: the union [`crate::Error`] stays small).
    pub source: Box<crate::nrs::NrsError>,
}
