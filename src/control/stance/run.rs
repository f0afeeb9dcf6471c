//! One trial integration of a step's stance (KLAW 1989 §4.2, spec §4) under given magnitudes
//! (τ1, p), segment by segment between the force switches and the events, and its dense record.
use nalgebra::{Vector2, Vector3};

use crate::dynamics::impact;
use crate::numerics::ode::{self, IntegrationError, Segment};
use crate::numerics::roots;
use crate::numerics::trig::sin_cos;

use super::{StanceForces, StanceSetup, StanceState};

/// Clamp events (the leg force reaching or leaving 0) located per stance trial; after them the
/// clamp's kink is left to the step-size control.
const CLAMP_EVENTS: usize = 8;

/// The dense record of one stance trial.
#[derive(Clone, Debug)]
pub struct StanceRun {
    /// Leg torque magnitude τ1 of the trial (N m).
    pub tau1: f64,
    /// Leg extension p of the position actuator (m).
    pub p: f64,
    /// Integration segments with their subphase (`true` = locked leg).
    pub segments: Vec<(Segment<6>, bool)>,
    /// The trial stopped early (|θ1| > 60° or w < l1/2).
    pub aborted: bool,
    /// End-condition residual (θ1 − θ1*, w − w*) at the end (or where it stopped).
    pub residual: Vector2<f64>,
    /// Right-hand-side evaluations spent.
    pub evaluations: u32,
    /// Some integration step was chosen by the step-size control (no mesh was followed
    /// throughout).
    pub adapted: bool,
}

impl StanceRun {
    /// One trial integration of the stance from `y0` over [0, t_step] with magnitudes (τ1, p).
    pub fn simulate(
        setup: &StanceSetup,
        y0: StanceState,
        tau1: f64,
        p: f64,
    ) -> Result<Self, IntegrationError> {
        Self::simulate_with(setup, y0, tau1, p, ode::Tolerance::default())
    }

    /// [`Self::simulate`] at integrator tolerance `tol` (to measure the integration error).
    pub fn simulate_with(
        setup: &StanceSetup,
        y0: StanceState,
        tau1: f64,
        p: f64,
        tol: impl Into<ode::Tolerance>,
    ) -> Result<Self, IntegrationError> {
        let mut run = Self::simulate_on(setup, y0, tau1, p, tol.into(), None)?;
        run.evaluations += run.densify(setup);
        Ok(run)
    }

    /// [`Self::simulate_with`] on the step sequences of `mesh`, a previous trial of the same
    /// stance ([`ode::integrate_on`]): its i-th segment's steps for the i-th segment (from the
    /// same start time, or shifted when the segment starts at an event), when the subphases
    /// agree. The dense output is left out ([`ode::integrate_trial`]): [`Self::densify`] the
    /// trial that is kept.
    pub(crate) fn simulate_on(
        setup: &StanceSetup,
        y0: StanceState,
        tau1: f64,
        p: f64,
        tol: ode::Tolerance,
        mesh: Option<&StanceRun>,
    ) -> Result<Self, IntegrationError> {
        let breaks = [
            setup.torque_off * setup.t_step,
            0.5 * setup.t_step,
            setup.t_step,
        ];
        let mut run = StanceRun {
            tau1,
            p,
            // (five in a typical stance: the clamp, the torque's end, the blend, mid-stance)
            segments: Vec::with_capacity(8),
            aborted: false,
            residual: Vector2::zeros(),
            evaluations: 0,
            adapted: false,
        };
        let (mut t, mut y, mut locked, mut past_mid) = (0.0, y0, false, false);
        // the leg force's side of its clamp after a clamp event (else its sign where a segment
        // starts), and the clamp events so far: past CLAMP_EVENTS (a force grazing 0) the kink
        // is left to the step-size control
        let (mut flipped, mut clamp_events) = (None, 0);
        'outer: for t_break in breaks {
            while t < t_break {
                let mut forces = StanceForces::new(setup, tau1, p, locked)
                    .with_torque(t < setup.torque_off * setup.t_step);
                forces.past_mid = Some(past_mid);
                let loaded = flipped
                    .take()
                    .unwrap_or_else(|| forces.leg_force(t, &y) > 0.0);
                let forces = if clamp_events < CLAMP_EVENTS {
                    forces.with_loaded(loaded)
                } else {
                    forces
                };
                let follow = match mesh.and_then(|m| m.segments.get(run.segments.len())) {
                    Some((seg, l)) if *l == locked && seg.t0 == t => ode::Mesh::Aligned(seg),
                    Some((seg, l)) if *l == locked => ode::Mesh::Shifted(seg),
                    _ => ode::Mesh::Adaptive,
                };
                let out = ode::integrate_trial(&forces, t, y, t_break, tol, follow)?;
                run.evaluations += out.evaluations;
                run.adapted |= out.adapted;
                t = out.segment.t1;
                y = out.segment.y1;
                run.segments.push((out.segment, locked));
                match out.event {
                    None => {}
                    Some(0) if locked => (locked, past_mid) = (false, true),
                    Some(3) => {
                        flipped = Some(!loaded);
                        clamp_events += 1;
                    }
                    Some(4) => past_mid = true,
                    Some(0) => {
                        // the knee locks: a plastic impulse along the leg stops ẇ
                        let q = Vector3::new(y[0], y[1], y[2]);
                        let qd_minus = Vector3::new(y[3], y[4], y[5]);
                        let (qd, _) = impact::heel_strike(&setup.model, &q, &qd_minus, 1.0);
                        y = StanceState::from([y[0], y[1], y[2], 0.0, qd[1], qd[2]]);
                        locked = true;
                    }
                    Some(_) => {
                        run.aborted = true;
                        break 'outer;
                    }
                }
            }
        }
        run.residual = Vector2::new(y[1] - setup.theta1_end, y[0] - setup.w_end);
        Ok(run)
    }

    /// Complete the dense output of a [`Self::simulate_on`] trial ([`ode::Segment::densify`]);
    /// returns the right-hand-side evaluations.
    pub(crate) fn densify(&mut self, setup: &StanceSetup) -> u32 {
        let (tau1, p, t_off) = (self.tau1, self.p, setup.torque_off * setup.t_step);
        self.segments
            .iter_mut()
            .map(|(seg, locked)| {
                let forces = StanceForces::new(setup, tau1, p, *locked).with_torque(seg.t0 < t_off);
                seg.densify(|_| forces)
            })
            .sum()
    }

    /// The state and subphase at time t.
    pub(crate) fn state(&self, t: f64) -> (StanceState, bool) {
        let i = self
            .segments
            .partition_point(|(s, _)| s.t1 < t)
            .min(self.segments.len() - 1);
        let (seg, locked) = &self.segments[i];
        (seg.state(t), *locked)
    }

    /// The time of the hip reference's heel-off, where θ1 rises through θ_ho past mid-stance
    /// ([`TerminalStance`](super::TerminalStance)): the reference is C³ there, and the hip
    /// acceleration's third derivative jumps. `None` where heel-off is at mid-stance (already a
    /// segment boundary) or not reached.
    pub(crate) fn heel_off_time(&self, setup: &StanceSetup) -> Option<f64> {
        let sin_ho = setup.terminal.sin_heel_off;
        if sin_ho <= 0.0 {
            return None;
        }
        let theta_ho = sin_ho.asin();
        let (seg, _) = self
            .segments
            .iter()
            .find(|(seg, _)| seg.y0[1] < theta_ho && seg.y1[1] >= theta_ho)?;
        let g = |t: f64| seg.state(t)[1] - theta_ho;
        let (a, b) = roots::illinois(
            g,
            (seg.t0, seg.y0[1] - theta_ho),
            (seg.t1, seg.y1[1] - theta_ho),
            1e-13,
            60,
        );
        Some(0.5 * (a + b))
    }

    /// Hip position at t (relative to the stance ankle's x): [`Self::hip`]`[0]` without the
    /// dynamics.
    pub(crate) fn hip_position(&self, setup: &StanceSetup, t: f64) -> [f64; 2] {
        let (y, _) = self.state(t);
        setup.model.hip(&Vector3::new(y[0], y[1], y[2]))
    }

    /// The hip acceleration as a function of t: [`Self::hip`]`[2]` with the step's constants
    /// (the hip reference's sin θ1^±) computed once and one `sin_cos` of θ1 per call.
    pub(crate) fn hip_acceleration<'a>(
        &'a self,
        setup: &'a StanceSetup,
    ) -> impl Fn(f64) -> [f64; 2] + 'a {
        let forces =
            [false, true].map(|locked| StanceForces::new(setup, self.tau1, self.p, locked));
        move |t| {
            let (y, locked) = self.state(t);
            let q = Vector3::new(y[0], y[1], y[2]);
            let qd = Vector3::new(y[3], y[4], y[5]);
            let (s1, c1) = sin_cos(y[1]);
            let f = &forces[usize::from(locked)];
            let qdd = setup.model.accelerations_with(
                s1,
                c1,
                &q,
                &qd,
                &f.generalized_sc(t, &y, s1, c1),
                locked,
            );
            setup.model.hip_acceleration_with(s1, c1, &q, &qd, &qdd)
        }
    }

    /// Hip position, velocity and acceleration at t (relative to the stance ankle's x).
    pub fn hip(&self, setup: &StanceSetup, t: f64) -> [[f64; 2]; 3] {
        let (y, locked) = self.state(t);
        let q = Vector3::new(y[0], y[1], y[2]);
        let qd = Vector3::new(y[3], y[4], y[5]);
        let forces = StanceForces::new(setup, self.tau1, self.p, locked);
        let qdd = forces.accelerations(t, &y);
        let m = &setup.model;
        [
            m.hip(&q),
            m.hip_velocity(&q, &qd),
            m.hip_acceleration(&q, &qd, &qdd),
        ]
    }
}
