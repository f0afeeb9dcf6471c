//! Bracketed one-dimensional root finding: the sign change of a function, or the point where a
//! predicate changes, inside a bracket the search keeps (so it cannot diverge).
//! - `illinois`: regula falsi with the Illinois modification, for continuous functions: the
//!   integrator's events, the actuators' power crossings, heel-off (the terminal stance's and
//!   the virtual stance leg's) and the terminal stance's end pitch;
//! - `bisect`: bisection, for predicates (the gait events, the foot's pitch limits), which give
//!   only a side and no value to interpolate;
//! - `bisect_steered`, `bisect_with_guess`: the same bisection with its decisions taken from
//!   a closed-form guess away from it (the foot's pitch limits, the heel rocker's sole angle);
//! - `scan`: sampling for the first bracket of a change that, once on, stays on (heel-off).

/// Shrink the bracket [a, b] of a sign change of `g` (`ga`, `gb` its values at the ends, of
/// opposite signs, or `gb` zero) until it is at most `tol` wide or `max_evaluations` are spent;
/// returns the final bracket, `g` keeping at its left end the sign `ga` had (a zero counts as
/// the right end's). The Illinois variant of regula falsi (M. Dowell & P. Jarratt, "A modified
/// regula falsi method for computing the root of an equation", BIT 11, 1971): the value at the
/// end that stays twice is halved, so it converges superlinearly (order ≈ 1.44) where bisection
/// gains one bit an evaluation.
pub(crate) fn illinois(
    g: impl Fn(f64) -> f64,
    (mut a, mut ga): (f64, f64),
    (mut b, mut gb): (f64, f64),
    tol: f64,
    max_evaluations: usize,
) -> (f64, f64) {
    let positive = ga > 0.0;
    // which end moved last: the other end's value is halved when the same end moves twice
    let mut side = 0;
    for _ in 0..max_evaluations {
        if b - a <= tol {
            break;
        }
        let mut t = (a * gb - b * ga) / (gb - ga);
        if !(t > a && t < b) {
            t = 0.5 * (a + b);
        }
        // no closer to an end than half the tolerance: where an end sits on the root, the
        // points would pile up there and the bracket shrink by bisection only
        let (h, m) = (0.5 * tol, 0.5 * (a + b));
        if t - a < h {
            t = (a + h).min(m);
        } else if b - t < h {
            t = (b - h).max(m);
        }
        let gt = g(t);
        if (gt > 0.0) == positive {
            (a, ga) = (t, gt);
            if side == -1 {
                gb *= 0.5;
            }
            side = -1;
        } else {
            (b, gb) = (t, gt);
            if side == 1 {
                ga *= 0.5;
            }
            side = 1;
        }
    }
    (a, b)
}

/// Bisection between `good`, where `ok` holds, and `bad`, where it fails (either order), until
/// they are at most `tol` apart or adjacent doubles (far into a long walk, 1e-9 s is below the
/// spacing of the times); returns the last (good, bad). Each step is decided by `ok` at the
/// midpoint. For the gait events' times (`analysis/events.rs`, to 1e-9 s) and the foot's pitch
/// limits without a guess (`kinematics/foot.rs`, to 1e-12 rad).
pub(crate) fn bisect(ok: impl Fn(f64) -> bool, good: f64, bad: f64, tol: f64) -> (f64, f64) {
    halve(ok, good, bad, tol, None)
}

/// [`bisect`] steered by `guess`, the boundary in closed form: each step is decided by the side
/// of `guess` the midpoint falls on, and by `ok` only within `slack` of it. When `ok` changes
/// once on the interval these are `ok`'s own decisions, so the end is that of [`bisect`], at a
/// few evaluations instead of ≈ 40; the ends are checked (`ok` at the last good point, not at the
/// last bad one), and the last good point is returned when they pass. None for a NaN guess or
/// failed ends. For the foot's pitch limits (`kinematics/foot.rs`).
pub(crate) fn bisect_steered(
    ok: impl Fn(f64) -> bool,
    good: f64,
    bad: f64,
    tol: f64,
    guess: f64,
    slack: f64,
) -> Option<f64> {
    if guess.is_nan() {
        return None;
    }
    let (good, bad) = halve(&ok, good, bad, tol, Some((guess, slack)));
    (ok(good) && !ok(bad)).then_some(good)
}

/// The last good point of [`bisect_steered`], or of [`bisect`] where the guess is off or NaN:
/// the end of bisecting `ok` whatever the guess. For the foot's pitch limits and the heel
/// rocker's sole angle (`kinematics/foot.rs`, `kinematics/stance_leg.rs`).
pub(crate) fn bisect_with_guess(
    ok: impl Fn(f64) -> bool,
    good: f64,
    bad: f64,
    tol: f64,
    guess: f64,
    slack: f64,
) -> f64 {
    bisect_steered(&ok, good, bad, tol, guess, slack)
        .unwrap_or_else(|| bisect(&ok, good, bad, tol).0)
}

/// [`bisect`]'s loop; `steer`: (guess, slack) of [`bisect_steered`].
fn halve(
    ok: impl Fn(f64) -> bool,
    mut good: f64,
    mut bad: f64,
    tol: f64,
    steer: Option<(f64, f64)>,
) -> (f64, f64) {
    // the side of the guess `ok` holds on, and the window where `ok` decides (NaN: everywhere)
    let (good_below, below, above) = match steer {
        Some((guess, slack)) => (good < guess, guess - slack, guess + slack),
        None => (false, f64::NAN, f64::NAN),
    };
    while (bad - good).abs() > tol {
        let m = 0.5 * (good + bad);
        if m == good || m == bad {
            break;
        }
        let holds = if m < below {
            good_below
        } else if m > above {
            !good_below
        } else {
            ok(m)
        };
        if holds { good = m } else { bad = m }
    }
    (good, bad)
}

/// What [`scan`] found: the last point that did not hit, with the value there (None at the
/// start), and the first that did, with its value.
pub(crate) type Scanned<T> = ((f64, Option<T>), (f64, T));

/// The first of `points` (in order, after `from`) at which `hit` holds of `f`'s value, and the
/// point before it (`from` for the first) with `f`'s value there (None at `from`, which is not
/// evaluated): the bracket of the first change of a test that, once on, stays on, for a
/// [`bisect`] or [`illinois`] to refine; None when no point hits. The points are evaluated in
/// order and no further than the first hit (an error can count as a hit, to stop the scan).
/// For heel-off: `StanceLeg::find_heel_off` (24 samples, then [`illinois`]) and the gait events
/// (1 ms steps, then [`bisect`]).
pub(crate) fn scan<T>(
    from: f64,
    points: impl IntoIterator<Item = f64>,
    f: impl Fn(f64) -> T,
    hit: impl Fn(&T) -> bool,
) -> Option<Scanned<T>> {
    let mut before = (from, None);
    for t in points {
        let v = f(t);
        if hit(&v) {
            return Some((before, (t, v)));
        }
        before = (t, Some(v));
    }
    None
}

/// `f` counting its calls in `calls`: the searches' tests compare evaluation counts.
#[cfg(test)]
pub(crate) fn counted(
    calls: &std::cell::Cell<usize>,
    f: fn(f64) -> f64,
) -> impl Fn(f64) -> f64 + '_ {
    move |x| {
        calls.set(calls.get() + 1);
        f(x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    /// The analytic roots of cos on [1, 2] (π/2) and of x³ − 2x − 5 (Wallis's cubic, root
    /// 2.0945514815423265), found to round-off in fewer than 12 evaluations (bisection: 47),
    /// the bracket kept; a falling function as well as a rising one.
    #[test]
    fn finds_analytic_roots_within_a_kept_bracket() {
        let calls = &Cell::new(0);
        let counted = |f| counted(calls, f);
        let (a, b) = illinois(
            counted(f64::cos),
            (1.0, 1.0_f64.cos()),
            (2.0, 2.0_f64.cos()),
            1e-14,
            100,
        );
        let pi2 = std::f64::consts::FRAC_PI_2;
        assert!(a <= pi2 && pi2 <= b + 1e-15 && b - a <= 1e-14, "{a} {b}");
        assert!(a.cos() > 0.0 && b.cos() <= 0.0);
        assert!(calls.get() < 12, "{} evaluations", calls.get());
        calls.set(0);
        let wallis = |x: f64| x * x * x - 2.0 * x - 5.0;
        let (a, b) = illinois(
            counted(wallis),
            (2.0, wallis(2.0)),
            (3.0, wallis(3.0)),
            1e-14,
            100,
        );
        let root = 2.094_551_481_542_326_5;
        assert!(
            (a - root).abs() < 1e-14 && (b - root).abs() < 1e-14,
            "{a} {b}"
        );
        assert!(wallis(a) < 0.0 && wallis(b) >= 0.0);
        assert!(calls.get() < 12, "{} evaluations", calls.get());
    }

    /// With no room left, or no evaluations allowed, the bracket comes back as it went in.
    #[test]
    fn respects_its_tolerance_and_budget() {
        let g = |x: f64| x - 0.3;
        assert_eq!(illinois(g, (0.0, -0.3), (1.0, 0.7), 2.0, 100), (0.0, 1.0));
        assert_eq!(illinois(g, (0.0, -0.3), (1.0, 0.7), 0.0, 0), (0.0, 1.0));
    }

    /// √2 as the boundary of x² ≤ 2, with the good end below or above: the last pair brackets
    /// it within the tolerance, `ok` holding at the good end only, in the 31 halvings of
    /// [0, 2] to 1e-9.
    #[test]
    fn bisection_brackets_an_analytic_boundary() {
        let root = std::f64::consts::SQRT_2;
        let calls = Cell::new(0);
        let below = |x: f64| {
            calls.set(calls.get() + 1);
            x * x <= 2.0
        };
        let (good, bad) = bisect(below, 0.0, 2.0, 1e-9);
        assert!(
            good <= root && root < bad && bad - good <= 1e-9,
            "{good} {bad}"
        );
        assert_eq!(calls.get(), 31);
        let above = |x: f64| x * x >= 2.0;
        let (good, bad) = bisect(above, 2.0, 0.0, 1e-9);
        assert!(
            bad < root && root <= good && good - bad <= 1e-9,
            "{good} {bad}"
        );
    }

    /// A tolerance below the spacing of the doubles (a time 1e5 s into a walk, to 1e-12 s, or
    /// to 0): the bisection ends at adjacent doubles instead of looping.
    #[test]
    fn bisection_ends_at_adjacent_doubles() {
        let t = 1e5 + 0.3;
        for tol in [1e-12, 0.0] {
            let (good, bad) = bisect(|x| x >= t, 1e5 + 1.0, 1e5, tol);
            assert_eq!((good, bad), (t, t.next_down()), "{tol}");
        }
    }

    /// Steered by an exact guess, the bisection evaluates its predicate a few times only and
    /// ends where bisecting the predicate does; a wrong guess fails its ends' check, and
    /// [`bisect_with_guess`] still ends there.
    #[test]
    fn steered_bisection_is_the_bisection() {
        let boundary = 0.123_456_789_012_345_6;
        let evaluations = Cell::new(0);
        let ok = |p: f64| {
            evaluations.set(evaluations.get() + 1);
            p <= boundary
        };
        let (plain, _) = bisect(ok, -1.0, 1.0, 1e-12);
        assert!(evaluations.get() > 40);
        assert!((plain - boundary).abs() <= 1e-12 && ok(plain) && !ok(plain + 1e-12));
        evaluations.set(0);
        let steered = bisect_steered(ok, -1.0, 1.0, 1e-12, boundary + 1e-15, 2e-13);
        assert_eq!(steered, Some(plain));
        assert!(evaluations.get() < 10, "{}", evaluations.get());
        for guess in [0.5, -3.0, f64::NAN] {
            assert_eq!(bisect_steered(ok, -1.0, 1.0, 1e-12, guess, 2e-13), None);
            assert_eq!(bisect_with_guess(ok, -1.0, 1.0, 1e-12, guess, 2e-13), plain);
        }
        assert_eq!(
            bisect_with_guess(ok, -1.0, 1.0, 1e-12, boundary, 2e-13),
            plain
        );
    }

    /// The first sample of t − 0.37 at or above 0 on a 0.1 grid, the sample before it with its
    /// value; no sample evaluated past the hit; the start when the first sample hits; none when
    /// no sample does. Refined by Illinois, the bracket gives the root.
    #[test]
    fn scan_brackets_the_first_change() {
        let calls = &Cell::new(0);
        let f = counted(calls, |t| t - 0.37);
        let grid = || (1..=10).map(|k| k as f64 / 10.0);
        let ((lo, g_lo), (hi, g_hi)) = scan(0.0, grid(), &f, |&g| g >= 0.0).unwrap();
        assert_eq!((lo, hi), (0.3, 0.4));
        assert_eq!((g_lo, g_hi), (Some(0.3 - 0.37), 0.4 - 0.37));
        assert_eq!(calls.get(), 4);
        let (_, b) = illinois(&f, (lo, g_lo.unwrap()), (hi, g_hi), 1e-15, 60);
        assert!((b - 0.37).abs() <= 1e-15, "{b}");
        let ((lo, g_lo), (hi, _)) = scan(0.0, grid(), &f, |&g| g >= -1.0).unwrap();
        assert_eq!((lo, g_lo, hi), (0.0, None, 0.1));
        assert!(scan(0.0, grid(), &f, |&g| g > 1.0).is_none());
    }
}
