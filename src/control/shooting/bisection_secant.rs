//! The 1-D shooting solver of KLAW (Bruderlin & Calvert 1989, §4.1): bisection first, then the
//! secant method, as an [`argmin`] solver.
use argmin::core::{
    CostFunction, Error as ArgminError, IterState, KV, Problem, Solver, State, TerminationReason,
    TerminationStatus,
};

use super::ShootingError;
use super::warm_start::FALLBACK_REL_STEP;

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
pub(crate) struct BisectionSecant {
    /// Absolute tolerance on `|r|`.
    tol: f64,
    /// Hard cap on residual evaluations, the one in `init` included.
    max_evaluations: usize,
    /// Consecutive failed trials tolerated before giving up (10).
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
        }
    }

    /// Cold start from `x0`; `dx` (non-zero) is the scale of the unknown: the first trial after
    /// `x0` is `x0 + dx`.
    pub(crate) fn cold(x0: f64, dx: f64, tol: f64, max_evaluations: usize) -> Self {
        Self::new(x0, dx, None, tol, max_evaluations)
    }

    /// Warm start from `x0` with the slope `dr/dx` remembered from the previous solve. If the
    /// slope is zero or not finite, the first trial probes `x0 + 1e-4 max(1, |x0|)` instead.
    pub(crate) fn warm(x0: f64, slope: f64, tol: f64, max_evaluations: usize) -> Self {
        let dx = FALLBACK_REL_STEP * x0.abs().max(1.0);
        Self::new(x0, dx, Some(slope), tol, max_evaluations)
    }

    /// Residual evaluations so far.
    pub(crate) fn evaluations(&self) -> usize {
        self.evaluations
    }

    /// The best sample `(x, r)` so far (smallest `|r|`).
    pub(crate) fn best(&self) -> Option<(f64, f64)> {
        self.best.map(|p| (p.x, p.f))
    }

    /// The latest slope estimate `dr/dx`: the secant through the two best samples, else the
    /// remembered warm-start slope, else NaN.
    pub(crate) fn slope(&self) -> f64 {
        match (self.best, self.second) {
            (Some(a), Some(b)) if a.x != b.x => (b.f - a.f) / (b.x - a.x),
            _ => self.warm_slope.unwrap_or(f64::NAN),
        }
    }

    fn evaluate<O>(&mut self, problem: &mut Problem<O>, x: f64) -> Option<f64>
    where
        O: CostFunction<Param = f64, Output = f64>,
    {
        self.evaluations += 1;
        match problem.cost(&x) {
            Ok(f) if f.is_finite() => Some(f),
            // a non-finite residual or a failed trial
            _ => None,
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

// (in their own file: with them this one would pass 600 lines)
#[cfg(test)]
mod tests;
