//! The 2-D shooting solver: good Broyden's method (C. G. Broyden, "A class of methods for
//! solving nonlinear simultaneous equations", Math. Comp. 19, 1965), the secant method in two
//! unknowns, as an [`argmin`] solver.
use argmin::core::{
    Error as ArgminError, IterState, KV, Operator, Problem, Solver, State, TerminationReason,
    TerminationStatus,
};
use nalgebra::{Matrix2, Vector2};

use super::ShootingError;
use super::warm_start::FALLBACK_REL_STEP;

/// Where [`Broyden2`] is in its cycle.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Phase {
    /// Forward-difference trial for column `column`; `tries` failed trials so far for it.
    Difference { column: usize, tries: u32 },
    /// A full step `x - J^-1 r` is next.
    Newton,
    /// The step was rejected `halvings` times; the next trial is `x + lambda * step`.
    Backtrack { lambda: f64, halvings: u32 },
}

/// Good Broyden's method in two unknowns (Broyden 1965), the secant method in 2-D.
///
/// Cold start: a forward-difference Jacobian (one trial per unknown, step `h[i]`). Warm start:
/// the previous solve's Jacobian (no difference trials). Each iteration tries the Newton step
/// `x - J^-1 r` (or a halved one); a trial is accepted when it decreases `||r||_2` (sufficient
/// decrease, Armijo factor 1e-4), otherwise the step is halved, up to `max_halvings` times
/// (2 when `J` is no longer a fresh difference Jacobian); when halving fails with a stale `J`,
/// `J` is refreshed by differences once more. Every finite trial, accepted or not, updates `J`
/// by Broyden's rank-1 formula in unknowns scaled by the Jacobian's column norms \[ours\],
/// `J += (dr - J dx) (W dx)^T / (dx^T W dx)`, `W = diag(|J e_k|²)`, invariant under rescaling
/// the unknowns. A failed trial (non-finite or `Err`) counts as a rejection (a failed difference
/// trial is retried with the opposite, then halved step). Converged when `max |r_i| <= tol` at
/// any trial; that point is returned. Each iteration evaluates the residual exactly once; `init`
/// once.
#[derive(Clone, Debug)]
pub(crate) struct Broyden2 {
    /// Absolute tolerance on `max |r_i|`.
    tol: f64,
    /// Hard cap on residual evaluations, the one in `init` included.
    max_evaluations: usize,
    /// Halvings of a rejected step tolerated with a fresh difference Jacobian (8).
    max_halvings: u32,
    /// Finite-difference steps, one per unknown.
    h: Vector2<f64>,
    /// Current (accepted) point and its residual.
    x: Vector2<f64>,
    r: Vector2<f64>,
    /// Current Jacobian estimate.
    jacobian: Option<Matrix2<f64>>,
    /// Jacobian being assembled by differences.
    difference: Matrix2<f64>,
    /// `jacobian` is an unmodified difference Jacobian.
    fresh: bool,
    /// The Jacobian that produced `step` was fresh.
    step_fresh: bool,
    /// Full step under test.
    step: Vector2<f64>,
    phase: Phase,
    /// Best trial (smallest max-norm) and its residual.
    best: Option<(Vector2<f64>, Vector2<f64>)>,
    /// Residual evaluations so far.
    evaluations: usize,
    /// Solver-side termination (stall, failure).
    exit: Option<&'static str>,
}

type State2 = IterState<Vector2<f64>, (), Matrix2<f64>, (), Vector2<f64>, f64>;

impl Broyden2 {
    fn new(
        x0: Vector2<f64>,
        h: Vector2<f64>,
        jacobian: Option<Matrix2<f64>>,
        tol: f64,
        max_evaluations: usize,
    ) -> Self {
        Broyden2 {
            tol,
            max_evaluations,
            max_halvings: 8,
            h,
            x: x0,
            r: Vector2::repeat(f64::NAN),
            jacobian,
            difference: Matrix2::zeros(),
            fresh: false,
            step_fresh: false,
            step: Vector2::zeros(),
            phase: Phase::Newton,
            best: None,
            evaluations: 0,
            exit: None,
        }
    }

    /// Cold start from `x0` with a forward-difference Jacobian (steps `h`, non-zero).
    pub(crate) fn cold(
        x0: Vector2<f64>,
        h: Vector2<f64>,
        tol: f64,
        max_evaluations: usize,
    ) -> Self {
        Self::new(x0, h, None, tol, max_evaluations)
    }

    /// Warm start from `x0` with the previous solve's Jacobian. A singular or non-finite
    /// Jacobian is replaced by differences with steps `1e-4 max(1, |x0_i|)`.
    pub(crate) fn warm(
        x0: Vector2<f64>,
        jacobian: Matrix2<f64>,
        tol: f64,
        max_evaluations: usize,
    ) -> Self {
        let h = x0.map(|v| FALLBACK_REL_STEP * v.abs().max(1.0));
        let usable = jacobian.iter().all(|v| v.is_finite()) && jacobian.try_inverse().is_some();
        Self::new(x0, h, usable.then_some(jacobian), tol, max_evaluations)
    }

    /// Residual evaluations so far.
    pub(crate) fn evaluations(&self) -> usize {
        self.evaluations
    }

    /// The best trial `(x, r)` so far (smallest max-norm).
    pub(crate) fn best(&self) -> Option<(Vector2<f64>, Vector2<f64>)> {
        self.best
    }

    /// The current Jacobian estimate.
    pub(crate) fn jacobian(&self) -> Option<Matrix2<f64>> {
        self.jacobian
    }

    fn evaluate<O>(&mut self, problem: &mut Problem<O>, x: &Vector2<f64>) -> Option<Vector2<f64>>
    where
        O: Operator<Param = Vector2<f64>, Output = Vector2<f64>>,
    {
        self.evaluations += 1;
        let r = match problem.apply(x) {
            Ok(r) if r.iter().all(|v| v.is_finite()) => r,
            // a non-finite residual or a failed trial
            _ => return None,
        };
        if self.best.is_none_or(|(_, b)| r.amax() < b.amax()) {
            self.best = Some((*x, r));
        }
        Some(r)
    }

    fn status(&self) -> Option<TerminationReason> {
        if let Some(why) = self.exit {
            return Some(TerminationReason::SolverExit(why.into()));
        }
        let (_, r) = self.best?;
        if r.amax() <= self.tol {
            Some(TerminationReason::SolverConverged)
        } else if self.evaluations >= self.max_evaluations {
            Some(TerminationReason::MaxItersReached)
        } else {
            None
        }
    }

    fn state_of(&self, state: State2) -> State2 {
        let (x, r) = self.best.unwrap_or((self.x, self.r));
        let state = state.param(x).cost(r.amax()).residuals(r);
        let state = match self.jacobian {
            Some(j) => state.jacobian(j),
            None => state,
        };
        match self.status() {
            Some(reason) => state.terminate_with(reason),
            None => state,
        }
    }

    /// The next trial point (setting up the step), or `None` if stuck.
    fn propose(&mut self) -> Option<Vector2<f64>> {
        loop {
            match self.phase {
                Phase::Difference { column, tries } => {
                    let sign = if tries % 2 == 0 { 1.0 } else { -1.0 };
                    let h = sign * self.h[column] * 0.5f64.powi((tries / 2) as i32);
                    let mut x = self.x;
                    x[column] += h;
                    return (x != self.x).then_some(x);
                }
                Phase::Newton => {
                    let Some(j) = self.jacobian else {
                        self.phase = Phase::Difference {
                            column: 0,
                            tries: 0,
                        };
                        continue;
                    };
                    let step = j.try_inverse().map(|inv| -(inv * self.r));
                    match step {
                        Some(s) if s.iter().all(|v| v.is_finite()) => {
                            self.step = s;
                            self.step_fresh = self.fresh;
                            let x = self.x + s;
                            return (x != self.x).then_some(x);
                        }
                        _ if !self.fresh => {
                            self.phase = Phase::Difference {
                                column: 0,
                                tries: 0,
                            };
                        }
                        _ => return None,
                    }
                }
                Phase::Backtrack { lambda, .. } => {
                    let x = self.x + self.step * lambda;
                    return (x != self.x).then_some(x);
                }
            }
        }
    }

    /// The current step was rejected: halve it, or refresh `J`, or give up.
    fn reject(&mut self, halvings: u32, lambda: f64) {
        let limit = if self.step_fresh {
            self.max_halvings
        } else {
            2
        };
        if halvings < limit {
            self.phase = Phase::Backtrack {
                lambda: 0.5 * lambda,
                halvings: halvings + 1,
            };
        } else if !self.step_fresh {
            self.phase = Phase::Difference {
                column: 0,
                tries: 0,
            };
        } else {
            self.exit = Some("no decrease along the Newton direction");
        }
    }
}

impl<O> Solver<O, State2> for Broyden2
where
    O: Operator<Param = Vector2<f64>, Output = Vector2<f64>>,
{
    fn name(&self) -> &str {
        "Broyden2"
    }

    fn init(
        &mut self,
        problem: &mut Problem<O>,
        state: State2,
    ) -> Result<(State2, Option<KV>), ArgminError> {
        if self.tol.is_nan() || self.tol < 0.0 {
            return Err(ShootingError::BadTolerance(self.tol).into());
        }
        if self.max_evaluations == 0 {
            return Err(ShootingError::NoBudget.into());
        }
        if !self.x.iter().all(|v| v.is_finite()) {
            return Err(ShootingError::BadStart("x0 is not finite").into());
        }
        if !self.h.iter().all(|v| v.is_finite() && *v != 0.0) {
            return Err(
                ShootingError::BadStart("difference steps must be finite and non-zero").into(),
            );
        }
        let x = self.x;
        match self.evaluate(problem, &x) {
            Some(r) => self.r = r,
            None => self.exit = Some("residual failed at the start point"),
        }
        self.phase = match self.jacobian {
            Some(_) => Phase::Newton,
            None => Phase::Difference {
                column: 0,
                tries: 0,
            },
        };
        Ok((self.state_of(state), None))
    }

    fn next_iter(
        &mut self,
        problem: &mut Problem<O>,
        state: State2,
    ) -> Result<(State2, Option<KV>), ArgminError> {
        if self.status().is_some() {
            return Ok((self.state_of(state), None));
        }
        let Some(trial) = self.propose() else {
            self.exit = Some("no further progress possible");
            return Ok((self.state_of(state), None));
        };
        let rt = self.evaluate(problem, &trial);
        match self.phase {
            Phase::Difference { column, tries } => match rt {
                Some(rt) => {
                    let h = trial[column] - self.x[column];
                    self.difference.set_column(column, &((rt - self.r) / h));
                    if column == 0 {
                        self.phase = Phase::Difference {
                            column: 1,
                            tries: 0,
                        };
                    } else {
                        self.jacobian = Some(self.difference);
                        self.fresh = true;
                        self.phase = Phase::Newton;
                    }
                }
                None if tries < 2 * self.max_halvings => {
                    self.phase = Phase::Difference {
                        column,
                        tries: tries + 1,
                    };
                }
                None => self.exit = Some("repeated failed difference trials"),
            },
            Phase::Newton | Phase::Backtrack { .. } => {
                let (lambda, halvings) = match self.phase {
                    Phase::Backtrack { lambda, halvings } => (lambda, halvings),
                    _ => (1.0, 0),
                };
                match rt {
                    Some(rt) => {
                        let dx = trial - self.x;
                        if let Some(j) = self.jacobian.as_mut() {
                            // Broyden's update in unknowns scaled by the residual they move
                            // (the Jacobian's column norms): scale-invariant, where the plain
                            // update in (τ1 in N m, p in m) corrects the τ1 column only
                            let w = Vector2::new(
                                j.column(0).norm_squared(),
                                j.column(1).norm_squared(),
                            );
                            let wdx = w.component_mul(&dx);
                            *j += (rt - self.r - *j * dx) * wdx.transpose() / dx.dot(&wdx);
                            self.fresh = false;
                        }
                        if rt.norm() <= (1.0 - 1e-4 * lambda) * self.r.norm() {
                            self.x = trial;
                            self.r = rt;
                            self.phase = Phase::Newton;
                        } else {
                            self.reject(halvings, lambda);
                        }
                    }
                    None => self.reject(halvings, lambda),
                }
            }
        }
        Ok((self.state_of(state), None))
    }

    fn terminate(&mut self, _state: &State2) -> TerminationStatus {
        match self.status() {
            Some(reason) => TerminationStatus::Terminated(reason),
            None => TerminationStatus::NotTerminated,
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::control::shooting::{Memory2, SolveOptions, Start2, solve2};
    use crate::numerics::ode::IntegrationError;
    use nalgebra::{Matrix2, Vector2};
    use proptest::prelude::*;
    use std::cell::Cell;

    /// Broyden's update in unknowns scaled by the Jacobian's column norms: rescaling the
    /// unknowns (by powers of two, exact in floating point) changes neither the trials nor the
    /// solution, as it would with the plain update (the stance's τ1 in N m and p in m).
    #[test]
    fn broyden_is_invariant_under_rescaled_unknowns() {
        let r = |x: Vector2<f64>| {
            Vector2::new(
                x[0] + 0.3 * x[1] + 0.2 * x[0] * x[1] - 1.0,
                0.5 * x[0] - x[1] + 0.1 * x[1] * x[1] + 0.3,
            )
        };
        // the exact Jacobian at the start, 20 % off in its second column
        let x0 = Vector2::new(0.5, 0.5);
        let j0 = Matrix2::new(
            1.0 + 0.2 * x0[1],
            1.2 * (0.3 + 0.2 * x0[0]),
            0.5,
            1.2 * (-1.0 + 0.2 * x0[1]),
        );
        let solve = |scale: Vector2<f64>| {
            let start = Start2::Warm(Memory2 {
                x: x0.component_div(&scale),
                jacobian: j0 * Matrix2::from_diagonal(&scale),
                earlier: [Vector2::repeat(f64::NAN); 2],
                ratio: f64::NAN,
            });
            let (y, rep, _) = solve2(
                |y: Vector2<f64>| Ok(r(y.component_mul(&scale))),
                start,
                &SolveOptions::default(),
            )
            .unwrap();
            (y.component_mul(&scale), rep)
        };
        let (x, rep) = solve(Vector2::new(1.0, 1.0));
        assert!(rep.converged && r(x).amax() <= 1e-8, "{rep:?}");
        for scale in [[1024.0, 1.0 / 1024.0], [1.0 / 64.0, 4096.0]] {
            let (xs, reps) = solve(Vector2::from(scale));
            assert_eq!(reps.iterations, rep.iterations, "{scale:?}");
            assert_eq!(xs, x, "{scale:?}");
        }
    }

    fn mild(c: f64) -> impl Fn(Vector2<f64>) -> Result<Vector2<f64>, IntegrationError> {
        move |x: Vector2<f64>| {
            Ok(Vector2::new(
                x[0] + 0.3 * x[1] + 0.1 * x[0] * x[0] - c,
                0.2 * x[0] + x[1] - 0.05 * x[1].powi(3) - 0.15,
            ))
        }
    }

    /// Root of `mild(c)` by Newton's method with the analytic Jacobian.
    fn mild_root(c: f64) -> Vector2<f64> {
        let mut x = Vector2::zeros();
        for _ in 0..50 {
            let r = mild(c)(x).unwrap();
            let j = Matrix2::new(1.0 + 0.2 * x[0], 0.3, 0.2, 1.0 - 0.15 * x[1] * x[1]);
            x -= j.try_inverse().unwrap() * r;
        }
        x
    }

    fn cold2(x0: [f64; 2], h: f64) -> Start2 {
        Start2::Cold {
            x0: Vector2::new(x0[0], x0[1]),
            h: Vector2::repeat(h),
        }
    }

    #[test]
    fn mild_system_cold() {
        let root = mild_root(1.1);
        assert!(mild(1.1)(root).unwrap().amax() < 1e-14);
        let (x, rep, _) =
            solve2(mild(1.1), cold2([0.0, 0.0], 1e-6), &SolveOptions::default()).unwrap();
        println!("mild cold: {rep:?}, root {root:?}");
        assert!(rep.converged && (x - root).amax() < 1e-9, "{x:?} {rep:?}");
        assert!(rep.iterations <= 10, "{rep:?}");
    }

    #[test]
    fn mild_system_warm_from_perturbed() {
        let (_, cold, mem) =
            solve2(mild(1.1), cold2([0.0, 0.0], 1e-6), &SolveOptions::default()).unwrap();
        let (x, warm, _) = solve2(mild(1.15), Start2::Warm(mem), &SolveOptions::default()).unwrap();
        println!("mild: cold {cold:?}, warm (perturbed) {warm:?}");
        assert!(
            warm.converged && (x - mild_root(1.15)).amax() < 1e-9,
            "{warm:?}"
        );
        assert!(warm.iterations <= 6, "{warm:?}");
    }

    #[test]
    fn rosenbrock_systems() {
        // Rosenbrock's function as a residual system (Dennis & Schnabel): r = (10 (y - x^2), 1 - x).
        let r = |v: Vector2<f64>| Ok(Vector2::new(10.0 * (v[1] - v[0] * v[0]), 1.0 - v[0]));
        let one = Vector2::new(1.0, 1.0);
        for start in [[0.0, 1.0], [0.9, 0.8], [2.0, 2.0]] {
            let (x, rep, _) = solve2(r, cold2(start, 1e-7), &SolveOptions::default()).unwrap();
            println!("rosenbrock residuals from {start:?}: {rep:?}");
            assert!(rep.converged && (x - one).amax() < 1e-9, "{x:?} {rep:?}");
            assert!(rep.iterations <= 25);
        }
        // From the classic (-1.2, 1) the monotone ||r|| acceptance creeps along the curved
        // valley: it converges, but needs a larger budget.
        let big = SolveOptions {
            tol: 1e-9,
            max_iterations: 100,
        };
        let (x, rep, _) = solve2(r, cold2([-1.2, 1.0], 1e-7), &big).unwrap();
        println!("rosenbrock residuals from (-1.2, 1): {rep:?}");
        assert!(rep.converged && (x - one).amax() < 1e-9, "{x:?} {rep:?}");
        // Gradient of the Rosenbrock function (a = 1, b = 100): root (1, 1).
        let g = |v: Vector2<f64>| {
            let (x, y) = (v[0], v[1]);
            Ok(Vector2::new(
                -2.0 * (1.0 - x) - 400.0 * x * (y - x * x),
                200.0 * (y - x * x),
            ))
        };
        let (x, rep, _) = solve2(g, cold2([1.05, 1.1], 1e-7), &SolveOptions::default()).unwrap();
        println!("rosenbrock gradient from (1.05, 1.1): {rep:?}");
        assert!(rep.converged && (x - one).amax() < 1e-9, "{x:?} {rep:?}");
        assert!(rep.iterations <= 25);
        // From (1.2, 1.2) the gradient norm is a poor merit function: the budget runs out, the
        // report says so, and the best point is far better than the start.
        let (x, rep, _) = solve2(g, cold2([1.2, 1.2], 1e-7), &SolveOptions::default()).unwrap();
        println!("rosenbrock gradient from (1.2, 1.2): {rep:?}");
        assert!(rep.iterations <= 25);
        assert_eq!(rep.converged, rep.residual <= 1e-9);
        assert!((rep.residual - g(x).unwrap().amax()).abs() < 1e-12);
        assert!(rep.residual < 0.01 * g(Vector2::new(1.2, 1.2)).unwrap().amax());
    }

    #[test]
    fn step_halving_rescues_overshoot() {
        // Newton on atan from 3 overshoots to -9.5 where |atan| is larger: halving is needed.
        let trials = std::cell::RefCell::new(Vec::new());
        let r = |v: Vector2<f64>| {
            trials.borrow_mut().push(v);
            Ok(Vector2::new(v[0].atan(), v[1]))
        };
        let (x, rep, _) = solve2(r, cold2([3.0, 0.5], 1e-6), &SolveOptions::default()).unwrap();
        println!("atan: {rep:?}");
        assert!(rep.converged && x.amax() < 1e-9, "{x:?} {rep:?}");
        assert_eq!(trials.borrow().len(), rep.iterations);
        // The full step landed beyond -9 (rejected), a halved one was taken.
        assert!(trials.borrow()[3][0] < -9.0, "{:?}", trials.borrow());
        assert!(trials.borrow()[4][0] > -9.0);
        // Without halving the full Newton iteration diverges.
        let mut y: f64 = 3.0;
        for _ in 0..5 {
            y -= y.atan() * (1.0 + y * y);
        }
        assert!(y.abs() > 1e3);
    }

    #[test]
    fn two_d_failures_and_budget() {
        // No root: budget respected, not converged.
        let calls = Cell::new(0usize);
        let r = |v: Vector2<f64>| {
            calls.set(calls.get() + 1);
            Ok(Vector2::new(v[0] * v[0] + 1.0, v[1]))
        };
        let (_, rep, _) = solve2(r, cold2([2.0, 1.0], 1e-6), &SolveOptions::default()).unwrap();
        assert!(
            !rep.converged && rep.iterations <= 25 && calls.get() == rep.iterations,
            "{rep:?}"
        );
        // NaN beyond x0 > 2: the overshooting step is halved back.
        let r = |v: Vector2<f64>| {
            Ok(if v[0] > 2.0 {
                Vector2::repeat(f64::NAN)
            } else {
                Vector2::new(v[0].exp() - 5.0, v[1] - v[0])
            })
        };
        let (x, rep, _) = solve2(r, cold2([-2.0, 0.0], 1e-6), &SolveOptions::default()).unwrap();
        assert!(
            rep.converged && (x[0] - 5f64.ln()).abs() < 1e-9,
            "{x:?} {rep:?}"
        );
        assert!(
            solve2(
                |_| Err(IntegrationError::NonFinite { t: 0.0 }),
                cold2([0.0, 0.0], 1e-6),
                &SolveOptions::default()
            )
            .is_err()
        );
    }

    proptest! {
        /// Linear systems: the difference Jacobian is exact (up to rounding), so a cold start
        /// takes r(x0), two difference trials and one Newton step: exactly 4 evaluations.
        #[test]
        fn linear_systems_cold_in_four(
            a in prop::array::uniform4(-2.0f64..2.0),
            b in prop::array::uniform2(-10.0f64..10.0),
            x0 in prop::array::uniform2(-10.0f64..10.0),
        ) {
            let m = Matrix2::new(a[0], a[1], a[2], a[3]) + Matrix2::identity() * 3.0;
            let sv = m.singular_values();
            prop_assume!(sv.max() / sv.min() < 20.0);
            let bv = Vector2::new(b[0], b[1]);
            let r = |x: Vector2<f64>| Ok(m * x - bv);
            let (x, rep, _) = solve2(r, cold2(x0, 1.0), &SolveOptions::default()).unwrap();
            let root = m.try_inverse().unwrap() * bv;
            prop_assert!(rep.converged, "{:?}", rep);
            prop_assert_eq!(rep.iterations, 4);
            prop_assert!((x - root).amax() < 1e-9);
        }
    }
}
