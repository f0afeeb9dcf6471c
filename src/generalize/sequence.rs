//! Timed sequences (Ko & Badler 1992, eq. 1) and their interpolation (eq. 2): strictly
//! increasing times t_i with a value (a number, or a point of the sagittal plane) at each.
//! \[ours\] Outside [t_1, t_n] a sequence holds its end value (eq. 2 is silent there).
use serde::{Deserialize, Serialize};

/// The interval of `times` that holds `t` and the fraction of the way through it (eq. 2): the
/// first or last interval's end, clamped, outside the times. `times` has at least one entry;
/// one entry gives (0, 0).
fn locate(times: &[f64], t: f64) -> (usize, f64) {
    let n = times.len();
    if n < 2 || t <= times[0] {
        return (0, 0.0);
    }
    if t >= times[n - 1] {
        return (n - 2, 1.0);
    }
    // the last time at or below t
    let i = times.partition_point(|&x| x <= t) - 1;
    (i, (t - times[i]) / (times[i + 1] - times[i]))
}

/// Eq. 2: the value at t of the sequence of `values` at `times`, the end values held outside.
pub fn interpolate(times: &[f64], values: &[f64], t: f64) -> f64 {
    let (i, s) = locate(times, t);
    match values.get(i + 1) {
        Some(b) => values[i] + s * (b - values[i]),
        None => values[i],
    }
}

/// A timed sequence of numbers (eq. 1).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Curve {
    /// Times t_i, strictly increasing (normalized step time).
    pub t: Vec<f64>,
    /// Values v_i.
    pub v: Vec<f64>,
}

impl Curve {
    /// The sequence of `(t, f(t))` at the times `t`.
    pub fn sample(t: Vec<f64>, f: impl Fn(f64) -> f64) -> Self {
        let v = t.iter().map(|&x| f(x)).collect();
        Curve { t, v }
    }

    /// Eq. 2 at t, the end values held outside the times.
    pub fn at(&self, t: f64) -> f64 {
        interpolate(&self.t, &self.v, t)
    }

    /// The first value.
    pub fn first(&self) -> f64 {
        self.v[0]
    }

    /// The last value.
    pub fn last(&self) -> f64 {
        self.v[self.v.len() - 1]
    }
}

/// A timed sequence of points (x forward, y up; m) of the sagittal plane (eq. 1, eq. 12).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Path {
    /// Times t_i, strictly increasing (normalized step time).
    pub t: Vec<f64>,
    /// x_i (m).
    pub x: Vec<f64>,
    /// y_i (m).
    pub y: Vec<f64>,
}

impl Path {
    /// Eq. 2 at t, the end points held outside the times.
    pub fn at(&self, t: f64) -> [f64; 2] {
        let (i, s) = locate(&self.t, t);
        let lerp = |v: &[f64]| match v.get(i + 1) {
            Some(b) => v[i] + s * (b - v[i]),
            None => v[i],
        };
        [lerp(&self.x), lerp(&self.y)]
    }

    /// The first point.
    pub fn first(&self) -> [f64; 2] {
        [self.x[0], self.y[0]]
    }

    /// The last point.
    pub fn last(&self) -> [f64; 2] {
        let n = self.t.len() - 1;
        [self.x[n], self.y[n]]
    }
}

/// `n + 1` equally spaced times from `a` to `b` (both included; `n` ≥ 1).
pub fn grid(a: f64, b: f64, n: usize) -> Vec<f64> {
    let n = n.max(1);
    (0..=n)
        .map(|i| {
            if i == n {
                b
            } else {
                a + (b - a) * i as f64 / n as f64
            }
        })
        .collect()
}

/// The affine map of the line through `from` to the line through `to`, pinned at both ends: x
/// with x = from.0 goes to to.0 and x = from.1 to to.1. Affine maps pinned this way compose
/// into the pinned map of the outer ends, exactly (Theorem 1's property). A degenerate `from`
/// (equal ends) moves x by to.0 − from.0.
pub fn pinned(x: f64, from: (f64, f64), to: (f64, f64)) -> f64 {
    let span = from.1 - from.0;
    if span == 0.0 {
        return x + to.0 - from.0;
    }
    to.0 + (to.1 - to.0) * ((x - from.0) / span)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Eq. 2: exact at the samples, linear between them, the ends held outside.
    #[test]
    fn interpolation_is_linear_between_samples_and_holds_outside() {
        let c = Curve {
            t: vec![0.0, 0.5, 2.0],
            v: vec![1.0, 3.0, 0.0],
        };
        assert_eq!(c.at(0.0), 1.0);
        assert_eq!(c.at(0.5), 3.0);
        assert_eq!(c.at(2.0), 0.0);
        assert!((c.at(0.25) - 2.0).abs() < 1e-15);
        assert!((c.at(1.25) - 1.5).abs() < 1e-15);
        assert_eq!(c.at(-1.0), 1.0);
        assert_eq!(c.at(5.0), 0.0);
        let one = Curve {
            t: vec![0.3],
            v: vec![7.0],
        };
        assert_eq!((one.at(0.0), one.at(0.3), one.at(1.0)), (7.0, 7.0, 7.0));
        let p = Path {
            t: vec![0.0, 1.0],
            x: vec![0.0, 2.0],
            y: vec![1.0, -1.0],
        };
        assert_eq!(p.at(0.5), [1.0, 0.0]);
        assert_eq!(p.at(2.0), [2.0, -1.0]);
    }

    /// A pinned map sends the ends to the ends, and two composed are the direct one.
    #[test]
    fn pinned_maps_compose() {
        let (a, b, c) = ((-0.3, 0.4), (-0.5, 0.9), (0.1, 0.2));
        assert_eq!(pinned(a.0, a, b), b.0);
        assert!((pinned(a.1, a, b) - b.1).abs() < 1e-15);
        for x in [-1.0, 0.0, 0.25, 3.0] {
            let two = pinned(pinned(x, a, b), b, c);
            assert!((two - pinned(x, a, c)).abs() < 1e-14);
        }
        assert_eq!(grid(0.0, 1.0, 4), vec![0.0, 0.25, 0.5, 0.75, 1.0]);
    }
}
