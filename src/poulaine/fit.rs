//! A sampled poulaine modelled (Pronost et al. §3.2): the four characteristic points found in
//! the samples, the shape through them, and the speed along it.
//!
//! The shape: the four knots' tangents fitted by least squares, one coordinate at a time, to
//! every sample at its curve parameter ψᵢ, alternating with ψᵢ moved to the point of its knot
//! interval's curve nearest the sample (the paper's "iterative algorithm, which searches for
//! the tangents minimizing the distance between the real and the calculated curve"), from
//! ψᵢ = φᵢ = tᵢ / T, until a round gains less than [`FitParameters::shape_tolerance`]; the knots keep their
//! samples' phases. The curve is
//! linear in its tangents (four unknowns per coordinate), so each fit solves the normal
//! equations AᵀA m = Aᵀ(y − p₀), by argmin's conjugate gradient (exact in four steps but for
//! round-off). The speed: per interval, ψ against the time, both normalized to the interval
//! ([`crate::poulaine::curve::Speed`]), made nondecreasing.
use argmin::core::{Error as ArgminError, Executor, Operator, State};
use argmin::solver::conjugategradient::ConjugateGradient;
use serde::{Deserialize, Serialize};

use crate::poulaine::curve::{Component, LegCurve, SPEED_STEPS, Speed, hermite};
use crate::poulaine::error::PoulaineError;
use crate::poulaine::parameters::FitParameters;
use crate::poulaine::trajectory::Trajectory;

/// A poulaine's model: both ankles' curves over a cycle of duration `period`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Model {
    /// The cycle's duration T (s).
    pub period: f64,
    /// The right ankle.
    pub right: LegCurve,
    /// The left ankle.
    pub left: LegCurve,
}

/// How far the model lies from the samples it was fitted to (m): the distance from each sample
/// to the model at its phase.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FitError {
    /// Root mean square over both ankles' samples.
    pub rms: f64,
    /// Largest.
    pub max: f64,
}

impl Model {
    /// The ankles at phase φ.
    pub fn at(&self, phi: f64) -> ([f64; 3], [f64; 3]) {
        (self.right.at(phi), self.left.at(phi))
    }

    /// The model sampled at `n` uniform instants over its cycle.
    pub fn sample(&self, n: usize) -> Trajectory {
        let phases: Vec<f64> = (0..n).map(|i| i as f64 / n as f64).collect();
        Trajectory {
            time: phases.iter().map(|p| p * self.period).collect(),
            period: self.period,
            right: phases.iter().map(|&p| self.right.at(p)).collect(),
            left: phases.iter().map(|&p| self.left.at(p)).collect(),
            pelvis_speed: None,
        }
    }

    /// The distance of the samples of `t` from the model.
    pub fn error(&self, t: &Trajectory) -> FitError {
        let mut sum = 0.0;
        let mut max: f64 = 0.0;
        for (i, time) in t.time.iter().enumerate() {
            let (r, l) = self.at(time / t.period);
            for (m, s) in [(r, t.right[i]), (l, t.left[i])] {
                let d2: f64 = (0..3).map(|a| (m[a] - s[a]).powi(2)).sum();
                sum += d2;
                max = max.max(d2.sqrt());
            }
        }
        FitError {
            rms: (sum / (2 * t.time.len()) as f64).sqrt(),
            max,
        }
    }
}

impl Model {
    /// The distance of the samples of `t` from the model's curves as shapes: each sample's
    /// distance to the nearest point of its ankle's curve, whatever its time (`nearest` over
    /// the whole cycle; the paper's Figure 3 compares shapes; the speed along them is modelled
    /// apart, §3.2). At most [`Self::error`] but for the search's round-off.
    pub fn shape_error(&self, t: &Trajectory) -> FitError {
        let mut sum = 0.0;
        let mut max: f64 = 0.0;
        for (curve, samples) in [(&self.right, &t.right), (&self.left, &t.left)] {
            for s in samples {
                let p = FitParameters::DEFAULT;
                let (_, d2) = nearest(curve, s, (0.0, 1.0), p.cycle_grid, p.golden_steps);
                sum += d2;
                max = max.max(d2.sqrt());
            }
        }
        FitError {
            rms: (sum / (2 * t.time.len()) as f64).sqrt(),
            max,
        }
    }
}

/// The characteristic points' sample indices of one ankle (points 1 to 4, module doc of
/// [`crate::poulaine::curve`]), checked to come in the cycle's order 1, 2, 3, 4.
pub fn characteristic_points(
    leg: &[[f64; 3]],
    name: &'static str,
) -> Result<[usize; 4], PoulaineError> {
    let n = leg.len();
    let arg = |key: &dyn Fn(&[f64; 3]) -> f64| {
        (0..n).fold(0, |b, i| if key(&leg[i]) > key(&leg[b]) { i } else { b })
    };
    let highest = arg(&|p| p[1]);
    let front = arg(&|p| p[0]);
    let back = arg(&|p| -p[0]);
    // after `from`, cyclically
    let after = |i: usize, from: usize| (i + n - from) % n;
    let support = after(back, front);
    let under = (0..=support)
        .map(|k| (front + k) % n)
        .min_by(|&a, &b| leg[a][0].abs().total_cmp(&leg[b][0].abs()))
        .expect("the support has a sample");
    let order = [highest, front, under, back];
    let offsets: Vec<usize> = order.iter().map(|&i| after(i, highest)).collect();
    if !(offsets[1] > 0 && offsets[1] < offsets[2] && offsets[2] < offsets[3]) {
        return Err(PoulaineError::Order {
            leg: name,
            reason: format!(
                "samples {highest} (highest), {front} (most forward), {under} (under the pelvis), \
                 {back} (most backward) of {n}"
            ),
        });
    }
    Ok(order)
}

/// One coordinate's least-squares problem in its four slopes: Σᵢ (p(φᵢ) − yᵢ)².
struct Slopes<'a> {
    /// The knots (phases and values; the slopes are the unknowns).
    knots: Component,
    phases: &'a [f64],
    samples: Vec<f64>,
}

impl Slopes<'_> {
    /// The residuals and, for each, the slopes' coefficients.
    fn rows(&self, slopes: &[f64]) -> impl Iterator<Item = (f64, [f64; 4])> + '_ {
        let c = Component {
            slope: [slopes[0], slopes[1], slopes[2], slopes[3]],
            ..self.knots
        };
        self.phases
            .iter()
            .zip(&self.samples)
            .map(move |(&phi, &y)| {
                let (k, s, d) = c.locate(phi);
                let [_, h10, _, h11] = hermite(s);
                let mut coef = [0.0; 4];
                coef[k] += h10 * d;
                coef[(k + 1) % 4] += h11 * d;
                (c.at(phi) - y, coef)
            })
    }
}

impl Slopes<'_> {
    /// AᵀA and Aᵀ(y − p₀) of the normal equations (p₀: the curve with zero slopes).
    fn normal_equations(&self) -> ([[f64; 4]; 4], Vec<f64>) {
        let (mut ata, mut atb) = ([[0.0; 4]; 4], vec![0.0; 4]);
        for (r0, coef) in self.rows(&[0.0; 4]) {
            for i in 0..4 {
                atb[i] -= coef[i] * r0;
                for j in 0..4 {
                    ata[i][j] += coef[i] * coef[j];
                }
            }
        }
        (ata, atb)
    }
}

/// The normal equations' matrix as an argmin operator.
struct Normal([[f64; 4]; 4]);

impl Operator for Normal {
    type Param = Vec<f64>;
    type Output = Vec<f64>;
    fn apply(&self, m: &Vec<f64>) -> Result<Vec<f64>, ArgminError> {
        Ok((0..4)
            .map(|i| (0..4).map(|j| self.0[i][j] * m[j]).sum())
            .collect())
    }
}

/// The slopes that fit one coordinate's samples: conjugate gradient from the
/// finite-difference slopes (the chord through each knot's neighbouring samples).
fn fit_component(
    knots: [usize; 4],
    phases: &[f64],
    samples: Vec<f64>,
    leg: &'static str,
) -> Result<Component, PoulaineError> {
    let n = phases.len();
    let start: Vec<f64> = knots
        .iter()
        .map(|&i| {
            let (a, b) = ((i + n - 1) % n, (i + 1) % n);
            let dphi = (phases[b] - phases[a]).rem_euclid(1.0);
            (samples[b] - samples[a]) / dphi
        })
        .collect();
    let knots = Component {
        phase: knots.map(|i| phases[i]),
        value: knots.map(|i| samples[i]),
        slope: [0.0; 4],
    };
    let problem = Slopes {
        knots,
        phases,
        samples,
    };
    let fail = |e: ArgminError| PoulaineError::Fit {
        leg,
        reason: e.to_string(),
    };
    let (ata, atb) = problem.normal_equations();
    let scale: f64 = atb.iter().map(|b| b * b).sum::<f64>().max(1e-300);
    let result = Executor::new(Normal(ata), ConjugateGradient::new(atb))
        .configure(|s| s.param(start).max_iters(12).target_cost(1e-28 * scale))
        .timer(false)
        .run()
        .map_err(fail)?;
    let m = result
        .state()
        .get_best_param()
        .cloned()
        .ok_or_else(|| fail(ArgminError::msg("no point")))?;
    if !m.iter().all(|v| v.is_finite()) {
        return Err(fail(ArgminError::msg("the tangents are not finite")));
    }
    Ok(Component {
        slope: [m[0], m[1], m[2], m[3]],
        ..knots
    })
}

/// Model the poulaine `t` (module doc), and the model's error on its samples.
pub fn fit(t: &Trajectory) -> Result<(Model, FitError), PoulaineError> {
    fit_with(t, &FitParameters::DEFAULT)
}

/// [`fit`] with the tolerances and grids `p`.
pub fn fit_with(t: &Trajectory, p: &FitParameters) -> Result<(Model, FitError), PoulaineError> {
    t.check(std::path::Path::new("(poulaine)"))?;
    let phases: Vec<f64> = t.time.iter().map(|x| x / t.period).collect();
    let model = Model {
        period: t.period,
        right: fit_leg(&t.right, &phases, "right", p)?,
        left: fit_leg(&t.left, &phases, "left", p)?,
    };
    let error = model.error(t);
    Ok((model, error))
}

/// One ankle's shape and speed (module doc).
fn fit_leg(
    samples: &[[f64; 3]],
    phases: &[f64],
    name: &'static str,
    p: &FitParameters,
) -> Result<LegCurve, PoulaineError> {
    let knots = characteristic_points(samples, name)?;
    let shape = |psi: &[f64]| -> Result<LegCurve, PoulaineError> {
        let axis =
            |a: usize| fit_component(knots, psi, samples.iter().map(|p| p[a]).collect(), name);
        Ok(LegCurve {
            x: axis(0)?,
            y: axis(1)?,
            z: axis(2)?,
            speed: Speed::default(),
        })
    };
    let distance = |curve: &LegCurve, psi: &[f64]| {
        let sum: f64 = psi
            .iter()
            .zip(samples)
            .map(|(&u, p)| {
                let m = curve.shape_at(u);
                (0..3).map(|a| (m[a] - p[a]).powi(2)).sum::<f64>()
            })
            .sum();
        (sum / psi.len() as f64).sqrt()
    };
    let mut psi = phases.to_vec();
    let mut curve = shape(&psi)?;
    let mut last = distance(&curve, &psi);
    let segments = intervals(knots, phases);
    for _ in 0..p.shape_rounds {
        let next = project(&curve, &segments, samples, phases, p);
        let refit = shape(&next)?;
        let d = distance(&refit, &next);
        (psi, curve) = (next, refit);
        if last - d < p.shape_tolerance * last {
            break;
        }
        last = d;
    }
    curve.speed = speed(&segments, phases, &psi);
    Ok(curve)
}

/// Per knot interval: its first knot's phase, its span and the samples strictly inside it.
type Segments = [(f64, f64, Vec<usize>); 4];

/// The samples' knot intervals: for interval k (knot k to k + 1, cyclically), its knots'
/// phases and the indices of the samples strictly inside it.
fn intervals(knots: [usize; 4], phases: &[f64]) -> Segments {
    let n = phases.len();
    std::array::from_fn(|k| {
        let (a, b) = (knots[k], knots[(k + 1) % 4]);
        let inside = (1..(b + n - a) % n).map(|j| (a + j) % n).collect();
        let span = (phases[b] - phases[a]).rem_euclid(1.0);
        (phases[a], span, inside)
    })
}

/// Each sample's parameter moved to the nearest point of its interval's curve (`curve`'s
/// shape, [`nearest`] on a 64-point grid). The knots keep their phases, and so do the samples
/// of an interval holding fewer than [`FitParameters::min_inside`] of them: free parameters on
/// so few samples let the cubic wind through them, while their phases tie the interval's two
/// tangents to the time (a 60 Hz poulaine's swing interval holds 3 samples: with every
/// interval held at its phases for it, the model missed its samples by 2.2 cm RMS at H 1.8 m,
/// 1.4 m/s, against 0.65 cm at 100 Hz).
fn project(
    curve: &LegCurve,
    segments: &Segments,
    samples: &[[f64; 3]],
    phases: &[f64],
    p: &FitParameters,
) -> Vec<f64> {
    let mut psi = phases.to_vec();
    for (start, span, inside) in segments {
        if inside.len() < p.min_inside {
            continue;
        }
        for &i in inside {
            let segment = (*start, *span);
            psi[i] = nearest(curve, &samples[i], segment, p.segment_grid, p.golden_steps).0;
        }
    }
    psi
}

/// The parameter ψ in the `(start, span)` segment [start, start + span] (cyclic) of the point
/// of `curve`'s shape nearest `p`, and its squared distance: the best of `grid` + 1 evenly
/// spaced points, refined by `golden_steps` of golden section between its neighbours.
fn nearest(
    curve: &LegCurve,
    p: &[f64; 3],
    (start, span): (f64, f64),
    grid: usize,
    golden_steps: usize,
) -> (f64, f64) {
    let d2 = |u: f64| {
        let m = curve.shape_at(start + span * u);
        (0..3).map(|a| (m[a] - p[a]).powi(2)).sum::<f64>()
    };
    let step = 1.0 / grid as f64;
    let best = (0..=grid)
        .map(|j| (j, d2(j as f64 * step)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .expect("a grid")
        .0;
    let (mut lo, mut hi) = (
        best.saturating_sub(1) as f64 * step,
        (best + 1).min(grid) as f64 * step,
    );
    let r = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..golden_steps {
        let (c, d) = (hi - r * (hi - lo), lo + r * (hi - lo));
        if d2(c) < d2(d) {
            hi = d;
        } else {
            lo = c;
        }
    }
    let u = 0.5 * (lo + hi);
    ((start + span * u).rem_euclid(1.0), d2(u))
}

/// The speed profile of the parameters `psi` at the times `phases` (module doc): per interval
/// the pairs (s, g) of its samples between (0, 0) and (1, 1), g made nondecreasing by
/// [`isotonic`] regression, read linearly at the profile's times.
fn speed(segments: &Segments, phases: &[f64], psi: &[f64]) -> Speed {
    let mut profile = [[0.0; SPEED_STEPS + 1]; 4];
    for (k, &(start, span, ref inside)) in segments.iter().enumerate() {
        let mut pairs = vec![(0.0, 0.0)];
        for &i in inside {
            let s = (phases[i] - start).rem_euclid(1.0) / span;
            pairs.push((s, ((psi[i] - start).rem_euclid(1.0) / span).min(1.0)));
        }
        pairs.push((1.0, 1.0));
        let g = isotonic(&pairs.iter().map(|p| p.1).collect::<Vec<_>>());
        pairs.iter_mut().zip(g).for_each(|(p, g)| p.1 = g);
        for (j, g) in profile[k].iter_mut().enumerate() {
            let s = j as f64 / SPEED_STEPS as f64;
            let w = pairs.windows(2).find(|w| w[1].0 >= s).expect("s ≤ 1");
            let f = if w[1].0 > w[0].0 {
                (s - w[0].0) / (w[1].0 - w[0].0)
            } else {
                1.0
            };
            *g = w[0].1 + f * (w[1].1 - w[0].1);
        }
        (profile[k][0], profile[k][SPEED_STEPS]) = (0.0, 1.0);
    }
    Speed(profile)
}

/// The nondecreasing sequence nearest `y` in least squares (pool adjacent violators: a block
/// that falls below its predecessor merges with it at their mean).
fn isotonic(y: &[f64]) -> Vec<f64> {
    let mut blocks: Vec<(f64, usize)> = Vec::with_capacity(y.len());
    for &v in y {
        blocks.push((v, 1));
        while let [.., (a, n), (b, m)] = blocks[..] {
            if a <= b {
                break;
            }
            blocks.truncate(blocks.len() - 2);
            blocks.push(((a * n as f64 + b * m as f64) / (n + m) as f64, n + m));
        }
    }
    blocks
        .into_iter()
        .flat_map(|(v, n)| std::iter::repeat_n(v, n))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pool adjacent violators, by hand: 1, 3, 2, 4 → 1, 2.5, 2.5, 4; 3, 2, 1 → their mean
    /// thrice; a nondecreasing sequence is kept.
    #[test]
    fn isotonic_regression_pools_the_violators() {
        assert_eq!(isotonic(&[1.0, 3.0, 2.0, 4.0]), [1.0, 2.5, 2.5, 4.0]);
        assert_eq!(isotonic(&[3.0, 2.0, 1.0]), [2.0, 2.0, 2.0]);
        assert_eq!(isotonic(&[0.0, 0.0, 0.5, 1.0]), [0.0, 0.0, 0.5, 1.0]);
    }
    use nalgebra::{Matrix4, Vector4};

    /// A poulaine-like closed curve: the ankle swings forward high and comes back low.
    fn trajectory(n: usize) -> Trajectory {
        let leg = |shift: f64, side: f64| -> Vec<[f64; 3]> {
            (0..n)
                .map(|i| {
                    let a = std::f64::consts::TAU * (i as f64 / n as f64 + shift);
                    [
                        0.4 * a.sin() + 0.05 * (2.0 * a).sin(),
                        -0.85 + 0.06 * (a - 1.0).cos().max(0.0).powi(2),
                        side * (0.05 + 0.01 * a.cos()),
                    ]
                })
                .collect()
        };
        Trajectory {
            time: (0..n).map(|i| i as f64 * 1.1 / n as f64).collect(),
            period: 1.1,
            right: leg(0.0, 1.0),
            left: leg(0.5, -1.0),
            pelvis_speed: None,
        }
    }

    /// argmin's slopes are the least-squares solution of the normal equations (nalgebra, an
    /// independent route) to 1e-8 of their size.
    #[test]
    fn the_fitted_slopes_solve_the_normal_equations() {
        let t = trajectory(90);
        let phases: Vec<f64> = t.time.iter().map(|x| x / t.period).collect();
        let knots = characteristic_points(&t.right, "right").unwrap();
        for a in 0..3 {
            let samples: Vec<f64> = t.right.iter().map(|p| p[a]).collect();
            let c = fit_component(knots, &phases, samples.clone(), "right").unwrap();
            let problem = Slopes {
                knots: Component {
                    slope: [0.0; 4],
                    ..c
                },
                phases: &phases,
                samples,
            };
            let (mut ata, mut atb) = (Matrix4::zeros(), Vector4::zeros());
            for (r0, coef) in problem.rows(&[0.0; 4]) {
                let v = Vector4::from(coef);
                ata += v * v.transpose();
                atb -= v * r0;
            }
            let exact = ata.lu().solve(&atb).unwrap();
            let got = Vector4::from(c.slope);
            assert!(
                (got - exact).amax() < 1e-8 * exact.amax().max(1.0),
                "{got} vs {exact}"
            );
        }
    }

    /// Samples of a known Hermite curve, with its knots on samples, give back its slopes and no
    /// error (the fit is exact where the model is).
    #[test]
    fn a_hermite_curve_is_fitted_exactly() {
        let n = 100;
        let phases: Vec<f64> = (0..n).map(|i| i as f64 / n as f64).collect();
        let knots = [85, 10, 37, 61];
        let truth = Component {
            phase: knots.map(|i| phases[i]),
            value: [0.12, 0.41, -0.02, -0.38],
            slope: [2.1, -0.4, -1.6, 0.25],
        };
        let samples: Vec<f64> = phases.iter().map(|&p| truth.at(p)).collect();
        let c = fit_component(knots, &phases, samples.clone(), "right").unwrap();
        for k in 0..4 {
            assert!((c.slope[k] - truth.slope[k]).abs() < 1e-9, "{:?}", c.slope);
        }
        let worst = phases
            .iter()
            .zip(&samples)
            .map(|(&p, y)| (c.at(p) - y).abs())
            .fold(0.0, f64::max);
        assert!(worst < 1e-12, "{worst}");
    }

    /// The shape error ignores timing: the model's own curve sampled at retimed phases
    /// (φ + 0.03 sin 2πφ) lies on the model (0 but for the 2000-point search) though far from it
    /// at the samples' times; and it never exceeds the time-aligned error.
    #[test]
    fn the_shape_error_ignores_timing() {
        let t = trajectory(90);
        let (model, err) = fit(&t).unwrap();
        assert!(
            model.shape_error(&t).rms <= err.rms,
            "{:?} {err:?}",
            model.shape_error(&t)
        );
        let n = 120;
        let phases: Vec<f64> = (0..n).map(|i| i as f64 / n as f64).collect();
        let warp = |p: f64| p + 0.03 * (std::f64::consts::TAU * p).sin();
        let retimed = Trajectory {
            time: phases.iter().map(|p| p * model.period).collect(),
            period: model.period,
            right: phases.iter().map(|&p| model.right.at(warp(p))).collect(),
            left: phases.iter().map(|&p| model.left.at(warp(p))).collect(),
            pelvis_speed: None,
        };
        let timed = model.error(&retimed);
        let shape = model.shape_error(&retimed);
        assert!(timed.rms > 0.02, "{timed:?}");
        assert!(shape.max < 1e-3, "{shape:?}");
    }

    /// A model whose characteristic points are its knots (x at its extremes and 0 at knots 2,
    /// 4 and 3, y highest at knot 1, monotone between), the knots on a 120-sample grid.
    fn knotted_model() -> Model {
        let leg = |phase: [f64; 4], side: f64| LegCurve {
            x: Component {
                phase,
                value: [-0.1, 0.4, 0.0, -0.35],
                slope: [2.0, 0.0, -1.5, 0.0],
            },
            y: Component {
                phase,
                value: [-0.75, -0.85, -0.87, -0.86],
                slope: [0.0, -0.2, 0.0, 0.3],
            },
            z: Component {
                phase,
                value: [0.08, 0.09, 0.1, 0.09].map(|v| side * v),
                slope: [0.0, 0.05, 0.0, -0.05].map(|v| side * v),
            },
            speed: Speed::default(),
        };
        Model {
            period: 1.1,
            right: leg([0.1, 0.3, 0.55, 0.8], 1.0),
            left: leg([0.6, 0.8, 0.05, 0.3], -1.0),
        }
    }

    /// The speed apart from the shape: a model's shape sampled at a known speed profile
    /// (g(s) = s + 0.1 sin 2πs in every interval, another pace along the same path) is fitted
    /// to within 1 mm RMS at the samples' times, where the same shape at the phase alone misses
    /// them by centimetres. (The profile itself is not unique: a Hermite segment's tangents
    /// also set the pace along its path, so the fit may trade the two.)
    #[test]
    fn a_known_speed_profile_is_recovered() {
        let mut model = knotted_model();
        let (plain, err) = fit(&model.sample(120)).unwrap();
        assert!(err.max < 1e-6, "{err:?}");
        assert!(
            plain
                .right
                .speed
                .0
                .iter()
                .flatten()
                .zip(Speed::default().0.iter().flatten())
                .all(|(a, b)| (a - b).abs() < 1e-6)
        );
        let warp = |s: f64| s + 0.1 * (std::f64::consts::TAU * s).sin();
        let known = Speed([std::array::from_fn(|j| warp(j as f64 / SPEED_STEPS as f64)); 4]);
        assert!(known.is_valid());
        model.right.speed = known;
        model.left.speed = known;
        let paced = model.sample(120);
        let (back, err) = fit(&paced).unwrap();
        assert!(err.rms < 1e-3 && err.max < 3e-3, "{err:?}");
        let mut unpaced = back;
        unpaced.right.speed = Speed::default();
        unpaced.left.speed = Speed::default();
        assert!(
            unpaced.error(&paced).rms > 0.01,
            "{:?}",
            unpaced.error(&paced)
        );
        assert!(back.right.speed.is_valid() && back.left.speed.is_valid());
    }

    /// The characteristic points of the test curve: highest, forward, under the pelvis, back,
    /// in order; a curve run backwards is refused naming the order.
    #[test]
    fn the_characteristic_points_come_in_order() {
        let t = trajectory(100);
        let [h, f, u, b] = characteristic_points(&t.right, "right").unwrap();
        assert!(t.right[f][0] > 0.39 && t.right[b][0] < -0.39 && t.right[u][0].abs() < 0.02);
        assert!(t.right[h][1] >= t.right.iter().map(|p| p[1]).fold(f64::MIN, f64::max));
        let mut reversed = t.right.clone();
        reversed.reverse();
        let e = characteristic_points(&reversed, "right").unwrap_err();
        assert!(e.to_string().contains("out of order"), "{e}");
    }
}
