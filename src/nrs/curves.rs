//! The curves an NRS is made of (Ko & Badler 1993 §5): the swing ankle's rise (eq. 3), its
//! planar path round the stance ankle (a quadratic de Casteljau curve), the end-point
//! interpolation of a borrowed trajectory (eq. 4, eq. 5) and the uniform tables `advance` reads.

/// Eq. 3: the swing ankle's rise over its take-off-to-landing line at s ∈ [0, 1] of the airborne
/// interval, for peak `height` (5 cm · swhf): `height (cosh ½ − cosh(s − ½)) / (cosh ½ − 1)`
/// (the paper's exponentials written as cosh); 0 at both ends, `height` at s = ½.
pub fn swing_rise(s: f64, height: f64) -> f64 {
    let c = 0.5f64.cosh();
    height * (c - (s - 0.5).cosh()) / (c - 1.0)
}

/// The quadratic de Casteljau (Bézier) curve through D1 and D3 with control point D2, at s.
pub fn de_casteljau(d: [[f64; 2]; 3], s: f64) -> [f64; 2] {
    let lerp = |a: [f64; 2], b: [f64; 2]| [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])];
    lerp(lerp(d[0], d[1]), lerp(d[1], d[2]))
}

/// The distance from `p` to the segment from `a` to `b` (floor points).
pub fn segment_distance(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1]];
    let ap = [p[0] - a[0], p[1] - a[1]];
    let n2 = ab[0] * ab[0] + ab[1] * ab[1];
    let s = if n2 > 0.0 {
        ((ap[0] * ab[0] + ap[1] * ab[1]) / n2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    ((ap[0] - s * ab[0]).powi(2) + (ap[1] - s * ab[1]).powi(2)).sqrt()
}

/// Eq. 4: a trajectory `h` sampled at `t` (t₁ = 0 … tₙ = 1) moved to start at `start` and end at
/// `end`: h′ᵢ = hᵢ + (1 − tᵢ)(start − h₁) + tᵢ(end − hₙ). h′ = h when the ends already match.
pub fn interpolate_ends(t: &[f64], h: &[f64], start: f64, end: f64) -> Vec<f64> {
    let (h1, hn) = (h[0], h[h.len() - 1]);
    t.iter()
        .zip(h)
        .map(|(&t, &h)| h + (1.0 - t) * (start - h1) + t * (end - hn))
        .collect()
}

/// Eq. 5: a backward step's heights from the forward step `h` it reverses (samples symmetric in
/// time, tᵢ = 1 − t_{n−i+1}): h′ᵢ = h_{n−i+1} + (1 − tᵢ)(start − hₙ) + tᵢ(end − h₁).
pub fn interpolate_reversed(t: &[f64], h: &[f64], start: f64, end: f64) -> Vec<f64> {
    let reversed: Vec<f64> = h.iter().rev().copied().collect();
    interpolate_ends(t, &reversed, start, end)
}

/// The cubic Hermite basis functions that carry a slope at one end and vanish, with the other
/// slope, at both ends: h₁₀(t) = t (1 − t)² (slope 1 at 0) and h₁₁(t) = t² (t − 1) (slope 1 at 1).
fn hermite_slopes(t: f64) -> (f64, f64) {
    (t * (1.0 - t) * (1.0 - t), t * t * (t - 1.0))
}

/// `q` (sampled uniformly on [0, 1]) with its slopes at the ends (per unit normalized time) set to
/// `m0` and `m1` where given, by adding the Hermite terms h₁₀ and h₁₁: the ends' values do not
/// change, and neither does the other end's slope. The slopes of `q` are its one-sided second
/// order differences.
pub fn set_end_slopes(q: &mut [f64], m0: Option<f64>, m1: Option<f64>) {
    let n = q.len() - 1;
    let dt = 1.0 / n as f64;
    let slope0 = (-3.0 * q[0] + 4.0 * q[1] - q[2]) / (2.0 * dt);
    let slope1 = (3.0 * q[n] - 4.0 * q[n - 1] + q[n - 2]) / (2.0 * dt);
    let d0 = m0.map_or(0.0, |m| m - slope0);
    let d1 = m1.map_or(0.0, |m| m - slope1);
    for (i, v) in q.iter_mut().enumerate() {
        let (a, b) = hermite_slopes(i as f64 * dt);
        *v += d0 * a + d1 * b;
    }
}

/// Resample `values` given at the increasing times `times` onto `n + 1` uniform points of
/// `[times[0], times[last]]` (linear interpolation).
pub fn resample(times: &[f64], values: &[f64], n: usize) -> Vec<f64> {
    let (t0, t1) = (times[0], times[times.len() - 1]);
    let mut j = 0;
    (0..=n)
        .map(|i| {
            let t = t0 + (t1 - t0) * i as f64 / n as f64;
            while j + 2 < times.len() && times[j + 1] < t {
                j += 1;
            }
            let (a, b) = (times[j], times[j + 1]);
            let s = if b > a {
                ((t - a) / (b - a)).clamp(0.0, 1.0)
            } else {
                0.0
            };
            values[j] + s * (values[j + 1] - values[j])
        })
        .collect()
}

/// `K` channels tabulated at `n + 1` uniform points of normalized time [0, 1]; read by linear
/// interpolation in constant time without allocating.
#[derive(Clone, Debug)]
pub struct Table<const K: usize> {
    rows: Vec<[f64; K]>,
}

impl<const K: usize> Table<K> {
    /// A table of `n + 1` rows, row i at t = i / n, made by `f(t)`.
    pub fn new(n: usize, mut f: impl FnMut(usize, f64) -> [f64; K]) -> Self {
        Table {
            rows: (0..=n).map(|i| f(i, i as f64 / n as f64)).collect(),
        }
    }

    /// The channels at t ∈ [0, 1] (clamped), interpolated linearly between the rows; exactly
    /// the rows at t = i / n.
    #[inline]
    pub fn at(&self, t: f64) -> [f64; K] {
        let n = self.rows.len() - 1;
        let x = t.clamp(0.0, 1.0) * n as f64;
        let i = (x.floor() as usize).min(n - 1);
        let s = x - i as f64;
        let (a, b) = (&self.rows[i], &self.rows[i + 1]);
        let mut out = [0.0; K];
        for k in 0..K {
            out[k] = a[k] + s * (b[k] - a[k]);
        }
        out
    }

    /// The rows.
    pub fn rows(&self) -> &[[f64; K]] {
        &self.rows
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eq3_vanishes_at_the_ends_and_peaks_at_the_middle() {
        for h in [0.05, 0.1, 0.0] {
            assert!(swing_rise(0.0, h).abs() < 1e-15);
            assert!(swing_rise(1.0, h).abs() < 1e-15);
            assert!((swing_rise(0.5, h) - h).abs() < 1e-15);
        }
        // the paper's exponential form at a few points
        let e = |t: f64| {
            let a = 0.5f64.exp() + (-0.5f64).exp();
            0.05 / (a - 2.0) * (a - (t - 0.5).exp() - (-t + 0.5).exp())
        };
        for t in [0.1, 0.3, 0.77] {
            assert!((swing_rise(t, 0.05) - e(t)).abs() < 1e-15);
        }
    }

    #[test]
    fn eq4_is_the_identity_when_the_ends_match_and_meets_them_otherwise() {
        let t: Vec<f64> = (0..=10).map(|i| i as f64 / 10.0).collect();
        let h: Vec<f64> = t.iter().map(|t| 0.9 + 0.03 * (6.0 * t).sin()).collect();
        let same = interpolate_ends(&t, &h, h[0], h[10]);
        assert_eq!(same, h);
        let moved = interpolate_ends(&t, &h, 0.8, 0.95);
        assert!((moved[0] - 0.8).abs() < 1e-15 && (moved[10] - 0.95).abs() < 1e-15);
        // the shape is kept: the difference is linear in t
        for i in 0..=10 {
            let d = moved[i] - h[i];
            let lin = (1.0 - t[i]) * (0.8 - h[0]) + t[i] * (0.95 - h[10]);
            assert!((d - lin).abs() < 1e-15);
        }
    }

    #[test]
    fn eq5_gives_the_reversed_heights_and_meets_its_ends() {
        let t: Vec<f64> = (0..=8).map(|i| i as f64 / 8.0).collect();
        let h: Vec<f64> = t.iter().map(|t| 0.9 + 0.02 * t + 0.01 * t * t).collect();
        let back = interpolate_reversed(&t, &h, h[8], h[0]);
        for i in 0..=8 {
            assert_eq!(back[i], h[8 - i]);
        }
        let moved = interpolate_reversed(&t, &h, 0.85, 0.87);
        assert!((moved[0] - 0.85).abs() < 1e-15 && (moved[8] - 0.87).abs() < 1e-15);
    }

    #[test]
    fn end_slopes_are_set_and_the_ends_kept() {
        let n = 400;
        let mut q: Vec<f64> = (0..=n).map(|i| (i as f64 / n as f64).powi(2)).collect();
        set_end_slopes(&mut q, Some(1.5), Some(-0.5));
        let dt = 1.0 / n as f64;
        assert!((q[0]).abs() < 1e-15 && (q[n] - 1.0).abs() < 1e-12);
        assert!(((q[1] - q[0]) / dt - 1.5).abs() < 1e-2);
        assert!(((q[n] - q[n - 1]) / dt + 0.5).abs() < 1e-2);
        // one end only: the other slope stays that of t² (2 at t = 1)
        let mut r: Vec<f64> = (0..=n).map(|i| (i as f64 / n as f64).powi(2)).collect();
        set_end_slopes(&mut r, Some(1.0), None);
        assert!(((r[n] - r[n - 1]) / dt - 2.0).abs() < 1e-2);
    }

    #[test]
    fn de_casteljau_interpolates_its_end_points_and_stays_in_the_hull() {
        let d = [[0.0, 0.0], [1.0, 2.0], [2.0, 0.0]];
        assert_eq!(de_casteljau(d, 0.0), d[0]);
        assert_eq!(de_casteljau(d, 1.0), d[2]);
        // the midpoint of a quadratic Bézier is (D1 + 2 D2 + D3) / 4
        assert_eq!(de_casteljau(d, 0.5), [1.0, 1.0]);
    }

    #[test]
    fn a_table_returns_its_rows_and_interpolates_linearly() {
        let t = Table::<2>::new(4, |_, t| [t, 2.0 * t * t]);
        assert_eq!(t.at(0.5), [0.5, 0.5]);
        assert_eq!(t.at(1.0), [1.0, 2.0]);
        let mid = t.at(0.125);
        assert!((mid[0] - 0.125).abs() < 1e-15 && (mid[1] - 0.0625).abs() < 1e-15);
    }

    #[test]
    fn resample_is_exact_on_linear_data() {
        let times = [0.0, 0.1, 0.5, 1.0];
        let v: Vec<f64> = times.iter().map(|t| 3.0 * t + 1.0).collect();
        for (i, x) in resample(&times, &v, 10).iter().enumerate() {
            assert!((x - (3.0 * i as f64 / 10.0 + 1.0)).abs() < 1e-14);
        }
    }
}
