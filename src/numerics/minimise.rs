//! Minimization of a smooth function of one variable on an interval: Brent's method (R. P.
//! Brent, *Algorithms for Minimization without Derivatives*, 1973, ch. 5) from the least of
//! uniform samples, and the candidates for every local minimum (`minima`).
//!
//! Not argmin's `BrentOpt`: it starts from its own golden-section point (one more evaluation per
//! search, where ours starts from the sample already evaluated), stops at a bracket of
//! 3 (√ε |x| + t) rather than an absolute one, and forms the parabola in another order, so its
//! evaluations, and the walk's measurements, would not be the same.

/// (x, f(x)) at `n` + 1 uniform samples x = a + (k / n) span of [a, a + span].
fn samples(f: impl Fn(f64) -> f64, a: f64, span: f64, n: usize) -> Vec<(f64, f64)> {
    (0..=n)
        .map(|k| {
            let x = a + k as f64 / n as f64 * span;
            (x, f(x))
        })
        .collect()
}

/// The least evaluation (x, f(x)) of Brent's minimization of `f` on [lo, hi] (R. P. Brent,
/// *Algorithms for Minimization without Derivatives*, 1973, ch. 5: successive parabolic
/// interpolation, safeguarded by golden-section steps), started from the evaluated interior (or
/// end) point `x0` and run down to a bracket of `tol`.
fn brent(
    f: impl Fn(f64) -> f64,
    (mut a, mut b): (f64, f64),
    x0: (f64, f64),
    tol: f64,
) -> (f64, f64) {
    const C: f64 = 0.381_966_011_250_105_1; // (3 − √5)/2
    // Brent's stop: |x − m| ≤ 2 tol1 − (b − a)/2, i.e. a bracket of at most 4 tol1
    let tol1 = 0.25 * tol;
    let ((mut x, mut fx), (mut w, mut fw), (mut v, mut fv)) = (x0, x0, x0);
    let (mut d, mut e) = (0.0_f64, 0.0_f64);
    loop {
        let m = 0.5 * (a + b);
        if (x - m).abs() <= 2.0 * tol1 - 0.5 * (b - a) {
            return (x, fx);
        }
        // the parabola through (x, w, v), where its step is inside the bracket and under half
        // the step before last; else a golden-section step into the larger part
        let mut parabolic = false;
        if e.abs() > tol1 {
            let r = (x - w) * (fx - fv);
            let q = (x - v) * (fx - fw);
            let (mut p, mut q) = ((x - v) * q - (x - w) * r, 2.0 * (q - r));
            if q > 0.0 {
                p = -p;
            } else {
                q = -q;
            }
            if p.abs() < (0.5 * q * e).abs() && p > q * (a - x) && p < q * (b - x) {
                e = d;
                d = p / q;
                if x + d - a < 2.0 * tol1 || b - (x + d) < 2.0 * tol1 {
                    d = tol1.copysign(m - x);
                }
                parabolic = true;
            }
        }
        if !parabolic {
            e = if x < m { b - x } else { a - x };
            d = C * e;
        }
        let u = x + if d.abs() >= tol1 { d } else { tol1.copysign(d) };
        let fu = f(u);
        if fu <= fx {
            if u < x {
                b = x;
            } else {
                a = x;
            }
            ((v, fv), (w, fw), (x, fx)) = ((w, fw), (x, fx), (u, fu));
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                ((v, fv), (w, fw)) = ((w, fw), (u, fu));
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
}

/// Candidates for the minima of a smooth `f` on [a, b], (x, f(x)): `n` + 1 uniform samples,
/// and a [`brent`] search down to 1e-5 (b − a) over the two intervals around every sample no
/// larger than its neighbours (to 1e-12: rounding noise; a run of such samples is searched as
/// one bracket, from its least), the ends included. The least candidate in a sub-interval whose
/// ends are samples is its minimum, for minima that the samples see as local minima
/// ([`least_in`]). At a smooth minimum the value's error is f″ δ² / 2, δ = 1e-5 (b − a).
pub(crate) fn minima(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> Vec<(f64, f64)> {
    const NOISE: f64 = 1e-12;
    let mut found = samples(&f, a, b - a, n);
    let value = |k: usize| found[k].1;
    let local = |k: usize| {
        (k == 0 || value(k) <= value(k - 1) + NOISE) && (k == n || value(k) <= value(k + 1) + NOISE)
    };
    let mut brackets = Vec::new();
    let mut k = 0;
    while k <= n {
        if !local(k) {
            k += 1;
            continue;
        }
        let mut last = k;
        while last < n && local(last + 1) {
            last += 1;
        }
        let least = (k..=last).fold(k, |i, j| if value(j) < value(i) { j } else { i });
        brackets.push((
            (found[k.saturating_sub(1)].0, found[(last + 1).min(n)].0),
            found[least],
        ));
        k = last + 1;
    }
    for (bracket, x0) in brackets {
        found.push(brent(&f, bracket, x0, 1e-5 * (b - a)));
    }
    found
}

/// The least of `candidates` (x, value) with x in [lo, hi] (to 1e-9 of the interval): (value, x).
pub(crate) fn least_in(candidates: &[(f64, f64)], lo: f64, hi: f64) -> (f64, f64) {
    let slack = 1e-9 * (hi - lo);
    candidates
        .iter()
        .filter(|(x, _)| *x >= lo - slack && *x <= hi + slack)
        .fold(
            (f64::INFINITY, lo),
            |best, &(x, v)| if v < best.0 { (v, x) } else { best },
        )
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    /// Brent's search finds the analytic minima, inside and at an end of its bracket, in fewer
    /// evaluations than the golden section needs for the same bracket (log_φ of the ratio).
    #[test]
    fn brent_finds_analytic_minima_quickly() {
        let calls = &Cell::new(0);
        let counted = |f| crate::numerics::roots::counted(calls, f);
        let golden_steps = (0.04_f64 / 1e-7).ln() / 1.618_033_988_749_895_f64.ln();
        // cos has its minimum −1 at π; seeded from a sample near it
        let (x, f) = brent(
            counted(f64::cos),
            (3.12, 3.16),
            (3.15, 3.15_f64.cos()),
            1e-7,
        );
        assert!((x - std::f64::consts::PI).abs() < 1e-7, "{x}");
        assert!((f + 1.0).abs() < 1e-14);
        assert!(
            (calls.get() as f64) < 0.5 * golden_steps,
            "{} evaluations",
            calls.get()
        );
        // a quartic's flat minimum, x = 0.3, f = 2
        calls.set(0);
        let quartic = |x: f64| 2.0 + (x - 0.3).powi(4) + (x - 0.3).powi(2);
        let (x, f) = brent(counted(quartic), (0.28, 0.32), (0.29, quartic(0.29)), 1e-7);
        assert!((x - 0.3).abs() < 1e-7 && (f - 2.0).abs() < 1e-13, "{x} {f}");
        // monotone: the minimum is the bracket's end, approached from the seed there
        calls.set(0);
        let (x, f) = brent(counted(|x| x * x), (1.0, 1.04), (1.0, 1.0), 1e-7);
        assert_eq!((x, f), (1.0, 1.0));
        assert!((calls.get() as f64) < golden_steps + 3.0, "{}", calls.get());
    }

    /// `minima` finds every local minimum of a function with several, including one between
    /// two samples and the ends'.
    #[test]
    fn minima_finds_each_local_minimum() {
        // minima of sin 7x + x/2 on [0, 3]: 7 cos 7x = −1/2, i.e. x = (2πk ± acos(−1/14))/7 with
        // sin 7x < 0; and the end x = 0
        let f = |x: f64| (7.0 * x).sin() + 0.5 * x;
        let found = minima(f, 0.0, 3.0, 20);
        let c = (-1.0_f64 / 14.0).acos();
        for k in 0..3 {
            let x = (2.0 * std::f64::consts::PI * (k + 1) as f64 - c) / 7.0;
            let (v, at) = least_in(&found, x - 0.1, x + 0.1);
            assert!(
                (at - x).abs() < 3e-5 && (v - f(x)).abs() < 1e-9,
                "{k}: {at} vs {x}"
            );
        }
        assert_eq!(least_in(&found, 0.0, 0.05), (0.0, 0.0));
    }
}
