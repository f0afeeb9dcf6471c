//! An NRS⁻, a forward, backward or lateral step (Ko & Badler 1993 §5): [`NrsStep::initialize`]
//! classifies the goal (§4), checks it, borrows the walking step of the same length from the
//! engine and tabulates every trajectory over normalized time; [`NrsStep::advance`] poses the
//! figure at t ∈ [0, 1] from the tables in constant time without allocating.
use crate::figure::Landmarks;
use crate::kinematics::foot::Foot;
use crate::kinematics::leg::reach;
use crate::model::InputError;
use crate::nrs::curves::{
    Table, de_casteljau, interpolate_ends, interpolate_reversed, segment_distance, set_end_slopes,
    swing_rise,
};
use crate::nrs::pose::{Planted, Upper, direction, heading_of, right_of, turn_between};
use crate::nrs::specs::{FootAngles, Side, StepSpecs, StepType};
use crate::nrs::state::{WalkerState, hanging_arm};
use crate::nrs::walking::WalkingStep;
use crate::nrs::{GoalReason, NrsError};
use crate::numerics::smooth::smoothstep;
use crate::plan::GaitRequest;

pub use crate::nrs::region::classify;
use crate::nrs::segment::{K, Segment};

/// What a step is asked to do, its defaults resolved.
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
    /// The pelvis at the end: `None` for the NRS rules (§5.3, §5.4).
    pub upper_end: Option<Upper>,
    pub velocity_end: [f64; 3],
}

fn affine(q: &[f64], i: usize, (ia, ib): (usize, usize), (a, b): (f64, f64)) -> f64 {
    let (wa, wb) = (q[ia], q[ib]);
    let s = if (wb - wa).abs() > 1e-6 {
        (q[i] - wa) / (wb - wa)
    } else {
        smoothstep((i - ia) as f64 / (ib - ia).max(1) as f64)
    };
    a + (b - a) * s
}

/// Tabulate a step from `state` (the NRS rules of §5, with the end conditions of `plan`).
pub(crate) fn build(state: &WalkerState, plan: &Plan) -> Result<Segment, NrsError> {
    let p = &state.params;
    let n = p.table_intervals;
    let body = state.body;
    let foot = Foot::new(&body);
    let lim = state.attrs.metatarsal_limit;
    let stance_foot = *state.foot(plan.stance);
    let swing_start = *state.foot(plan.stance.other());
    let idx = |f: f64| ((f * n as f64).round() as usize).min(n);
    // the phase moments and the walking step's foot pitches
    let (flat, heel_off, toe_off, st_w, sw_w) = match &plan.walking {
        Some(w) => (
            idx(w.flat),
            idx(w.heel_off),
            idx(w.toe_off),
            w.stance_pitch.clone(),
            w.swing_pitch.clone(),
        ),
        None => {
            let sf = 60.0 / plan.duration;
            let tom = ((-0.16 * sf + 29.08) / 50.0).clamp(0.05, 0.5);
            let ramp: Vec<f64> = (0..=n).map(|i| i as f64 / n as f64).collect();
            (idx(0.1), idx(0.7), idx(tom), ramp.clone(), ramp)
        }
    };
    let heel_off = heel_off.max(flat).min(n);
    let a = &plan.angles;
    let stance_pitch: Vec<f64> = (0..=n)
        .map(|i| {
            if i <= flat {
                affine(&st_w, i, (0, flat), (stance_foot.pitch, 0.0))
            } else if i <= heel_off {
                0.0
            } else {
                affine(&st_w, i, (heel_off, n), (0.0, a.strike_stance))
            }
        })
        .collect();
    let swing_pitch: Vec<f64> = (0..=n)
        .map(|i| {
            if i <= toe_off {
                affine(&sw_w, i, (0, toe_off), (swing_start.pitch, a.toe_off_swing))
                    .max(swing_start.pitch.min(0.0))
            } else {
                affine(&sw_w, i, (toe_off, n), (a.toe_off_swing, a.strike_swing))
            }
        })
        .collect();
    // the swing ankle: rolling on the floor until TOM, then eq. 3 over the take-off–landing line
    let take_off = Planted {
        pitch: swing_pitch[toe_off],
        ..swing_start
    }
    .pose(&foot, lim);
    let landing = plan.goal.pose(&foot, lim);
    let stance_end = Planted {
        pitch: a.strike_stance,
        ..stance_foot
    }
    .pose(&foot, lim);
    let s_ankle = [stance_foot.flat[0], stance_foot.flat[1]];
    let d1 = [take_off.ankle[0], take_off.ankle[2]];
    let d3 = [landing.ankle[0], landing.ankle[2]];
    let clearance = state.attrs.step_width;
    let curved = segment_distance(s_ankle, d1, d3) < clearance - 1e-9;
    let d2 = {
        let v = [d3[0] - d1[0], d3[1] - d1[1]];
        let len = (v[0] * v[0] + v[1] * v[1]).sqrt().max(1e-12);
        let mut perp = [-v[1] / len, v[0] / len];
        let out = right_of(stance_foot.heading);
        let sgn = plan.stance.other().sign();
        if (perp[0] * out[0] + perp[1] * out[1]) * sgn < 0.0 {
            perp = [-perp[0], -perp[1]];
        }
        [
            s_ankle[0] + body.l0 * perp[0],
            s_ankle[1] + body.l0 * perp[1],
        ]
    };
    let turn = turn_between(swing_start.heading, plan.goal.heading);
    let mut swing_rows = Vec::with_capacity(n + 1);
    for (i, &rule) in swing_pitch.iter().enumerate() {
        if i <= toe_off {
            let f = Planted {
                pitch: rule,
                ..swing_start
            }
            .pose(&foot, lim);
            swing_rows.push([
                f.ankle[0], f.ankle[1], f.ankle[2], f.heading, f.pitch, f.theta6,
            ]);
            continue;
        }
        let s = (i - toe_off) as f64 / (n - toe_off) as f64;
        let xz = if curved {
            de_casteljau([d1, d2, d3], s)
        } else {
            [d1[0] + s * (d3[0] - d1[0]), d1[1] + s * (d3[1] - d1[1])]
        };
        let y = take_off.ankle[1]
            + s * (landing.ankle[1] - take_off.ankle[1])
            + swing_rise(s, plan.swing_height);
        let theta6 = take_off.theta6 * (1.0 - smoothstep(2.0 * s));
        let (pitch, _) = foot.clear_pitch(rule, [0.0, y], theta6, 0.0);
        let heading = swing_start.heading + smoothstep(s) * turn;
        swing_rows.push([
            xz[0],
            y,
            xz[1],
            heading,
            if i == n { landing.pitch } else { pitch },
            theta6,
        ]);
    }
    // the pelvis at the end: above the ankles' midpoint, facing by §5.4, as high as both legs
    // reach with the walking step's knees at HSM⁺ (the lower of the two)
    let heading0 = state.upper.heading;
    let heading_end = match (&plan.upper_end, plan.kind) {
        (Some(u), _) => u.heading,
        (None, StepType::Lateral) => {
            let out = right_of(stance_foot.heading);
            let sgn = plan.stance.other().sign();
            let lateral = heading_of([sgn * out[0], sgn * out[1]]);
            let line = heading_of([d3[0] - s_ankle[0], d3[1] - s_ankle[1]]);
            stance_foot.heading + 0.5 * turn_between(lateral, line)
        }
        (None, _) => {
            stance_foot.heading + 0.5 * turn_between(stance_foot.heading, plan.goal.heading)
        }
    };
    let rule = |heading: f64, gaze: f64| Upper {
        centre: [0.0; 3],
        heading,
        tilt: state.attrs.pelvis_tilt,
        list: 0.0,
        lumbar_extension: state.attrs.pelvis_tilt - state.attrs.trunk_lean,
        lumbar_bending: 0.0,
        lumbar_rotation: (1.0 - p.neck_share) * turn_between(heading, gaze),
        neck_rotation: p.neck_share * turn_between(heading, gaze),
        arms: [hanging_arm(); 2],
    };
    let centre_end = match &plan.upper_end {
        Some(u) => u.centre,
        None => {
            let mid = [
                (stance_end.ankle[0] + landing.ankle[0]) / 2.0,
                (stance_end.ankle[2] + landing.ankle[2]) / 2.0,
            ];
            let reaches = match &plan.walking {
                Some(w) => w.reach_at_strike,
                None => [reach(body.l3, body.l4, p.stand_knee.cos()); 2],
            };
            let mut up = rule(heading_end, plan.gaze_end);
            up.centre = [mid[0], 0.0, mid[1]];
            let mut h = f64::INFINITY;
            for (ankle, side, l) in [
                (landing.ankle, plan.stance.other(), reaches[0]),
                (stance_end.ankle, plan.stance, reaches[1]),
            ] {
                let o = crate::nrs::pose::hip_joint(&up, side, body.l0 / 2.0);
                let horiz2 = (o.x - ankle[0]).powi(2) + (o.z - ankle[2]).powi(2);
                let dy = (l * l - horiz2).max(0.0).sqrt();
                h = h.min(ankle[1] - o.y + dy);
            }
            [mid[0], h, mid[1]]
        }
    };
    // the centre's time law and height (eq. 4, eq. 5 or the pendulum), then its end slopes
    let c0 = state.upper.centre;
    let t: Vec<f64> = (0..=n).map(|i| i as f64 / n as f64).collect();
    let travel: Vec<f64> = match (&plan.walking, plan.kind) {
        (Some(w), StepType::Backward) => w.travel.iter().rev().map(|s| 1.0 - s).collect(),
        (Some(w), _) => w.travel.clone(),
        (None, _) => t.iter().map(|&t| smoothstep(t)).collect(),
    };
    let mut x: Vec<f64> = travel
        .iter()
        .map(|s| c0[0] + s * (centre_end[0] - c0[0]))
        .collect();
    let mut z: Vec<f64> = travel
        .iter()
        .map(|s| c0[2] + s * (centre_end[2] - c0[2]))
        .collect();
    let mut y = match (&plan.walking, plan.kind) {
        (Some(w), StepType::Backward) => interpolate_reversed(&t, &w.height, c0[1], centre_end[1]),
        (Some(w), _) => interpolate_ends(&t, &w.height, c0[1], centre_end[1]),
        (None, _) => {
            let r2 = (c0[0] - s_ankle[0]).powi(2) + (c0[1]).powi(2) + (c0[2] - s_ankle[1]).powi(2);
            let pend: Vec<f64> = (0..=n)
                .map(|i| {
                    (r2 - (x[i] - s_ankle[0]).powi(2) - (z[i] - s_ankle[1]).powi(2))
                        .max(0.0)
                        .sqrt()
                })
                .collect();
            interpolate_ends(&t, &pend, c0[1], centre_end[1])
        }
    };
    let v0 = state.velocity.map(|v| v * plan.duration);
    let v1 = plan.velocity_end.map(|v| v * plan.duration);
    set_end_slopes(&mut x, Some(v0[0]), Some(v1[0]));
    set_end_slopes(&mut y, Some(v0[1]), Some(v1[1]));
    set_end_slopes(&mut z, Some(v0[2]), Some(v1[2]));
    // no leg stretched: where a height asks more than both legs reach, the centre is lowered to
    // what the shorter reach allows (the hips by the pelvis's heading of the row)
    for i in 0..=n {
        let w = smoothstep(t[i]);
        let heading = heading0 + w * turn_between(heading0, heading_end);
        let probe = Upper {
            centre: [x[i], 0.0, z[i]],
            heading,
            tilt: state.attrs.pelvis_tilt,
            ..Upper::default()
        };
        let stance_ankle = Planted {
            pitch: stance_pitch[i],
            ..stance_foot
        }
        .pose(&foot, lim)
        .ankle;
        let swing_ankle = [swing_rows[i][0], swing_rows[i][1], swing_rows[i][2]];
        for (ankle, side) in [
            (stance_ankle, plan.stance),
            (swing_ankle, plan.stance.other()),
        ] {
            let o = crate::nrs::pose::hip_joint(&probe, side, body.l0 / 2.0);
            let horiz2 = (o.x - ankle[0]).powi(2) + (o.z - ankle[2]).powi(2);
            let l = body.l1 - 1e-7;
            if horiz2 < l * l {
                y[i] = y[i].min(ankle[1] - o.y + (l * l - horiz2).sqrt());
            }
        }
    }
    // the upper body: the rules of §5.4, moved to start at the state's and end at `upper_end`
    let gaze0 = state.gaze();
    let upper_vec = |u: &Upper| {
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
    };
    let rule_at = |w: f64| {
        let heading = heading0 + w * turn_between(heading0, heading_end);
        let gaze = gaze0 + w * turn_between(gaze0, plan.gaze_end);
        (heading, upper_vec(&rule(heading, gaze)))
    };
    let start = upper_vec(&state.upper);
    let (_, r0) = rule_at(0.0);
    let (_, r1) = rule_at(1.0);
    let end = plan.upper_end.as_ref().map_or(r1, upper_vec);
    let table = Table::new(n, |i, t| {
        let w = smoothstep(t);
        let (heading, r) = rule_at(w);
        let mut row = [0.0; K];
        row[0] = x[i];
        row[1] = y[i];
        row[2] = z[i];
        row[3] = heading;
        for k in 0..12 {
            row[4 + k] = r[k] + (1.0 - w) * (start[k] - r0[k]) + w * (end[k] - r1[k]);
        }
        row[16] = stance_pitch[i];
        row[17..23].copy_from_slice(&swing_rows[i]);
        row
    });
    let seg = Segment {
        table,
        stance: plan.stance,
        stance_foot,
        swing_foot: swing_start,
        toe_off: toe_off as f64 / n as f64,
        duration: plan.duration,
        t0: state.time,
        step: state.step + 1,
        foot,
        body,
        theta6_max: lim,
    };
    // no leg stretched beyond its length at any instant
    for i in 0..=n {
        if let Err((side, distance)) = seg.pose(i as f64 / n as f64) {
            return Err(NrsError::Goal {
                position: plan.goal.flat,
                side: plan.stance.other().name(),
                reason: GoalReason::Unreachable {
                    leg: side.name(),
                    distance,
                    length: body.l1,
                    t: i as f64 / n as f64,
                },
            });
        }
    }
    Ok(seg)
}

/// A non-rhythmic step, precomputed.
#[derive(Clone, Debug)]
pub struct NrsStep {
    pub(crate) segment: Segment,
    kind: StepType,
    end: WalkerState,
}

impl NrsStep {
    /// Precompute the step `specs` from `state` lasting `duration` s (`None`: the walking step's
    /// of the same length by the normalizing formula, or the preferred walk's for a lateral
    /// step). Fails on an illegal goal (§4), a goal on the stance foot, a forward or backward
    /// step shorter than the engine's shortest step, a leg that cannot reach, or an input out of
    /// its range.
    pub fn initialize(
        state: &WalkerState,
        specs: &StepSpecs,
        duration: Option<f64>,
    ) -> Result<NrsStep, NrsError> {
        let p = &state.params;
        let name = specs.side.name();
        let goal_err = |reason| NrsError::Goal {
            position: specs.foot_position,
            side: name,
            reason,
        };
        for (what, v) in [
            ("foot_position.x", specs.foot_position[0]),
            ("foot_position.z", specs.foot_position[1]),
            ("foot_direction", specs.foot_direction),
        ] {
            if !v.is_finite() {
                return Err(InputError::NotFinite {
                    name: what.into(),
                    value: v,
                }
                .into());
            }
        }
        InputError::check_range(
            "swing_height_factor",
            specs.swing_height_factor,
            0.0,
            p.swing_height_factor_max,
            "",
        )?;
        let stance_side = specs.side.other();
        let stance = *state.foot(stance_side);
        let foot = Foot::new(&state.body);
        let kind = classify(
            &stance,
            specs.side,
            specs.foot_position,
            specs.foot_direction,
            (p.region_angle, p.boundary_tolerance, p.parallel_tolerance),
            foot.l8,
        )
        .map_err(|phi| {
            goal_err(GoalReason::Illegal {
                angle_deg: phi.to_degrees(),
                lateral_deg: (std::f64::consts::FRAC_PI_2 + p.region_angle / 2.0).to_degrees(),
            })
        })?;
        let g = [
            specs.foot_position[0] - stance.flat[0],
            specs.foot_position[1] - stance.flat[1],
        ];
        let distance = (g[0] * g[0] + g[1] * g[1]).sqrt();
        let min = 0.75 * state.attrs.step_width;
        if distance < min {
            return Err(goal_err(GoalReason::Overlap { distance, min }));
        }
        let d = direction(stance.heading);
        let length = (g[0] * d[0] + g[1] * d[1]).abs();
        let walking = if kind == StepType::Lateral {
            None
        } else {
            if length < state.attrs.step_length_min {
                return Err(goal_err(GoalReason::TooShort {
                    kind: kind.name(),
                    length,
                    min: state.attrs.step_length_min,
                }));
            }
            let request = GaitRequest {
                step_length: Some(length),
                step_frequency: duration.map(|t| 60.0 / t),
                velocity: None,
            };
            let gait = request.complete(&state.body, &state.attrs)?;
            Some(WalkingStep::simulate(
                state.body,
                &state.attrs,
                gait,
                p.table_intervals,
            )?)
        };
        let duration = match (duration, &walking) {
            (Some(t), _) => t,
            (None, Some(w)) => w.duration,
            (None, None) => {
                60.0 / GaitRequest::preferred(&state.body, &state.attrs)?.step_frequency
            }
        };
        InputError::check_range("duration", duration, p.duration_min, p.duration_max, "s")?;
        let angles = specs.foot_angles.unwrap_or(FootAngles {
            toe_off_swing: walking
                .as_ref()
                .map_or(p.lateral_toe_off_swing, |w| w.toe_off_pitch()),
            strike_swing: p.strike_swing,
            strike_stance: p.strike_stance,
        });
        let goal = Planted {
            flat: specs.foot_position,
            heading: specs.foot_direction,
            pitch: angles.strike_swing,
        };
        let mut plan = Plan {
            kind,
            stance: stance_side,
            goal,
            angles,
            walking,
            duration,
            swing_height: p.swing_height * specs.swing_height_factor,
            gaze_end: 0.0,
            upper_end: None,
            velocity_end: [0.0; 3],
        };
        // the gaze ends where the pelvis faces unless given
        let probe = build(
            state,
            &Plan {
                gaze_end: state.gaze(),
                ..plan.clone_shallow()
            },
        )?;
        let pelvis_end = probe.table.at(1.0)[3];
        plan.gaze_end = specs.gaze_direction.unwrap_or(pelvis_end);
        Self::from_plan(state, &plan)
    }

    /// The step of `plan` from `state`.
    pub(crate) fn from_plan(state: &WalkerState, plan: &Plan) -> Result<NrsStep, NrsError> {
        let segment = build(state, plan)?;
        let row = segment.table.at(1.0);
        let (upper, _, _) = segment.parts(&row, 1.0);
        let mut end = state.clone();
        end.time += plan.duration;
        end.step += 1;
        end.upper = upper;
        end.velocity = plan.velocity_end;
        let stance = plan.stance;
        let stance_foot = Planted {
            pitch: plan.angles.strike_stance,
            ..*state.foot(stance)
        };
        end.feet = match stance {
            Side::Right => [stance_foot, plan.goal],
            Side::Left => [plan.goal, stance_foot],
        };
        Ok(NrsStep {
            segment,
            kind: plan.kind,
            end,
        })
    }

    /// The figure at normalized time t ∈ [0, 1] (clamped).
    pub fn advance(&self, t: f64) -> Landmarks {
        self.segment
            .pose(t)
            .expect("every instant's reach is checked by initialize")
    }

    /// The step's type.
    pub fn kind(&self) -> StepType {
        self.kind
    }

    /// Its duration (s).
    pub fn duration(&self) -> f64 {
        self.segment.duration
    }

    /// The walker after the step.
    pub fn end_state(&self) -> &WalkerState {
        &self.end
    }
}

impl Plan {
    fn clone_shallow(&self) -> Plan {
        Plan {
            walking: self.walking.clone(),
            upper_end: self.upper_end,
            ..*self
        }
    }
}
