//! A turnaround on the spot (Ko & Badler 1993 §6): at most `turn_max` (100°) at a time, larger
//! turns split into equal turnarounds; each is an anticipation of 0.5δ in which the torso and
//! head begin to turn, and two steps of δ with the feet flat: for a left turn the left foot
//! lands 2λ back and 2λ left of the right foot facing the goal direction (measured in the goal
//! frame), then the right foot 2λ ahead and 2λ right of it (dynamic) or 2λ right of it, beside
//! it (stationary). The gaze reaches the goal direction δ after the anticipation begins; the
//! pelvis turns by a smoothstep in each step, to the bisector of the feet and then to the goal
//! direction (§5.4's rule; a turn of A needs about A/2 of axial rotation at the hips where the
//! steps meet, whatever the pelvis does); the hip falls monotonically in the first
//! step and rises in the second, as far as both legs reach with the standing knee. 2λ is the
//! pelvis width `l0`.
use crate::figure::Landmarks;
use crate::model::InputError;
use crate::nrs::NrsError;
use crate::nrs::build::{Clock, Height, Plan};
use crate::nrs::pose::{Planted, Upper, direction, right_of};
use crate::nrs::specs::{FootAngles, Side, StepType, TurnKind, TurnSpecs};
use crate::nrs::state::WalkerState;
use crate::nrs::step::NrsStep;

/// One turnaround of at most `turn_max`: the state it starts from (the anticipation's feet and
/// pelvis), the gaze's turn, and its two steps.
#[derive(Clone, Debug)]
struct Part {
    start: WalkerState,
    /// The gaze's change of heading over the turnaround (rad, + left).
    turn: f64,
    steps: [NrsStep; 2],
}

/// A turnaround (eq. 2 specs), precomputed: [`Turnaround::advance`] poses it at t ∈ [0, 1] of
/// its whole duration, 2.5 δ per part.
#[derive(Clone, Debug)]
pub struct Turnaround {
    parts: Vec<Part>,
    delta: f64,
    end: WalkerState,
}

/// Where the second foot of a turnaround lands relative to the first, and the first relative
/// to the pivot foot, in the goal frame (forward, to the turn's side), in units of 2λ.
fn placements(kind: TurnKind) -> [[f64; 2]; 2] {
    let ahead = match kind {
        TurnKind::Dynamic => 1.0,
        TurnKind::Stationary => 0.0,
    };
    [[-1.0, 1.0], [ahead, -1.0]]
}

impl Turnaround {
    /// Precompute the turnaround `specs` from `state` with first-step duration δ = `delta` s
    /// (`None`: `turn_step_duration`). Fails on a turn angle that is not positive, a δ out of
    /// the NRS durations' range, or a leg that cannot reach.
    pub fn initialize(
        state: &WalkerState,
        specs: &TurnSpecs,
        delta: Option<f64>,
    ) -> Result<Turnaround, NrsError> {
        let p = &state.params;
        let delta = delta.unwrap_or(p.turn_step_duration);
        InputError::check_range("step_duration", delta, p.duration_min, p.duration_max, "s")?;
        let max_deg = 10.0 * 360.0;
        InputError::check_range("angle", specs.angle.to_degrees(), 1e-3, max_deg, "°")?;
        let count = (specs.angle / p.turn_max - 1e-9).ceil().max(1.0) as usize;
        let each = specs.angle / count as f64;
        let mut parts = Vec::with_capacity(count);
        let mut at = state.clone();
        for _ in 0..count {
            let part = Self::part(&at, specs.side, specs.kind, each, delta)?;
            at = part.steps[1].end_state().clone();
            parts.push(part);
        }
        Ok(Turnaround {
            parts,
            delta,
            end: at,
        })
    }

    /// One turnaround of `angle` ≤ `turn_max` from `state`.
    fn part(
        state: &WalkerState,
        side: Side,
        kind: TurnKind,
        angle: f64,
        delta: f64,
    ) -> Result<Part, NrsError> {
        let sign = match side {
            Side::Left => 1.0,
            Side::Right => -1.0,
        };
        let turn = sign * angle;
        let goal_heading = state.upper.heading + turn;
        let lambda2 = state.body.l0;
        // the goal frame: forward, and towards the turn's side
        let fwd = direction(goal_heading);
        let r = right_of(goal_heading);
        let toward = [-sign * r[0], -sign * r[1]];
        let place = |from: [f64; 2], [a, b]: [f64; 2]| Planted {
            flat: [
                from[0] + lambda2 * (a * fwd[0] + b * toward[0]),
                from[1] + lambda2 * (a * fwd[1] + b * toward[1]),
            ],
            heading: goal_heading,
            pitch: 0.0,
        };
        let [first, second] = placements(kind);
        let mut anticipated = state.clone();
        anticipated.time += 0.5 * delta;
        anticipated.upper = twist(state, 0.5, turn);
        let plan = |stance: Side, goal: Planted, heading_clock, gaze_clock| Plan {
            kind: StepType::Forward,
            stance,
            goal,
            angles: FootAngles {
                toe_off_swing: 0.0,
                strike_swing: 0.0,
                strike_stance: 0.0,
            },
            walking: None,
            duration: delta,
            swing_height: state.params.swing_height * state.params.swing_height_factor,
            gaze_end: goal_heading,
            upper_end: None,
            velocity_end: [0.0; 3],
            height: Height::Monotone,
            toe_off: Some(state.params.turn_lift_off),
            heading_clock,
            gaze_clock,
        };
        let pivot = side.other();
        let goal1 = place(state.foot(pivot).flat, first);
        let step1 = NrsStep::from_plan(
            &anticipated,
            &plan(pivot, goal1, Clock::WHOLE, Clock(0.5, 1.5)),
        )?;
        let goal2 = place(goal1.flat, second);
        let step2 = NrsStep::from_plan(
            step1.end_state(),
            &plan(side, goal2, Clock::WHOLE, Clock::WHOLE),
        )?;
        // the anticipation's instants: the feet and the pelvis stay, so the legs reach
        state.figure()?;
        Ok(Part {
            start: state.clone(),
            turn,
            steps: [step1, step2],
        })
    }

    /// The figure at normalized time t ∈ [0, 1] (clamped) of the whole turnaround.
    pub fn advance(&self, t: f64) -> Landmarks {
        let span = 2.5 * self.delta;
        let tau = t.clamp(0.0, 1.0) * span * self.parts.len() as f64;
        let i = ((tau / span) as usize).min(self.parts.len() - 1);
        let part = &self.parts[i];
        let u = (tau - i as f64 * span) / self.delta;
        if u < 0.5 {
            let start = &part.start;
            let upper = twist(start, u, part.turn);
            start
                .figure_with(&upper, start.time + u * self.delta)
                .expect("the anticipation's feet and pelvis are the start's, checked")
        } else if u < 1.5 {
            part.steps[0].advance(u - 0.5)
        } else {
            part.steps[1].advance(u - 1.5)
        }
    }

    /// How many turnarounds the turn was split into.
    pub fn parts(&self) -> usize {
        self.parts.len()
    }

    /// δ, the duration of each step (s).
    pub fn step_duration(&self) -> f64 {
        self.delta
    }

    /// The whole duration (s): 2.5 δ per part.
    pub fn duration(&self) -> f64 {
        2.5 * self.delta * self.parts.len() as f64
    }

    /// The two steps of each part, in order.
    pub fn steps(&self) -> impl Iterator<Item = &NrsStep> {
        self.parts.iter().flat_map(|p| p.steps.iter())
    }

    /// The walker after the turn.
    pub fn end_state(&self) -> &WalkerState {
        &self.end
    }
}

/// The anticipation at u = τ/δ ∈ [0, ½] (§6): the gaze turned by `turn` · S(u) (it reaches the
/// goal direction at u = 1), the twist split as in §5.4 between the neck and the lumbar joint.
fn twist(state: &WalkerState, u: f64, turn: f64) -> Upper {
    let g = turn * crate::numerics::smooth::smoothstep(u);
    let share = state.params.neck_share;
    let mut upper = state.upper;
    upper.neck_rotation += share * g;
    upper.lumbar_rotation += (1.0 - share) * g;
    upper
}
