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
//! The two solvers are [`argmin`] solvers ([`BisectionSecant`], [`Broyden2`]); [`solve1`] and
//! [`solve2`] drive them directly (without the `Executor`) for the engine and return the best
//! point, a [`SolveReport`] and a memory for the next step's warm start.

use argmin::core::{
    CostFunction, Error as ArgminError, IterState, KV, Operator, Problem, Solver, State,
    TerminationReason, TerminationStatus,
};
use nalgebra::{Matrix2, Vector2};
use thiserror::Error;

/// Relative step used when a warm start carries no usable slope or Jacobian.
const FALLBACK_REL_STEP: f64 = 1e-4;

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

/// Options of [`solve1`] and [`solve2`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Absolute tolerance on the residual: converged when `max |r_i| <= tol`.
    pub tol: f64,
    /// Hard cap on residual evaluations (trial integrations, finite-difference trials included).
    pub max_iterations: usize,
}

impl Default for Options {
    fn default() -> Self {
        Options {
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

/// What a 1-D solve remembers for the next step's warm start.
#[derive(Clone, Copy, Debug)]
pub struct Memory1 {
    /// The returned point.
    pub x: f64,
    /// The last secant slope estimate `dr/dx` (NaN if none was formed).
    pub slope: f64,
    /// The points returned by the two solves before this one (NaN if none).
    pub earlier: [f64; 2],
    /// The step ratio λ to extrapolate with ([`extrapolate`]; NaN: from `earlier`).
    pub ratio: f64,
}

/// What a 2-D solve remembers: the solution and the last Broyden Jacobian.
#[derive(Clone, Copy, Debug)]
pub struct Memory2 {
    /// The returned point.
    pub x: Vector2<f64>,
    /// The last Jacobian estimate (NaN entries if none was formed).
    pub jacobian: Matrix2<f64>,
    /// The points returned by the two solves before this one (NaN if none).
    pub earlier: [Vector2<f64>; 2],
    /// The step ratio λ to extrapolate with ([`extrapolate`]; NaN: from `earlier`).
    pub ratio: f64,
}

/// The next solution predicted from the last three of a sequence converging geometrically:
/// x + λ (x − x₋₁), λ the ratio of the last two differences (least squares over the components,
/// each relative to its own size) unless `ratio` gives it, clipped to [−0.5, 0.5]; `x` itself
/// when the history is incomplete. Successive steps of a walk approach the limit cycle with one
/// ratio for all its unknowns, λ ≈ −0.04 to −0.15 over the grid of `tests/walk.rs`.
fn extrapolate<const D: usize>(x: [f64; D], earlier: [[f64; D]; 2], ratio: f64) -> [f64; D] {
    let lambda = if ratio.is_finite() {
        ratio
    } else {
        step_ratio(x, earlier)
    };
    if !(lambda.is_finite() && earlier[0].iter().all(|v| v.is_finite())) {
        return x;
    }
    let lambda = lambda.clamp(-0.5, 0.5);
    let mut out = x;
    for i in 0..D {
        out[i] += lambda * (x[i] - earlier[0][i]);
    }
    out
}

/// The ratio λ of the last two differences of a sequence ending x₋₂, x₋₁, x (`earlier` =
/// [x₋₁, x₋₂]): least squares over the components, each relative to its own size; NaN when the
/// history is incomplete or constant.
pub fn step_ratio<const D: usize>(x: [f64; D], earlier: [[f64; D]; 2]) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for i in 0..D {
        let (d1, d0) = (x[i] - earlier[0][i], earlier[0][i] - earlier[1][i]);
        let w = 1.0 / x[i].abs().max(1e-12).powi(2);
        num += w * d1 * d0;
        den += w * d0 * d0;
    }
    if den > 0.0 { num / den } else { f64::NAN }
}

/// How a 1-D solve starts.
#[derive(Clone, Copy, Debug)]
pub enum Start1 {
    /// From `x0`, with `dx` the scale of the unknown (the first trial is `x0 + dx`).
    Cold { x0: f64, dx: f64 },
    /// From the previous solve's memory: a Newton-like step with the remembered slope.
    Warm(Memory1),
}

/// How a 2-D solve starts.
#[derive(Clone, Copy, Debug)]
pub enum Start2 {
    /// From `x0` with a forward-difference Jacobian, step `h[i]` for unknown `i`.
    Cold { x0: Vector2<f64>, h: Vector2<f64> },
    /// From the previous solve's memory: its point and Jacobian, no finite-difference trials.
    Warm(Memory2),
}

// ---------------------------------------------------------------------------------------------
// 1-D: bisection, then secant
// ---------------------------------------------------------------------------------------------

/// A finite residual sample.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Point {
    x: f64,
    f: f64,
}

/// What the last trial of [`BisectionSecant`] was.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    /// The start point (init).
    Start,
    /// Bracket search: secant step capped by geometric expansion (or the first trial).
    Search,
    /// Secant step inside the bracket.
    Secant,
    /// Illinois (modified regula falsi) step inside the bracket.
    Illinois,
    /// Bisection of the bracket.
    Bisect,
    /// Halfway back toward the best point after a failed trial.
    Retreat,
}

/// The 1-D shooting solver of KLAW (Bruderlin & Calvert 1989, section 4.1): "bisection first,
/// to bracket and approach the root, then the secant method".
///
/// * **Search** (no sign change known yet): secant steps through the two best samples, moving
///   downhill in `|r|`, each at most twice as long as the previous step, so the step expands
///   geometrically (x2) until the root is bracketed (or a plain secant step lands on it).
/// * **Bracketed**: a secant step through the two best samples when it falls strictly inside
///   the bracket; otherwise an Illinois (modified regula falsi) step; a bisection whenever the
///   previous interpolation step did not at least halve the best `|r|` (the linear model's
///   promise was not kept, so the bracket is still too wide for it).
/// * **Warm start**: from `x0` with the remembered slope a Newton-like step, then the same
///   logic, which is plain secant until a step fails.
///
/// A failed trial (non-finite or `Err` residual) is followed by a trial halfway back toward the
/// best point; later trials stay short of the nearest failed point on either side. Converged
/// when `|r| <= tol`; stops (not converged) when the bracket is narrower than ~1e-14 relative,
/// when a step no longer moves `x`, after `max_failures` consecutive failed trials or when the
/// evaluation budget is spent. Each iteration evaluates the residual exactly once; `init` once.
#[derive(Clone, Debug)]
pub struct BisectionSecant {
    /// Absolute tolerance on `|r|`.
    tol: f64,
    /// Hard cap on residual evaluations, the one in `init` included.
    max_evaluations: usize,
    /// Consecutive failed trials tolerated before giving up.
    max_failures: usize,
    /// Start point.
    x0: f64,
    /// Cold start: first step (scale of the unknown). Warm start: fallback step.
    dx: f64,
    /// Warm start: slope remembered from the previous solve.
    warm_slope: Option<f64>,
    /// Residual evaluations so far.
    evaluations: usize,
    /// Sample with the smallest `|r|`.
    best: Option<Point>,
    /// Sample with the second smallest `|r|`.
    second: Option<Point>,
    /// All finite samples (few: the budget is small).
    samples: Vec<Point>,
    /// Sign-change bracket `(lo, hi)`, `lo.x < hi.x`, if known.
    bracket: Option<(Point, Point)>,
    /// Illinois weights of the bracket ends' residuals.
    weights: (f64, f64),
    /// Bracket end replaced by the last bracketed trial (-1 lo, +1 hi, 0 none).
    last_replaced: i8,
    /// Length of the last successful search step.
    step: f64,
    /// Direction of the last search step (+1 or -1).
    direction: f64,
    /// Kind of the last trial.
    last_kind: Kind,
    /// Best `|r|` before the last trial (progress test).
    best_before: f64,
    /// The last trial failed at this `x`.
    failed_at: Option<f64>,
    /// Nearest failed trial below / above the best point.
    fail_below: Option<f64>,
    fail_above: Option<f64>,
    /// Consecutive failed trials.
    failures: usize,
    /// Message of the last `Err` returned by the residual.
    last_error: Option<String>,
}

impl BisectionSecant {
    fn new(x0: f64, dx: f64, warm_slope: Option<f64>, tol: f64, max_evaluations: usize) -> Self {
        BisectionSecant {
            tol,
            max_evaluations,
            max_failures: 10,
            x0,
            dx,
            warm_slope,
            evaluations: 0,
            best: None,
            second: None,
            samples: Vec::new(),
            bracket: None,
            weights: (1.0, 1.0),
            last_replaced: 0,
            step: dx.abs(),
            direction: if dx < 0.0 { -1.0 } else { 1.0 },
            last_kind: Kind::Start,
            best_before: f64::INFINITY,
            failed_at: None,
            fail_below: None,
            fail_above: None,
            failures: 0,
            last_error: None,
        }
    }

    /// Cold start from `x0`; `dx` (non-zero) is the scale of the unknown: the first trial after
    /// `x0` is `x0 + dx`.
    pub fn cold(x0: f64, dx: f64, tol: f64, max_evaluations: usize) -> Self {
        Self::new(x0, dx, None, tol, max_evaluations)
    }

    /// Warm start from `x0` with the slope `dr/dx` remembered from the previous solve. If the
    /// slope is zero or not finite, the first trial probes `x0 + 1e-4 max(1, |x0|)` instead.
    pub fn warm(x0: f64, slope: f64, tol: f64, max_evaluations: usize) -> Self {
        let dx = FALLBACK_REL_STEP * x0.abs().max(1.0);
        Self::new(x0, dx, Some(slope), tol, max_evaluations)
    }

    /// Consecutive failed trials tolerated before giving up (default 10).
    #[must_use]
    pub fn with_max_failures(mut self, max_failures: usize) -> Self {
        self.max_failures = max_failures;
        self
    }

    /// Residual evaluations so far.
    pub fn evaluations(&self) -> usize {
        self.evaluations
    }

    /// The best sample `(x, r)` so far (smallest `|r|`).
    pub fn best(&self) -> Option<(f64, f64)> {
        self.best.map(|p| (p.x, p.f))
    }

    /// The sign-change bracket `(lo, hi)` if one is known.
    pub fn bracket(&self) -> Option<(f64, f64)> {
        self.bracket.map(|(lo, hi)| (lo.x, hi.x))
    }

    /// The latest slope estimate `dr/dx`: the secant through the two best samples, else the
    /// remembered warm-start slope, else NaN.
    pub fn slope(&self) -> f64 {
        match (self.best, self.second) {
            (Some(a), Some(b)) if a.x != b.x => (b.f - a.f) / (b.x - a.x),
            _ => self.warm_slope.unwrap_or(f64::NAN),
        }
    }

    /// The message of the last `Err` returned by the residual, if any.
    pub fn last_error(&self) -> Option<&str> {
        self.last_error.as_deref()
    }

    fn evaluate<O>(&mut self, problem: &mut Problem<O>, x: f64) -> Option<f64>
    where
        O: CostFunction<Param = f64, Output = f64>,
    {
        self.evaluations += 1;
        match problem.cost(&x) {
            Ok(f) if f.is_finite() => Some(f),
            Ok(_) => None,
            Err(e) => {
                self.last_error = Some(e.to_string());
                None
            }
        }
    }

    /// Secant root through the two best samples.
    fn secant(&self) -> Option<f64> {
        let (a, b) = (self.best?, self.second?);
        let x = a.x - a.f * (b.x - a.x) / (b.f - a.f);
        x.is_finite().then_some(x)
    }

    /// The next trial point, or why there is none.
    fn propose(&self) -> Result<(f64, Kind), &'static str> {
        let best = self.best.ok_or("no finite residual")?;
        if let Some(xf) = self.failed_at {
            let x = 0.5 * (best.x + xf);
            if x == best.x || x == xf {
                return Err("failed trials next to the best point");
            }
            return Ok((x, Kind::Retreat));
        }
        let (x, kind) = if let Some((lo, hi)) = self.bracket {
            let width = hi.x - lo.x;
            let mid = lo.x + 0.5 * width;
            if width <= 1e-14 * lo.x.abs().max(hi.x.abs()) || mid <= lo.x || mid >= hi.x {
                return Err("bracket collapsed");
            }
            let poor = matches!(self.last_kind, Kind::Secant | Kind::Illinois)
                && best.f.abs() > 0.5 * self.best_before;
            let inside = |x: f64| x > lo.x && x < hi.x;
            match self.secant() {
                _ if poor => (mid, Kind::Bisect),
                Some(x) if inside(x) => (x, Kind::Secant),
                _ => {
                    let (flo, fhi) = (lo.f * self.weights.0, hi.f * self.weights.1);
                    let x = (lo.x * fhi - hi.x * flo) / (fhi - flo);
                    if inside(x) {
                        (x, Kind::Illinois)
                    } else {
                        (mid, Kind::Bisect)
                    }
                }
            }
        } else if self.second.is_none() && self.last_kind == Kind::Start {
            match self.warm_slope {
                Some(s) if s != 0.0 && (best.f / s).is_finite() => {
                    (best.x - best.f / s, Kind::Search)
                }
                _ => (best.x + self.dx, Kind::Search),
            }
        } else {
            // Downhill in |r| by the secant through the two best samples, at most twice the last
            // step: geometric expansion until bracketed.
            let limit = 2.0 * self.step;
            match self.secant() {
                Some(xs) if xs != best.x => {
                    let d = xs - best.x;
                    (best.x + d.signum() * d.abs().min(limit), Kind::Search)
                }
                _ => (best.x + self.direction * limit, Kind::Search),
            }
        };
        // Stay short of the nearest failed trials.
        let x = match (self.fail_below, self.fail_above) {
            (_, Some(b)) if b > best.x && x >= b => 0.5 * (best.x + b),
            (Some(b), _) if b < best.x && x <= b => 0.5 * (best.x + b),
            _ => x,
        };
        if !x.is_finite() || self.samples.iter().any(|p| p.x == x) {
            return Err("no further progress possible");
        }
        Ok((x, kind))
    }

    /// Record a finite sample: best two, bracket, Illinois weights.
    fn record(&mut self, p: Point) {
        match (self.best, self.second) {
            (Some(b), _) if p.f.abs() < b.f.abs() => {
                self.second = Some(b);
                self.best = Some(p);
            }
            (None, _) => self.best = Some(p),
            (Some(_), None) => self.second = Some(p),
            (Some(_), Some(s)) if p.f.abs() < s.f.abs() => self.second = Some(p),
            _ => {}
        }
        self.samples.push(p);
        if p.f == 0.0 {
            return;
        }
        match self.bracket {
            Some((lo, hi)) if p.x > lo.x && p.x < hi.x => {
                let side: i8 = if (p.f > 0.0) == (lo.f > 0.0) { -1 } else { 1 };
                if side < 0 {
                    self.bracket = Some((p, hi));
                    self.weights.0 = 1.0;
                    if self.last_replaced == side {
                        self.weights.1 *= 0.5;
                    }
                } else {
                    self.bracket = Some((lo, p));
                    self.weights.1 = 1.0;
                    if self.last_replaced == side {
                        self.weights.0 *= 0.5;
                    }
                }
                self.last_replaced = side;
            }
            Some(_) => {}
            None => {
                // Nearest sample of opposite sign; samples in between share p's sign.
                let opposite = self
                    .samples
                    .iter()
                    .filter(|q| q.f != 0.0 && (q.f > 0.0) != (p.f > 0.0))
                    .min_by(|a, b| (a.x - p.x).abs().total_cmp(&(b.x - p.x).abs()))
                    .copied();
                if let Some(q) = opposite {
                    let near = self
                        .samples
                        .iter()
                        .filter(|r| (r.x - p.x) * (q.x - r.x) >= 0.0 && (r.f > 0.0) == (p.f > 0.0))
                        .min_by(|a, b| (a.x - q.x).abs().total_cmp(&(b.x - q.x).abs()))
                        .copied()
                        .unwrap_or(p);
                    self.bracket = Some(if near.x < q.x { (near, q) } else { (q, near) });
                }
            }
        }
    }

    fn state_of(
        &self,
        state: IterState<f64, (), (), (), (), f64>,
    ) -> IterState<f64, (), (), (), (), f64> {
        match self.best {
            Some(b) => state.param(b.x).cost(b.f.abs()),
            None => state.param(self.x0).cost(f64::INFINITY),
        }
    }

    fn status(&self) -> Option<TerminationReason> {
        let best = self.best?;
        if best.f.abs() <= self.tol {
            Some(TerminationReason::SolverConverged)
        } else if self.evaluations >= self.max_evaluations {
            Some(TerminationReason::MaxItersReached)
        } else {
            None
        }
    }
}

impl<O> Solver<O, IterState<f64, (), (), (), (), f64>> for BisectionSecant
where
    O: CostFunction<Param = f64, Output = f64>,
{
    fn name(&self) -> &str {
        "BisectionSecant"
    }

    fn init(
        &mut self,
        problem: &mut Problem<O>,
        state: IterState<f64, (), (), (), (), f64>,
    ) -> Result<(IterState<f64, (), (), (), (), f64>, Option<KV>), ArgminError> {
        if self.tol.is_nan() || self.tol < 0.0 {
            return Err(ShootingError::BadTolerance(self.tol).into());
        }
        if self.max_evaluations == 0 {
            return Err(ShootingError::NoBudget.into());
        }
        if !self.x0.is_finite() {
            return Err(ShootingError::BadStart("x0 is not finite").into());
        }
        if !self.dx.is_finite() || self.dx == 0.0 {
            return Err(ShootingError::BadStart("dx must be finite and non-zero").into());
        }
        let x0 = self.x0;
        let state = match self.evaluate(problem, x0) {
            Some(f) => {
                self.record(Point { x: x0, f });
                let state = self.state_of(state);
                match self.status() {
                    Some(reason) => state.terminate_with(reason),
                    None => state,
                }
            }
            None => self
                .state_of(state)
                .terminate_with(TerminationReason::SolverExit(
                    "residual failed at the start point".into(),
                )),
        };
        Ok((state, None))
    }

    fn next_iter(
        &mut self,
        problem: &mut Problem<O>,
        state: IterState<f64, (), (), (), (), f64>,
    ) -> Result<(IterState<f64, (), (), (), (), f64>, Option<KV>), ArgminError> {
        if let Some(reason) = self.status() {
            return Ok((self.state_of(state).terminate_with(reason), None));
        }
        let (x, kind) = match self.propose() {
            Ok(p) => p,
            Err(why) => {
                let state = self
                    .state_of(state)
                    .terminate_with(TerminationReason::SolverExit(why.into()));
                return Ok((state, None));
            }
        };
        let from = self.best.map_or(self.x0, |b| b.x);
        self.best_before = self.best.map_or(f64::INFINITY, |b| b.f.abs());
        match self.evaluate(problem, x) {
            Some(f) => {
                self.failures = 0;
                self.failed_at = None;
                self.record(Point { x, f });
                if matches!(kind, Kind::Search | Kind::Retreat) {
                    self.step = (x - from).abs();
                    self.direction = if x < from { -1.0 } else { 1.0 };
                }
                self.last_kind = kind;
            }
            None => {
                self.failures += 1;
                self.failed_at = Some(x);
                if x > from {
                    self.fail_above = Some(self.fail_above.map_or(x, |b| b.min(x)));
                } else {
                    self.fail_below = Some(self.fail_below.map_or(x, |b| b.max(x)));
                }
                if self.failures > self.max_failures {
                    let reason = TerminationReason::SolverExit("repeated failed trials".into());
                    return Ok((self.state_of(state).terminate_with(reason), None));
                }
            }
        }
        let state = self.state_of(state);
        Ok((
            match self.status() {
                Some(reason) => state.terminate_with(reason),
                None => state,
            },
            None,
        ))
    }

    fn terminate(&mut self, _state: &IterState<f64, (), (), (), (), f64>) -> TerminationStatus {
        match self.status() {
            Some(reason) => TerminationStatus::Terminated(reason),
            None => TerminationStatus::NotTerminated,
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 2-D: Broyden
// ---------------------------------------------------------------------------------------------

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
/// by Broyden's rank-1 formula `J += (dr - J dx) dx^T / (dx^T dx)`. A failed trial (non-finite
/// or `Err`) counts as a rejection (a failed difference trial is retried with the opposite,
/// then halved step). Converged when `max |r_i| <= tol` at any trial; that point is returned.
/// Each iteration evaluates the residual exactly once; `init` once.
#[derive(Clone, Debug)]
pub struct Broyden2 {
    /// Absolute tolerance on `max |r_i|`.
    tol: f64,
    /// Hard cap on residual evaluations, the one in `init` included.
    max_evaluations: usize,
    /// Halvings of a rejected step tolerated with a fresh difference Jacobian.
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
    /// Message of the last `Err` returned by the residual.
    last_error: Option<String>,
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
            last_error: None,
        }
    }

    /// Cold start from `x0` with a forward-difference Jacobian (steps `h`, non-zero).
    pub fn cold(x0: Vector2<f64>, h: Vector2<f64>, tol: f64, max_evaluations: usize) -> Self {
        Self::new(x0, h, None, tol, max_evaluations)
    }

    /// Warm start from `x0` with the previous solve's Jacobian. A singular or non-finite
    /// Jacobian is replaced by differences with steps `1e-4 max(1, |x0_i|)`.
    pub fn warm(
        x0: Vector2<f64>,
        jacobian: Matrix2<f64>,
        tol: f64,
        max_evaluations: usize,
    ) -> Self {
        let h = x0.map(|v| FALLBACK_REL_STEP * v.abs().max(1.0));
        let usable = jacobian.iter().all(|v| v.is_finite()) && jacobian.try_inverse().is_some();
        Self::new(x0, h, usable.then_some(jacobian), tol, max_evaluations)
    }

    /// Halvings of a rejected step tolerated with a fresh difference Jacobian (default 8).
    #[must_use]
    pub fn with_max_halvings(mut self, max_halvings: u32) -> Self {
        self.max_halvings = max_halvings;
        self
    }

    /// Residual evaluations so far.
    pub fn evaluations(&self) -> usize {
        self.evaluations
    }

    /// The best trial `(x, r)` so far (smallest max-norm).
    pub fn best(&self) -> Option<(Vector2<f64>, Vector2<f64>)> {
        self.best
    }

    /// The current Jacobian estimate.
    pub fn jacobian(&self) -> Option<Matrix2<f64>> {
        self.jacobian
    }

    /// The message of the last `Err` returned by the residual, if any.
    pub fn last_error(&self) -> Option<&str> {
        self.last_error.as_deref()
    }

    fn evaluate<O>(&mut self, problem: &mut Problem<O>, x: &Vector2<f64>) -> Option<Vector2<f64>>
    where
        O: Operator<Param = Vector2<f64>, Output = Vector2<f64>>,
    {
        self.evaluations += 1;
        let r = match problem.apply(x) {
            Ok(r) if r.iter().all(|v| v.is_finite()) => r,
            Ok(_) => return None,
            Err(e) => {
                self.last_error = Some(e.to_string());
                return None;
            }
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

// ---------------------------------------------------------------------------------------------
// Convenience functions for the engine
// ---------------------------------------------------------------------------------------------

/// A closure residual `f64 -> f64` as an argmin cost function.
struct Residual1<R>(R);

impl<R: Fn(f64) -> Result<f64, String>> CostFunction for Residual1<R> {
    type Param = f64;
    type Output = f64;
    fn cost(&self, x: &f64) -> Result<f64, ArgminError> {
        (self.0)(*x).map_err(ArgminError::msg)
    }
}

/// A closure residual `R^2 -> R^2` as an argmin operator.
struct Residual2<R>(R);

impl<R: Fn(Vector2<f64>) -> Result<Vector2<f64>, String>> Operator for Residual2<R> {
    type Param = Vector2<f64>;
    type Output = Vector2<f64>;
    fn apply(&self, x: &Vector2<f64>) -> Result<Vector2<f64>, ArgminError> {
        (self.0)(*x).map_err(ArgminError::msg)
    }
}

/// Drive a solver from `init` until it terminates (argmin's Executor without its per-iteration
/// bookkeeping: observers, timers and key-value logs the shooting loop does not use).
fn run_to_end<O, S, I>(solver: &mut S, problem: &mut Problem<O>) -> Result<(), String>
where
    S: Solver<O, I>,
    I: State,
{
    let (mut state, _) = solver.init(problem, I::new()).map_err(|e| e.to_string())?;
    while !state.terminated() {
        state = solver
            .next_iter(problem, state)
            .map_err(|e| e.to_string())?
            .0;
    }
    Ok(())
}

/// Solve `residual(x) = 0` for one unknown with [`BisectionSecant`].
///
/// Returns the best point found (smallest `|r|`), a report (`iterations` = residual
/// evaluations, at most `opts.max_iterations`) and the memory for a warm start. Not converging
/// is not an error (`converged == false`). `Err` for invalid options or start, or when the
/// residual returned `Err` at the start point (nothing to step back to).
pub fn solve1<R: Fn(f64) -> Result<f64, String>>(
    residual: R,
    start: Start1,
    opts: &Options,
) -> Result<(f64, SolveReport, Memory1), String> {
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
    let mut problem = Problem::new(Residual1(residual));
    run_to_end(&mut solver, &mut problem)?;
    let Some((x, f)) = solver.best() else {
        return match solver.last_error() {
            Some(msg) => Err(format!("residual failed at the start point: {msg}")),
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
pub fn solve2<R: Fn(Vector2<f64>) -> Result<Vector2<f64>, String>>(
    residual: R,
    start: Start2,
    opts: &Options,
) -> Result<(Vector2<f64>, SolveReport, Memory2), String> {
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
    let mut problem = Problem::new(Residual2(residual));
    run_to_end(&mut solver, &mut problem)?;
    let jacobian = solver.jacobian().unwrap_or(Matrix2::repeat(f64::NAN));
    let Some((x, r)) = solver.best() else {
        return match solver.last_error() {
            Some(msg) => Err(format!("residual failed at the start point: {msg}")),
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

#[cfg(test)]
mod tests {
    use super::*;
    use argmin::core::Executor;
    use argmin::solver::brent::BrentRoot;
    use proptest::prelude::*;
    use std::cell::Cell;

    const CUBIC_ROOT: f64 = 2.094_551_481_542_326_5;

    fn opts() -> Options {
        Options::default()
    }

    fn cubic(c: f64) -> impl Fn(f64) -> Result<f64, String> {
        move |x: f64| Ok(x * x * x - 2.0 * x - c)
    }

    /// Root of x^3 - 2x - c by Newton's method with the analytic derivative.
    fn cubic_root(c: f64) -> f64 {
        let mut x: f64 = 2.0;
        for _ in 0..50 {
            x -= (x * x * x - 2.0 * x - c) / (3.0 * x * x - 2.0);
        }
        x
    }

    fn cold1(x0: f64, dx: f64) -> Start1 {
        Start1::Cold { x0, dx }
    }

    #[test]
    fn cubic_cold() {
        let (x, rep, mem) = solve1(cubic(5.0), cold1(2.0, 1.0), &opts()).unwrap();
        println!("cubic cold: {rep:?}");
        assert!(rep.converged, "{rep:?}");
        assert!((x - CUBIC_ROOT).abs() < 1e-9, "{x}");
        assert!(rep.residual <= 1e-9);
        assert!(rep.iterations <= 8, "{rep:?}");
        // Slope memory close to r'(root) = 3 x^2 - 2.
        assert!(
            (mem.slope - (3.0 * CUBIC_ROOT * CUBIC_ROOT - 2.0)).abs() < 1e-3,
            "{mem:?}"
        );
    }

    #[test]
    fn tanh_cold() {
        let r = |x: f64| Ok(4.0 * (x - 1.3).tanh());
        let (x, rep, _) = solve1(r, cold1(-2.0, 1.0), &opts()).unwrap();
        println!("tanh cold: {rep:?}");
        assert!(rep.converged, "{rep:?}");
        assert!((x - 1.3).abs() < 1e-9, "{x}");
        assert!(rep.iterations <= 10, "{rep:?}");
    }

    #[test]
    fn exp_cold_far() {
        let r = |x: f64| Ok(x.exp() - 10.0);
        let (x, rep, _) = solve1(r, cold1(-5.0, 1.0), &opts()).unwrap();
        println!("exp cold far: {rep:?}");
        assert!(rep.converged, "{rep:?}");
        assert!((x - 10f64.ln()).abs() < 1e-9, "{x}");
        assert!(rep.iterations <= 14, "{rep:?}");
    }

    /// Evaluations of argmin's BrentRoot (stopping at |r| <= tol) on the bracket `[a, b]`.
    fn brent_evaluations<F: Fn(f64) -> f64>(f: F, a: f64, b: f64) -> (f64, usize) {
        struct P<F>(F);
        impl<F: Fn(f64) -> f64> CostFunction for P<F> {
            type Param = f64;
            type Output = f64;
            fn cost(&self, x: &f64) -> Result<f64, ArgminError> {
                Ok((self.0)(*x))
            }
        }
        let res = Executor::new(P(f), BrentRoot::new(a, b, 1e-15))
            .configure(|s| s.max_iters(100).target_cost(1e-9).counting(true))
            .run()
            .unwrap();
        let n = res.state.get_func_counts()["cost_count"] as usize;
        (res.state.best_param.unwrap(), n)
    }

    #[test]
    fn compare_with_brent() {
        // Same bracket: our cold start evaluates a and a + (b - a) first, as Brent's init does.
        type Case = (&'static str, fn(f64) -> f64, f64, f64, f64);
        let cases: [Case; 4] = [
            ("cubic", |x| x * x * x - 2.0 * x - 5.0, 2.0, 3.0, CUBIC_ROOT),
            ("tanh", |x| 4.0 * (x - 1.3).tanh(), -2.0, 4.0, 1.3),
            ("exp", |x| x.exp() - 10.0, 0.0, 5.0, 10f64.ln()),
            ("exp wide", |x| x.exp() - 10.0, -5.0, 10.0, 10f64.ln()),
        ];
        for (name, f, a, b, root) in cases {
            let (xb, nb) = brent_evaluations(f, a, b);
            let (x, rep, _) = solve1(|x| Ok(f(x)), cold1(a, b - a), &opts()).unwrap();
            println!("{name}: ours {} evaluations, Brent {nb}", rep.iterations);
            assert!((xb - root).abs() < 1e-8, "Brent {name}");
            assert!(
                rep.converged && (x - root).abs() < 1e-9,
                "{name}: {x} {rep:?}"
            );
            assert!(
                rep.iterations <= nb + 3,
                "{name}: ours {} vs Brent {nb}",
                rep.iterations
            );
        }
    }

    #[test]
    fn warm_start_is_cheaper() {
        let (_, cold, mem) = solve1(cubic(5.0), cold1(2.0, 1.0), &opts()).unwrap();
        let (x, warm, _) = solve1(cubic(5.1), Start1::Warm(mem), &opts()).unwrap();
        let (_, cold2, _) = solve1(cubic(5.1), cold1(2.0, 1.0), &opts()).unwrap();
        println!("cold {cold:?}, warm {warm:?}, cold on the same problem {cold2:?}");
        assert!(warm.converged);
        assert!((x - cubic_root(5.1)).abs() < 1e-9);
        assert!(warm.iterations <= 4, "{warm:?}");
        assert!(warm.iterations < cold2.iterations);
    }

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
                &opts(),
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

    #[test]
    fn extrapolation_predicts_a_geometric_sequence() {
        // x_n = 3 + (-0.13)^n (1, -2): the next point from the last three, exactly
        let x = |n: i32| {
            let c = (-0.13f64).powi(n);
            [3.0 + c, 5.0 - 2.0 * c]
        };
        let p = extrapolate(x(2), [x(1), x(0)], f64::NAN);
        assert!((p[0] - x(3)[0]).abs() < 1e-12 && (p[1] - x(3)[1]).abs() < 1e-12);
        // no history, or no change: the last point
        assert_eq!(
            extrapolate([1.0], [[f64::NAN], [f64::NAN]], f64::NAN),
            [1.0]
        );
        assert_eq!(extrapolate([1.0], [[1.0], [1.0]], f64::NAN), [1.0]);
        // a ratio beyond ±0.5 is clipped
        assert_eq!(extrapolate([4.0], [[2.0], [1.0]], f64::NAN), [5.0]);
        // a given ratio (another sequence's with the same λ) replaces a history that is not
        // geometric yet, and needs only the last difference
        let y = |n: i32| 7.0 - 4.0 * (-0.13f64).powi(n);
        assert!((step_ratio(x(2), [x(1), x(0)]) + 0.13).abs() < 1e-12);
        let p = extrapolate([y(2)], [[y(1)], [f64::NAN]], -0.13);
        assert!((p[0] - y(3)).abs() < 1e-12);
        assert!(step_ratio([1.0], [[1.0], [1.0]]).is_nan());
    }

    #[test]
    fn warm_start_with_bad_slope_recovers() {
        // A slope of the wrong sign sends the first trial uphill; the secant recovers.
        let mem = Memory1 {
            x: 2.0,
            slope: -10.0,
            earlier: [f64::NAN; 2],
            ratio: f64::NAN,
        };
        let (x, rep, _) = solve1(cubic(5.0), Start1::Warm(mem), &opts()).unwrap();
        println!("warm, wrong slope: {rep:?}");
        assert!(rep.converged && (x - CUBIC_ROOT).abs() < 1e-9, "{rep:?}");
        // No slope at all: a small probe, then secant.
        let mem = Memory1 {
            x: 2.0,
            slope: f64::NAN,
            earlier: [f64::NAN; 2],
            ratio: f64::NAN,
        };
        let (x, rep, _) = solve1(cubic(5.0), Start1::Warm(mem), &opts()).unwrap();
        assert!(rep.converged && (x - CUBIC_ROOT).abs() < 1e-9, "{rep:?}");
    }

    #[test]
    fn nan_region_is_stepped_back_from() {
        let r = |x: f64| Ok(if x > 3.0 { f64::NAN } else { x.exp() - 10.0 });
        let (x, rep, _) = solve1(r, cold1(0.0, 5.0), &opts()).unwrap();
        println!("NaN above 3: {rep:?}");
        assert!(rep.converged, "{rep:?}");
        assert!((x - 10f64.ln()).abs() < 1e-9);
        // The same with a residual that returns Err (failed integration).
        let r = |x: f64| {
            if x > 3.0 {
                Err("integration blew up".to_string())
            } else {
                Ok(x.exp() - 10.0)
            }
        };
        let (x, rep, _) = solve1(r, cold1(0.0, 5.0), &opts()).unwrap();
        assert!(rep.converged && (x - 10f64.ln()).abs() < 1e-9, "{rep:?}");
    }

    #[test]
    fn no_root_respects_budget() {
        let calls = Cell::new(0usize);
        let r = |x: f64| {
            calls.set(calls.get() + 1);
            Ok(x * x + 1.0)
        };
        for max in [1, 2, 5, 25] {
            calls.set(0);
            let o = Options {
                tol: 1e-9,
                max_iterations: max,
            };
            let (x, rep, _) = solve1(r, cold1(3.0, 1.0), &o).unwrap();
            assert!(!rep.converged);
            assert!(
                rep.iterations <= max && calls.get() == rep.iterations,
                "{rep:?}"
            );
            assert!((rep.residual - (x * x + 1.0)).abs() < 1e-12);
        }
    }

    #[test]
    fn always_nan_is_not_converged_and_err_at_start_is_err() {
        let (_, rep, _) = solve1(|_| Ok(f64::NAN), cold1(0.0, 1.0), &opts()).unwrap();
        assert!(!rep.converged && rep.iterations == 1 && rep.residual.is_infinite());
        assert!(solve1(|_| Err("boom".to_string()), cold1(0.0, 1.0), &opts()).is_err());
        assert!(solve1(cubic(5.0), cold1(0.0, 0.0), &opts()).is_err());
        // NaN everywhere but the start: the solver gives up after repeated halvings.
        let r = |x: f64| Ok(if x == 1.0 { 1.0 } else { f64::NAN });
        let (x, rep, _) = solve1(r, cold1(1.0, 1.0), &opts()).unwrap();
        assert!(
            !rep.converged && x == 1.0 && rep.iterations <= 25,
            "{rep:?}"
        );
    }

    #[test]
    fn argmin_executor_runs_bisection_secant() {
        struct P;
        impl CostFunction for P {
            type Param = f64;
            type Output = f64;
            fn cost(&self, x: &f64) -> Result<f64, ArgminError> {
                Ok(x * x * x - 2.0 * x - 5.0)
            }
        }
        let res = Executor::new(P, BisectionSecant::cold(2.0, 1.0, 1e-9, 25))
            .configure(|s| s.counting(true))
            .run()
            .unwrap();
        let x = res.state.best_param.unwrap();
        assert!((x - CUBIC_ROOT).abs() < 1e-9);
        assert_eq!(
            res.state.termination_status,
            TerminationStatus::Terminated(TerminationReason::SolverConverged)
        );
        // One evaluation in init, one per iteration.
        assert_eq!(
            res.state.get_func_counts()["cost_count"],
            res.state.get_iter() + 1
        );
    }

    // ----- 2-D -------------------------------------------------------------------------------

    fn mild(c: f64) -> impl Fn(Vector2<f64>) -> Result<Vector2<f64>, String> {
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
        let (x, rep, _) = solve2(mild(1.1), cold2([0.0, 0.0], 1e-6), &opts()).unwrap();
        println!("mild cold: {rep:?}, root {root:?}");
        assert!(rep.converged && (x - root).amax() < 1e-9, "{x:?} {rep:?}");
        assert!(rep.iterations <= 10, "{rep:?}");
    }

    #[test]
    fn mild_system_warm_from_perturbed() {
        let (_, cold, mem) = solve2(mild(1.1), cold2([0.0, 0.0], 1e-6), &opts()).unwrap();
        let (x, warm, _) = solve2(mild(1.15), Start2::Warm(mem), &opts()).unwrap();
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
            let (x, rep, _) = solve2(r, cold2(start, 1e-7), &opts()).unwrap();
            println!("rosenbrock residuals from {start:?}: {rep:?}");
            assert!(rep.converged && (x - one).amax() < 1e-9, "{x:?} {rep:?}");
            assert!(rep.iterations <= 25);
        }
        // From the classic (-1.2, 1) the monotone ||r|| acceptance creeps along the curved
        // valley: it converges, but needs a larger budget.
        let big = Options {
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
        let (x, rep, _) = solve2(g, cold2([1.05, 1.1], 1e-7), &opts()).unwrap();
        println!("rosenbrock gradient from (1.05, 1.1): {rep:?}");
        assert!(rep.converged && (x - one).amax() < 1e-9, "{x:?} {rep:?}");
        assert!(rep.iterations <= 25);
        // From (1.2, 1.2) the gradient norm is a poor merit function: the budget runs out, the
        // report says so, and the best point is far better than the start.
        let (x, rep, _) = solve2(g, cold2([1.2, 1.2], 1e-7), &opts()).unwrap();
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
        let (x, rep, _) = solve2(r, cold2([3.0, 0.5], 1e-6), &opts()).unwrap();
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
        let (_, rep, _) = solve2(r, cold2([2.0, 1.0], 1e-6), &opts()).unwrap();
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
        let (x, rep, _) = solve2(r, cold2([-2.0, 0.0], 1e-6), &opts()).unwrap();
        assert!(
            rep.converged && (x[0] - 5f64.ln()).abs() < 1e-9,
            "{x:?} {rep:?}"
        );
        assert!(solve2(|_| Err("boom".into()), cold2([0.0, 0.0], 1e-6), &opts()).is_err());
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
            let (x, rep, _) = solve2(r, cold2(x0, 1.0), &opts()).unwrap();
            let root = m.try_inverse().unwrap() * bv;
            prop_assert!(rep.converged, "{:?}", rep);
            prop_assert_eq!(rep.iterations, 4);
            prop_assert!((x - root).amax() < 1e-9);
        }
    }
}
