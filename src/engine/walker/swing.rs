//! The walker's swing (KLAW 1989 §4.3, spec §5, §6): the double pendulum hung from the swing side's
//! hip joint, in the leg's own plane, through three subphases each solved by shooting — swing1
//! (hip and knee magnitudes A, B), swing2 (knee torque C), the knee lock, swing3 (hip moment
//! D0 + D1 s).
use nalgebra::Vector2;

use super::{StepPlan, Walker};
use crate::control::shooting::{self, Memory1, Memory2, SolveError, SolveReport, Start1, Start2};
use crate::control::stance::{HipPath, StanceRun, StanceSetup};
use crate::control::swing::{Subphase, SwingSetup, SwingState, SwingTrial};
use crate::dynamics::impact;
use crate::engine::error::SimulationError;
use crate::engine::pose::swing_hip_offset;
use crate::engine::report::SolveRecord;
use crate::engine::startup::{tables, with_fallback};
use crate::engine::trials::Trials;
use crate::numerics::ode::{IntegrationError, Segment};

/// The swing-side hip's vertical velocity at heel strike: the stance hip's plus the rate of the
/// determinants' `offset` (a backward difference over 1e-6 t_step).
pub fn swing_hip_vy_end(
    stance: &StanceRun,
    setup: &StanceSetup,
    offset: &dyn Fn(f64) -> [f64; 2],
) -> f64 {
    let t = setup.t_step;
    let e = 1e-6 * t;
    stance.hip(setup, t)[1][1] + (offset(t)[1] - offset(t - e)[1]) / e
}

/// The swing side's hip path over the swing (the stance's hip moved by the determinants of
/// gait, spec §7), tabulated every `step` s at most, and its vertical velocity at heel strike.
pub(super) fn hip_path(
    plan: &StepPlan,
    stance: &StanceRun,
    setup: &StanceSetup,
    step: f64,
) -> (HipPath, f64) {
    let t = plan.c.timing;
    let offset = |tau: f64| swing_hip_offset(&plan.det, plan.side, &plan.c, &plan.pelvis(tau));
    let offset_acceleration = |tau: f64| {
        plan.det
            .swing_offset_acceleration(plan.side, tau, t.t_step, plan.c.fold_length)
    };
    let path = HipPath::with_offset_acceleration(
        stance,
        setup,
        t.t_ds,
        t.t_step,
        step,
        &offset,
        &offset_acceleration,
    );
    (path, swing_hip_vy_end(stance, setup, &offset))
}

impl Walker {
    /// Swing1 from toe-off: the hip and knee magnitudes (A, B) together.
    pub(super) fn swing1(
        &mut self,
        plan: &StepPlan,
        sw: &SwingSetup,
        y_off: SwingState,
        mesh: Option<Segment<4>>,
    ) -> Result<(SwingTrial, SolveRecord), SimulationError> {
        let torque = self.torque_unit();
        let start = plan.startup.start2(
            self.swing1_memory,
            [2, 3],
            [torque; 2],
            (tables().cold_swing1, [1.0; 2]),
            Start2::Cold {
                x0: Vector2::zeros(),
                h: Vector2::new(0.01 * torque, 0.005 * torque),
            },
        );
        let sub = |x: Vector2<f64>| Subphase::Swing1 {
            hip: x[0],
            knee: x[1],
        };
        let tol = self.parameters.waypoint_tolerance;
        let solved = self.solve_2d(sw, start, sub, (sw.t_off, y_off), mesh, tol);
        let (s1, report, memory) = solved.map_err(plan.integration("swing1"))?;
        let record = plan.converged("swing1", report)?;
        self.swing1_memory = Some(memory);
        Ok((s1, record))
    }

    /// Swing2 from swing1's end state `y1`: the knee torque C.
    pub(super) fn swing2(
        &mut self,
        plan: &StepPlan,
        sw: &SwingSetup,
        y1: SwingState,
        mesh: Option<Segment<4>>,
    ) -> Result<(SwingTrial, SolveRecord), SimulationError> {
        let torque = self.torque_unit();
        let start = plan.startup.start1(
            self.swing2_memory,
            4,
            torque,
            tables().cold_swing2_slope,
            Start1::Cold {
                x0: 0.0,
                dx: 0.1 * torque,
            },
        );
        let sub = |x: f64| Subphase::Swing2 {
            knee: x,
            knee_start: y1[1],
        };
        let tol = self.parameters.waypoint_tolerance;
        let solved = self.solve_1d(sw, start, sub, (sw.t1, y1), mesh, tol);
        let (s2, report, memory) = solved.map_err(plan.integration("swing2"))?;
        let record = plan.converged("swing2", report)?;
        self.swing2_memory = Some(memory);
        Ok((s2, record))
    }

    /// The knee lock at swing2's end state `y2` (the leg's angular momentum about the hip
    /// conserved), then swing3 to heel strike: the hip moment D0 + D1 s.
    pub(super) fn swing3(
        &mut self,
        plan: &StepPlan,
        sw: &SwingSetup,
        y2: SwingState,
        mesh: Option<Segment<4>>,
    ) -> Result<(SwingTrial, SolveRecord), SimulationError> {
        let q2 = Vector2::new(y2[0], y2[1]);
        let qd2 = impact::knee_lock(&self.swing_model, &q2, &Vector2::new(y2[2], y2[3]));
        let y2 = SwingState::from([y2[0], plan.c.theta4, qd2[0], 0.0]);
        let torque = self.torque_unit();
        let start = plan.startup.start2(
            self.swing3_memory,
            [5, 6],
            [torque; 2],
            (tables().cold_swing3, [1.0; 2]),
            Start2::Cold {
                x0: Vector2::zeros(),
                h: Vector2::repeat(0.01 * torque),
            },
        );
        let sub = |x: Vector2<f64>| Subphase::Swing3 {
            hip: x[0],
            ramp: x[1],
        };
        let tol = self.parameters.solve_tolerance;
        let solved = self.solve_2d(sw, start, sub, (sw.t2, y2), mesh, tol);
        let (s3, report, memory) = solved.map_err(plan.integration("swing3"))?;
        let record = plan.converged("swing3", report)?;
        self.swing3_memory = Some(memory);
        Ok((s3, record))
    }

    /// One swing trial of a solve, on the solve's mesh.
    fn swing_trial(
        &self,
        trials: &Trials<SwingTrial>,
        sw: &SwingSetup,
        sub: Subphase,
        (t0, y0): (f64, SwingState),
    ) -> Result<Vector2<f64>, IntegrationError> {
        let p = &self.parameters;
        let tol = sub.tolerance(p.ode, p.swing2_tolerance_scale);
        trials.run(|mesh| SwingTrial::simulate_on(sw, sub, t0, y0, tol, mesh))
    }

    /// A 2-D swing solve (Broyden) of `sub` from (t0, y0), from `start` (then `fallback`,
    /// [`with_fallback`]), its first trial on `mesh`; the kept trial densified.
    fn solve_2d(
        &mut self,
        sw: &SwingSetup,
        (start, fallback): (Start2, Option<Start2>),
        sub: impl Fn(Vector2<f64>) -> Subphase,
        from: (f64, SwingState),
        mesh: Option<Segment<4>>,
        tol: f64,
    ) -> Result<(SwingTrial, SolveReport, Memory2), SolveError> {
        let trials = Trials::new(mesh);
        let residual = |x| self.swing_trial(&trials, sw, sub(x), from);
        let options = self.options(tol);
        let solved = with_fallback(start, fallback, |start| {
            shooting::solve2(residual, start, &options).map(|(_, r, m)| (m, r))
        });
        self.densified(sw, trials, solved)
    }

    /// A 1-D swing solve (bisection then secant), as [`Self::solve_2d`].
    fn solve_1d(
        &mut self,
        sw: &SwingSetup,
        (start, fallback): (Start1, Option<Start1>),
        sub: impl Fn(f64) -> Subphase,
        from: (f64, SwingState),
        mesh: Option<Segment<4>>,
        tol: f64,
    ) -> Result<(SwingTrial, SolveReport, Memory1), SolveError> {
        let trials = Trials::new(mesh);
        let residual = |x| Ok(self.swing_trial(&trials, sw, sub(x), from)?[0]);
        let options = self.options(tol);
        let solved = with_fallback(start, fallback, |start| {
            shooting::solve1(residual, start, &options).map(|(_, r, m)| (m, r))
        });
        self.densified(sw, trials, solved)
    }

    /// A swing solve's outcome with its kept trial densified, the trials' evaluations counted.
    fn densified<M>(
        &mut self,
        sw: &SwingSetup,
        trials: Trials<SwingTrial>,
        solved: Result<(M, SolveReport), SolveError>,
    ) -> Result<(SwingTrial, SolveReport, M), SolveError> {
        let (best, evaluations) = trials.finish();
        self.evaluations += evaluations;
        let (memory, report) = solved?;
        let mut trial = best.expect("a solve that returns has run a trial");
        self.evaluations += u64::from(trial.densify(sw));
        Ok((trial, report, memory))
    }
}
