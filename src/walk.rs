//! The step loop (KLAW 1989 Figure 1, top to bottom): plan the step constraints, shoot the stance,
//! complete the hind leg through double support, shoot the swing subphases, strike the heel, and
//! carry the warm starts to the next step.
use nalgebra::{Vector2, Vector3};
use serde::Serialize;
use std::f64::consts::PI;

use crate::attributes::Attributes;
use crate::body::Body;
use crate::control::shooting::{self, Memory2, Options, SolveReport, Start2};
use crate::control::stance::{StanceRun, StanceSetup, StanceState};
use crate::dynamics::impact::{self, ImpactReport};
use crate::dynamics::{StanceModel, SwingModel};
use crate::error::{Error, Result};
use crate::params::Gait;
use crate::plan::StepConstraints;

/// One shooting solve in the report.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct SolveRecord {
    pub phase: &'static str,
    #[serde(flatten)]
    pub report: SolveReport,
}

/// A simulated step: its constraints, its dynamic records and its report.
#[derive(Clone, Debug)]
pub struct Step {
    pub index: usize,
    /// Time of the heel strike that starts the step (s).
    pub t_start: f64,
    /// Global x of the stance ankle pivot (m).
    pub x_ankle: f64,
    pub constraints: StepConstraints,
    pub stance_setup: StanceSetup,
    pub stance: StanceRun,
    pub impact: ImpactReport,
    pub solves: Vec<SolveRecord>,
}

/// Walks step after step, carrying the state and the warm starts.
pub struct Walker {
    pub body: Body,
    pub attrs: Attributes,
    stance_model: StanceModel,
    #[allow(dead_code)]
    swing_model: SwingModel,
    options: Options,
    prev: Option<(StepConstraints, StanceState)>,
    stance_memory: Option<Memory2>,
    t: f64,
    x_ankle: f64,
    index: usize,
}

impl Walker {
    pub fn new(body: Body, attrs: Attributes) -> Self {
        Walker {
            stance_model: StanceModel::new(&body),
            swing_model: SwingModel::new(&body),
            body,
            attrs,
            options: Options { tol: 1e-9, max_iterations: 25 },
            prev: None,
            stance_memory: None,
            t: 0.0,
            x_ankle: 0.0,
            index: 0,
        }
    }

    fn stance_setup(&self, prev: &StepConstraints, c: &StepConstraints) -> StanceSetup {
        let a = &self.attrs;
        let m = self.stance_model;
        let ww = 2.0 * PI * a.leg_frequency;
        let w2 = 2.0 * PI * a.trunk_frequency;
        let j2 = m.trunk_inertia();
        StanceSetup {
            model: m,
            l1: self.body.l1,
            k_w: m.m2 * ww * ww,
            d_w: 2.0 * a.leg_damping_ratio * m.m2 * ww,
            k_2: j2 * w2 * w2,
            d_2: 2.0 * a.trunk_damping_ratio * j2 * w2,
            theta2_ref: a.trunk_lean,
            t_step: c.timing.t_step,
            theta1_start: prev.theta1,
            theta1_end: c.theta1,
            w_end: c.w,
            y_start: prev.hip[1],
            y_end: c.hip[1],
            bounce: c.bounce,
        }
    }

    /// Simulate the next step with gait `gait`.
    pub fn step(&mut self, gait: Gait) -> Result<Step> {
        let c = StepConstraints::new(&self.body, &self.attrs, gait)?;
        let index = self.index;
        // pre-impact posture and rates about the new pivot
        let (prev_c, q, hip_v, trunk_rate) = match &self.prev {
            // first step [ours]: the mirrored heel-strike posture, hip moving horizontally at v
            None => (c, Vector3::new(c.w, -c.theta1, self.attrs.trunk_lean), [gait.velocity, 0.0], 0.0),
            Some((pc, y_end)) => {
                let q_old = Vector3::new(y_end[0], y_end[1], y_end[2]);
                let qd_old = Vector3::new(y_end[3], y_end[4], y_end[5]);
                let v = self.stance_model.hip_velocity(&q_old, &qd_old);
                (*pc, Vector3::new(pc.w, -pc.theta1, y_end[2]), v, y_end[5])
            }
        };
        let qd_minus = impact::rates_about_pivot(&q, hip_v, trunk_rate);
        let (qd, impact) = impact::heel_strike(&self.stance_model, &q, &qd_minus);
        let y0 = StanceState::from([q[0], q[1], q[2], qd[0], qd[1], qd[2]]);
        let setup = self.stance_setup(&prev_c, &c);

        let start = match self.stance_memory {
            Some(m) => Start2::Warm(m),
            None => {
                let scale = self.body.mass * self.body.l1;
                Start2::Cold { x0: Vector2::new(0.5 * scale, 0.0), h: Vector2::new(0.01 * scale, 1e-3) }
            }
        };
        let best = std::cell::RefCell::new(None::<StanceRun>);
        let residual = |x: Vector2<f64>| {
            let run = StanceRun::simulate(&setup, y0, x[0], x[1])?;
            let r = run.residual;
            let mut b = best.borrow_mut();
            if b.as_ref().is_none_or(|o: &StanceRun| r.amax() < o.residual.amax()) {
                *b = Some(run);
            }
            Ok(r)
        };
        let (x, report, memory) = shooting::solve2(residual, start, &self.options)
            .map_err(|reason| Error::Integration { step: index, phase: "stance", reason })?;
        let stance = best.into_inner().expect("at least one trial ran");
        if !report.converged {
            return Err(Error::NotConverged {
                step: index,
                phase: "stance",
                residual: report.residual,
                iterations: report.iterations,
            });
        }
        debug_assert!(stance.tau1 == x[0] && stance.p == x[1]);
        self.stance_memory = Some(memory);
        let step = Step {
            index,
            t_start: self.t,
            x_ankle: self.x_ankle,
            constraints: c,
            stance_setup: setup,
            impact,
            solves: vec![SolveRecord { phase: "stance", report }],
            stance,
        };
        let y_end = step.stance.segments.last().expect("a converged run has segments").0.y1;
        self.prev = Some((c, y_end));
        self.t += c.timing.t_step;
        self.x_ankle += gait.step_length;
        self.index += 1;
        Ok(step)
    }
}

/// A simulated walk.
pub struct Walk {
    pub body: Body,
    pub attrs: Attributes,
    pub steps: Vec<Step>,
}

/// Simulate one step per entry of `gaits` (parameters may change from step to step).
pub fn simulate(body: Body, attrs: Attributes, gaits: &[Gait]) -> Result<Walk> {
    let mut walker = Walker::new(body, attrs.clone());
    let steps = gaits.iter().map(|g| walker.step(*g)).collect::<Result<Vec<_>>>()?;
    Ok(Walk { body, attrs, steps })
}

impl Walk {
    /// Simulated duration (s).
    pub fn duration(&self) -> f64 {
        self.steps.iter().map(|s| s.constraints.timing.t_step).sum()
    }

    /// Frames at `fps` frames per second from t = 0 to the last heel strike.
    pub fn frames(&self, _fps: f64) -> Vec<crate::report::Frame> {
        Vec::new() // TODO(engine): sampled in the next commit
    }

    /// The per-step report.
    pub fn report(&self) -> crate::report::Report {
        crate::report::Report { height: self.body.height, mass: self.body.mass, steps: Vec::new() }
    }
}
