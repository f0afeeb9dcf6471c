//! What one step's stance keeps between shooting trials (KLAW 1989 §4.2, spec §4).
use crate::dynamics::StanceModel;

use super::TerminalStance;

/// Everything about one step's stance that does not change between shooting trials.
#[derive(Clone, Copy, Debug)]
pub struct StanceSetup {
    /// The stance model of the body.
    pub model: StanceModel,
    /// Leg length l1 (m).
    pub(crate) l1: f64,
    /// Leg axis spring and damper (N/m, N s/m).
    pub(crate) k_w: f64,
    pub(crate) d_w: f64,
    /// Balance spring and damper (N m/rad, N m s/rad) and the forward-lean reference (rad).
    pub(crate) k_2: f64,
    pub(crate) d_2: f64,
    pub(crate) theta2_ref: f64,
    /// The step's duration t_step (s).
    pub t_step: f64,
    /// The fraction of the step after which the leg torque τ1 is switched off (the engine's
    /// constant `torque_off`).
    pub torque_off: f64,
    /// |θ1| at the start of the step (the previous step's θ1*) and θ1* at its end.
    pub(crate) theta1_start: f64,
    pub(crate) theta1_end: f64,
    /// w* at the end of the step.
    pub(crate) w_end: f64,
    /// Hip height at the step's heel strike (m).
    pub y_start: f64,
    /// Hip height at the next heel strike, y_hs of the step's constraints (m).
    pub y_end: f64,
    /// Bounce e of the hip reference (m).
    pub(crate) bounce: f64,
    /// The virtual leg's reference from mid-stance on.
    pub(crate) terminal: TerminalStance,
}
