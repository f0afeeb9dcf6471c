//! What a walk produces besides its motion: per-frame records (the CSV rows) and the per-step
//! report (targets, achievements, shooting statistics). Plain data, serialized by `io`.
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
    pub time_s: f64,
    pub step: usize,
    /// `double_support`, `swing1`, `swing2` or `swing3` (the swing leg's subphase).
    pub phase: &'static str,
    /// `right` or `left`: the stance leg (step 0 stands on the right leg).
    pub stance_side: &'static str,
    /// `telescopic` or `locked`.
    pub stance_mode: &'static str,
    pub w_m: f64,
    pub theta1_deg: f64,
    pub theta2_deg: f64,
    pub theta3_deg: f64,
    pub theta4_deg: f64,
    pub hip_x_m: f64,
    pub hip_y_m: f64,
    pub stance_ankle_x_m: f64,
    pub stance_ankle_y_m: f64,
    pub swing_knee_x_m: f64,
    pub swing_knee_y_m: f64,
    pub swing_ankle_x_m: f64,
    pub swing_ankle_y_m: f64,
    pub swing_heel_x_m: f64,
    pub swing_heel_y_m: f64,
    pub swing_toe_x_m: f64,
    pub swing_toe_y_m: f64,
}

/// Target of a step (SI; step frequency in steps/min).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct Target {
    pub velocity: f64,
    pub step_length: f64,
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

/// One shooting solve in the report.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct SolveRecord {
    pub phase: &'static str,
    #[serde(flatten)]
    pub report: SolveReport,
}

/// The report of one step.
#[derive(Clone, Debug, Serialize)]
pub struct StepReport {
    pub index: usize,
    pub target: Target,
    pub achieved: Achieved,
    pub solves: Vec<SolveRecord>,
    /// Largest |end-condition error| of the step: θ1, w, θ3, θ4 at heel strike (rad or m).
    pub end_condition_error: f64,
    /// Height of the heel above the ground at heel strike (m).
    pub heel_height_at_strike: f64,
    /// Hip rise above its heel-strike height during the stance (m), and the reference e.
    pub hip_excursion: f64,
    pub bounce_reference: f64,
    /// Lowest hip height minus the lower heel-strike height (m; ≥ −1e-6 by invariant).
    pub hip_min_margin: f64,
    /// Hip speed after / before the heel strike.
    pub impact_speed_ratio: f64,
    /// Lowest point of the swing foot over the whole swing (m), and the lowest toe height in
    /// mid swing (25–75 %).
    pub min_foot_height: f64,
    pub min_toe_clearance: f64,
    /// Heel vertical velocity at contact (m/s, ≤ 0).
    pub heel_contact_velocity: f64,
    /// Largest knee flexion of the swing (rad).
    pub peak_swing_knee_flexion: f64,
    /// Right-hand-side evaluations of the step's dynamic models over all shooting trials.
    pub rhs_evaluations: u64,
    /// Mechanical work of the actuators over the step (J): positive (Σ over the actuators of
    /// ∫ max(power, 0) dt) and net (∫ Σ power dt); see `work`.
    pub positive_work: f64,
    pub net_work: f64,
}

impl StepReport {
    /// The report of step `index` before its measurements (`Step::measure`; NaN until then):
    /// its target, duration, bounce reference, impact and work.
    pub(super) fn unmeasured(
        index: usize,
        gait: &Gait,
        c: &StepConstraints,
        impact_speed_ratio: f64,
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
            min_foot_height: f64::NAN,
            min_toe_clearance: f64::NAN,
            heel_contact_velocity: f64::NAN,
            rhs_evaluations: 0,
            peak_swing_knee_flexion: f64::NAN,
            positive_work: work.positive,
            net_work: work.net,
        }
    }
}

/// The report of a walk.
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    pub height: f64,
    pub mass: f64,
    pub steps: Vec<StepReport>,
}
