//! Swing control (KLAW 1989 §4.3, spec §5): the hip and knee torques of the three swing
//! subphases, one trial integration of each, and their end-condition residuals.
//!
//! - swing1 [0, ½ t_swing]: hip torque A (1 − 1.5 s) and knee torque B s² − d₁ θ̇4, s the
//!   fraction of swing1 \[ours\]; end conditions θ3 = θ3*, tibia vertical (θ3 + θ4 = 0, i.e.
//!   x_ankle = x_knee). Constant torques whip the shank forward late and put the toe under the
//!   ground (over the grid of measure/grid.rs); a hip push that turns into a brake and a knee
//!   extension that grows late keep the knee flexed while the foot passes under the hip. The
//!   knee damper d₁ = 2ζ √(a22 m4 g r4) damps the shank's own pendulum at the servo damping
//!   ratio ζ (the rectus femoris braking the knee's flexion in initial swing): without it the
//!   knee, handed over at toe-off flexing fast, folds freely far past the norm (docs/realism.md).
//! - swing2 [½, 0.85 t_swing]: hip servo F_θ3 = −k_h (θ3 − θ3*) − d_h θ̇3; the knee follows the
//!   quadratic reference θ4_ref = θ4(t1) + (κ_hs − θ4(t1)) u², u = (t − t1)/(t2 − t1), from its
//!   swing1-end angle (at rate 0) to κ_hs at t2, through a servo
//!   −k_k (θ4 − θ4_ref) − d_k (θ̇4 − θ̇4_ref), plus the unknown constant knee torque C found so
//!   that θ4 first reaches κ_hs at t2 \[ours\]; then the knee locks. The knee is still extending at
//!   t2 (the reference's rate 2 (κ_hs − θ4(t1))/(t2 − t1)), so the crossing is transversal and
//!   the residual monotone in C. A constant or a decaying knee torque alone leaves no such root
//!   at slow speeds: the knee, handed over extending fast, either crosses early or turns back
//!   before t2 (the residual jumps at the tangency).
//! - swing3 [0.85, 1 t_swing]: knee locked at κ_hs, hip moment D0 + D1 s (s the fraction of
//!   swing3) such that θ3 = θ3* at heel strike and the heel comes down at the landing velocity
//!   attribute [ours: the spec asks for a heel velocity ≤ 0 at contact; with one unknown the leg
//!   still swings forward at contact at slow speeds and the heel scrapes up from below].
use nalgebra::{SVector, Vector2};

use crate::control::stance::HipPath;
use crate::dynamics::SwingModel;
use crate::model::attributes::Attributes;
use crate::model::servos::Servos;
use crate::numerics::ode::{self, IntegrationError, Phase, Segment};
use crate::plan::StepConstraints;

/// State (θ3, θ4, θ̇3, θ̇4).
pub type SwingState = SVector<f64, 4>;

/// Ends of swing1 and swing2 as fractions of the swing (paper).
pub(crate) const SWING1_END: f64 = 0.5;
pub(crate) const SWING2_END: f64 = 0.85;
/// A trial stops when the thigh swings beyond ±100° (a wild guess).
pub(crate) const THETA3_ABORT: f64 = 1.75;

/// The swing1 knee damper d₁ = 2ζ √(a22 m4 g r4) (N m s/rad) \[ours\]: the shank swinging about
/// the knee is a pendulum of inertia a22 = I4 + m4 r4² and stiffness m4 g r4 (small angles), and
/// d₁ damps it at the ratio ζ.
pub(crate) fn knee_damper(model: &SwingModel, zeta: f64) -> f64 {
    let a22 = model.mass_matrix(&Vector2::zeros())[(1, 1)];
    2.0 * zeta * (a22 * model.m4 * model.g * model.r4).sqrt()
}

/// Everything about one swing that does not change between trials.
#[derive(Clone, Copy, Debug)]
pub struct SwingSetup<'a> {
    /// The swing leg's model.
    pub model: SwingModel,
    /// The swing-side hip's acceleration over the swing (the stance's hip moved by the
    /// determinants of gait), tabulated.
    pub hip_path: &'a HipPath,
    /// The swing-side hip's vertical velocity at heel strike (m/s).
    pub hip_vy_end: f64,
    /// Toe-off, t_ds (s from the step's start).
    pub t_off: f64,
    /// End of swing1, t_ds + 0.5 t_swing (s).
    pub t1: f64,
    /// Knee lock, the end of swing2: t_ds + 0.85 t_swing (s).
    pub t2: f64,
    /// Heel strike, t_step (s).
    pub t_end: f64,
    /// θ3*, the thigh's angle at heel strike (rad).
    pub theta3_target: f64,
    /// κ_hs, the knee's flexion at heel strike, where it locks (rad).
    pub kappa_hs: f64,
    /// Heel ahead of the hip at heel strike, x_heel − x_hip = sl/2 − l8 (m).
    pub heel_ahead: f64,
    /// Downward heel velocity wanted at contact (m/s).
    pub landing_velocity: f64,
    /// Swing1 knee damper d₁ (N m s/rad).
    pub d_swing1: f64,
    /// Swing2 knee servo's spring (N m/rad).
    pub k_k: f64,
    /// Swing2 knee servo's damper (N m s/rad).
    pub d_k: f64,
    /// Swing2 hip servo's spring k_h (N m/rad).
    pub k_h: f64,
    /// Swing2 hip servo's damper d_h (N m s/rad).
    pub d_h: f64,
}

impl<'a> SwingSetup<'a> {
    /// The swing of a step with constraints `c` (timing, θ3*, κ_hs, where the heel lands) hanging
    /// from `hip_path`, the servos' gains from the model's `servos`: k = a (2π f_h)²,
    /// d = 2ζ a (2π f_h) with a = a11, a22 of the leg at heel strike, and the swing1 knee damper
    /// `knee_damper`; the heel's landing velocity from the attributes.
    pub fn new(
        model: SwingModel,
        hip_path: &'a HipPath,
        hip_vy_end: f64,
        c: &StepConstraints,
        attrs: &Attributes,
        servos: &Servos,
    ) -> Self {
        let t = c.timing;
        let m_hs = model.mass_matrix(&Vector2::new(0.0, c.theta4));
        let (a11, a22) = (m_hs[(0, 0)], m_hs[(1, 1)]);
        let wh = 2.0 * std::f64::consts::PI * servos.swing_hip_frequency;
        let z = servos.damping_ratio;
        SwingSetup {
            model,
            hip_path,
            hip_vy_end,
            t_off: t.t_ds,
            t1: t.t_ds + SWING1_END * t.t_swing,
            t2: t.t_ds + SWING2_END * t.t_swing,
            t_end: t.t_step,
            theta3_target: c.theta3,
            kappa_hs: c.theta4,
            heel_ahead: c.heel_x - c.hip[0] - c.hip_shift,
            landing_velocity: attrs.heel_strike_velocity,
            d_swing1: knee_damper(&model, z),
            k_k: a22 * wh * wh,
            d_k: 2.0 * z * a22 * wh,
            k_h: a11 * wh * wh,
            d_h: 2.0 * z * a11 * wh,
        }
    }
}

/// Which subphase, with its torque magnitudes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Subphase {
    /// Toe-off to 0.5 t_swing (spec §5): the thigh is brought to θ3* with the tibia vertical.
    Swing1 {
        /// Hip torque magnitude A (N m): A (1 − 1.5 s), s the fraction of swing1.
        hip: f64,
        /// Knee torque magnitude B (N m): B s², braked by the knee damper.
        knee: f64,
    },
    /// 0.5 to 0.85 t_swing: the knee extends to κ_hs under its servo, the hip servo holds θ3*.
    Swing2 {
        /// Constant knee torque (N m) added to the servo's.
        knee: f64,
        /// θ4 at the start of swing2, where the knee reference starts (rad).
        knee_start: f64,
    },
    /// 0.85 t_swing to heel strike, the knee locked: the heel lands at t_step.
    Swing3 {
        /// Hip torque at the start of swing3 (N m).
        hip: f64,
        /// The hip torque's change over swing3 (N m), linear in time.
        ramp: f64,
    },
}

/// How much looser swing2 integrates than the other phases \[ours\]. Its servos make the leg
/// stiff — the coupled knee and hip servo have an eigenvalue ≈ −190 /s (default walk) — and
/// DOP853's step size there is held at h|λ| ≈ 0.8 by accuracy, while the same stiff mode damps
/// the local errors away: at 100 times the tolerance swing2's end condition, re-integrated at
/// 1e-12, is met about as well as at the common tolerance (`measure/evals.rs`).
pub(crate) const SWING2_TOLERANCE_SCALE: f64 = 100.0;

impl Subphase {
    /// The integrator tolerance of this subphase for the walk's tolerance `tol`: `tol` scaled
    /// by `swing2_scale` in swing2 (by default [`SWING2_TOLERANCE_SCALE`]).
    pub(crate) fn tolerance(&self, tol: ode::Tolerance, swing2_scale: f64) -> ode::Tolerance {
        match self {
            Subphase::Swing2 { .. } => tol.scaled(swing2_scale),
            _ => tol,
        }
    }

    /// The subphase's name: `swing1`, `swing2` or `swing3`.
    pub fn name(&self) -> &'static str {
        match self {
            Subphase::Swing1 { .. } => "swing1",
            Subphase::Swing2 { .. } => "swing2",
            Subphase::Swing3 { .. } => "swing3",
        }
    }
}

/// The swing leg under one subphase's torques.
#[derive(Clone, Copy, Debug)]
pub struct SwingForces<'a> {
    /// The swing's constants.
    pub setup: &'a SwingSetup<'a>,
    /// The subphase and its torque magnitudes.
    pub sub: Subphase,
    /// The hip path's piece the integration is on ([`HipPath::acceleration_on`]), so that its
    /// stages at a break see the piece's acceleration, not the next one's; `None`: the piece
    /// holding t.
    pub piece: Option<usize>,
}

impl SwingForces<'_> {
    /// Generalized forces (F_θ3, F_θ4).
    pub(crate) fn torques(&self, t: f64, y: &SwingState) -> Vector2<f64> {
        match self.sub {
            Subphase::Swing1 { hip, knee } => {
                // hip: a push that turns into a brake, A (1 − 1.5 s); knee: B s², an extension
                // that grows late, so the knee flexes first (s = fraction of swing1), braked
                // by the damper
                let s =
                    ((t - self.setup.t_off) / (self.setup.t1 - self.setup.t_off)).clamp(0.0, 1.0);
                Vector2::new(
                    hip * (1.0 - 1.5 * s),
                    knee * s * s - self.setup.d_swing1 * y[3],
                )
            }
            Subphase::Swing2 { knee, knee_start } => {
                let s = self.setup;
                let span = s.t2 - s.t1;
                let u = (t - s.t1) / span;
                let reference = knee_start + (s.kappa_hs - knee_start) * u * u;
                let rate = 2.0 * (s.kappa_hs - knee_start) * u / span;
                Vector2::new(
                    -s.k_h * (y[0] - s.theta3_target) - s.d_h * y[2],
                    knee - s.k_k * (y[1] - reference) - s.d_k * (y[3] - rate),
                )
            }
            Subphase::Swing3 { hip, ramp } => {
                let s = self.setup;
                Vector2::new(hip + ramp * (t - s.t2) / (s.t_end - s.t2), 0.0)
            }
        }
    }
}

/// Events: 0 the knee reaches κ_hs (swing2 only), 1 the thigh swings wild.
impl Phase<4, 2> for SwingForces<'_> {
    fn rhs(&self, t: f64, y: &SwingState) -> SwingState {
        let s = self.setup;
        let hip_acc = match self.piece {
            Some(piece) => s.hip_path.acceleration_on(piece, t),
            None => s.hip_path.acceleration(t),
        };
        let q = Vector2::new(y[0], y[1]);
        let qd = Vector2::new(y[2], y[3]);
        let locked = matches!(self.sub, Subphase::Swing3 { .. });
        let a = s
            .model
            .accelerations(&q, &qd, &self.torques(t, y), hip_acc, locked);
        SwingState::from([y[2], y[3], a[0], a[1]])
    }

    fn events(&self, _t: f64, y: &SwingState) -> [f64; 2] {
        let knee = match self.sub {
            Subphase::Swing2 { .. } => y[1] - self.setup.kappa_hs,
            _ => 1.0,
        };
        [knee, THETA3_ABORT - y[0].abs()]
    }
}

/// One trial of one subphase.
#[derive(Clone, Debug)]
pub struct SwingTrial {
    /// The subphase and the magnitudes tried.
    pub sub: Subphase,
    /// The dense solution over the subphase (or up to where the trial stopped).
    pub segment: Segment<4>,
    /// End-condition residual (spec §5; one component for swing2 and swing3, the second 0).
    pub residual: Vector2<f64>,
    /// Right-hand-side evaluations spent.
    pub evaluations: u32,
    /// The integration chose (some of) its own steps rather than following a given mesh.
    pub(crate) adapted: bool,
}

impl SwingTrial {
    /// Integrate `sub` from (t0, y0) to its end time and measure its end-condition residual
    /// (one component for swing2 and swing3, the second then 0).
    pub fn simulate(
        setup: &SwingSetup,
        sub: Subphase,
        t0: f64,
        y0: SwingState,
    ) -> Result<Self, IntegrationError> {
        let tol = sub.tolerance(ode::Tolerance::default(), SWING2_TOLERANCE_SCALE);
        Self::simulate_with(setup, sub, t0, y0, tol)
    }

    /// [`Self::simulate`] at integrator tolerance `tol` (to measure the integration error),
    /// whatever the subphase.
    pub fn simulate_with(
        setup: &SwingSetup,
        sub: Subphase,
        t0: f64,
        y0: SwingState,
        tol: impl Into<ode::Tolerance>,
    ) -> Result<Self, IntegrationError> {
        let mut trial = Self::simulate_on(setup, sub, t0, y0, tol.into(), None)?;
        trial.evaluations += trial.densify(setup);
        Ok(trial)
    }

    /// Complete the dense output of a [`Self::simulate_on`] trial ([`ode::Segment::densify`]);
    /// returns the right-hand-side evaluations.
    pub(crate) fn densify(&mut self, setup: &SwingSetup) -> u32 {
        let sub = self.sub;
        self.segment.densify(|t| SwingForces {
            setup,
            sub,
            piece: Some(setup.hip_path.piece(t)),
        })
    }

    /// [`Self::simulate_with`] on the step sequence of `mesh`, a previous trial of the same
    /// subphase ([`ode::integrate_on`]): the shooting's residual stays smooth in the unknowns.
    /// The dense output is left out ([`ode::integrate_trial`]): [`Self::densify`] the trial
    /// that is kept.
    pub(crate) fn simulate_on(
        setup: &SwingSetup,
        sub: Subphase,
        t0: f64,
        y0: SwingState,
        tol: ode::Tolerance,
        mesh: Option<&Segment<4>>,
    ) -> Result<Self, IntegrationError> {
        let t_end = match sub {
            Subphase::Swing1 { .. } => setup.t1,
            Subphase::Swing2 { .. } => setup.t2,
            Subphase::Swing3 { .. } => setup.t_end,
        };
        // piecewise between the hip path's breaks, where the hip acceleration jumps
        let stops = setup
            .hip_path
            .breaks()
            .filter(|&b| b > t0 && b < t_end)
            .chain(std::iter::once(t_end));
        let mut out: Option<ode::Outcome<4>> = None;
        for stop in stops {
            let (t, y) = out
                .as_ref()
                .map_or((t0, y0), |o| (o.segment.t1, o.segment.y1));
            let follow = mesh.map_or(ode::Mesh::Adaptive, ode::Mesh::Aligned);
            let forces = SwingForces {
                setup,
                sub,
                piece: Some(setup.hip_path.piece(t)),
            };
            let piece = ode::integrate_trial(&forces, t, y, stop, tol, follow)?;
            let event = piece.event.is_some();
            out = Some(match out {
                None => piece,
                Some(o) => o.then(piece),
            });
            if event {
                break;
            }
        }
        let out = out.expect("at least one piece");
        let y = out.segment.y1;
        let residual = match sub {
            Subphase::Swing1 { .. } => Vector2::new(y[0] - setup.theta3_target, y[0] + y[1]),
            Subphase::Swing2 { .. } if out.event == Some(0) => {
                // reached κ_hs early, at t_c: the signed, continuous stand-in θ̇4 (t2 − t_c)
                Vector2::new(y[3] * (t_end - out.segment.t1), 0.0)
            }
            Subphase::Swing2 { .. } => Vector2::new(y[1] - setup.kappa_hs, 0.0),
            Subphase::Swing3 { .. } => {
                // heel velocity of the rigid leg rotating about the moving hip:
                // v_heel,y = v_hip,y − θ̇3 (x_heel − x_hip)
                let heel_vy = setup.hip_vy_end - y[2] * setup.heel_ahead;
                Vector2::new(y[0] - setup.theta3_target, heel_vy + setup.landing_velocity)
            }
        };
        Ok(SwingTrial {
            sub,
            segment: out.segment,
            residual,
            evaluations: out.evaluations,
            adapted: out.adapted,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::body::Body;

    /// The damper gives the shank, swinging about the knee under the thigh held still, the
    /// damping ratio ζ: a22 θ̈4 + d₁ θ̇4 + k θ4 = 0 with k the knee's gravity stiffness, taken
    /// here as the second difference of the model's potential energy (not from m4 g r4).
    #[test]
    fn knee_damper_damps_the_shank_pendulum_at_zeta() {
        for (h, m) in [(1.5, 50.0), (1.8, 80.0), (1.95, 95.0)] {
            let model = SwingModel::new(&Body::standard(h, m).unwrap());
            let e = 1e-4;
            let v = |k: f64| model.potential_energy(&Vector2::new(0.0, k));
            let stiffness = (v(e) - 2.0 * v(0.0) + v(-e)) / (e * e);
            let a22 = model.mass_matrix(&Vector2::zeros())[(1, 1)];
            for zeta in [0.3, 0.7, 1.0] {
                let d = knee_damper(&model, zeta);
                let achieved = d / (2.0 * (a22 * stiffness).sqrt());
                assert!((achieved - zeta).abs() < 1e-6, "{h} {zeta}: {achieved}");
            }
        }
    }
}
