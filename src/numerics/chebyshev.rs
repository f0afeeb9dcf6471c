//! Chebyshev interpolation of a smooth function on an interval, kept as a polynomial with its
//! derivative and evaluated by Estrin's scheme: a table that costs two short multiply-add trees
//! per lookup and no division.
use std::f64::consts::PI;

/// Terms of every [`Chebyshev`] series (its interpolation nodes, and the degree + 1 of its
/// polynomial).
pub(crate) const TERMS: usize = 20;

/// A function on [lo, hi] interpolated at the Chebyshev nodes: the series Σ′ c_j T_j(y),
/// y = (2x − lo − hi)/(hi − lo) (the first term halved; Press et al., *Numerical Recipes*, §5.8:
/// `chebft`), kept as the polynomial Σ a_k y^k (§5.10: `chebpc`) and its derivative's
/// Σ (k + 1) a_{k+1} y^k, each evaluated by [`estrin`]'s scheme (Knuth, *TAOCP* vol. 2, §4.6.4):
/// one multiply-add a term like Horner's rule, where Clenshaw's recurrence on the series and its
/// derivative's takes three a term for each, but in a tree five multiply-adds deep instead of a
/// chain of twenty, for a caller that waits for the value. The power form is accurate when the
/// coefficients c_j fall fast (a function smooth on the interval): the large coefficients of
/// T_j's high powers multiply small c_j.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Chebyshev {
    lo: f64,
    hi: f64,
    /// y = (x − mid) · scale: the interval's midpoint and 2 / (hi − lo), kept so that an
    /// evaluation divides nothing.
    mid: f64,
    scale: f64,
    a: [f64; TERMS],
    /// The derivative's coefficients (in y), (k + 1) a_{k+1}; the last is 0.
    da: [f64; TERMS],
}

/// Σ a_k y^k by Estrin's scheme: pairs a_{2i} + a_{2i+1} y, then pairs of those with y², y⁴,
/// y⁸, y¹⁶ (twenty terms).
#[inline(always)]
pub(crate) fn estrin(a: &[f64; TERMS], y: f64) -> f64 {
    const _: () = assert!(TERMS == 20);
    let y2 = y * y;
    let y4 = y2 * y2;
    let y8 = y4 * y4;
    let p: [f64; 10] = std::array::from_fn(|i| a[2 * i] + a[2 * i + 1] * y);
    let q: [f64; 5] = std::array::from_fn(|i| p[2 * i] + p[2 * i + 1] * y2);
    let r = [q[0] + q[1] * y4, q[2] + q[3] * y4];
    (r[0] + r[1] * y8) + q[4] * (y8 * y8)
}

impl Chebyshev {
    /// The zero function on [0, 1].
    pub(crate) const ZERO: Chebyshev = Chebyshev {
        lo: 0.0,
        hi: 1.0,
        mid: 0.5,
        scale: 2.0,
        a: [0.0; TERMS],
        da: [0.0; TERMS],
    };

    /// The series interpolating `f` at the [`TERMS`] Chebyshev nodes of [lo, hi].
    pub(crate) fn fit(f: impl Fn(f64) -> f64, lo: f64, hi: f64) -> Self {
        const N: usize = TERMS;
        let (mid, half) = (0.5 * (hi + lo), 0.5 * (hi - lo));
        // c_j = (2/N) Σ_k f(x_k) T_j(y_k), y_k = cos(π (k + ½)/N), T_j by its recurrence
        let mut c = [0.0; N];
        for k in 0..N {
            let y = (PI * (k as f64 + 0.5) / N as f64).cos();
            let f = 2.0 / N as f64 * f(mid + half * y);
            let (mut t0, mut t1) = (1.0, y);
            for cj in c.iter_mut() {
                *cj += f * t0;
                (t0, t1) = (t1, 2.0 * y * t1 - t0);
            }
        }
        c[0] *= 0.5;
        // Σ c_j T_j as powers of y: the coefficients of T_j and T_{j+1}, by the same recurrence
        let mut a = [0.0; N];
        let (mut t0, mut t1) = ([0.0; N], [0.0; N]);
        (t0[0], t1[1]) = (1.0, 1.0);
        for &cj in &c {
            a.iter_mut().zip(&t0).for_each(|(ak, tk)| *ak += cj * tk);
            let next = std::array::from_fn(|k| if k > 0 { 2.0 * t1[k - 1] } else { 0.0 } - t0[k]);
            (t0, t1) = (t1, next);
        }
        let da = std::array::from_fn(|k| {
            if k + 1 < N {
                (k + 1) as f64 * a[k + 1]
            } else {
                0.0
            }
        });
        Chebyshev {
            lo,
            hi,
            mid,
            scale: 1.0 / half,
            a,
            da,
        }
    }

    /// The interval's lower end.
    #[inline]
    pub(crate) fn lo(&self) -> f64 {
        self.lo
    }

    /// The interval's upper end.
    #[inline]
    pub(crate) fn hi(&self) -> f64 {
        self.hi
    }

    /// f(x) and f′(x) ([`estrin`]).
    #[inline]
    pub(crate) fn eval(&self, x: f64) -> (f64, f64) {
        let y = (x - self.mid) * self.scale;
        (estrin(&self.a, y), estrin(&self.da, y) * self.scale)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Estrin's scheme against the binomial theorem: Σ C(19, k) y^k = (1 + y)^19.
    #[test]
    fn estrin_sums_a_known_polynomial() {
        let mut a = [1.0; TERMS];
        for k in 1..TERMS {
            a[k] = a[k - 1] * (TERMS - k) as f64 / k as f64;
        }
        for y in [-1.0, -0.7, -0.25, 0.0, 0.3, 0.5, 1.0] {
            let exact = (1.0_f64 + y).powi(19);
            let got = estrin(&a, y);
            assert!(
                (got - exact).abs() <= 1e-15 * 2f64.powi(19),
                "{y}: {got} {exact}"
            );
        }
    }

    /// The Chebyshev series of exp on [0.2, 0.9] and of its derivative against exp itself (the
    /// derivative to the rounding of its terms, amplified by up to TERMS²).
    #[test]
    fn chebyshev_series_meets_an_analytic_function() {
        let ch = Chebyshev::fit(f64::exp, 0.2, 0.9);
        for k in 0..=100 {
            let x = 0.2 + 0.7 * k as f64 / 100.0;
            let (f, df) = ch.eval(x);
            assert!(
                (f - x.exp()).abs() < 1e-14 && (df - x.exp()).abs() < 1e-11,
                "{x}: {f} {df}"
            );
        }
    }
}
