//! A simulated step and a simulated walk: the records the step loop leaves (KLAW 1989 Figure 1),
//! from which the figure, the frames, the events and the report are read.
use crate::control::stance::{StanceRun, StanceSetup};
use crate::control::swing::Subphase;
use crate::engine::report::{Report, SolveRecord, StateFrame, StepReport};
use crate::kinematics::foot::Foot;
use crate::kinematics::pelvis::{Determinants, Side};
use crate::kinematics::stance_leg::StanceLeg;
use crate::model::attributes::Attributes;
use crate::model::body::Body;
use crate::numerics::ode::Segment;
use crate::plan::StepConstraints;

/// A simulated step: its constraints, its dynamic records and its report.
#[derive(Clone, Debug)]
pub struct Step {
    /// Index of the step in the walk (0-based).
    pub index: usize,
    /// Time of the heel strike that starts the step (s).
    pub t_start: f64,
    /// Global x of the stance ankle pivot (m).
    pub x_ankle: f64,
    /// The step's constraints from its gait (the high level, KLAW 1989 §3, spec §3).
    pub constraints: StepConstraints,
    /// What the step's stance trials share (spec §4).
    pub stance_setup: StanceSetup,
    /// The kept stance trial: its dense-output segments and the solved τ1, p (spec §4).
    pub stance: StanceRun,
    /// The step's shooting solves, in order: stance, swing1, swing2, swing3.
    pub solves: Vec<SolveRecord>,
    /// The stance side (step 0 stands on the right leg).
    pub side: Side,
    /// The determinants of gait.
    pub(crate) determinants: Determinants,
    /// This step's virtual stance leg (heel strike to the next heel strike; its toe-off falls in
    /// the next step, which continues it as its hind leg).
    pub stance_leg: StanceLeg,
    /// The previous step's stance leg, completing its stance through this double support.
    pub hind_leg: StanceLeg,
    /// The swing subphases, in order.
    pub swing: Vec<(Subphase, Segment<4>)>,
    /// Swing foot: ankle dorsiflexion and toe angle at toe-off (rad).
    pub(crate) theta5_off: f64,
    pub(crate) theta6_off: f64,
    /// Toe clearance attribute (m).
    pub(crate) toe_clearance: f64,
    /// Where in the swing (fraction) the foot is lowest.
    pub(crate) lowest_at: f64,
    /// Measurements of the step (targets, achievements, invariants).
    pub report: StepReport,
}

/// A simulated walk.
pub struct Walk {
    /// The walking body.
    pub body: Body,
    /// Its locomotion attributes.
    pub attrs: Attributes,
    /// The steps, in order.
    pub steps: Vec<Step>,
}

impl Walk {
    /// Simulated duration (s).
    pub fn duration(&self) -> f64 {
        self.steps.iter().map(|s| s.constraints.timing.t_step).sum()
    }

    /// Frames at `fps` frames per second from t = 0 to the last heel strike (inclusive).
    pub fn frames(&self, fps: f64) -> Vec<StateFrame> {
        let foot = Foot::new(&self.body);
        let n = last_frame(self.duration(), fps);
        let mut frames = Vec::with_capacity(n + 1);
        let mut i = 0;
        for k in 0..=n {
            let t = k as f64 / fps;
            while i + 1 < self.steps.len() && t >= self.steps[i + 1].t_start {
                i += 1;
            }
            if let Some(step) = self.steps.get(i) {
                frames.push(step.frame(t, &foot));
            }
        }
        frames
    }

    /// The per-step report.
    pub fn report(&self) -> Report {
        Report {
            height: self.body.height,
            mass: self.body.mass,
            steps: self.steps.iter().map(|s| s.report.clone()).collect(),
        }
    }
}

/// The last frame k of a walk of `duration` s sampled at k / `fps` (the 1e-9 keeps the frame
/// that falls on the last heel strike whatever the rounding of the product).
pub(crate) fn last_frame(duration: f64, fps: f64) -> usize {
    (duration * fps + 1e-9).floor() as usize
}
