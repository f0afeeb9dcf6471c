//! The step-size control of an explicit Runge–Kutta pair (Hairer, Nørsett & Wanner, *Solving
//! ODEs I*, II.4: the error norm, the starting step size, the step size selection, with the
//! controllers of Hairer's DOPRI5 and DOP853 codes), one attempted step of each pair (Dopri5,
//! II.5; DOP853, II.10), and the loop that integrates one (sub)phase, adaptively or on a frozen
//! mesh.
use nalgebra::SVector;

use super::dense::{DenseStep, Stages};
use super::events;
use super::tableau::{dop853, dopri5};
use super::{IntegrationError, Mesh, Method, Outcome, Phase, Segment, Tolerance};

// PI step-size controller (Hairer's DOPRI5 defaults, as in ode_solvers).
const BETA: f64 = 0.04;
const ALPHA: f64 = 0.2 - 0.75 * BETA;
const SAFETY: f64 = 0.9;
/// 1 / (smallest step factor 0.2) and 1 / (largest 10).
const FACC1: f64 = 5.0;
const FACC2: f64 = 0.1;

/// Weighted RMS norm of `e` with the scale atol + rtol max(|a|, |b|) (II.4).
fn error_norm<const N: usize>(
    e: &SVector<f64, N>,
    a: &SVector<f64, N>,
    b: &SVector<f64, N>,
    tol: f64,
) -> f64 {
    let mut sum = 0.0;
    for i in 0..N {
        let sc = tol + tol * a[i].abs().max(b[i].abs());
        let q = e[i] / sc;
        sum += q * q;
    }
    (sum / N as f64).sqrt()
}

/// Initial step (II.4, Hairer's HINIT): two right-hand-side evaluations, `f0` given.
fn initial_step<P: Phase<N, K>, const N: usize, const K: usize>(
    phase: &P,
    t0: f64,
    y0: &SVector<f64, N>,
    f0: &SVector<f64, N>,
    h_max: f64,
    tol: f64,
    order: f64,
) -> f64 {
    let zero = SVector::<f64, N>::zeros();
    let d0 = error_norm(y0, y0, &zero, tol);
    let d1 = error_norm(f0, y0, &zero, tol);
    let mut h0 = if d0 < 1e-10 || d1 < 1e-10 {
        1e-6
    } else {
        0.01 * d0 / d1
    };
    h0 = h0.min(h_max);
    let f1 = phase.rhs(t0 + h0, &(y0 + f0 * h0));
    let d2 = error_norm(&(f1 - f0), y0, &zero, tol) / h0;
    let h1 = if d1.max(d2) <= 1e-15 {
        1e-6_f64.max(h0 * 1e-3)
    } else {
        (0.01 / d1.max(d2)).powf(1.0 / order)
    };
    (100.0 * h0).min(h1).min(h_max)
}

impl Method {
    /// The order that sets the step-size control's exponent.
    fn order(self) -> f64 {
        match self {
            Method::Dopri5 => 5.0,
            Method::Dop853 => 8.0,
        }
    }

    /// The step-size control (Hairer's defaults for each code): exponents α and β of the PI
    /// controller, 1 / smallest and 1 / largest step factor.
    fn control(self) -> (f64, f64, f64, f64) {
        match self {
            Method::Dopri5 => (ALPHA, BETA, FACC1, FACC2),
            Method::Dop853 => (0.125, 0.0, 1.0 / 0.333, 1.0 / 6.0),
        }
    }
}

/// One attempted step: the new state, the error norm, the stages.
struct Attempt<const N: usize> {
    y_new: SVector<f64, N>,
    err: f64,
    k: [SVector<f64, N>; 12],
}

/// A Dopri5 step from (t, y) with k1 = f(t, y): its stages k2..k7 (k7 = f(t + h, y_new)) in
/// `k[1..7]`.
fn dopri5_attempt<P: Phase<N, K>, const N: usize, const K: usize>(
    phase: &P,
    t: f64,
    y: &SVector<f64, N>,
    k1: &SVector<f64, N>,
    h: f64,
    tol: f64,
) -> Attempt<N> {
    use dopri5::*;
    let k1 = *k1;
    let k2 = phase.rhs(t + C2 * h, &(y + k1 * (h * A21)));
    let k3 = phase.rhs(t + C3 * h, &(y + (k1 * A31 + k2 * A32) * h));
    let k4 = phase.rhs(t + C4 * h, &(y + (k1 * A41 + k2 * A42 + k3 * A43) * h));
    let k5 = phase.rhs(
        t + C5 * h,
        &(y + (k1 * A51 + k2 * A52 + k3 * A53 + k4 * A54) * h),
    );
    let k6 = phase.rhs(
        t + h,
        &(y + (k1 * A61 + k2 * A62 + k3 * A63 + k4 * A64 + k5 * A65) * h),
    );
    let y_new = y + (k1 * A71 + k3 * A73 + k4 * A74 + k5 * A75 + k6 * A76) * h;
    let k7 = phase.rhs(t + h, &y_new);
    let e = (k1 * E1 + k3 * E3 + k4 * E4 + k5 * E5 + k6 * E6 + k7 * E7) * h;
    let err = error_norm(&e, y, &y_new, tol);
    let z = SVector::<f64, N>::zeros();
    Attempt {
        y_new,
        err,
        k: [k1, k2, k3, k4, k5, k6, k7, z, z, z, z, z],
    }
}

/// A DOP853 step from (t, y) with k1 = f(t, y): its stages k2..k12 in `k[1..12]`.
// the tableau's twelve rows written out, one expression each, in a fixed summation order
fn dop853_attempt<P: Phase<N, K>, const N: usize, const K: usize>(
    phase: &P,
    t: f64,
    y: &SVector<f64, N>,
    k1: &SVector<f64, N>,
    h: f64,
    tol: f64,
) -> Attempt<N> {
    let k1 = *k1;
    // each stage's argument sums y and its older stages first and the newest, k_{i−1}, last,
    // with the coefficients scaled by h: one multiply and one add stand between the right-hand
    // side that produced k_{i−1} and the next (the stages are a chain: its latency is the step's)
    let k2 = phase.rhs(t + dop853::C2 * h, &(y + k1 * (h * dop853::A2_1)));
    let k3 = phase.rhs(
        t + dop853::C3 * h,
        &((y + k1 * (h * dop853::A3_1)) + k2 * (h * dop853::A3_2)),
    );
    let k4 = phase.rhs(
        t + dop853::C4 * h,
        &((y + k1 * (h * dop853::A4_1)) + k3 * (h * dop853::A4_3)),
    );
    let k5 = phase.rhs(
        t + dop853::C5 * h,
        &((y + k1 * (h * dop853::A5_1) + k3 * (h * dop853::A5_3)) + k4 * (h * dop853::A5_4)),
    );
    let k6 = phase.rhs(
        t + dop853::C6 * h,
        &((y + k1 * (h * dop853::A6_1) + k4 * (h * dop853::A6_4)) + k5 * (h * dop853::A6_5)),
    );
    let k7 = phase.rhs(
        t + dop853::C7 * h,
        &((y + k1 * (h * dop853::A7_1) + k4 * (h * dop853::A7_4) + k5 * (h * dop853::A7_5))
            + k6 * (h * dop853::A7_6)),
    );
    let k8 = phase.rhs(
        t + dop853::C8 * h,
        &((y + k1 * (h * dop853::A8_1)
            + k4 * (h * dop853::A8_4)
            + k5 * (h * dop853::A8_5)
            + k6 * (h * dop853::A8_6))
            + k7 * (h * dop853::A8_7)),
    );
    let k9 = phase.rhs(
        t + dop853::C9 * h,
        &((y + k1 * (h * dop853::A9_1)
            + k4 * (h * dop853::A9_4)
            + k5 * (h * dop853::A9_5)
            + k6 * (h * dop853::A9_6)
            + k7 * (h * dop853::A9_7))
            + k8 * (h * dop853::A9_8)),
    );
    let k10 = phase.rhs(
        t + dop853::C10 * h,
        &((y + k1 * (h * dop853::A10_1)
            + k4 * (h * dop853::A10_4)
            + k5 * (h * dop853::A10_5)
            + k6 * (h * dop853::A10_6)
            + k7 * (h * dop853::A10_7)
            + k8 * (h * dop853::A10_8))
            + k9 * (h * dop853::A10_9)),
    );
    let k11 = phase.rhs(
        t + dop853::C11 * h,
        &((y + k1 * (h * dop853::A11_1)
            + k4 * (h * dop853::A11_4)
            + k5 * (h * dop853::A11_5)
            + k6 * (h * dop853::A11_6)
            + k7 * (h * dop853::A11_7)
            + k8 * (h * dop853::A11_8)
            + k9 * (h * dop853::A11_9))
            + k10 * (h * dop853::A11_10)),
    );
    let k12 = phase.rhs(
        t + h,
        &((y + k1 * (h * dop853::A12_1)
            + k4 * (h * dop853::A12_4)
            + k5 * (h * dop853::A12_5)
            + k6 * (h * dop853::A12_6)
            + k7 * (h * dop853::A12_7)
            + k8 * (h * dop853::A12_8)
            + k9 * (h * dop853::A12_9)
            + k10 * (h * dop853::A12_10))
            + k11 * (h * dop853::A12_11)),
    );
    let slope = k1 * dop853::B1
        + k6 * dop853::B6
        + k7 * dop853::B7
        + k8 * dop853::B8
        + k9 * dop853::B9
        + k10 * dop853::B10
        + k11 * dop853::B11
        + k12 * dop853::B12;
    let y_new = y + slope * h;
    // the 5th-order estimate, and the 3rd-order one that keeps it from being too optimistic
    // (Hairer's err = h e5² / √(e5² + 0.01 e3²))
    let e5 = k1 * dop853::ER1
        + k6 * dop853::ER6
        + k7 * dop853::ER7
        + k8 * dop853::ER8
        + k9 * dop853::ER9
        + k10 * dop853::ER10
        + k11 * dop853::ER11
        + k12 * dop853::ER12;
    let e3 = slope - k1 * dop853::BHH1 - k9 * dop853::BHH2 - k12 * dop853::BHH3;
    let (mut s5, mut s3) = (0.0, 0.0);
    for i in 0..N {
        let sc = tol + tol * y[i].abs().max(y_new[i].abs());
        s5 += (e5[i] / sc).powi(2);
        s3 += (e3[i] / sc).powi(2);
    }
    let deno = s5 + 0.01 * s3;
    let deno = if deno > 0.0 { deno } else { 1.0 };
    let err = h.abs() * s5 * (1.0 / (deno * N as f64)).sqrt();
    Attempt {
        y_new,
        err,
        k: [k1, k2, k3, k4, k5, k6, k7, k8, k9, k10, k11, k12],
    }
}

impl<'a, const N: usize> Mesh<'a, N> {
    /// The steps to follow from t0 towards t1, and the first one's size (none: adaptive).
    fn follow(self, t0: f64, t1: f64) -> (&'a [DenseStep<N>], f64) {
        match self {
            Mesh::Shifted(m) => (&m.steps, m.steps.first().map_or(0.0, |s| s.h)),
            Mesh::Aligned(m) => {
                // the step that contains t0 (ends after it), its rest merged into the next step
                // when under a tenth of it
                let mut i = m.steps.partition_point(|s| s.t + s.h <= t0);
                match m.steps.get(i) {
                    Some(s) if s.t <= t0 => {
                        let mut h = s.t + s.h - t0;
                        if i + 1 < m.steps.len() && h < 0.1 * s.h {
                            i += 1;
                            h += m.steps[i].h;
                        }
                        let j = i + m.steps[i..].partition_point(|s| s.t < t1);
                        (&m.steps[i..j], h)
                    }
                    _ => (&[], 0.0),
                }
            }
            Mesh::Adaptive => (&[], 0.0),
        }
    }
}

/// [`super::integrate_by`], the dense output left out when `lazy` ([`super::integrate_trial`]).
// Hairer's step-size loop kept whole: the step size, the controller's memory, the rejection
// flag and the position on the mesh are shared by the accept and reject branches.
#[allow(clippy::too_many_arguments)]
pub(super) fn run<P: Phase<N, K>, const N: usize, const K: usize>(
    method: Method,
    lazy: bool,
    phase: &P,
    t0: f64,
    y0: SVector<f64, N>,
    t1: f64,
    tolerance: Tolerance,
    mesh: Mesh<'_, N>,
) -> Result<Outcome<N>, IntegrationError> {
    let tol = tolerance.step;
    if !y0.iter().all(|v| v.is_finite()) {
        return Err(IntegrationError::NonFiniteStart { t: t0 });
    }
    let (follow, h_first) = mesh.follow(t0, t1);
    let mut next = 0;
    let mut adapted = follow.is_empty();
    let h_max = t1 - t0;
    let mut g_last = phase.events(t0, &y0);
    let mut k1 = phase.rhs(t0, &y0);
    let mut evaluations = 1u32;
    let mut h = match follow.first() {
        Some(_) => h_first,
        None => {
            evaluations += 2;
            initial_step(phase, t0, &y0, &k1, h_max, tol, method.order())
        }
    };
    let mut steps: Vec<DenseStep<N>> = Vec::with_capacity(64);
    // (as large as `steps` when lazy: grown by doubling it was reallocated and copied in every
    // trial)
    let mut pending: Vec<Stages<N>> = Vec::with_capacity(if lazy { 64 } else { 0 });
    let (mut t, mut y) = (t0, y0);
    let (alpha, beta, facc1, facc2) = method.control();
    let mut fac_old = 1e-4_f64;
    let mut reject = false;
    let mut hit = None;
    loop {
        if steps.len() >= tolerance.max_steps {
            return Err(IntegrationError::TooManySteps {
                limit: tolerance.max_steps,
                t,
            });
        }
        if 0.1 * h.abs() <= f64::EPSILON * t.abs() {
            return Err(IntegrationError::StepSizeUnderflow { t });
        }
        // the last step takes up a remainder under 1 % of it (under 10 % on a mesh, whose
        // steps end where the mesh's phase ended: a start moved back would otherwise add a
        // sliver step each time the mesh is followed again)
        let stretch = if next < follow.len() { 1.1 } else { 1.01 };
        let last = t + stretch * h >= t1;
        if last {
            h = t1 - t;
        }
        let attempt = match method {
            Method::Dopri5 => dopri5_attempt(phase, t, &y, &k1, h, tol),
            Method::Dop853 => dop853_attempt(phase, t, &y, &k1, h, tol),
        };
        evaluations += match method {
            Method::Dopri5 => 6,
            Method::Dop853 => 11,
        };
        let err = attempt.err;
        if !err.is_finite() {
            return Err(IntegrationError::NonFinite { t });
        }
        let following = next < follow.len();
        if following && err > tolerance.frozen_mesh {
            next = follow.len();
            adapted = true;
        }
        if err <= 1.0 || (following && err <= tolerance.frozen_mesh) {
            // PI control of the next step (needed only off the mesh: two `powf`)
            let (h_acc, err_old, rejected) = (h, fac_old, reject);
            let h_new = move || {
                let fac = (err.powf(alpha) / err_old.powf(beta) / SAFETY).clamp(facc2, facc1);
                let h_new = (h_acc / fac).min(h_max);
                if rejected { h_new.min(h_acc) } else { h_new }
            };
            fac_old = err.max(1e-4);
            reject = false;
            let (step, k_next) = match method {
                Method::Dopri5 => (
                    DenseStep::dopri5(t, h, &y, &attempt.y_new, &attempt.k),
                    attempt.k[6],
                ),
                Method::Dop853 => {
                    let k13 = phase.rhs(t + h, &attempt.y_new);
                    evaluations += 1;
                    let k = &attempt.k;
                    let stages = [k[0], k[5], k[6], k[7], k[8], k[9], k[10], k[11], k13];
                    let mut step = DenseStep::dop853(t, h, &y, &attempt.y_new, &k[0], &k13);
                    if lazy {
                        pending.push(stages);
                    } else {
                        step.complete(phase, &stages);
                        evaluations += 3;
                    }
                    (step, k13)
                }
            };
            steps.push(step);
            t = if last { t1 } else { t + h };
            y = attempt.y_new;
            k1 = k_next;
            let g = phase.events(t, &y);
            if let Some(k) = events::fired(&g_last, &g) {
                hit = Some(k);
                break;
            }
            g_last = g;
            if last {
                break;
            }
            h = if following {
                next += 1;
                match follow.get(next) {
                    Some(s) => s.h,
                    None => {
                        adapted = true;
                        h_new()
                    }
                }
            } else {
                h_new()
            };
        } else {
            h /= facc1.min(err.powf(alpha) / SAFETY);
            reject = true;
        }
    }
    let mut segment = Segment {
        t0,
        t1: t,
        y0,
        y1: y,
        steps,
        pending,
    };
    if let Some(k) = hit {
        evaluations += events::locate(phase, &mut segment, k, tolerance.event_time);
    }
    Ok(Outcome {
        segment,
        event: hit,
        evaluations,
        adapted,
    })
}

#[cfg(test)]
mod tests {
    use super::super::problems::{Damped, Exponentials, exact};
    use super::super::{integrate_by, integrate_on, integrate_with};
    use super::*;

    #[test]
    fn a_frozen_mesh_is_followed_while_accurate() {
        let y0 = SVector::<f64, 2>::new(1.0, 0.0);
        let tol = 1e-6;
        let first = integrate_with(&Damped(3.0), 0.0, y0, 5.0, tol).unwrap();
        assert!(first.adapted);
        // on its own mesh, the same integration again, with no step-size choices
        let again = integrate_on(
            &Damped(3.0),
            0.0,
            y0,
            5.0,
            tol,
            Mesh::Aligned(&first.segment),
        )
        .unwrap();
        assert!(!again.adapted);
        assert_eq!(again.segment.y1, first.segment.y1);
        assert_eq!(
            again.evaluations + 2,
            first.evaluations,
            "no initial-step trials"
        );
        // a nearby parameter follows the same mesh, as accurately as the adaptive integration
        let near = integrate_on(
            &Damped(3.01),
            0.0,
            y0,
            5.0,
            tol,
            Mesh::Aligned(&first.segment),
        )
        .unwrap();
        let adaptive = integrate_with(&Damped(3.01), 0.0, y0, 5.0, tol).unwrap();
        assert!(!near.adapted);
        assert!((near.segment.y1 - adaptive.segment.y1).amax() < 1e-5);
        // a very different one leaves the mesh where its error estimate grows
        let far = integrate_on(
            &Damped(6.0),
            0.0,
            y0,
            5.0,
            tol,
            Mesh::Aligned(&first.segment),
        )
        .unwrap();
        assert!(far.adapted);
    }

    /// The last step's mesh, as the engine follows it into the next step
    /// (`walk::Walker::step`): entered inside one of its steps, and over a phase a sliver
    /// longer than its own, it still needs no step-size choice and no extra step.
    #[test]
    fn a_mesh_is_entered_mid_step_and_not_outgrown() {
        let y0 = SVector::<f64, 2>::new(1.0, 0.0);
        let tol = 1e-6;
        let first = integrate_with(&Damped(3.0), 0.0, y0, 5.0, tol).unwrap();
        let steps: Vec<(f64, f64)> = first.segment.steps().collect();
        let n = steps.len();
        // from the middle of the 4th step: its rest, then the mesh's steps
        let (a, b) = steps[3];
        let t0 = 0.5 * (a + b);
        let y_mid = first.segment.state(t0);
        let mid = integrate_on(
            &Damped(3.0),
            t0,
            y_mid,
            5.0,
            tol,
            Mesh::Aligned(&first.segment),
        )
        .unwrap();
        assert!(!mid.adapted);
        let mid_steps: Vec<(f64, f64)> = mid.segment.steps().collect();
        assert_eq!(mid_steps.len(), n - 3);
        assert_eq!(mid_steps[0], (t0, b));
        assert_eq!(mid_steps[1], steps[4]);
        let adaptive = integrate_with(&Damped(3.0), t0, y_mid, 5.0, tol).unwrap();
        assert!((mid.segment.y1 - adaptive.segment.y1).amax() < 1e-5);
        // a phase 5 % of its last step longer: the last step takes up the rest
        let (a, b) = steps[n - 2];
        let t1 = 5.0 + 0.05 * (b - a);
        let longer = integrate_on(
            &Damped(3.0),
            0.0,
            y0,
            t1,
            tol,
            Mesh::Shifted(&first.segment),
        )
        .unwrap();
        assert!(!longer.adapted);
        assert_eq!(longer.segment.steps().count(), n);
        assert_eq!(longer.segment.t1, t1);
    }

    #[test]
    fn adaptive_dop853_meets_its_tolerance() {
        // (at 1e-6 the steps are long and the dense output's error inside them reaches 1.8e-5)
        for tol in [1e-8, 1e-10] {
            let out = integrate_by(
                Method::Dop853,
                &Exponentials,
                0.0,
                exact(0.0),
                2.0,
                tol,
                Mesh::Adaptive,
            )
            .unwrap();
            let end = (out.segment.y1 - exact(2.0)).amax();
            assert!(end < 10.0 * tol, "{tol}: {end:e}");
            for i in 0..=200 {
                let t = 0.01 * i as f64;
                let e = (out.segment.state(t) - exact(t)).amax();
                assert!(e < 10.0 * tol, "{tol}, t {t}: {e:e}");
            }
        }
    }
}
