//! Swing control (KLAW 1989 §4.3, spec §5): the hip and knee torques of the three swing
//! subphases, one trial integration of each, and their end-condition residuals.
//!
//! - swing1 [0, ½ t_swing]: hip torque A (1 − 1.5 s) and knee torque B s², s the fraction of
//!   swing1 [ours]; end conditions θ3 = θ3*, tibia vertical (θ3 + θ4 = 0, i.e. x_ankle = x_knee).
//!   Measured over the grid (examples/grid.rs): constant torques whip the shank forward late and
//!   put the toe 1–3 cm under the ground; a hip push that turns into a brake and a knee
//!   extension that grows late keep the knee flexed while the foot passes under the hip.
//! - swing2 [½, 0.85 t_swing]: hip servo F_θ3 = −k_h (θ3 − θ3*) − d_h θ̇3 and a knee braking
//!   burst C·exp(−(t − t1)/τ), τ = 0.1 (t2 − t1) [ours], whose magnitude C is found so that θ4
//!   first reaches κ_hs at the end (no hyperextension before); then the knee locks. A constant
//!   knee torque cannot do it: swing1 hands over a knee extending at ≈ 10 rad/s, and a constant
//!   torque that delays the crossing to t2 reverses the knee before it gets there (the residual
//!   jumps at the tangency). A short braking burst slows the knee and lets it coast in, still
//!   extending, so the residual is monotone in C; the knee lock absorbs the rest.
//! - swing3 [0.85, 1 t_swing]: knee locked at κ_hs, constant hip moment D such that θ3 = θ3*
//!   at heel strike.
use nalgebra::{SVector, Vector2};

use crate::control::stance::{StanceRun, StanceSetup};
use crate::dynamics::SwingModel;
use crate::ode::{self, Phase, Segment};

/// State (θ3, θ4, θ̇3, θ̇4).
pub type SwingState = SVector<f64, 4>;

/// Ends of swing1 and swing2 as fractions of the swing (paper).
pub const SWING1_END: f64 = 0.5;
pub const SWING2_END: f64 = 0.85;
/// A trial stops when the thigh swings beyond ±100° (a wild guess).
pub const THETA3_ABORT: f64 = 1.75;
/// Time constant of the swing2 knee braking burst, as a fraction of swing2.
pub const SWING2_BRAKE: f64 = 0.1;

/// Everything about one swing that does not change between trials.
#[derive(Clone, Copy, Debug)]
pub struct SwingSetup<'a> {
    pub model: SwingModel,
    /// The stance of the same step: it moves the hip.
    pub stance: &'a StanceRun,
    pub stance_setup: &'a StanceSetup,
    /// Toe-off, end of swing1, knee lock, heel strike (s from the step's start).
    pub t_off: f64,
    pub t1: f64,
    pub t2: f64,
    pub t_end: f64,
    /// θ3* and κ_hs.
    pub theta3_target: f64,
    pub kappa_hs: f64,
    /// Swing2 hip servo.
    pub k_h: f64,
    pub d_h: f64,
}

/// Which subphase, with its torque magnitudes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Subphase {
    Swing1 { hip: f64, knee: f64 },
    Swing2 { knee: f64 },
    Swing3 { hip: f64 },
}

impl Subphase {
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
    pub setup: &'a SwingSetup<'a>,
    pub sub: Subphase,
}

impl SwingForces<'_> {
    /// Generalized forces (F_θ3, F_θ4).
    pub fn torques(&self, t: f64, y: &SwingState) -> Vector2<f64> {
        match self.sub {
            Subphase::Swing1 { hip, knee } => {
                // hip: a push that turns into a brake, A (1 − 1.5 s); knee: B s², an extension
                // that grows late, so the knee flexes first (s = fraction of swing1)
                let s = ((t - self.setup.t_off) / (self.setup.t1 - self.setup.t_off)).clamp(0.0, 1.0);
                Vector2::new(hip * (1.0 - 1.5 * s), knee * s * s)
            }
            Subphase::Swing2 { knee } => {
                let s = self.setup;
                let tau = SWING2_BRAKE * (s.t2 - s.t1);
                Vector2::new(-s.k_h * (y[0] - s.theta3_target) - s.d_h * y[2], knee * (-(t - s.t1) / tau).exp())
            }
            Subphase::Swing3 { hip } => Vector2::new(hip, 0.0),
        }
    }
}

/// Events: 0 the knee reaches κ_hs (swing2 only), 1 the thigh swings wild.
impl Phase<4, 2> for SwingForces<'_> {
    fn rhs(&self, t: f64, y: &SwingState) -> SwingState {
        let s = self.setup;
        let hip_acc = s.stance.hip(s.stance_setup, t)[2];
        let q = Vector2::new(y[0], y[1]);
        let qd = Vector2::new(y[2], y[3]);
        let locked = matches!(self.sub, Subphase::Swing3 { .. });
        let a = s.model.accelerations(&q, &qd, &self.torques(t, y), hip_acc, locked);
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
    pub sub: Subphase,
    pub segment: Segment<4>,
    pub residual: Vector2<f64>,
    pub evaluations: u32,
}

impl SwingTrial {
    /// Integrate `sub` from (t0, y0) to its end time and measure its end-condition residual
    /// (one component for swing2 and swing3, the second then 0).
    pub fn simulate(setup: &SwingSetup, sub: Subphase, t0: f64, y0: SwingState) -> Result<Self, String> {
        let t_end = match sub {
            Subphase::Swing1 { .. } => setup.t1,
            Subphase::Swing2 { .. } => setup.t2,
            Subphase::Swing3 { .. } => setup.t_end,
        };
        let out = ode::integrate(&SwingForces { setup, sub }, t0, y0, t_end)?;
        let y = out.segment.y1;
        let residual = match sub {
            Subphase::Swing1 { .. } => Vector2::new(y[0] - setup.theta3_target, y[0] + y[1]),
            Subphase::Swing2 { .. } if out.event == Some(0) => {
                // reached κ_hs early, at t_c: the signed, continuous stand-in θ̇4 (t2 − t_c)
                Vector2::new(y[3] * (t_end - out.segment.t1), 0.0)
            }
            Subphase::Swing2 { .. } => Vector2::new(y[1] - setup.kappa_hs, 0.0),
            Subphase::Swing3 { .. } => Vector2::new(y[0] - setup.theta3_target, 0.0),
        };
        Ok(SwingTrial { sub, segment: out.segment, residual, evaluations: out.evaluations })
    }
}
