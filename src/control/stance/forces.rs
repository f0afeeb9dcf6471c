//! The stance forces (KLAW 1989 §4.2, spec §4): the leg torque step τ1, the balance torque on the
//! upper body, the leg axis force with its position actuator; the right-hand side of the stance
//! model under them and its events.
use nalgebra::Vector3;
use std::f64::consts::PI;

use crate::numerics::ode::Phase;
use crate::numerics::smooth::smoothstep;
use crate::numerics::trig::sin_cos;

use super::reference::hip_reference_sc;
use super::{StanceSetup, StanceState};

/// A trial stops when |θ1| exceeds this (rad): the residual of a wild guess (spec §4).
pub const THETA1_ABORT: f64 = PI / 3.0;

/// The forces of one stance trial (KLAW 1989 §4.2, spec §4): the unknown magnitudes (τ1, p) and
/// the subphase.
#[derive(Clone, Copy, Debug)]
pub struct StanceForces<'a> {
    pub(crate) setup: &'a StanceSetup,
    /// Leg torque magnitude τ1 (N m), on for t < 0.4 t_step.
    pub(crate) tau1: f64,
    /// Leg extension p (m) of the position actuator, blended in over the second half-step.
    pub(crate) p: f64,
    pub(crate) locked: bool,
    /// In an integration segment: whether it runs after mid-stance (event 4 has fired), which
    /// picks the hip reference's side; `None`: by the sign of θ1, and no mid-stance event.
    pub(crate) past_mid: Option<bool>,
    /// The leg torque on or off whatever t ([`Self::with_torque`]); `None`: on for
    /// t < 0.4 t_step.
    torque: Option<bool>,
    /// Which side of its clamp at 0 the leg force F_w starts on in this integration segment
    /// ([`Self::with_loaded`]; the clamp event fires when it leaves it); `None`: no clamp event.
    loaded: Option<bool>,
    /// 1 / sin θ1^− of the hip reference's bounce (a constant of the step).
    inv_sin_start: f64,
}

impl<'a> StanceForces<'a> {
    /// The forces of a trial with magnitudes τ1 (N m) and p (m), on the telescopic leg or, when
    /// `locked`, the locked one (spec §4 subphases); the leg torque by its switch-off time, the
    /// hip reference's side by the sign of θ1, no clamp event.
    pub fn new(setup: &'a StanceSetup, tau1: f64, p: f64, locked: bool) -> Self {
        StanceForces {
            setup,
            tau1,
            p,
            locked,
            past_mid: None,
            torque: None,
            loaded: None,
            inv_sin_start: 1.0 / setup.theta1_start.sin(),
        }
    }

    /// The same forces with the leg torque on (or off) at every t: an integration segment lies
    /// on one side of the switch at 0.4 t_step, and the stages at its end, t = 0.4 t_step, must
    /// see the segment's torque (its limit from inside), not the value past the switch (with
    /// which the step fails its error test, shrinks and keeps an error).
    pub(crate) fn with_torque(mut self, on: bool) -> Self {
        self.torque = Some(on);
        self
    }

    /// The same forces in an integration segment that starts with the leg force F_w positive
    /// (`loaded`) or clamped at 0: F_w is that side's (the servo's force, or 0) throughout, and
    /// the clamp event (event 3) fires where the servo's force changes sign, so that no
    /// integrator step straddles the clamp's kink (after the heel strike the unloaded leg's
    /// servo pulls, and F_w is 0 for the first ≈ 60 ms). The step in which the event fires
    /// continues that side's force smoothly past the crossing, where the event is located.
    pub(crate) fn with_loaded(mut self, loaded: bool) -> Self {
        self.loaded = Some(loaded);
        self
    }

    /// The leg force F_w at (t, y) before its clamp at 0 (telescopic subphase).
    pub fn leg_force(&self, t: f64, y: &StanceState) -> f64 {
        let (s1, c1) = sin_cos(y[1]);
        self.leg_force_sc(t, y, s1, c1)
    }

    /// [`Self::leg_force`] with sin θ1, cos θ1 known.
    #[inline(always)]
    fn leg_force_sc(&self, t: f64, y: &StanceState, s1: f64, c1: f64) -> f64 {
        let s = self.setup;
        let (w, wd, th1d) = (y[0], y[3], y[4]);
        // pa = w_ref − l1 + (m2 g cos θ1 + d_w ẇ_ref)/k_w + p s(t), F_w = k_w (l1 + pa − w) − d_w ẇ ≥ 0
        let terminal = self.past_mid.unwrap_or(s1 >= 0.0);
        let (y_ref, dy_ref) = hip_reference_sc(s, s1, c1, self.inv_sin_start, terminal);
        // w_ref = (y_ref − l9) / cos θ1, dw_ref/dθ1 = (dy_ref + w_ref sin θ1) / cos θ1
        let inv_c1 = 1.0 / c1;
        let w_ref = (y_ref - s.model.l9) * inv_c1;
        let dw_ref = (dy_ref + w_ref * s1) * inv_c1;
        let wd_ref = dw_ref * th1d;
        let blend = smoothstep((t - 0.5 * s.t_step) / (0.5 * s.t_step));
        s.k_w * (w_ref - w + self.p * blend) + s.model.m2 * s.model.g * c1 + s.d_w * (wd_ref - wd)
    }

    /// Generalized forces Q = (F_w, F_θ1 − F_θ2, F_θ2) at (t, y).
    pub(crate) fn generalized(&self, t: f64, y: &StanceState) -> Vector3<f64> {
        let (s1, c1) = sin_cos(y[1]);
        self.generalized_sc(t, y, s1, c1)
    }

    /// [`Self::generalized`] with sin θ1, cos θ1 known.
    #[inline(always)]
    pub(super) fn generalized_sc(&self, t: f64, y: &StanceState, s1: f64, c1: f64) -> Vector3<f64> {
        let s = self.setup;
        let (th2, th2d) = (y[2], y[5]);
        let f2 = -s.k_2 * (th2 - s.theta2_ref) - s.d_2 * th2d;
        let f1 = if self.torque.unwrap_or(t < s.torque_off * s.t_step) {
            self.tau1
        } else {
            0.0
        };
        // in a segment on one side of the clamp, that side's force continued smoothly past the
        // crossing (the integrator's steps see no kink; the event ends the segment there)
        let fw = match (self.locked, self.loaded) {
            (true, _) | (false, Some(false)) => 0.0,
            (false, Some(true)) => self.leg_force_sc(t, y, s1, c1),
            (false, None) => self.leg_force_sc(t, y, s1, c1).max(0.0),
        };
        Vector3::new(fw, f1 - f2, f2)
    }

    /// q̈ at (t, y).
    pub(crate) fn accelerations(&self, t: f64, y: &StanceState) -> Vector3<f64> {
        let q = Vector3::new(y[0], y[1], y[2]);
        let qd = Vector3::new(y[3], y[4], y[5]);
        let (s1, c1) = sin_cos(y[1]);
        self.setup.model.accelerations_with(
            s1,
            c1,
            &q,
            &qd,
            &self.generalized_sc(t, y, s1, c1),
            self.locked,
        )
    }
}

/// Events: 0 lock / release, 1 |θ1| too large, 2 leg collapsed, 3 the leg force's clamp engages
/// or lets go (`StanceForces::with_loaded`), 4 mid-stance (θ1 rising through 0, where the hip
/// reference changes from the bounce to the virtual leg and its curvature jumps: the
/// integration and the hip table break there).
impl Phase<6, 5> for StanceForces<'_> {
    fn rhs(&self, t: f64, y: &StanceState) -> StanceState {
        let a = self.accelerations(t, y);
        StanceState::from([y[3], y[4], y[5], a[0], a[1], a[2]])
    }

    fn events(&self, t: f64, y: &StanceState) -> [f64; 5] {
        let (w, th1) = (y[0], y[1]);
        let switch = if self.locked {
            -th1 // release when the leg passes the vertical
        } else if th1 < 0.0 {
            self.setup.l1 - w // lock when w crosses l1 upward while θ1 < 0
        } else {
            1.0
        };
        let clamp = match (self.locked, self.loaded) {
            (false, Some(true)) => self.leg_force(t, y),
            (false, Some(false)) => -self.leg_force(t, y),
            _ => 1.0,
        };
        let mid = if !self.locked && self.past_mid == Some(false) {
            -th1
        } else {
            1.0
        };
        [
            switch,
            THETA1_ABORT - th1.abs(),
            w - 0.5 * self.setup.l1,
            clamp,
            mid,
        ]
    }
}
