//! What a walk produces besides its motion: per-frame records (the CSV rows) and the per-step
//! report (targets, achievements, shooting statistics; spec §9). Plain data, written by
//! `export::state` (CSV) and `export::report` (JSON); docs/export.md describes both files.
use serde::Serialize;

use crate::control::shooting::SolveReport;
use crate::engine::work::Work;
use crate::plan::StepConstraints;
use crate::plan::gait::Gait;

/// The engine's state at one output frame: the stance's degrees of freedom, the swing leg's
/// angles and the points of both legs. Field names are the CSV header; positions are world
/// coordinates (x forward from the first stance ankle, y up from the ground), angles in degrees.
#[derive(Clone, Debug, Default, Serialize)]
pub struct StateFrame {
    /// Time since the first heel strike (s).
    pub time_s: f64,
    /// Index of the step the frame falls in (0-based; a step runs from one heel strike to the
    /// next).
    pub step: usize,
    /// `double_support`, `swing1`, `swing2` or `swing3` (the swing leg's subphase).
    pub phase: &'static str,
    /// `right` or `left`: the stance leg (step 0 stands on the right leg).
    pub stance_side: &'static str,
    /// `telescopic` or `locked`.
    pub stance_mode: &'static str,
    /// w: the telescopic stance leg's length, ankle pivot to hip (m; spec §1, §4).
    pub w_m: f64,
    /// θ1: the stance leg from the upward vertical through the ankle pivot, + with the hip ahead
    /// of the ankle (deg; spec §1).
    pub theta1_deg: f64,
    /// θ2: the upper body from the upward vertical, + leaning forward (deg; spec §1).
    pub theta2_deg: f64,
    /// θ3: the swing thigh from the downward vertical through the hip, − with the knee ahead of
    /// the hip (deg; spec §1); in double support the hind leg's.
    pub theta3_deg: f64,
    /// θ4: the swing knee's flexion, thigh to shank (deg; spec §1); in double support the hind
    /// leg's.
    pub theta4_deg: f64,
    /// The dynamic hip, the pelvis centre C (m; spec §7).
    pub hip_x_m: f64,
    /// Height of the dynamic hip (m).
    pub hip_y_m: f64,
    /// The stance ankle pivot (m).
    pub stance_ankle_x_m: f64,
    /// Height of the stance ankle pivot: the ankle height l9 of the flat foot (m).
    pub stance_ankle_y_m: f64,
    /// The swing knee, in double support the hind leg's (m).
    pub swing_knee_x_m: f64,
    /// Height of the swing knee (m).
    pub swing_knee_y_m: f64,
    /// The swing ankle, in double support the hind leg's (m).
    pub swing_ankle_x_m: f64,
    /// Height of the swing ankle (m).
    pub swing_ankle_y_m: f64,
    /// The swing foot's heel, in double support the hind foot's (m).
    pub swing_heel_x_m: f64,
    /// Height of the swing heel (m).
    pub swing_heel_y_m: f64,
    /// The swing foot's toe tip, in double support the hind foot's (m).
    pub swing_toe_x_m: f64,
    /// Height of the swing toe tip (m).
    pub swing_toe_y_m: f64,
}

/// Target of a step: its gait, completed by the normalizing formula (KLAW 1989 eq. 1).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Target {
    /// Walking speed v (m/s).
    pub velocity: f64,
    /// Step length sl (m).
    pub step_length: f64,
    /// Step frequency sf (steps/min).
    pub step_frequency: f64,
}

/// What a step achieved.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Achieved {
    /// step_length / duration (m/s).
    pub velocity: f64,
    /// Heel landing + l8: flat-foot ankle to flat-foot ankle (m).
    pub step_length: f64,
    /// Heel strike to heel strike (s).
    pub duration: f64,
}

/// One shooting solve in the report (KLAW 1989 §4.1, spec §6).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct SolveRecord {
    /// The solved phase: `stance`, `swing1`, `swing2` or `swing3`.
    pub phase: &'static str,
    /// Its trial integrations (`iterations`, count), the max-norm of the end-condition residual
    /// (`residual`, rad, m or m/s as the phase's end conditions) and `converged`; flattened into
    /// the record in the JSON.
    #[serde(flatten)]
    pub report: SolveReport,
}

/// The report of one step.
#[derive(Clone, Debug, Serialize)]
pub struct StepReport {
    /// Index of the step (0-based; step 0 stands on the right leg).
    pub index: usize,
    /// The gait the step was asked for.
    pub target: Target,
    /// What the step achieved.
    pub achieved: Achieved,
    /// The step's shooting solves, in order: stance, swing1, swing2, swing3.
    pub solves: Vec<SolveRecord>,
    /// Largest |end-condition error| of the step: θ1, w, θ3, θ4 at heel strike (rad or m).
    pub end_condition_error: f64,
    /// Height of the heel above the ground at heel strike (m).
    pub heel_height_at_strike: f64,
    /// Rise of the hip during the step above its height at the step's closing heel strike (m;
    /// spec §4).
    pub hip_excursion: f64,
    /// The hip height reference's bounce e = min(εE, g t_step² / 4π²) (m; spec §4).
    pub bounce_reference: f64,
    /// Lowest hip height minus the lower heel-strike height (m; ≥ −1e-6 by invariant).
    pub hip_min_margin: f64,
    /// Hip speed after / before the heel strike that starts the step (1; spec §7).
    pub impact_speed_ratio: f64,
    /// The fraction of the new leg's axial velocity that heel strike removed (1): the attribute
    /// heel_strike_impulse, or more where the loading response would have let the hip sink
    /// under its heel-strike height (`Walker::step`).
    pub impact_fraction: f64,
    /// The pelvic list amplitude the step walked with (rad; in degrees in the JSON, as
    /// `pelvic_list_deg`): the walk's attribute at its speed, or less where a step could not
    /// walk it (`Walker::step`).
    #[serde(rename = "pelvic_list_deg", serialize_with = "degrees")]
    pub pelvic_list: f64,
    /// Height of the swing foot's lowest point over the whole swing (m; ≥ −1e-6 by invariant,
    /// spec §5).
    pub min_foot_height: f64,
    /// Height of the swing foot's lowest point in mid swing, 25–75 % of the swing (m; > 1e-6 by
    /// invariant).
    pub min_toe_clearance: f64,
    /// Heel vertical velocity at contact (m/s, ≤ 0).
    pub heel_contact_velocity: f64,
    /// Largest knee flexion of the swing (rad; in degrees in the JSON, as
    /// `peak_swing_knee_flexion_deg`, like every joint angle the user sees).
    #[serde(rename = "peak_swing_knee_flexion_deg", serialize_with = "degrees")]
    pub peak_swing_knee_flexion: f64,
    /// Right-hand-side evaluations of the step's dynamic models over all its shooting trials
    /// (count).
    pub rhs_evaluations: u64,
    /// Positive mechanical work of the actuators over the step: Σ over the actuators of
    /// ∫ max(power, 0) dt (J; `engine::work`).
    pub positive_work: f64,
    /// Net mechanical work of the actuators over the step: ∫ Σ power dt (J).
    pub net_work: f64,
    /// The walker's fallbacks this step walked with (`Walker::step`): how far each had to
    /// change the plan, its own tries and those the earlier steps kept. All 0: the plan walked
    /// as made.
    pub repairs: Repairs,
}

/// The fallbacks a step walked with, each in its own unit of change (counts).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Repairs {
    /// Raises of the heel-strike impulse (the loading response let the hip sink under y_hs).
    pub impulse: u32,
    /// `reach_margin_step`s added to the bounce's reach margin (the flat foot out of reach).
    pub reach: u32,
    /// `toe_off_knee_step`s taken off the toe-off knee (the hind foot out of the hip's reach).
    pub toe_off_knee: u32,
    /// Tenths (1 / `list_retries`) of the pelvic list left out.
    pub list: u32,
}

impl Repairs {
    /// Whether any fallback changed the step's plan.
    pub fn any(&self) -> bool {
        *self != Repairs::default()
    }
}

impl StepReport {
    /// The report of step `index` before its measurements (`Step::measure`; NaN until then):
    /// its target, duration, bounce reference, impact, pelvic list and work.
    pub(super) fn unmeasured(
        index: usize,
        gait: &Gait,
        c: &StepConstraints,
        (impact_speed_ratio, impact_fraction): (f64, f64),
        pelvic_list: f64,
        work: Work,
    ) -> Self {
        StepReport {
            index,
            target: Target {
                velocity: gait.velocity,
                step_length: gait.step_length,
                step_frequency: gait.step_frequency,
            },
            achieved: Achieved {
                velocity: f64::NAN,
                step_length: f64::NAN,
                duration: c.timing.t_step,
            },
            solves: Vec::new(),
            end_condition_error: f64::NAN,
            heel_height_at_strike: f64::NAN,
            hip_excursion: f64::NAN,
            bounce_reference: c.bounce,
            hip_min_margin: f64::NAN,
            impact_speed_ratio,
            impact_fraction,
            pelvic_list,
            min_foot_height: f64::NAN,
            min_toe_clearance: f64::NAN,
            heel_contact_velocity: f64::NAN,
            rhs_evaluations: 0,
            peak_swing_knee_flexion: f64::NAN,
            positive_work: work.positive,
            net_work: work.net,
            repairs: Repairs::default(),
        }
    }
}

/// The report of a walk.
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    /// Body height H (m).
    pub height: f64,
    /// Body mass M (kg).
    pub mass: f64,
    /// One report per step, in order.
    pub steps: Vec<StepReport>,
}

/// Serialize an angle given in radians as degrees.
fn degrees<S: serde::Serializer>(radians: &f64, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_f64(radians.to_degrees())
}
