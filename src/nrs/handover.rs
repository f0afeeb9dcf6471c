//! Starting and stopping (issue 15 item 9): an NRS forward step from quiet standing into the
//! first heel strike of a walk of the dynamic engine, and one from its last heel strike into
//! quiet standing. Each ends (or starts) at the walk's own pose at the hand-over instant, its
//! feet, pelvis and upper body, and its centre site meets the walk's hip velocity there (the
//! Hermite end slopes of §5.3's time law), so the pelvis path is C¹ across the hand-over. The
//! underlying walking step (eq. 4, the foot-angle timing) is the walk's first, or last, step.
use crate::engine::step::Step;
use crate::engine::walker::Walk;
use crate::figure::placement::Placement;
use crate::figure::{Landmarks, LegPoints, landmarks};
use crate::kinematics::foot::Foot;
use crate::nrs::NrsError;
use crate::nrs::build::{Clock, Height, Plan};
use crate::nrs::pose::{Planted, Upper, grounded_ankle, right_of};
use crate::nrs::specs::{FootAngles, Side, StepType};
use crate::nrs::state::WalkerState;
use crate::nrs::step::NrsStep;
use crate::nrs::walking::{WalkingStep, sagittal_pitch};

/// The time step of the one-sided differences that give the walk's hip velocity (s).
const DT: f64 = 1e-4;

/// The foot of a walk's leg (in the walk's own frame, feet along +x) as a [`Planted`] foot:
/// pitch from its sole, the flat foot's ankle from the ankle's offset at that pitch
/// ([`grounded_ankle`]).
pub fn planted(leg: &LegPoints, foot: &Foot, theta6_max: f64) -> Planted {
    let pitch = sagittal_pitch(leg);
    let (a, _) = grounded_ankle(foot, pitch, theta6_max);
    Planted {
        flat: [leg.ankle[0] - a[0], leg.ankle[2]],
        heading: 0.0,
        pitch,
    }
}

/// `planted` put in the world by `at`.
fn placed(p: Planted, at: &Placement) -> Planted {
    let [x, _, z] = at.to_world([p.flat[0], 0.0, p.flat[1]]);
    Planted {
        flat: [x, z],
        heading: p.heading + at.heading,
        pitch: p.pitch,
    }
}

/// The pelvis and upper body of a frame.
pub fn upper_of(lm: &Landmarks) -> Upper {
    Upper {
        centre: lm.pelvis,
        heading: lm.pelvis_rotation,
        tilt: lm.pelvis_tilt,
        list: lm.pelvis_list,
        lumbar_extension: lm.lumbar_extension,
        lumbar_bending: lm.lumbar_bending,
        lumbar_rotation: lm.lumbar_rotation,
        neck_rotation: lm.neck_rotation,
        arms: [lm.right_arm, lm.left_arm],
    }
}

/// The walk's figure at `t` of `step`, placed.
fn figure(walk: &Walk, step: &Step, t: f64, at: &Placement) -> Result<Landmarks, NrsError> {
    Ok(at.apply(&landmarks(step, t, &walk.attrs)?))
}

/// The hip velocity of `step` at `t` (world), by a second-order one-sided difference into the
/// step (`dir` +1 forward in time, −1 backward).
fn velocity(
    walk: &Walk,
    step: &Step,
    t: f64,
    dir: f64,
    at: &Placement,
) -> Result<[f64; 3], NrsError> {
    let p = |k: f64| figure(walk, step, t + dir * k * DT, at).map(|lm| lm.pelvis);
    let (p0, p1, p2) = (p(0.0)?, p(1.0)?, p(2.0)?);
    Ok(std::array::from_fn(|i| {
        dir * (-3.0 * p0[i] + 4.0 * p1[i] - p2[i]) / (2.0 * DT)
    }))
}

/// The walker at a frame of a walk: feet, pelvis and upper body, hip velocity.
fn state_at(
    base: &WalkerState,
    walk: &Walk,
    lm: &Landmarks,
    at: &Placement,
    velocity: [f64; 3],
) -> Result<WalkerState, NrsError> {
    let foot = Foot::new(&walk.body);
    let lim = walk.attrs.metatarsal_limit;
    let own = at.inverse().apply(lm);
    let mut s = base.clone();
    s.feet = [own.right, own.left].map(|l| placed(planted(&l, &foot, lim), at));
    s.upper = upper_of(lm);
    s.velocity = velocity;
    s.time = lm.time;
    Ok(s)
}

/// The start: where the walk goes (its placement: the hind foot of its first heel strike on
/// the standing foot of that side, heading as that foot), and the NRS forward step of the
/// other foot from `state` into that heel strike. `state` stands with its feet flat.
pub fn start(state: &WalkerState, walk: &Walk) -> Result<(NrsStep, Placement), NrsError> {
    let first = &walk.steps[0];
    let front = first.side;
    let hind = front.other();
    let own = landmarks(first, first.t_start, &walk.attrs)?;
    let foot = Foot::new(&walk.body);
    let lim = walk.attrs.metatarsal_limit;
    let leg = |s: Side| match s {
        Side::Right => own.right,
        Side::Left => own.left,
    };
    let hind_own = planted(&leg(hind), &foot, lim);
    let standing = state.foot(hind);
    let heading = standing.heading;
    let turned = Placement::new([0.0, 0.0], heading);
    let [x, _, z] = turned.to_world([hind_own.flat[0], 0.0, hind_own.flat[1]]);
    let at = Placement::new([standing.flat[0] - x, standing.flat[1] - z], heading);
    let mut lm0 = at.apply(&own);
    lm0.time = state.time + first.constraints.timing.t_step;
    let goal = placed(planted(&leg(front), &foot, lim), &at);
    let walking = WalkingStep::from_step(first, &walk.attrs, state.params.table_intervals)?;
    let plan = Plan {
        kind: StepType::Forward,
        stance: hind,
        goal,
        angles: FootAngles {
            toe_off_swing: walking.toe_off_pitch(),
            strike_swing: goal.pitch,
            strike_stance: hind_own.pitch,
        },
        duration: walking.duration,
        walking: Some(walking),
        swing_height: state.params.swing_height * state.params.swing_height_factor,
        gaze_end: lm0.pelvis_rotation + lm0.lumbar_rotation + lm0.neck_rotation,
        upper_end: Some(upper_of(&lm0)),
        velocity_end: velocity(walk, first, first.t_start, 1.0, &at)?,
        height: Height::Rules,
        toe_off: Some(state.params.start_toe_off),
        heading_clock: Clock::WHOLE,
        gaze_clock: Clock::WHOLE,
    };
    Ok((NrsStep::from_plan(state, &plan)?, at))
}

/// The walker `tau` after the walk's last heel strike (time `t0` + the walk's duration + `tau`),
/// placed by `at`: the pose and hip velocity of `next`, the step the engine takes after the
/// walk's last, `tau` into it (the engine's hip velocity jumps at the heel strike; from `tau` on
/// its motion is smooth, and the stop goes on from it without a jump).
pub fn walk_end(
    base: &WalkerState,
    walk: &Walk,
    next: &Step,
    at: &Placement,
    (t0, tau): (f64, f64),
) -> Result<WalkerState, NrsError> {
    let t = next.t_start + tau;
    let mut lm = figure(walk, next, t, at)?;
    lm.time = t0 + t;
    let v = velocity(walk, next, t, -1.0, at)?;
    let mut s = state_at(base, walk, &lm, at, v)?;
    s.step = base.step + walk.steps.len();
    Ok(s)
}

/// The stop: from `state` (the walk's last heel strike, [`walk_end`]) the hind foot steps
/// beside the front one, the attributes' step width apart, into quiet standing facing the
/// walk's heading, the hip coming to rest.
pub fn stop(state: &WalkerState, walk: &Walk, heading: f64) -> Result<NrsStep, NrsError> {
    let last = walk.steps.last().expect("a walk has a step");
    // the foot that strikes at the end is the last step's swing foot
    let front = last.side.other();
    let hind = front.other();
    let f = state.foot(front);
    let r = right_of(heading);
    let w = state.attrs.step_width;
    let toward = hind.sign();
    let goal = Planted {
        flat: [f.flat[0] + toward * w * r[0], f.flat[1] + toward * w * r[1]],
        heading,
        pitch: 0.0,
    };
    let mid = [
        (f.flat[0] + goal.flat[0]) / 2.0,
        (f.flat[1] + goal.flat[1]) / 2.0,
    ];
    let rest =
        WalkerState::standing_with(state.body, state.attrs.clone(), state.params, mid, heading);
    let walking = WalkingStep::from_step(last, &walk.attrs, state.params.table_intervals)?;
    let plan = Plan {
        kind: StepType::Forward,
        stance: front,
        goal,
        angles: FootAngles {
            toe_off_swing: walking.toe_off_pitch(),
            strike_swing: 0.0,
            strike_stance: 0.0,
        },
        duration: walking.duration,
        walking: Some(walking),
        swing_height: state.params.swing_height * state.params.swing_height_factor,
        gaze_end: heading,
        upper_end: Some(rest.upper),
        velocity_end: [0.0; 3],
        height: Height::Rules,
        toe_off: None,
        heading_clock: Clock::WHOLE,
        gaze_clock: Clock::WHOLE,
    };
    NrsStep::from_plan(state, &plan)
}
