//! Stance control (KLAW 1989 §4.2, spec §4): the forces of the telescopic stance model — the leg
//! torque step τ1, the upper-body balance torque, the leg axis force with its position actuator
//! pa — the telescopic / locked subphases, and one trial integration of a step's stance.
use nalgebra::{SVector, Vector2, Vector3};
use std::f64::consts::PI;

use crate::dynamics::StanceModel;
use crate::dynamics::impact;
use crate::ode::{self, Phase, Segment};
use crate::trig::sin_cos;

/// State (w, θ1, θ2, ẇ, θ̇1, θ̇2).
pub type StanceState = SVector<f64, 6>;

/// Fraction of the step after which the leg torque τ1 is switched off (paper: EMG shows the
/// hip-extensor push only early in stance).
pub const TORQUE_OFF: f64 = 0.4;
/// A trial stops when |θ1| exceeds this (rad): the residual of a wild guess (spec §4).
pub const THETA1_ABORT: f64 = PI / 3.0;

/// Everything about one step's stance that does not change between shooting trials.
#[derive(Clone, Copy, Debug)]
pub struct StanceSetup {
    pub model: StanceModel,
    /// Leg length l1 (m).
    pub l1: f64,
    /// Leg axis spring and damper (N/m, N s/m).
    pub k_w: f64,
    pub d_w: f64,
    /// Balance spring and damper (N m/rad, N m s/rad) and the forward-lean reference (rad).
    pub k_2: f64,
    pub d_2: f64,
    pub theta2_ref: f64,
    pub t_step: f64,
    /// |θ1| at the start of the step (the previous step's θ1*) and θ1* at its end.
    pub theta1_start: f64,
    pub theta1_end: f64,
    /// w* at the end of the step.
    pub w_end: f64,
    /// Hip heights at the two heel strikes (m).
    pub y_start: f64,
    pub y_end: f64,
    /// Bounce e of the hip reference (m).
    pub bounce: f64,
}

/// The hip height reference and its derivative with respect to θ1, spec §4 [ours]:
/// y_ref = ȳ(u) + (e/2)(1 + cos πu), u = sin θ1 / sin θ1^± clipped to [−1, 1], with ȳ blending
/// the two heel-strike heights (ȳ = y_hs when they are equal).
pub fn hip_reference(s: &StanceSetup, theta1: f64) -> (f64, f64) {
    let (s1, c1) = sin_cos(theta1);
    hip_reference_sc(s, s1, c1, s.theta1_start.sin(), s.theta1_end.sin())
}

/// [`hip_reference`] from sin θ1, cos θ1 and the two denominators sin θ1^− (start), sin θ1^+
/// (end): one `sin_cos` of πu/2, since cos(π(1+u)/2) = −sin(πu/2), sin(π(1+u)/2) = cos(πu/2),
/// 1 + cos πu = 2 cos²(πu/2) and sin πu = 2 sin(πu/2) cos(πu/2).
fn hip_reference_sc(s: &StanceSetup, s1: f64, c1: f64, sin_start: f64, sin_end: f64) -> (f64, f64) {
    let denom = if s1 < 0.0 { sin_start } else { sin_end };
    let raw = s1 / denom;
    let (u, du) = if raw.abs() >= 1.0 {
        (raw.signum(), 0.0)
    } else {
        (raw, c1 / denom)
    };
    let (sh, ch) = sin_cos(0.5 * PI * u);
    let dy = s.y_end - s.y_start;
    let base = s.y_start + dy * 0.5 * (1.0 + sh);
    let dbase = dy * 0.25 * PI * ch;
    let bump = s.bounce * ch * ch;
    let dbump = -s.bounce * PI * sh * ch;
    (base + bump, (dbase + dbump) * du)
}

/// smoothstep(x) = 3x² − 2x³ on [0, 1], clamped.
pub fn smoothstep(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

/// Clamp events (the leg force reaching or leaving 0) located per stance trial; after them the
/// clamp's kink is left to the step-size control.
const CLAMP_EVENTS: usize = 8;

/// One stance trial: the unknown magnitudes (τ1, p) and the subphase.
#[derive(Clone, Copy, Debug)]
pub struct StanceForces<'a> {
    pub setup: &'a StanceSetup,
    /// Leg torque magnitude τ1 (N m), on for t < 0.4 t_step.
    pub tau1: f64,
    /// Leg extension p (m) of the position actuator, blended in over the second half-step.
    pub p: f64,
    pub locked: bool,
    /// The leg torque on or off whatever t ([`Self::with_torque`]); `None`: on for
    /// t < 0.4 t_step.
    torque: Option<bool>,
    /// Which side of its clamp at 0 the leg force F_w starts on in this integration segment
    /// ([`Self::with_loaded`]; the clamp event fires when it leaves it); `None`: no clamp event.
    loaded: Option<bool>,
    /// sin θ1^− and sin θ1^+ of the hip reference (constants of the step).
    sin_start: f64,
    sin_end: f64,
}

impl<'a> StanceForces<'a> {
    pub fn new(setup: &'a StanceSetup, tau1: f64, p: f64, locked: bool) -> Self {
        StanceForces {
            setup,
            tau1,
            p,
            locked,
            torque: None,
            loaded: None,
            sin_start: setup.theta1_start.sin(),
            sin_end: setup.theta1_end.sin(),
        }
    }

    /// The same forces with the leg torque on (or off) at every t: an integration segment lies
    /// on one side of the switch at 0.4 t_step, and the stages at its end, t = 0.4 t_step, must
    /// see the segment's torque (its limit from inside), not the value past the switch (the
    /// step then failed its error test, down to 1e-5 s steps, and kept a 1e-7 error).
    pub fn with_torque(mut self, on: bool) -> Self {
        self.torque = Some(on);
        self
    }

    /// The same forces in an integration segment that starts with the leg force F_w positive
    /// (`loaded`) or clamped at 0: F_w is that side's (the servo's force, or 0) throughout, and
    /// the clamp event (event 3) fires where the servo's force changes sign, so that no
    /// integrator step straddles the clamp's kink (after the heel strike the unloaded leg's
    /// servo pulls, and F_w is 0 for the first ≈ 60 ms). The step in which the event fires
    /// continues that side's force smoothly past the crossing, where the event is located.
    pub fn with_loaded(mut self, loaded: bool) -> Self {
        self.loaded = Some(loaded);
        self
    }

    /// The leg force F_w at (t, y) before its clamp at 0 (telescopic subphase).
    pub fn leg_force(&self, t: f64, y: &StanceState) -> f64 {
        let (s1, c1) = sin_cos(y[1]);
        self.leg_force_sc(t, y, s1, c1)
    }

    /// [`Self::leg_force`] with sin θ1, cos θ1 known.
    fn leg_force_sc(&self, t: f64, y: &StanceState, s1: f64, c1: f64) -> f64 {
        let s = self.setup;
        let (w, wd, th1d) = (y[0], y[3], y[4]);
        // pa = w_ref − l1 + (m2 g cos θ1 + d_w ẇ_ref)/k_w + p s(t), F_w = k_w (l1 + pa − w) − d_w ẇ ≥ 0
        let (y_ref, dy_ref) = hip_reference_sc(s, s1, c1, self.sin_start, self.sin_end);
        let w_ref = (y_ref - s.model.l9) / c1;
        let dw_ref = dy_ref / c1 + (y_ref - s.model.l9) * s1 / (c1 * c1);
        let wd_ref = dw_ref * th1d;
        let blend = smoothstep((t - 0.5 * s.t_step) / (0.5 * s.t_step));
        s.k_w * (w_ref - w + self.p * blend) + s.model.m2 * s.model.g * c1 + s.d_w * (wd_ref - wd)
    }

    /// Generalized forces Q = (F_w, F_θ1 − F_θ2, F_θ2) at (t, y).
    pub fn generalized(&self, t: f64, y: &StanceState) -> Vector3<f64> {
        let (s1, c1) = sin_cos(y[1]);
        self.generalized_sc(t, y, s1, c1)
    }

    /// [`Self::generalized`] with sin θ1, cos θ1 known.
    fn generalized_sc(&self, t: f64, y: &StanceState, s1: f64, c1: f64) -> Vector3<f64> {
        let s = self.setup;
        let (th2, th2d) = (y[2], y[5]);
        let f2 = -s.k_2 * (th2 - s.theta2_ref) - s.d_2 * th2d;
        let f1 = if self.torque.unwrap_or(t < TORQUE_OFF * s.t_step) {
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
    pub fn accelerations(&self, t: f64, y: &StanceState) -> Vector3<f64> {
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
/// or lets go ([`StanceForces::with_loaded`]).
impl Phase<6, 4> for StanceForces<'_> {
    fn rhs(&self, t: f64, y: &StanceState) -> StanceState {
        let a = self.accelerations(t, y);
        StanceState::from([y[3], y[4], y[5], a[0], a[1], a[2]])
    }

    fn events(&self, t: f64, y: &StanceState) -> [f64; 4] {
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
        [
            switch,
            THETA1_ABORT - th1.abs(),
            w - 0.5 * self.setup.l1,
            clamp,
        ]
    }
}

/// The dense record of one stance trial.
#[derive(Clone, Debug)]
pub struct StanceRun {
    pub tau1: f64,
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

/// The hip's acceleration over an interval, tabulated on a uniform grid from the stance run
/// and interpolated by the quintic through the six nearest grid points (Lagrange; at the ends of
/// a piece the six are shifted inside it): the swing's right-hand side reads the moving hip
/// here instead of re-evaluating the stance dynamics at every stage (spec §5: the swing uses
/// the hip of the same step's stance). The table is split wherever the stance run has a segment
/// boundary — the leg torque switching off, the position actuator's blend starting, the leg
/// locking or releasing, the leg force's clamp — since the acceleration or its derivative jumps
/// there. The swing integrations stop at the same
/// [`HipPath::breaks`], so no integrator step straddles a jump (measured: stepping across the
/// torque switch-off left a 2e-7 global error in swing1 at a 1e-10 tolerance).
/// Grid ≤ 4 ms: measured 7e-7 m/s² (2 ms: 1.4e-7; the cubic through four points every 1 ms,
/// before: 7e-6, with 4 times the table's points). A kinematic offset of the swing-side hip
/// joint from the dynamic hip (the determinants of gait, spec §7) adds its acceleration, by
/// central second differences (step 1e-4 s: truncation ≈ h² f⁗ / 12 ≈ 1e-8 m/s²).
#[derive(Clone, Debug)]
pub struct HipPath {
    pieces: Vec<Piece>,
}

#[derive(Clone, Debug)]
struct Piece {
    t0: f64,
    t1: f64,
    dt: f64,
    /// acc[i] is the value at t0 + i dt (the ends just inside the piece), i = 0..=n, n ≥ 5.
    acc: Vec<[f64; 2]>,
}

/// Largest grid step of [`HipPath`] (s).
pub const HIP_PATH_STEP: f64 = 4e-3;

/// The step of [`HipPath::new`]'s central difference of the swing hip's offset (s).
pub const OFFSET_DIFFERENCE_STEP: f64 = 1e-4;
const H: f64 = OFFSET_DIFFERENCE_STEP;

impl HipPath {
    /// Tabulate the hip acceleration of `run` plus that of `offset(t)` on [t0, t1].
    pub fn new(
        run: &StanceRun,
        setup: &StanceSetup,
        t0: f64,
        t1: f64,
        offset: &dyn Fn(f64) -> [f64; 2],
    ) -> Self {
        Self::with_offset_acceleration(run, setup, t0, t1, offset, &|_| None)
    }

    /// [`Self::new`] with the offset's acceleration where `offset_acceleration(t)` gives it (in
    /// closed form); elsewhere the offset is differenced as in [`Self::new`].
    pub fn with_offset_acceleration(
        run: &StanceRun,
        setup: &StanceSetup,
        t0: f64,
        t1: f64,
        offset: &dyn Fn(f64) -> [f64; 2],
        offset_acceleration: &dyn Fn(f64) -> Option<[f64; 2]>,
    ) -> Self {
        let hip_acceleration = run.hip_acceleration(setup);
        let acceleration = |t: f64| {
            let a = hip_acceleration(t);
            if let Some(o) = offset_acceleration(t) {
                return [a[0] + o[0], a[1] + o[1]];
            }
            let (m, o, p) = (offset(t - H), offset(t), offset(t + H));
            [
                a[0] + (m[0] - 2.0 * o[0] + p[0]) / (H * H),
                a[1] + (m[1] - 2.0 * o[1] + p[1]) / (H * H),
            ]
        };
        let mut cuts = vec![t0];
        cuts.extend(
            run.segments
                .iter()
                .map(|(seg, _)| seg.t1)
                .filter(|&t| t > t0 && t < t1),
        );
        cuts.push(t1);
        // the ends of a piece are its inner limits (the state or the forces jump at a cut)
        let eps = 1e-12 * setup.t_step;
        let pieces = cuts
            .windows(2)
            .map(|w| {
                let (a, b) = (w[0], w[1]);
                let n = ((b - a) / HIP_PATH_STEP).ceil().max(5.0) as usize;
                let dt = (b - a) / n as f64;
                let mut acc = Vec::with_capacity(n + 1);
                for i in 0..=n {
                    let t = if i == n {
                        b - eps
                    } else if i == 0 {
                        a + eps
                    } else {
                        a + i as f64 * dt
                    };
                    acc.push(acceleration(t));
                }
                Piece {
                    t0: a,
                    t1: b,
                    dt,
                    acc,
                }
            })
            .collect();
        HipPath { pieces }
    }

    /// The times inside the tabulated interval where the acceleration may jump.
    pub fn breaks(&self) -> impl Iterator<Item = f64> + '_ {
        self.pieces[..self.pieces.len() - 1].iter().map(|p| p.t1)
    }

    /// The hip acceleration at t (clamped to the tabulated interval).
    pub fn acceleration(&self, t: f64) -> [f64; 2] {
        self.acceleration_on(self.piece(t), t)
    }

    /// The index of the piece (between [`Self::breaks`]) that holds t, a break starting the
    /// next piece.
    pub fn piece(&self, t: f64) -> usize {
        self.pieces
            .iter()
            .position(|p| t < p.t1)
            .unwrap_or(self.pieces.len() - 1)
    }

    /// The acceleration of piece `piece` at t (clamped to the piece): at a break, the limit
    /// from inside the piece, which an integration that stops at the break needs for its last
    /// stages.
    pub fn acceleration_on(&self, piece: usize, t: f64) -> [f64; 2] {
        let p = &self.pieces[piece];
        let n = p.acc.len() - 1;
        let x = ((t - p.t0) / p.dt).clamp(0.0, n as f64);
        // the six grid points around t's interval (shifted inside the piece at its ends)
        let j = (x.floor() as usize).saturating_sub(2).min(n - 5);
        let u = x - j as f64;
        let d = [u, u - 1.0, u - 2.0, u - 3.0, u - 4.0, u - 5.0];
        // Lagrange weights: Π_{m≠k} (u − m) / Π_{m≠k} (k − m)
        let (mut left, mut right) = ([1.0; 6], [1.0; 6]);
        for k in 1..6 {
            left[k] = left[k - 1] * d[k - 1];
            right[5 - k] = right[6 - k] * d[6 - k];
        }
        const DENOM: [f64; 6] = [-120.0, 24.0, -12.0, 12.0, -24.0, 120.0];
        let mut a = [0.0; 2];
        for k in 0..6 {
            let w = left[k] * right[k] / DENOM[k];
            let v = p.acc[j + k];
            a[0] += w * v[0];
            a[1] += w * v[1];
        }
        a
    }
}

impl StanceRun {
    /// One trial integration of the stance from `y0` over [0, t_step] with magnitudes (τ1, p).
    pub fn simulate(
        setup: &StanceSetup,
        y0: StanceState,
        tau1: f64,
        p: f64,
    ) -> Result<Self, String> {
        Self::simulate_with(setup, y0, tau1, p, ode::TOLERANCE)
    }

    /// [`Self::simulate`] at integrator tolerance `tol` (to measure the integration error).
    pub fn simulate_with(
        setup: &StanceSetup,
        y0: StanceState,
        tau1: f64,
        p: f64,
        tol: f64,
    ) -> Result<Self, String> {
        let mut run = Self::simulate_on(setup, y0, tau1, p, tol, None)?;
        run.evaluations += run.densify(setup);
        Ok(run)
    }

    /// [`Self::simulate_with`] on the step sequences of `mesh`, a previous trial of the same
    /// stance ([`ode::integrate_on`]): its i-th segment's steps for the i-th segment (from the
    /// same start time, or shifted when the segment starts at an event), when the subphases
    /// agree. The dense output is left out ([`ode::integrate_trial`]): [`Self::densify`] the
    /// trial that is kept.
    pub fn simulate_on(
        setup: &StanceSetup,
        y0: StanceState,
        tau1: f64,
        p: f64,
        tol: f64,
        mesh: Option<&StanceRun>,
    ) -> Result<Self, String> {
        let breaks = [TORQUE_OFF * setup.t_step, 0.5 * setup.t_step, setup.t_step];
        let mut run = StanceRun {
            tau1,
            p,
            segments: Vec::with_capacity(4),
            aborted: false,
            residual: Vector2::zeros(),
            evaluations: 0,
            adapted: false,
        };
        let (mut t, mut y, mut locked) = (0.0, y0, false);
        // the leg force's side of its clamp after a clamp event (else its sign where a segment
        // starts), and the clamp events so far: past CLAMP_EVENTS (a force grazing 0) the kink
        // is left to the step-size control
        let (mut flipped, mut clamp_events) = (None, 0);
        'outer: for t_break in breaks {
            while t < t_break {
                let forces = StanceForces::new(setup, tau1, p, locked)
                    .with_torque(t < TORQUE_OFF * setup.t_step);
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
                    Some(0) if locked => locked = false,
                    Some(3) => {
                        flipped = Some(!loaded);
                        clamp_events += 1;
                    }
                    Some(0) => {
                        // the knee locks: a plastic impulse along the leg stops ẇ
                        let q = Vector3::new(y[0], y[1], y[2]);
                        let (qd, _) =
                            impact::heel_strike(&setup.model, &q, &Vector3::new(y[3], y[4], y[5]));
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
    pub fn densify(&mut self, setup: &StanceSetup) -> u32 {
        let (tau1, p, t_off) = (self.tau1, self.p, TORQUE_OFF * setup.t_step);
        self.segments
            .iter_mut()
            .map(|(seg, locked)| {
                let forces = StanceForces::new(setup, tau1, p, *locked).with_torque(seg.t0 < t_off);
                seg.densify(|_| forces)
            })
            .sum()
    }

    /// End time of the record (t_step unless aborted).
    pub fn t_end(&self) -> f64 {
        self.segments.last().map_or(0.0, |(s, _)| s.t1)
    }

    /// The state and subphase at time t.
    pub fn state(&self, t: f64) -> (StanceState, bool) {
        let i = self
            .segments
            .partition_point(|(s, _)| s.t1 < t)
            .min(self.segments.len() - 1);
        let (seg, locked) = &self.segments[i];
        (seg.state(t), *locked)
    }

    /// Hip position at t (relative to the stance ankle's x): [`Self::hip`]`[0]` without the
    /// dynamics.
    pub fn hip_position(&self, setup: &StanceSetup, t: f64) -> [f64; 2] {
        let (y, _) = self.state(t);
        setup.model.hip(&Vector3::new(y[0], y[1], y[2]))
    }

    /// The hip acceleration as a function of t: [`Self::hip`]`[2]` with the step's constants
    /// (the hip reference's sin θ1^±) computed once and one `sin_cos` of θ1 per call.
    pub fn hip_acceleration<'a>(&'a self, setup: &'a StanceSetup) -> impl Fn(f64) -> [f64; 2] + 'a {
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
