//! Tabulating one step of an NRS⁻ or a turnaround (Ko & Badler 1993 §5, §6) from the figure's
//! state and a [`Plan`], in stages: the foot pitches (§5.1), the swing ankle (§5.2), the pelvis
//! at HSM⁺ and the centre site's path (§5.3), the upper body (§5.4); then every instant is
//! checked for a leg that cannot reach.
use crate::kinematics::foot::{Foot, swing_floor};
use crate::kinematics::leg::reach;
use crate::nrs::NrsError;
use crate::nrs::curves::{
    Table, de_casteljau, interpolate_ends, interpolate_reversed, segment_distance, set_end_slopes,
    swing_rise,
};
use crate::nrs::pose::{FootPose, Planted, Upper, heading_of, hip_joint, right_of, turn_between};
use crate::nrs::range::{plantarflex_in_air, raised_height};
use crate::nrs::segment::{K, Segment};
use crate::nrs::specs::{FootAngles, Side, StepType};
use crate::nrs::state::{WalkerState, hanging_arm};
use crate::nrs::walking::WalkingStep;
use crate::numerics::smooth::{smootherstep, smoothstep};

/// How the centre site's height goes over a step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Height {
    /// §5.3: the walking step's heights moved to the ends (eq. 4; eq. 5 for a backward step),
    /// or without a walking step the inverted pendulum about the stance ankle.
    Rules,
    /// §6: monotone from the start height to the end height (a turnaround's steps).
    Monotone,
}

/// The progress of a blend that is the part [a, b] of one smoothstep over a longer motion:
/// (S(a + t (b − a)) − S(a)) / (S(b) − S(a)), 0 at t = 0 and 1 at t = 1. `Clock(0, 1)` is the
/// smoothstep of the step itself; consecutive parts of one motion share its rate at their
/// joins.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Clock(pub f64, pub f64);

impl Clock {
    /// The whole smoothstep over the step.
    pub const WHOLE: Clock = Clock(0.0, 1.0);

    /// The progress at normalized time t.
    pub fn at(self, t: f64) -> f64 {
        let Clock(a, b) = self;
        let (sa, sb) = (smoothstep(a), smoothstep(b));
        (smoothstep(a + t * (b - a)) - sa) / (sb - sa)
    }
}

/// What a step is asked to do, its defaults resolved.
#[derive(Clone, Debug)]
pub(crate) struct Plan {
    pub kind: StepType,
    pub stance: Side,
    /// The swing foot at HSM⁺.
    pub goal: Planted,
    pub angles: FootAngles,
    /// The walking step of the same length (forward and backward steps).
    pub walking: Option<WalkingStep>,
    pub duration: f64,
    pub swing_height: f64,
    pub gaze_end: f64,
    /// The pelvis and upper body at the end: `None` for the NRS rules (§5.3, §5.4).
    pub upper_end: Option<Upper>,
    pub velocity_end: [f64; 3],
    pub height: Height,
    /// TOM (normalized time); `None`: the walking step's, or without one that of a walk of
    /// the step's frequency.
    pub toe_off: Option<f64>,
    /// The pelvis heading's blend and the gaze's.
    pub heading_clock: Clock,
    pub gaze_clock: Clock,
}

/// The phase moments (row indices) and the feet's pitch over the step.
struct Pitches {
    toe_off: usize,
    stance: Vec<f64>,
    swing: Vec<f64>,
}

/// The value at row i of the piece [ia, ib] of a pitch curve `q`, scaled so that it runs from
/// a to b (§5.1); a piece along which `q` is constant is a smoothstep.
fn affine(q: &[f64], i: usize, (ia, ib): (usize, usize), (a, b): (f64, f64)) -> f64 {
    let (wa, wb) = (q[ia], q[ib]);
    let s = if (wb - wa).abs() > 1e-6 {
        (q[i] - wa) / (wb - wa)
    } else {
        smoothstep((i - ia) as f64 / (ib - ia).max(1) as f64)
    };
    a + (b - a) * s
}

/// §5.1: the walking step's sole-angle curves split at FGM, heel-off and TOM, each piece
/// scaled to the plan's control angles; without a walking step, ramps with the phase moments
/// of a walk of the step's frequency.
fn foot_pitches(state: &WalkerState, plan: &Plan) -> Pitches {
    let n = state.params.table_intervals;
    let idx = |f: f64| ((f * n as f64).round() as usize).min(n);
    let (flat, heel_off, toe_off, st_w, mut sw_w) = match &plan.walking {
        Some(w) => (
            idx(w.flat),
            idx(w.heel_off),
            idx(plan.toe_off.unwrap_or(w.toe_off)),
            w.stance_pitch.clone(),
            w.swing_pitch.clone(),
        ),
        None => {
            let sf = 60.0 / plan.duration;
            let tom = plan
                .toe_off
                .unwrap_or(((-0.16 * sf + 29.08) / 50.0).clamp(0.05, 0.5));
            let ramp: Vec<f64> = (0..=n).map(|i| i as f64 / n as f64).collect();
            (idx(0.1), idx(0.7), idx(tom), ramp.clone(), ramp)
        }
    };
    // a TOM of the plan's own (a start from standing): the swing foot rolls up to it by a
    // smootherstep, from rest without a jump in acceleration \[ours\]: with a smoothstep the
    // stepping hip went from rest to ≈ 280°/s in 10 ms (docs/nrs.md, "Starting and stopping")
    if plan.toe_off.is_some() {
        for (i, q) in sw_w.iter_mut().enumerate().take(toe_off + 1) {
            *q = smootherstep(i as f64 / toe_off.max(1) as f64);
        }
    }
    let heel_off = heel_off.max(flat).min(n);
    let a = &plan.angles;
    let stance_start = state.foot(plan.stance).pitch;
    let swing_start = state.foot(plan.stance.other()).pitch;
    let stance = (0..=n)
        .map(|i| {
            if i <= flat {
                affine(&st_w, i, (0, flat), (stance_start, 0.0))
            } else if i <= heel_off {
                0.0
            } else {
                affine(&st_w, i, (heel_off, n), (0.0, a.strike_stance))
            }
        })
        .collect();
    let swing = (0..=n)
        .map(|i| {
            if i <= toe_off {
                affine(&sw_w, i, (0, toe_off), (swing_start, a.toe_off_swing))
                    .max(swing_start.min(0.0))
            } else {
                affine(&sw_w, i, (toe_off, n), (a.toe_off_swing, a.strike_swing))
            }
        })
        .collect();
    Pitches {
        toe_off,
        stance,
        swing,
    }
}

/// §5.2: the swing foot's rows (ankle, heading, pitch, θ6): rolling on the floor until TOM,
/// then eq. 3 over the take-off–landing line, on a straight path, both in the parameter a =
/// smoothstep(s) of the airborne time s (the foot leaves and lands at rest; docs/nrs.md) or, where that passes within
/// the clearance of the stance ankle, on the de Casteljau curve with D2 a pelvis width from the
/// stance ankle on the swing side. In the air the foot's heading relative to the pelvis
/// (`pelvis(t)`) goes by a smoothstep from its value at take-off to its value at landing, so
/// the swing hip's axial rotation stays between the two.
fn swing_ankle(
    state: &WalkerState,
    plan: &Plan,
    pitches: &Pitches,
    pelvis: impl Fn(f64) -> f64,
) -> Vec<[f64; 6]> {
    let n = state.params.table_intervals;
    let foot = Foot::new(&state.body);
    let lim = state.attrs.metatarsal_limit;
    let stance_foot = *state.foot(plan.stance);
    let swing_start = *state.foot(plan.stance.other());
    let toe_off = pitches.toe_off;
    let take_off = Planted {
        pitch: pitches.swing[toe_off],
        ..swing_start
    }
    .pose(&foot, lim);
    let landing = plan.goal.pose(&foot, lim);
    let s_ankle = stance_foot.flat;
    let d1 = [take_off.ankle[0], take_off.ankle[2]];
    let d3 = [landing.ankle[0], landing.ankle[2]];
    let curved = segment_distance(s_ankle, d1, d3) < state.attrs.step_width - 1e-9;
    let d2 = {
        let v = [d3[0] - d1[0], d3[1] - d1[1]];
        let len = (v[0] * v[0] + v[1] * v[1]).sqrt().max(1e-12);
        let mut perp = [-v[1] / len, v[0] / len];
        let out = right_of(stance_foot.heading);
        if (perp[0] * out[0] + perp[1] * out[1]) * plan.stance.other().sign() < 0.0 {
            perp = [-perp[0], -perp[1]];
        }
        let l0 = state.body.l0;
        [s_ankle[0] + l0 * perp[0], s_ankle[1] + l0 * perp[1]]
    };
    // the foot's heading relative to the pelvis, blended from take-off to landing
    let t_off = toe_off as f64 / n as f64;
    let r_off = turn_between(pelvis(t_off), swing_start.heading);
    let r_land = turn_between(pelvis(1.0), plan.goal.heading);
    let row = |f: FootPose| {
        [
            f.ankle[0], f.ankle[1], f.ankle[2], f.heading, f.pitch, f.theta6,
        ]
    };
    (0..=n)
        .map(|i| {
            let rule = pitches.swing[i];
            if i <= toe_off {
                return row(Planted {
                    pitch: rule,
                    ..swing_start
                }
                .pose(&foot, lim));
            }
            let s = (i - toe_off) as f64 / (n - toe_off) as f64;
            // eq. 3 and the path in a = S(s): the foot leaves and lands at rest
            let a = smoothstep(s);
            let xz = if curved {
                de_casteljau([d1, d2, d3], a)
            } else {
                [d1[0] + a * (d3[0] - d1[0]), d1[1] + a * (d3[1] - d1[1])]
            };
            let y = take_off.ankle[1]
                + a * (landing.ankle[1] - take_off.ankle[1])
                + swing_rise(a, plan.swing_height);
            // the toes straighten in the first half of the swing and, for a foot that lands
            // heel up (toe first), bend to the landing's in the second
            let theta6 = take_off.theta6 * (1.0 - smoothstep(2.0 * s))
                + landing.theta6 * smoothstep(2.0 * s - 1.0);
            // the toe above the engine's rising swing floor
            let floor = swing_floor(state.attrs.toe_clearance, s);
            let (pitch, _) = foot.clear_pitch(rule, [0.0, y], theta6, floor);
            let t = i as f64 / n as f64;
            let heading = pelvis(t) + r_off + smoothstep(s) * (r_land - r_off);
            let pitch = if i == n { landing.pitch } else { pitch };
            [xz[0], y, xz[1], heading, pitch, theta6]
        })
        .collect()
}

/// The upper body of the §5.4 rules for a pelvis facing `heading` and a gaze `gaze`: the
/// attributes' tilt and lean, the twist between gaze and pelvis split `neck_share` at the neck
/// and the rest at the lumbar joint, the arms hanging.
pub(crate) fn upper_rule(state: &WalkerState, heading: f64, gaze: f64) -> Upper {
    let share = state.params.neck_share;
    let twist = turn_between(heading, gaze);
    Upper {
        centre: [0.0; 3],
        heading,
        tilt: state.attrs.pelvis_tilt,
        list: 0.0,
        lumbar_extension: state.attrs.pelvis_tilt - state.attrs.trunk_lean,
        lumbar_bending: 0.0,
        lumbar_rotation: (1.0 - share) * twist,
        neck_rotation: share * twist,
        arms: [hanging_arm(); 2],
    }
}

/// The pelvis's heading at HSM⁺ (§5.4: half the angle α of a lateral step; the bisector of the
/// stance and goal directions otherwise) unless the plan gives the pelvis.
fn heading_end(state: &WalkerState, plan: &Plan) -> f64 {
    let stance = state.foot(plan.stance);
    match (&plan.upper_end, plan.kind) {
        (Some(u), _) => u.heading,
        (None, StepType::Lateral) => {
            let out = right_of(stance.heading);
            let sgn = plan.stance.other().sign();
            let lateral = heading_of([sgn * out[0], sgn * out[1]]);
            let g = plan.goal.flat;
            let line = heading_of([g[0] - stance.flat[0], g[1] - stance.flat[1]]);
            stance.heading + 0.5 * turn_between(lateral, line)
        }
        (None, _) => stance.heading + 0.5 * turn_between(stance.heading, plan.goal.heading),
    }
}

/// §5.3: the centre site at HSM⁺ on the line between the ankles, as high as both legs reach
/// with the walking step's knees at its heel strike (or the standing knee): the lower of the
/// two heights. Above the ankles' midpoint, except in a forward step whose stance heel is up at
/// HSM⁺ [ours]: there the point of the line where that height is greatest, so that both legs
/// keep the walking step's knee flexions (§5.3's assumption) and the raised heel lifts the hip
/// instead of bending the hind knee (docs/nrs.md).
fn centre_end(state: &WalkerState, plan: &Plan, heading: f64) -> [f64; 3] {
    if let Some(u) = &plan.upper_end {
        return u.centre;
    }
    let body = state.body;
    let foot = Foot::new(&body);
    let lim = state.attrs.metatarsal_limit;
    let landing = plan.goal.pose(&foot, lim).ankle;
    let stance = Planted {
        pitch: plan.angles.strike_stance,
        ..*state.foot(plan.stance)
    }
    .pose(&foot, lim)
    .ankle;
    let reaches = match &plan.walking {
        Some(w) => w.reach_at_strike,
        None => [reach(body.l3, body.l4, state.params.stand_knee.cos()); 2],
    };
    let up0 = upper_rule(state, heading, plan.gaze_end);
    // the centre a fraction f of the way from the stance ankle to the landing one, its height
    let at = |f: f64| {
        let c = [
            stance[0] + f * (landing[0] - stance[0]),
            stance[2] + f * (landing[2] - stance[2]),
        ];
        let up = Upper {
            centre: [c[0], 0.0, c[1]],
            ..up0
        };
        let mut h = f64::INFINITY;
        for (ankle, side, l) in [
            (landing, plan.stance.other(), reaches[0]),
            (stance, plan.stance, reaches[1]),
        ] {
            let o = hip_joint(&up, side, body.l0 / 2.0);
            let horiz2 = (o.x - ankle[0]).powi(2) + (o.z - ankle[2]).powi(2);
            h = h.min(ankle[1] - o.y + (l * l - horiz2).max(0.0).sqrt());
        }
        [c[0], h, c[1]]
    };
    if plan.kind != StepType::Forward || plan.angles.strike_stance <= 0.0 {
        return at(0.5);
    }
    // golden-section search: the lower of a rising and a falling height has one maximum
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (0.0, 1.0);
    for _ in 0..60 {
        let (p, q) = (b - g * (b - a), a + g * (b - a));
        if at(p)[1] < at(q)[1] {
            a = p;
        } else {
            b = q;
        }
    }
    at(0.5 * (a + b))
}

/// §5.3: the centre site's rows from the state's to `end`: the planar path a line with the
/// time law of the walking step's hip (reversed for a backward step), the height by eq. 4 /
/// eq. 5, the pendulum or monotone, the ends' velocities set by Hermite terms, and every row
/// lowered where a leg would have to stretch (the pelvis's heading, tilt and list at t).
fn centre_path(
    state: &WalkerState,
    plan: &Plan,
    end: [f64; 3],
    (heading, tilt_list): (impl Fn(f64) -> f64, impl Fn(f64) -> (f64, f64)),
    stance_pitch: &mut [f64],
    swing: &[[f64; 6]],
) -> [Vec<f64>; 3] {
    let n = state.params.table_intervals;
    let c0 = state.upper.centre;
    let s_ankle = state.foot(plan.stance).flat;
    let t: Vec<f64> = (0..=n).map(|i| i as f64 / n as f64).collect();
    let travel: Vec<f64> = match (&plan.walking, plan.kind) {
        (Some(w), StepType::Backward) => w.travel.iter().rev().map(|s| 1.0 - s).collect(),
        (Some(w), _) => w.travel.clone(),
        (None, _) => t.iter().map(|&t| smoothstep(t)).collect(),
    };
    let line = |k: usize| -> Vec<f64> {
        travel
            .iter()
            .map(|s| c0[k] + s * (end[k] - c0[k]))
            .collect()
    };
    let (mut x, mut z) = (line(0), line(2));
    let mut y = match (plan.height, &plan.walking, plan.kind) {
        (Height::Monotone, _, _) => t
            .iter()
            .map(|&t| c0[1] + smoothstep(t) * (end[1] - c0[1]))
            .collect(),
        (_, Some(w), StepType::Backward) => interpolate_reversed(&t, &w.height, c0[1], end[1]),
        (_, Some(w), _) => interpolate_ends(&t, &w.height, c0[1], end[1]),
        (_, None, _) => {
            let r2 = (c0[0] - s_ankle[0]).powi(2) + c0[1].powi(2) + (c0[2] - s_ankle[1]).powi(2);
            let pendulum: Vec<f64> = (0..=n)
                .map(|i| {
                    (r2 - (x[i] - s_ankle[0]).powi(2) - (z[i] - s_ankle[1]).powi(2))
                        .max(0.0)
                        .sqrt()
                })
                .collect();
            interpolate_ends(&t, &pendulum, c0[1], end[1])
        }
    };
    let v0 = state.velocity.map(|v| v * plan.duration);
    let v1 = plan.velocity_end.map(|v| v * plan.duration);
    set_end_slopes(&mut x, Some(v0[0]), Some(v1[0]));
    set_end_slopes(&mut y, Some(v0[1]), Some(v1[1]));
    set_end_slopes(&mut z, Some(v0[2]), Some(v1[2]));
    let body = state.body;
    let foot = Foot::new(&body);
    let stance_foot = *state.foot(plan.stance);
    let straighten =
        plan.kind == StepType::Forward && plan.walking.is_some() && plan.upper_end.is_none();
    for i in 0..=n {
        let (tilt, list) = tilt_list(t[i]);
        let probe = Upper {
            centre: [x[i], 0.0, z[i]],
            heading: heading(t[i]),
            tilt,
            list,
            ..Upper::default()
        };
        let stance_at = |p: f64| {
            Planted {
                pitch: p,
                ..stance_foot
            }
            .pose(&foot, state.attrs.metatarsal_limit)
            .ankle
        };
        let swing_ankle = [swing[i][0], swing[i][1], swing[i][2]];
        // [ours] a forward step's centre rises where eq. 4 would dorsiflex the stance ankle
        // beyond its bound (docs/nrs.md): the heights are the walking step's, whose stance heel
        // rises under them; the NRS's stays down, so its leg straightens instead, at most to
        // the standing knee; where that is not enough (before HSM⁺) its heel rises by the
        // excess and the hip with it; the swing leg's reach below still limits the height
        if straighten {
            let o = hip_joint(&probe, plan.stance, body.l0 / 2.0);
            let eq4 = y[i];
            for _ in 0..6 {
                let ankle = stance_at(stance_pitch[i]);
                let (h, excess) =
                    raised_height(state, o, ankle, stance_foot.heading, stance_pitch[i], eq4);
                y[i] = h;
                if excess <= 1e-4 || i == n {
                    break;
                }
                stance_pitch[i] += excess;
            }
        }
        let stance_ankle = stance_at(stance_pitch[i]);
        for (ankle, side) in [
            (stance_ankle, plan.stance),
            (swing_ankle, plan.stance.other()),
        ] {
            let o = hip_joint(&probe, side, body.l0 / 2.0);
            let horiz2 = (o.x - ankle[0]).powi(2) + (o.z - ankle[2]).powi(2);
            let l = body.l1 - 1e-7;
            if horiz2 < l * l {
                y[i] = y[i].min(ankle[1] - o.y + (l * l - horiz2).sqrt());
            }
        }
    }
    if plan.height == Height::Monotone {
        monotone(&mut y, end[1] < c0[1]);
    }
    [x, y, z]
}

/// Make `y` monotone without raising any value: a running minimum from the start when it
/// falls, from the end when it rises.
fn monotone(y: &mut [f64], falling: bool) {
    if falling {
        for i in 1..y.len() {
            y[i] = y[i].min(y[i - 1]);
        }
    } else {
        for i in (0..y.len() - 1).rev() {
            y[i] = y[i].min(y[i + 1]);
        }
    }
}

/// The upper-body channels the table carries (tilt … the left elbow).
fn upper_channels(u: &Upper) -> [f64; 12] {
    let [r, l] = u.arms;
    [
        u.tilt,
        u.list,
        u.lumbar_extension,
        u.lumbar_bending,
        u.lumbar_rotation,
        u.neck_rotation,
        r.shoulder_flexion,
        r.shoulder_abduction,
        r.elbow_flexion,
        l.shoulder_flexion,
        l.shoulder_abduction,
        l.elbow_flexion,
    ]
}

/// Tabulate a step from `state` (the NRS rules of §5 with the end conditions and clocks of
/// `plan`), and check that both legs reach at every row.
pub(crate) fn build(state: &WalkerState, plan: &Plan) -> Result<Segment, NrsError> {
    let n = state.params.table_intervals;
    let body = state.body;
    let mut pitches = foot_pitches(state, plan);
    let heading0 = state.upper.heading;
    let heading1 = heading_end(state, plan);
    let heading = |t: f64| heading0 + plan.heading_clock.at(t) * turn_between(heading0, heading1);
    let mut swing = swing_ankle(state, plan, &pitches, heading);
    let end = centre_end(state, plan, heading1);
    // the upper body: the rules of §5.4, moved to start at the state's and end at `upper_end`
    let gaze0 = state.gaze();
    let rule_at = |t: f64| {
        let gaze = gaze0 + plan.gaze_clock.at(t) * turn_between(gaze0, plan.gaze_end);
        upper_channels(&upper_rule(state, heading(t), gaze))
    };
    let start = upper_channels(&state.upper);
    let (r0, r1) = (rule_at(0.0), rule_at(1.0));
    let end_upper = plan.upper_end.as_ref().map_or(r1, upper_channels);
    let upper_at = |t: f64| -> [f64; 12] {
        let (w, r) = (smoothstep(t), rule_at(t));
        std::array::from_fn(|k| r[k] + (1.0 - w) * (start[k] - r0[k]) + w * (end_upper[k] - r1[k]))
    };
    let tilt_list = |t: f64| {
        let u = upper_at(t);
        (u[0], u[1])
    };
    let pitch = &mut pitches.stance;
    let [x, y, z] = centre_path(state, plan, end, (heading, tilt_list), pitch, &swing);
    let segment = |swing: &[[f64; 6]]| Segment {
        table: Table::new(n, |i, t| {
            let mut row = [0.0; K];
            row[0] = x[i];
            row[1] = y[i];
            row[2] = z[i];
            row[3] = heading(t);
            row[4..16].copy_from_slice(&upper_at(t));
            row[16] = pitches.stance[i];
            row[17..23].copy_from_slice(&swing[i]);
            row
        }),
        stance: plan.stance,
        stance_foot: *state.foot(plan.stance),
        swing_foot: *state.foot(plan.stance.other()),
        toe_off: pitches.toe_off as f64 / n as f64,
        duration: plan.duration,
        t0: state.time,
        step: state.step + 1,
        foot: Foot::new(&body),
        body,
        theta6_max: state.attrs.metatarsal_limit,
        eversion_max: state.params.ankle_eversion_max,
    };
    let seg = segment(&swing);
    seg.check_reach(plan.goal.flat, n)?;
    // the airborne swing foot plantarflexes where its ankle would leave its range (docs/nrs.md)
    let max = state.params.ankle_dorsiflexion_max;
    if plantarflex_in_air(&seg, &mut swing, pitches.toe_off, max) {
        return Ok(segment(&swing));
    }
    Ok(seg)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Consecutive parts of one smoothstep join with the same rate: the progress of the whole
    /// is recovered from the parts.
    #[test]
    fn clocks_split_one_smoothstep() {
        let (a, b) = (Clock(0.0, 0.5), Clock(0.5, 1.0));
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            let whole = smoothstep(t / 2.0);
            assert!((0.5 * a.at(t) - whole).abs() < 1e-15);
            let whole = smoothstep(0.5 + t / 2.0);
            assert!((0.5 + 0.5 * b.at(t) - whole).abs() < 1e-15);
            assert!((Clock::WHOLE.at(t) - smoothstep(t)).abs() < 1e-15);
        }
        // the rates at the join: d/dt of the whole at ½, in each part's time
        let h = 1e-6;
        let ra = (a.at(1.0) - a.at(1.0 - h)) / h * 0.5;
        let rb = (b.at(h) - b.at(0.0)) / h * 0.5;
        assert!((ra - rb).abs() < 1e-5, "{ra} vs {rb}");
    }

    /// The running minimum keeps a falling sequence falling and a rising one rising, never
    /// raising a value.
    #[test]
    fn monotone_never_raises() {
        let mut y = vec![1.0, 0.9, 0.95, 0.8, 0.85];
        monotone(&mut y, true);
        assert_eq!(y, vec![1.0, 0.9, 0.9, 0.8, 0.8]);
        let mut y = vec![0.8, 0.9, 0.85, 1.0];
        monotone(&mut y, false);
        assert_eq!(y, vec![0.8, 0.85, 0.85, 1.0]);
    }
}
