//! The dense output of the accepted steps (Hairer, Nørsett & Wanner, *Solving ODEs I*, II.6):
//! Dopri5's quartic from the step's own stages, and DOP853's 7th-degree polynomial (II.10,
//! Hairer's `contd8`), whose last four coefficients cost three more stages and are left out of a
//! shooting trial's steps until [`Segment::densify`].
use nalgebra::SVector;

use super::tableau::{dop853, dopri5};
use super::{Phase, Segment};

/// The dense output of one accepted step on [t, t + h]: with θ = (t' − t)/h and θ' = 1 − θ,
/// y(t') = r0 + θ (r1 + θ' (r2 + θ (r3 + θ' (r4 + θ (r5 + θ' (r6 + θ r7)))))): Dopri5's
/// quartic has r5 = r6 = r7 = 0, DOP853's 7th-degree polynomial uses all eight.
/// `ready`: r4..r7 are computed (a shooting trial's DOP853 steps leave them to
/// [`Segment::densify`]).
#[derive(Clone, Copy, Debug)]
pub(super) struct DenseStep<const N: usize> {
    pub(super) t: f64,
    pub(super) h: f64,
    pub(super) r: [SVector<f64, N>; 8],
    pub(super) ready: bool,
}

/// What DOP853's dense output needs of an accepted step besides its ends: the stages k1,
/// k6..k12 and k13 = f(t + h, y_new).
pub(super) type Stages<const N: usize> = [SVector<f64, N>; 9];

impl<const N: usize> DenseStep<N> {
    /// Dopri5's accepted step (t, h) from y to `y_new` with stages `k` (k1..k7 in `k[..7]`):
    /// its quartic, complete.
    pub(super) fn dopri5(
        t: f64,
        h: f64,
        y: &SVector<f64, N>,
        y_new: &SVector<f64, N>,
        k: &[SVector<f64, N>; 12],
    ) -> Self {
        use dopri5::{D1, D3, D4, D5, D6, D7};
        let (k1, k3, k4, k5, k6, k7) = (k[0], k[2], k[3], k[4], k[5], k[6]);
        let ydiff = y_new - y;
        let bspl = k1 * h - ydiff;
        let r4 = (k1 * D1 + k3 * D3 + k4 * D4 + k5 * D5 + k6 * D6 + k7 * D7) * h;
        let z = SVector::<f64, N>::zeros();
        let r = [*y, ydiff, bspl, ydiff - k7 * h - bspl, r4, z, z, z];
        DenseStep {
            t,
            h,
            r,
            ready: true,
        }
    }

    /// DOP853's accepted step (t, h) from y to `y_new`, k1 = f(t, y), k13 = f(t + h, y_new):
    /// r0..r3, not yet ready ([`Self::complete`] adds r4..r7).
    pub(super) fn dop853(
        t: f64,
        h: f64,
        y: &SVector<f64, N>,
        y_new: &SVector<f64, N>,
        k1: &SVector<f64, N>,
        k13: &SVector<f64, N>,
    ) -> Self {
        let ydiff = y_new - y;
        let bspl = k1 * h - ydiff;
        let z = SVector::<f64, N>::zeros();
        let r = [*y, ydiff, bspl, ydiff - k13 * h - bspl, z, z, z, z];
        DenseStep {
            t,
            h,
            r,
            ready: false,
        }
    }

    /// DOP853's r4..r7 from the step's stages `k` ([`Stages`]) and three more evaluations of
    /// `phase`, the step's right-hand side.
    pub(super) fn complete<P: Phase<N, K>, const K: usize>(&mut self, phase: &P, k: &Stages<N>) {
        let tail = dop853_dense(phase, self.t, self.h, &self.r[0], k);
        self.r[4..].copy_from_slice(&tail);
        self.ready = true;
    }

    /// The state at t in [self.t, self.t + h].
    pub(super) fn eval(&self, t: f64) -> SVector<f64, N> {
        assert!(self.ready, "a dense output not computed (Segment::densify)");
        let th = (t - self.t) / self.h;
        // the nested form multiplied out, Σ w_k r_k with w = 1, θ, p, θp, p², θp², p³, θp³
        // (p = θθ'), summed as a tree: the same terms, but three vector additions deep
        // instead of a chain of seven multiply-adds
        let p = th * (1.0 - th);
        let (p2, th_p) = (p * p, th * p);
        let r = &self.r;
        (r[0] + r[1] * th + (r[2] * p + r[3] * th_p))
            + ((r[4] * p2 + r[5] * (th * p2)) + (r[6] * (p * p2) + r[7] * (th_p * p2)))
    }
}

/// The dense output's r4..r7 of DOP853's accepted step from (t, y) with stages `k` (k1,
/// k6..k13): three more stages.
fn dop853_dense<P: Phase<N, K>, const N: usize, const K: usize>(
    phase: &P,
    t: f64,
    h: f64,
    y: &SVector<f64, N>,
    k: &Stages<N>,
) -> [SVector<f64, N>; 4] {
    let [k1, k6, k7, k8, k9, k10, k11, k12, k13] = *k;
    let k14 = phase.rhs(
        t + dop853::C14 * h,
        &(y + (k1 * dop853::A14_1
            + k7 * dop853::A14_7
            + k8 * dop853::A14_8
            + k9 * dop853::A14_9
            + k10 * dop853::A14_10
            + k11 * dop853::A14_11
            + k12 * dop853::A14_12
            + k13 * dop853::A14_13)
            * h),
    );
    let k15 = phase.rhs(
        t + dop853::C15 * h,
        &(y + (k1 * dop853::A15_1
            + k6 * dop853::A15_6
            + k7 * dop853::A15_7
            + k8 * dop853::A15_8
            + k11 * dop853::A15_11
            + k12 * dop853::A15_12
            + k13 * dop853::A15_13
            + k14 * dop853::A15_14)
            * h),
    );
    let k16 = phase.rhs(
        t + dop853::C16 * h,
        &(y + (k1 * dop853::A16_1
            + k6 * dop853::A16_6
            + k7 * dop853::A16_7
            + k8 * dop853::A16_8
            + k9 * dop853::A16_9
            + k13 * dop853::A16_13
            + k14 * dop853::A16_14
            + k15 * dop853::A16_15)
            * h),
    );
    let d = |c: [f64; 16]| {
        (k1 * c[0]
            + k6 * c[5]
            + k7 * c[6]
            + k8 * c[7]
            + k9 * c[8]
            + k10 * c[9]
            + k11 * c[10]
            + k12 * c[11]
            + k13 * c[12]
            + k14 * c[13]
            + k15 * c[14]
            + k16 * c[15])
            * h
    };
    [d(dop853::D4), d(dop853::D5), d(dop853::D6), d(dop853::D7)]
}

impl<const N: usize> Segment<N> {
    /// Whether [`Self::state`] is available everywhere (else [`Self::densify`] first).
    #[cfg(test)]
    pub(crate) fn is_dense(&self) -> bool {
        self.pending.is_empty()
    }

    /// Complete the dense output that [`super::integrate_trial`] left out: three evaluations
    /// per step of the right-hand side `phase_at(t)` gives for the step starting at t (the phase
    /// of the integration that made it). Returns the evaluations.
    pub(crate) fn densify<P: Phase<N, K>, const K: usize>(
        &mut self,
        phase_at: impl Fn(f64) -> P,
    ) -> u32 {
        let mut evaluations = 0;
        for (step, k) in self.steps.iter_mut().zip(&self.pending) {
            if !step.ready {
                step.complete(&phase_at(step.t), k);
                evaluations += 3;
            }
        }
        self.pending = Vec::new();
        evaluations
    }

    /// The accepted steps (start, end), in order, within [t0, t1]: on each, the dense output is
    /// one polynomial.
    pub(crate) fn steps(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.steps
            .iter()
            .map(|s| (s.t.max(self.t0), (s.t + s.h).min(self.t1)))
            .filter(|(a, b)| b > a)
    }

    /// The state at `t`, clamped to [t0, t1].
    pub fn state(&self, t: f64) -> SVector<f64, N> {
        if t <= self.t0 {
            return self.y0;
        }
        if t >= self.t1 {
            return self.y1;
        }
        let i = self
            .steps
            .partition_point(|s| s.t + s.h < t)
            .min(self.steps.len() - 1);
        self.steps[i].eval(t)
    }
}

#[cfg(test)]
mod tests {
    use super::super::problems::{Exponentials, Oscillator, exact};
    use super::super::{Mesh, Method, integrate_by, integrate_trial, integrate_with};
    use super::*;

    #[test]
    fn dense_output_matches_the_analytic_solution() {
        struct Free;
        impl Phase<2, 0> for Free {
            fn rhs(&self, _t: f64, y: &SVector<f64, 2>) -> SVector<f64, 2> {
                SVector::<f64, 2>::new(y[1], -y[0])
            }
        }
        let out = integrate_with(&Free, 0.0, SVector::<f64, 2>::new(1.0, 0.0), 3.0, 1e-10).unwrap();
        assert_eq!(out.event, None);
        for i in 0..=30 {
            let t = 0.1 * i as f64;
            let y = out.segment.state(t);
            assert!((y[0] - t.cos()).abs() < 1e-8, "t {t}: {}", y[0]);
        }
        assert!((out.segment.y1[0] - 3.0_f64.cos()).abs() < 1e-9);
    }

    /// The dense output's tree sum against Hairer's nested form of DOP853's `contd8`,
    /// r0 + θ (r1 + θ' (r2 + θ (r3 + θ' (r4 + θ (r5 + θ' (r6 + θ r7)))))), on coefficients
    /// of both signs and sizes.
    #[test]
    fn dense_output_sums_the_nested_form() {
        let r: [SVector<f64, 1>; 8] = std::array::from_fn(|k| {
            SVector::<f64, 1>::new((k as f64 * 1.7 - 5.0) * 10f64.powi(k as i32 % 3))
        });
        let step = DenseStep {
            t: 0.3,
            h: 0.02,
            r,
            ready: true,
        };
        for i in 0..=20 {
            let t = 0.3 + 0.02 * i as f64 / 20.0;
            let (th, th1) = ((t - 0.3) / 0.02, 1.0 - (t - 0.3) / 0.02);
            let c = r.map(|v| v[0]);
            let nested = c[0]
                + th * (c[1]
                    + th1
                        * (c[2]
                            + th * (c[3] + th1 * (c[4] + th * (c[5] + th1 * (c[6] + th * c[7]))))));
            let got = step.eval(t)[0];
            assert!(
                (got - nested).abs() <= 1e-13 * nested.abs().max(1.0),
                "θ {th}: {got} {nested}"
            );
        }
    }

    #[test]
    fn a_trial_densified_later_has_the_same_dense_output() {
        let y0 = exact(0.0);
        let eager = integrate_by(
            Method::Dop853,
            &Exponentials,
            0.0,
            y0,
            2.0,
            1e-8,
            Mesh::Adaptive,
        )
        .unwrap();
        let mut lazy = integrate_trial(&Exponentials, 0.0, y0, 2.0, 1e-8, Mesh::Adaptive).unwrap();
        assert!(!lazy.segment.is_dense());
        let n = lazy.segment.steps.len() as u32;
        assert_eq!(lazy.evaluations + 3 * n, eager.evaluations);
        assert_eq!(lazy.segment.densify(|_| Exponentials), 3 * n);
        assert!(lazy.segment.is_dense());
        assert_eq!(lazy.segment.y1, eager.segment.y1);
        for i in 0..=40 {
            let t = 0.05 * i as f64;
            assert_eq!(lazy.segment.state(t), eager.segment.state(t), "t {t}");
        }
        // an event's step gets its dense output at once: the event is located on it
        let osc = integrate_trial(
            &Oscillator,
            0.0,
            SVector::<f64, 2>::new(1.0, 0.0),
            3.0,
            1e-10,
            Mesh::Adaptive,
        )
        .unwrap();
        assert!((osc.segment.t1 - std::f64::consts::FRAC_PI_2).abs() < 1e-10);
    }

    #[test]
    #[should_panic(expected = "densify")]
    fn a_trial_without_its_dense_output_is_not_read() {
        let out =
            integrate_trial(&Exponentials, 0.0, exact(0.0), 2.0, 1e-8, Mesh::Adaptive).unwrap();
        out.segment.state(1.0);
    }
}
