//! Functions known by their samples: piecewise-linear and local Lagrange interpolation, and
//! finite-difference derivatives on a uniform grid (Fornberg's weights, second order, one-sided
//! at the grid's ends).

/// ys at x, linear between the points (xs increasing, as long as ys, not empty) and held at the
/// end values beyond them.
pub fn piecewise_linear(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let n = xs.len();
    if x <= xs[0] {
        return ys[0];
    }
    if x >= xs[n - 1] {
        return ys[n - 1];
    }
    let i = xs.partition_point(|&p| p <= x) - 1;
    let u = (x - xs[i]) / (xs[i + 1] - xs[i]);
    ys[i] + u * (ys[i + 1] - ys[i])
}

/// Nodes of the local interpolation: a polynomial of degree 5 through the 6 samples around `t`.
const NODES: usize = 6;

/// The value at `t` of the degree-5 polynomial through the 6 samples `(times[i], values[i])`
/// nearest `t` (the 3 before and the 3 after it where the samples allow, else the first or last
/// 6; all of them when there are fewer). Exact at the sample times and for polynomials of degree
/// ≤ 5; for a smooth function sampled every h, the error is O(h⁶ f⁽⁶⁾). `times` must be
/// increasing and as long as `values` (not checked: the callers check their frames).
pub fn lagrange(times: &[f64], values: &[f64], t: f64) -> f64 {
    let n = times.len().min(values.len());
    if n == 0 {
        return f64::NAN;
    }
    // the last sample at or before t
    let i = times[..n].partition_point(|&x| x <= t).saturating_sub(1);
    let first = i.saturating_sub(NODES / 2 - 1).min(n.saturating_sub(NODES));
    let nodes = first..(first + NODES).min(n);
    let mut sum = 0.0;
    for j in nodes.clone() {
        if times[j] == t {
            return values[j];
        }
        let weight: f64 = nodes
            .clone()
            .filter(|&k| k != j)
            .map(|k| (t - times[k]) / (times[j] - times[k]))
            .product();
        sum += weight * values[j];
    }
    sum
}

/// Weights of the third derivative on 5 consecutive nodes, at node p (row p), times h³: the
/// central difference (−½, 1, 0, −1, ½) at p = 2 and the one-sided ones at the ends (Fornberg
/// 1988). Each is exact for polynomials of degree ≤ 4: second order.
const THIRD: [[f64; 5]; 5] = [
    [-2.5, 9.0, -12.0, 7.0, -1.5],
    [-1.5, 5.0, -6.0, 3.0, -0.5],
    [-0.5, 1.0, 0.0, -1.0, 0.5],
    [0.5, -3.0, 6.0, -5.0, 1.5],
    [1.5, -7.0, 12.0, -9.0, 2.5],
];

/// The third derivative of samples spaced `h` apart, at every sample: the central difference
/// (f₊₂ − 2f₊₁ + 2f₋₁ − f₋₂) / (2h³) where two samples lie on each side, the second-order
/// one-sided stencils (Fornberg 1988, second order) within two samples of an end. Fewer than 5 samples: NaN.
pub fn third_derivative(samples: &[f64], h: f64) -> Vec<f64> {
    let n = samples.len();
    if n < 5 {
        return vec![f64::NAN; n];
    }
    (0..n)
        .map(|k| {
            let start = k.saturating_sub(2).min(n - 5);
            let w = &THIRD[k - start];
            let s: f64 = (0..5).map(|j| w[j] * samples[start + j]).sum();
            s / (h * h * h)
        })
        .collect()
}

/// The first derivative of samples spaced `h` apart, at every sample: (f₊₁ − f₋₁) / 2h inside,
/// (∓3f₀ ± 4f₁ ∓ f₂) / 2h at the ends (second order). Fewer than 3 samples: NaN.
pub fn first_derivative(samples: &[f64], h: f64) -> Vec<f64> {
    let n = samples.len();
    if n < 3 {
        return vec![f64::NAN; n];
    }
    (0..n)
        .map(|k| match k {
            0 => (-3.0 * samples[0] + 4.0 * samples[1] - samples[2]) / (2.0 * h),
            k if k == n - 1 => {
                (3.0 * samples[k] - 4.0 * samples[k - 1] + samples[k - 2]) / (2.0 * h)
            }
            k => (samples[k + 1] - samples[k - 1]) / (2.0 * h),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every stencil is exact on polynomials of degree ≤ 4 (the Taylor conditions), so the
    /// third derivative of t⁴ − 2t³ + t, 24t − 12, comes out to round-off at every sample,
    /// including the one-sided ones at the ends.
    #[test]
    fn third_derivative_is_exact_on_quartics() {
        let h = 0.1;
        let f = |t: f64| t.powi(4) - 2.0 * t.powi(3) + t;
        let samples: Vec<f64> = (0..9).map(|k| f(0.3 + k as f64 * h)).collect();
        for (k, d) in third_derivative(&samples, h).iter().enumerate() {
            let t = 0.3 + k as f64 * h;
            assert!((d - (24.0 * t - 12.0)).abs() < 1e-8, "{k}: {d}");
        }
        // the rows are the moments Σ w oᵐ = 0, 0, 0, 6, 0 about their node
        for (p, w) in THIRD.iter().enumerate() {
            for (m, want) in [(0, 0.0), (1, 0.0), (2, 0.0), (3, 6.0), (4, 0.0)] {
                let s: f64 = (0..5).map(|j| w[j] * (j as f64 - p as f64).powi(m)).sum();
                assert!((s - want).abs() < 1e-12, "row {p}, moment {m}: {s}");
            }
        }
    }

    /// On sin(ωt) the central difference is exactly −ω³ cos(ωt) · 4 sin(x) sin²(x/2) / x³ with
    /// x = ωh; the error falls as h² (halving h divides it by 4), inside and at the ends.
    #[test]
    fn third_derivative_of_a_sine_converges_at_second_order() {
        let w = 2.0 * std::f64::consts::PI;
        let error = |h: f64, at: fn(usize) -> usize| {
            let n = (1.0 / h).round() as usize + 1;
            let s: Vec<f64> = (0..n).map(|k| (w * k as f64 * h).sin()).collect();
            let d = third_derivative(&s, h);
            let k = at(n);
            (d[k] + w.powi(3) * (w * k as f64 * h).cos(), d[k])
        };
        let middle = |n: usize| n / 2;
        let end = |_n: usize| 0;
        for h in [1.0 / 60.0, 1.0 / 120.0] {
            let x = w * h;
            let gain = 4.0 * x.sin() * (x / 2.0).sin().powi(2) / x.powi(3);
            let (_, d) = error(h, middle);
            let k = (1.0 / h).round() as usize / 2;
            let exact = -w.powi(3) * (w * k as f64 * h).cos() * gain;
            assert!((d - exact).abs() < 1e-9 * w.powi(3), "{d} vs {exact}");
        }
        for at in [middle, end] {
            let (e1, _) = error(1.0 / 60.0, at);
            let (e2, _) = error(1.0 / 120.0, at);
            let ratio = e1 / e2;
            assert!((ratio - 4.0).abs() < 0.1, "{ratio}");
        }
    }

    #[test]
    fn first_derivative_is_exact_on_quadratics() {
        let s: Vec<f64> = (0..5).map(|k| (k * k) as f64 * 0.01).collect();
        // f = t² at t = 0.1 k: f' = 0.2 k
        for (k, d) in first_derivative(&s, 0.1).iter().enumerate() {
            assert!((d - 0.2 * k as f64).abs() < 1e-12, "{k}: {d}");
        }
        assert!(first_derivative(&[1.0, 2.0], 0.1)[0].is_nan());
        assert!(third_derivative(&[1.0; 4], 0.1)[0].is_nan());
    }

    /// Degree-5 polynomials come back exactly between unevenly spaced samples; sample times
    /// return their samples; a sine at 100 Hz is recovered between the frames to O(h⁶).
    #[test]
    fn lagrange_is_exact_to_degree_five_and_accurate_beyond() {
        let p = |t: f64| 1.0 - t + 0.5 * t.powi(3) - 0.2 * t.powi(5);
        let times: Vec<f64> = (0..12)
            .map(|k| 0.1 * k as f64 + 0.01 * (k % 3) as f64)
            .collect();
        let values: Vec<f64> = times.iter().map(|&t| p(t)).collect();
        for t in [0.0, 0.05, 0.333, 0.71, 1.1, 1.12] {
            assert!((lagrange(&times, &values, t) - p(t)).abs() < 1e-12, "{t}");
        }
        assert_eq!(lagrange(&times, &values, times[4]), values[4]);
        let h = 0.01;
        let times: Vec<f64> = (0..200).map(|k| k as f64 * h).collect();
        let values: Vec<f64> = times.iter().map(|&t| (6.0 * t).sin()).collect();
        let worst = (0..300)
            .map(|k| k as f64 / 160.0)
            .map(|t| (lagrange(&times, &values, t) - (6.0 * t).sin()).abs())
            .fold(0.0, f64::max);
        // |f⁽⁶⁾| h⁶ max|Π(t − tᵢ)| / 6! ≤ 6⁶ · 1e-12 · 17 / 720 ≈ 1.1e-9 (one-sided at the ends)
        assert!(worst < 1.1e-9, "{worst}");
    }
}
