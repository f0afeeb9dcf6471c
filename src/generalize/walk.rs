//! The kinematic walk mode: a prototype generalized to a body and a gait (a steady step,
//! [`steady`]) and repeated, each step mirrored onto the other leg, as the whole figure at any
//! time, the gait events and the engine-state rows of `klaw walk`.
use crate::analysis::events::Event;
use crate::engine::report::StateFrame;
use crate::engine::step::last_frame;
use crate::engine::walker::walk_attributes;
use crate::figure::{Landmarks, LegPoints};
use crate::generalize::condition::BodyCondition;
use crate::generalize::error::GeneralizeError;
use crate::generalize::extract::knee_flexion;
use crate::generalize::geometry::Pelvis;
use crate::generalize::parameters::GeneralizeParameters;
use crate::generalize::pose::StepPose;
use crate::generalize::transform::steady;
use crate::generalize::walk_data::WalkData;
use crate::kinematics::pelvis::Side;
use crate::model::attributes::Attributes;
use crate::model::body::Body;
use crate::plan::Gait;

/// The frames of a walk of `duration` s at `fps` (t = 0 to the last heel strike, inclusive).
pub fn frame_count(duration: f64, fps: f64) -> usize {
    last_frame(duration, fps) + 1
}

/// A walk of `steps` steady generalized steps of one gait.
#[derive(Clone, Debug)]
pub struct KinematicWalk {
    /// The generalized step and how it is posed.
    pub step: StepPose,
    /// The gait of every step.
    pub gait: Gait,
    /// The number of steps.
    pub steps: usize,
    /// The most the hip comes down from H to let the legs reach (m).
    pub hip_drop: f64,
}

impl KinematicWalk {
    /// `prototype` generalized to `body` at the step length of `gait` (the step before as
    /// long), lasting 60 / sf s, with the pelvis of the engine's walk at that gait
    /// ([`walk_attributes`]), checked at `params.check_samples` instants of either leg's step
    /// (no leg stretched, no foot under the floor, no swing foot sliding on it) before anything
    /// is walked.
    pub fn new(
        prototype: &WalkData,
        body: Body,
        attrs: Attributes,
        gait: Gait,
        steps: usize,
        params: &GeneralizeParameters,
    ) -> Result<Self, GeneralizeError> {
        prototype.check()?;
        let attrs = walk_attributes(&body, &attrs, &[gait]);
        let pelvis = Pelvis {
            rotation: attrs.pelvic_rotation,
            step_width: attrs.step_width,
        };
        let condition = BodyCondition::of(&body);
        let posed = |sl: f64| -> Result<(StepPose, f64), GeneralizeError> {
            let data = steady(prototype, &condition, &pelvis, sl)?;
            let step = StepPose::new(data, body, attrs.clone(), 60.0 / gait.step_frequency)?;
            let drop = step.check(params)?;
            if drop > params.hip_drop_max {
                return Err(GeneralizeError::HipDrop {
                    drop,
                    max: params.hip_drop_max,
                });
            }
            Ok((step, drop))
        };
        let sl = gait.step_length;
        match posed(sl) {
            Ok((step, hip_drop)) => Ok(KinematicWalk {
                step,
                gait,
                steps,
                hip_drop,
            }),
            Err(e) => Err(limit(e, sl, prototype, &condition, &|s| posed(s).is_ok())),
        }
    }

    /// The walk's duration (s): heel strike to heel strike, `steps` times.
    pub fn duration(&self) -> f64 {
        self.steps as f64 * self.step.duration
    }

    /// The step `time` falls in and the normalized time in it (the last step's end is its 1).
    fn locate(&self, time: f64) -> (usize, f64) {
        let x = time.max(0.0) / self.step.duration;
        let k = (x.floor() as usize).min(self.steps - 1);
        (k, (x - k as f64).min(1.0))
    }

    /// The figure at `time` (s, clamped to the walk).
    pub fn figure_at(&self, time: f64) -> Result<Landmarks, GeneralizeError> {
        let (k, t) = self.locate(time);
        let n = k as f64 * self.step.data.step_length;
        self.step.figure(k, Side::of_step(k), n, t, time)
    }

    /// The figure at `fps` frames per second from t = 0 to the last heel strike (inclusive),
    /// as `klaw walk` samples it.
    pub fn frames(
        &self,
        fps: f64,
    ) -> impl Iterator<Item = Result<Landmarks, GeneralizeError>> + '_ {
        (0..=last_frame(self.duration(), fps)).map(move |i| self.figure_at(i as f64 / fps))
    }

    /// The heel strikes of the right foot (the starts of the even steps).
    pub fn right_heel_strikes(&self) -> Vec<f64> {
        (0..self.steps)
            .step_by(2)
            .map(|k| k as f64 * self.step.duration)
            .collect()
    }

    /// Every gait event of the stance feet of the walk's steps, in time order: heel strike,
    /// foot flat (FGM), heel-off (F2 leaves 0), meta-off (MOM) and toe-off (1 + TOM), those
    /// after the walk's end left out (as `klaw walk` does).
    pub fn events(&self) -> Vec<Event> {
        let w = &self.step.data;
        let p = w.phases;
        let moments = [
            ("HS", Some(0.0)),
            ("FGM", Some(p.fgm)),
            ("heel_off", Some(p.heel_off)),
            ("MOM", (p.mom < 1.0 + p.tom).then_some(p.mom)),
            ("TO", Some(1.0 + p.tom)),
        ];
        let end = self.duration() + 1e-9;
        let mut out: Vec<Event> = (0..self.steps)
            .flat_map(|k| {
                let t0 = k as f64 * self.step.duration;
                moments.iter().filter_map(move |(event, at)| {
                    let time_s = t0 + (*at)? * self.step.duration;
                    (time_s <= end).then_some(Event {
                        time_s,
                        side: Side::of_step(k).name(),
                        event,
                        step: k,
                    })
                })
            })
            .collect();
        out.sort_by(|a, b| a.time_s.total_cmp(&b.time_s));
        out
    }

    /// The engine-state row of `klaw walk --state-out` for the figure `lm`: the telescopic
    /// stance leg from the stance foot's flat ankle to the pelvis centre (w, θ1), the upper body
    /// θ2 (the trunk sequence plus the lean), the swing (in double support the hind) leg's thigh
    /// angle θ3, knee flexion θ4 and points; `stance_mode` is `kinematic`, `phase`
    /// `double_support` or `swing`.
    pub fn state_frame(&self, lm: &Landmarks) -> StateFrame {
        let (k, t) = self.locate(lm.time);
        let side = Side::of_step(k);
        let w = &self.step.data;
        let pivot = [k as f64 * w.step_length, w.body.ankle_to_n];
        let swing: LegPoints = match side {
            Side::Right => lm.left,
            Side::Left => lm.right,
        };
        let (dx, dy) = (lm.pelvis[0] - pivot[0], lm.pelvis[1] - pivot[1]);
        StateFrame {
            time_s: lm.time,
            step: k,
            phase: if t < w.phases.tom {
                "double_support"
            } else {
                "swing"
            },
            stance_side: side.name(),
            stance_mode: "kinematic",
            w_m: dx.hypot(dy),
            theta1_deg: dx.atan2(dy).to_degrees(),
            theta2_deg: (w.trunk.at(t) + self.step.attrs.trunk_lean).to_degrees(),
            theta3_deg: -crate::figure::landmarks::thigh_angle(&swing).to_degrees(),
            theta4_deg: knee_flexion(&swing).to_degrees(),
            hip_x_m: lm.pelvis[0],
            hip_y_m: lm.pelvis[1],
            stance_ankle_x_m: pivot[0],
            stance_ankle_y_m: pivot[1],
            swing_knee_x_m: swing.knee[0],
            swing_knee_y_m: swing.knee[1],
            swing_ankle_x_m: swing.ankle[0],
            swing_ankle_y_m: swing.ankle[1],
            swing_heel_x_m: swing.heel[0],
            swing_heel_y_m: swing.heel[1],
            swing_toe_x_m: swing.toe[0],
            swing_toe_y_m: swing.toe[1],
        }
    }
}

/// A walk that fails at step length `sl` as the step too long or too short, with the longest or
/// shortest step length that works (to 1 mm) between `sl` and the prototype's own step in this
/// body's leg lengths (the error as it is when that fails too, or for an error of the data).
fn limit(
    e: GeneralizeError,
    sl: f64,
    prototype: &WalkData,
    body: &BodyCondition,
    works: &dyn Fn(f64) -> bool,
) -> GeneralizeError {
    use GeneralizeError::{BelowFloor, HipDrop, Stretched, TooLong, TooShort};
    if !matches!(
        e,
        TooLong { .. } | Stretched { .. } | BelowFloor { .. } | HipDrop { .. }
    ) {
        return e;
    }
    let own = prototype.character.step_length * body.leg_length();
    if !works(own) {
        return e;
    }
    let limit = crate::numerics::roots::bisect(works, own, sl, 1e-3).0;
    let (leg_length, reason) = (body.leg_length(), e.to_string());
    if sl > own {
        TooLong {
            step_length: sl,
            leg_length,
            limit,
            reason,
        }
    } else {
        TooShort {
            step_length: sl,
            leg_length,
            limit,
            reason,
        }
    }
}
