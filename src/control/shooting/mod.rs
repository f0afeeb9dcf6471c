//! Shooting solvers: find the force and torque magnitudes of a phase so that its
//! end-condition residual vanishes.
//!
//! Each phase of a simulated step is a boundary-value problem. KLAW (Bruderlin & Calvert 1989,
//! section 4.1) solves it by shooting: guess the magnitudes, integrate the phase, compare the
//! end state with the required one, correct the guess. The paper's 1-D scheme is *bisection
//! first, to bracket and approach the root, then the secant method*, and it reports that "a
//! solution is usually obtained within a few iterations (between 6 and 10)". Where two
//! magnitudes are coupled we use the secant method in two dimensions, Broyden's "good" method
//! (C. G. Broyden, "A class of methods for solving nonlinear simultaneous equations",
//! Math. Comp. 19, 1965).
//!
//! Cost is measured in **residual evaluations** (one evaluation = one trial integration,
//! finite-difference trials included); every solver here performs exactly one evaluation per
//! iteration after `init`, which performs one, and treats its evaluation budget as a hard cap.
//! A non-finite residual, or an `Err` from the residual, is a failed trial: the solvers step back
//! toward the last good point and never panic.
//!
//! The two solvers are [`argmin`] solvers (`BisectionSecant`, `Broyden2`); `solve1` and
//! `solve2` drive them directly (without the `Executor`) for the engine and return the best
//! point, a [`SolveReport`] and a memory for the next step's warm start:
//! - `bisection_secant`: `BisectionSecant`, the paper's 1-D scheme;
//! - `broyden`: `Broyden2`, the 2-D secant method;
//! - `warm_start`: what a solve remembers ([`Memory1`], [`Memory2`]) and how the next one starts
//!   from it ([`Start1`], [`Start2`]), extrapolated along the step sequence.

use std::cell::Cell;

use argmin::core::{CostFunction, Error as ArgminError, Operator, Problem, Solver, State};
use nalgebra::{Matrix2, Vector2};
use thiserror::Error;

use crate::numerics::ode::IntegrationError;

mod bisection_secant;
mod broyden;
mod warm_start;

pub(crate) use bisection_secant::BisectionSecant;
pub(crate) use broyden::Broyden2;
pub use warm_start::{Memory1, Memory2, Start1, Start2, step_ratio};

use warm_start::extrapolate;

/// Invalid solver parameters, or a start point where nothing can be done.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ShootingError {
    /// The tolerance must be a non-negative number.
    #[error("shooting: tolerance must be non-negative, got {0}")]
    BadTolerance(f64),
    /// The evaluation budget must allow at least one evaluation.
    #[error("shooting: the evaluation budget must be at least 1")]
    NoBudget,
    /// Start point, initial step or finite-difference steps are not finite (or a step is zero).
    #[error("shooting: bad start: {0}")]
    BadStart(&'static str),
}

/// Why a shooting solve (`solve1`, `solve2`) returned no point.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SolveError {
    /// Invalid options or start point.
    #[error(transparent)]
    Shooting(#[from] ShootingError),
    /// The trial at the start point failed (and no later one succeeded): there is nothing to step
    /// back to.
    #[error("residual failed at the start point: {0}")]
    StartFailed(#[source] IntegrationError),
}

/// SolveOptions of [`solve1`] and [`solve2`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SolveOptions {
    /// Absolute tolerance on the residual: converged when `max |r_i| <= tol`.
    pub(crate) tol: f64,
    /// Hard cap on residual evaluations (trial integrations, finite-difference trials included).
    pub(crate) max_iterations: usize,
}

impl Default for SolveOptions {
    fn default() -> Self {
        SolveOptions {
            tol: 1e-9,
            max_iterations: 25,
        }
    }
}

/// Outcome of one shooting solve.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct SolveReport {
    /// Residual evaluations spent (trial integrations, finite-difference trials included).
    pub iterations: usize,
    /// Max-norm of the residual at the returned point (`inf` if no trial was finite).
    pub residual: f64,
    /// `residual <= tol`.
    pub converged: bool,
}

/// A closure residual as an argmin problem, which keeps the error of the last failed trial (for
/// [`SolveError::StartFailed`]: argmin's errors are type-erased).
struct Residual<'a, R> {
    residual: R,
    failed: &'a Cell<Option<IntegrationError>>,
}

impl<R> Residual<'_, R> {
    fn trial<T>(&self, r: Result<T, IntegrationError>) -> Result<T, ArgminError> {
        r.map_err(|e| {
            self.failed.set(Some(e));
            ArgminError::new(e)
        })
    }
}

/// `f64 -> f64` as an argmin cost function.
impl<R: Fn(f64) -> Result<f64, IntegrationError>> CostFunction for Residual<'_, R> {
    type Param = f64;
    type Output = f64;
    fn cost(&self, x: &f64) -> Result<f64, ArgminError> {
        self.trial((self.residual)(*x))
    }
}

/// `R^2 -> R^2` as an argmin operator.
impl<R: Fn(Vector2<f64>) -> Result<Vector2<f64>, IntegrationError>> Operator for Residual<'_, R> {
    type Param = Vector2<f64>;
    type Output = Vector2<f64>;
    fn apply(&self, x: &Vector2<f64>) -> Result<Vector2<f64>, ArgminError> {
        self.trial((self.residual)(*x))
    }
}

/// Drive a solver from `init` until it terminates (argmin's Executor without its per-iteration
/// bookkeeping: observers, timers and key-value logs the shooting loop does not use).
fn run_to_end<O, S, I>(solver: &mut S, problem: &mut Problem<O>) -> Result<(), ShootingError>
where
    S: Solver<O, I>,
    I: State,
{
    // the two solvers fail only in `init`, with a ShootingError (a failed trial is not an error)
    let shooting = |e: ArgminError| {
        e.downcast::<ShootingError>()
            .expect("the shooting solvers fail only with a ShootingError")
    };
    let (mut state, _) = solver.init(problem, I::new()).map_err(shooting)?;
    while !state.terminated() {
        state = solver.next_iter(problem, state).map_err(shooting)?.0;
    }
    Ok(())
}

/// Solve `residual(x) = 0` for one unknown with [`BisectionSecant`].
///
/// Returns the best point found (smallest `|r|`), a report (`iterations` = residual
/// evaluations, at most `opts.max_iterations`) and the memory for a warm start. Not converging
/// is not an error (`converged == false`). `Err` for invalid options or start, or when the
/// residual returned `Err` at the start point (nothing to step back to).
pub(crate) fn solve1<R: Fn(f64) -> Result<f64, IntegrationError>>(
    residual: R,
    start: Start1,
    opts: &SolveOptions,
) -> Result<(f64, SolveReport, Memory1), SolveError> {
    let mut solver = match start {
        Start1::Cold { x0, dx } => BisectionSecant::cold(x0, dx, opts.tol, opts.max_iterations),
        Start1::Warm(m) => BisectionSecant::warm(
            extrapolate([m.x], [[m.earlier[0]], [m.earlier[1]]], m.ratio)[0],
            m.slope,
            opts.tol,
            opts.max_iterations,
        ),
    };
    let earlier = match start {
        Start1::Cold { .. } => [f64::NAN; 2],
        Start1::Warm(m) => [m.x, m.earlier[0]],
    };
    let failed = Cell::new(None);
    let mut problem = Problem::new(Residual {
        residual,
        failed: &failed,
    });
    run_to_end(&mut solver, &mut problem)?;
    let Some((x, f)) = solver.best() else {
        return match failed.get() {
            Some(e) => Err(SolveError::StartFailed(e)),
            None => {
                let x = match start {
                    Start1::Cold { x0, .. } => x0,
                    Start1::Warm(m) => m.x,
                };
                let report = SolveReport {
                    iterations: solver.evaluations(),
                    residual: f64::INFINITY,
                    converged: false,
                };
                Ok((
                    x,
                    report,
                    Memory1 {
                        x,
                        slope: f64::NAN,
                        earlier,
                        ratio: f64::NAN,
                    },
                ))
            }
        };
    };
    let report = SolveReport {
        iterations: solver.evaluations(),
        residual: f.abs(),
        converged: f.abs() <= opts.tol,
    };
    Ok((
        x,
        report,
        Memory1 {
            x,
            slope: solver.slope(),
            earlier,
            ratio: f64::NAN,
        },
    ))
}

/// Solve `residual(x) = 0` for two unknowns with [`Broyden2`].
///
/// Returns the best point found (smallest max-norm of `r`), a report (`iterations` = residual
/// evaluations, difference trials included, at most `opts.max_iterations`) and the memory for a
/// warm start. Not converging is not an error (`converged == false`). `Err` for invalid
/// options or start, or when the residual returned `Err` at the start point.
pub(crate) fn solve2<R: Fn(Vector2<f64>) -> Result<Vector2<f64>, IntegrationError>>(
    residual: R,
    start: Start2,
    opts: &SolveOptions,
) -> Result<(Vector2<f64>, SolveReport, Memory2), SolveError> {
    let (mut solver, x0) = match start {
        Start2::Cold { x0, h } => (Broyden2::cold(x0, h, opts.tol, opts.max_iterations), x0),
        Start2::Warm(m) => {
            let x = extrapolate(
                m.x.into(),
                [m.earlier[0].into(), m.earlier[1].into()],
                m.ratio,
            );
            let x = Vector2::from(x);
            (
                Broyden2::warm(x, m.jacobian, opts.tol, opts.max_iterations),
                x,
            )
        }
    };
    let earlier = match start {
        Start2::Cold { .. } => [Vector2::repeat(f64::NAN); 2],
        Start2::Warm(m) => [m.x, m.earlier[0]],
    };
    let failed = Cell::new(None);
    let mut problem = Problem::new(Residual {
        residual,
        failed: &failed,
    });
    run_to_end(&mut solver, &mut problem)?;
    let jacobian = solver.jacobian().unwrap_or(Matrix2::repeat(f64::NAN));
    let Some((x, r)) = solver.best() else {
        return match failed.get() {
            Some(e) => Err(SolveError::StartFailed(e)),
            None => {
                let report = SolveReport {
                    iterations: solver.evaluations(),
                    residual: f64::INFINITY,
                    converged: false,
                };
                Ok((
                    x0,
                    report,
                    Memory2 {
                        x: x0,
                        jacobian,
                        earlier,
                        ratio: f64::NAN,
                    },
                ))
            }
        };
    };
    let residual = r.amax();
    let report = SolveReport {
        iterations: solver.evaluations(),
        residual,
        converged: residual <= opts.tol,
    };
    Ok((
        x,
        report,
        Memory2 {
            x,
            jacobian,
            earlier,
            ratio: f64::NAN,
        },
    ))
}
