//! Tests of [`BisectionSecant`](super::BisectionSecant), alone and through [`solve1`].
use super::*;
use crate::control::shooting::{Memory1, SolveOptions, Start1, solve1};
use crate::numerics::ode::IntegrationError;
use argmin::core::Executor;
use argmin::solver::brent::BrentRoot;
use std::cell::Cell;

const CUBIC_ROOT: f64 = 2.094_551_481_542_326_5;

fn cubic(c: f64) -> impl Fn(f64) -> Result<f64, IntegrationError> {
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
    let (x, rep, mem) = solve1(cubic(5.0), cold1(2.0, 1.0), &SolveOptions::default()).unwrap();
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
    let (x, rep, _) = solve1(r, cold1(-2.0, 1.0), &SolveOptions::default()).unwrap();
    println!("tanh cold: {rep:?}");
    assert!(rep.converged, "{rep:?}");
    assert!((x - 1.3).abs() < 1e-9, "{x}");
    assert!(rep.iterations <= 10, "{rep:?}");
}

#[test]
fn exp_cold_far() {
    let r = |x: f64| Ok(x.exp() - 10.0);
    let (x, rep, _) = solve1(r, cold1(-5.0, 1.0), &SolveOptions::default()).unwrap();
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
        let (x, rep, _) = solve1(|x| Ok(f(x)), cold1(a, b - a), &SolveOptions::default()).unwrap();
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
    let (_, cold, mem) = solve1(cubic(5.0), cold1(2.0, 1.0), &SolveOptions::default()).unwrap();
    let (x, warm, _) = solve1(cubic(5.1), Start1::Warm(mem), &SolveOptions::default()).unwrap();
    let (_, cold2, _) = solve1(cubic(5.1), cold1(2.0, 1.0), &SolveOptions::default()).unwrap();
    println!("cold {cold:?}, warm {warm:?}, cold on the same problem {cold2:?}");
    assert!(warm.converged);
    assert!((x - cubic_root(5.1)).abs() < 1e-9);
    assert!(warm.iterations <= 4, "{warm:?}");
    assert!(warm.iterations < cold2.iterations);
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
    let (x, rep, _) = solve1(cubic(5.0), Start1::Warm(mem), &SolveOptions::default()).unwrap();
    println!("warm, wrong slope: {rep:?}");
    assert!(rep.converged && (x - CUBIC_ROOT).abs() < 1e-9, "{rep:?}");
    // No slope at all: a small probe, then secant.
    let mem = Memory1 {
        x: 2.0,
        slope: f64::NAN,
        earlier: [f64::NAN; 2],
        ratio: f64::NAN,
    };
    let (x, rep, _) = solve1(cubic(5.0), Start1::Warm(mem), &SolveOptions::default()).unwrap();
    assert!(rep.converged && (x - CUBIC_ROOT).abs() < 1e-9, "{rep:?}");
}

#[test]
fn nan_region_is_stepped_back_from() {
    let r = |x: f64| Ok(if x > 3.0 { f64::NAN } else { x.exp() - 10.0 });
    let (x, rep, _) = solve1(r, cold1(0.0, 5.0), &SolveOptions::default()).unwrap();
    println!("NaN above 3: {rep:?}");
    assert!(rep.converged, "{rep:?}");
    assert!((x - 10f64.ln()).abs() < 1e-9);
    // The same with a residual that returns Err (failed integration).
    let r = |x: f64| {
        if x > 3.0 {
            Err(IntegrationError::NonFinite { t: x })
        } else {
            Ok(x.exp() - 10.0)
        }
    };
    let (x, rep, _) = solve1(r, cold1(0.0, 5.0), &SolveOptions::default()).unwrap();
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
        let o = SolveOptions {
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
    let (_, rep, _) = solve1(|_| Ok(f64::NAN), cold1(0.0, 1.0), &SolveOptions::default()).unwrap();
    assert!(!rep.converged && rep.iterations == 1 && rep.residual.is_infinite());
    assert!(
        solve1(
            |_| Err(IntegrationError::NonFinite { t: 0.0 }),
            cold1(0.0, 1.0),
            &SolveOptions::default()
        )
        .is_err()
    );
    assert!(solve1(cubic(5.0), cold1(0.0, 0.0), &SolveOptions::default()).is_err());
    // NaN everywhere but the start: the solver gives up after repeated halvings.
    let r = |x: f64| Ok(if x == 1.0 { 1.0 } else { f64::NAN });
    let (x, rep, _) = solve1(r, cold1(1.0, 1.0), &SolveOptions::default()).unwrap();
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
