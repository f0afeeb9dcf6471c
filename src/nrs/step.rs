//! An NRS⁻, a forward, backward or lateral step (Ko & Badler 1993 §5): [`NrsStep::initialize`]
//! classifies the goal (§4), checks it, borrows the walking step of the same length from the
//! engine and tabulates every trajectory over normalized time; [`NrsStep::advance`] poses the
//! figure at t ∈ [0, 1] from the tables in constant time without allocating.
use crate::figure::Landmarks;
use crate::kinematics::foot::Foot;
use crate::model::InputError;
use crate::nrs::build::{Clock, Height, Plan, build};
use crate::nrs::pose::{Planted, direction};
use crate::nrs::range::largest_dorsiflexion;
use crate::nrs::segment::Segment;
use crate::nrs::specs::{FootAngles, Side, StepSpecs, StepType};
use crate::nrs::state::WalkerState;
use crate::nrs::walking::WalkingStep;
use crate::nrs::{GoalReason, NrsError};
use crate::plan::GaitRequest;
use crate::plan::gait::NORMALIZING_CONSTANT;

pub use crate::nrs::region::classify;

/// [ours] The step frequency (steps/min) of the walking step a step of `length` m borrows when
/// no duration is given: the normalizing formula's, sf = sl / (0.004 k H) (KLAW 1989 eq. 1,
/// k the attribute `stride_factor`), moved into the engine's ranges — the speed sl · sf / 60
/// within [velocity_min, velocity_limit] (velocity_max or the body's walk–run transition,
/// [`crate::plan::gait::velocity_limit`]) and sf within [step_frequency_min, step_frequency_max].
/// Short steps thus borrow the engine's slowest walk of their length rather than one it refuses
/// (docs/nrs.md); where the ranges do not meet, the formula's and the engine's error.
fn walking_frequency(state: &WalkerState, length: f64) -> f64 {
    let a = &state.attrs;
    let formula = length / (NORMALIZING_CONSTANT * a.stride_factor * state.body.height);
    let lo = a.step_frequency_min.max(60.0 * a.velocity_min / length);
    let v_max = crate::plan::gait::velocity_limit(&state.body, a);
    let hi = a.step_frequency_max.min(60.0 * v_max / length);
    if lo <= hi {
        formula.clamp(lo, hi)
    } else {
        formula
    }
}

/// [ours] θ_foot's defaults at HSM⁺ for the hind foot (docs/nrs.md): a backward step's swing
/// foot lands flat, and a forward step's stance foot ends flat, unless its ankle would then
/// dorsiflex beyond `ankle_dorsiflexion_max` (at the landing; at HSM⁺ for the stance foot);
/// then the heel is raised (the swing foot lands toe first) by the excess, and again with the
/// rebuilt step (the pelvis and knee follow the foot), up to 8 times, keeping the best whole
/// step (its largest dorsiflexion of that foot).
fn fit_hind_pitch(state: &WalkerState, plan: &mut Plan) -> Result<(), NrsError> {
    let max = state.params.ankle_dorsiflexion_max;
    let n = state.params.table_intervals;
    let backward = plan.kind == StepType::Backward;
    let hind = if backward {
        plan.stance.other()
    } else {
        plan.stance
    };
    let pitch_of = |plan: &Plan| {
        if backward {
            plan.angles.strike_swing
        } else {
            plan.angles.strike_stance
        }
    };
    let mut best = (f64::INFINITY, pitch_of(plan));
    for k in 0..8 {
        let seg = match build(state, plan) {
            Ok(seg) => seg,
            Err(e) if k == 0 => return Err(e),
            Err(_) => break,
        };
        let whole = largest_dorsiflexion(&seg, hind, (0..=n).map(|i| i as f64 / n as f64));
        // the landing foot's excess over the whole step: its heel up at the landing also
        // tilts it in the air before, where its toe tip may already rest on the floor
        let worst = if backward {
            whole
        } else {
            largest_dorsiflexion(&seg, hind, std::iter::once(1.0))
        };
        let pitch = pitch_of(plan);
        if whole < best.0 {
            best = (whole, pitch);
        }
        if worst <= max {
            break;
        }
        set_hind_pitch(plan, backward, pitch + (worst - max));
    }
    set_hind_pitch(plan, backward, best.1);
    Ok(())
}

fn set_hind_pitch(plan: &mut Plan, backward: bool, pitch: f64) {
    if backward {
        plan.angles.strike_swing = pitch;
        plan.goal.pitch = pitch;
    } else {
        plan.angles.strike_stance = pitch;
    }
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
        if let Some(t) = duration {
            InputError::check_range("duration", t, p.duration_min, p.duration_max, "s")?;
        }
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
            // the engine's shortest step: the attribute is a fraction of the leg length l1
            let min = (state.attrs.step_length_min * state.body.l1 * 1e4).round() / 1e4;
            if length < min {
                return Err(goal_err(GoalReason::TooShort {
                    kind: kind.name(),
                    length,
                    min,
                }));
            }
            let request = GaitRequest {
                step_length: Some(length),
                step_frequency: Some(
                    duration.map_or_else(|| walking_frequency(state, length), |t| 60.0 / t),
                ),
                velocity: None,
            };
            let gait = request.complete(&state.body, &state.attrs)?;
            Some(WalkingStep::borrowed(
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
            height: Height::Rules,
            toe_off: None,
            heading_clock: Clock::WHOLE,
            gaze_clock: Clock::WHOLE,
        };
        if specs.foot_angles.is_none() && kind != StepType::Lateral {
            fit_hind_pitch(state, &mut plan)?;
        }
        // the gaze ends where the pelvis faces unless given
        let probe = build(
            state,
            &Plan {
                gaze_end: state.gaze(),
                ..plan.clone()
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

    /// The stepping leg.
    pub fn side(&self) -> Side {
        self.segment.stance.other()
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::attributes::AttributeTable;
    use crate::model::body::Body;

    fn standing(height: f64) -> WalkerState {
        let body = Body::standard(height, 60.0).unwrap();
        WalkerState::standing(body, AttributeTable::builtin().defaults(), [0.0, 0.0], 0.0)
    }

    /// Hand computation (1.6 m, k = 1, v_min 0.4 m/s, sf in [50, 182]): a 0.6 m step keeps the
    /// formula's sf = 0.6 / (0.004 · 1.6) = 93.75 steps/min (0.9375 m/s); a 0.32 m step's
    /// formula gives 50 steps/min, 0.267 m/s, so it takes the slowest speed's 60 · 0.4 / 0.32 =
    /// 75 steps/min; a 0.2 m step 120.
    #[test]
    fn the_walking_frequency_stays_in_the_engines_ranges() {
        let s = standing(1.6);
        assert!((walking_frequency(&s, 0.6) - 93.75).abs() < 1e-9);
        assert!((walking_frequency(&s, 0.32) - 75.0).abs() < 1e-9);
        assert!((walking_frequency(&s, 0.2) - 120.0).abs() < 1e-9);
    }

    /// The shortest forward step is the engine's, step_length_min (0.2) · l1 in metres: just
    /// below it a typed error naming that length, just above it not that error.
    #[test]
    fn the_minimum_step_length_is_in_metres() {
        let s = standing(1.6);
        let min = 0.2 * s.body.l1;
        let start = s.foot(Side::Right).flat;
        let step = |l: f64| {
            let specs = StepSpecs {
                foot_position: [start[0] + l, start[1]],
                foot_direction: 0.0,
                side: Side::Right,
                swing_height_factor: 1.0,
                gaze_direction: None,
                foot_angles: None,
            };
            NrsStep::initialize(&s, &specs, None)
        };
        match step(min - 0.002) {
            Err(NrsError::Goal {
                reason: GoalReason::TooShort { min: m, .. },
                ..
            }) => assert!((m - min).abs() < 1e-4, "{m} vs {min}"),
            other => panic!("{other:?}"),
        }
        assert!(!matches!(
            step(min + 0.002),
            Err(NrsError::Goal {
                reason: GoalReason::TooShort { .. },
                ..
            })
        ));
    }
}
