//! Mechanical work of the actuators over a step: the power of every actuator of the stance and
//! swing models, integrated over the step's dense-output segments.
//!
//! The actuators and their powers (docs/dynamics.md, "Generalized forces"):
//! - stance leg axis force F_w (the position actuator pa, telescopic subphase only; in the
//!   locked subphase F_w is a workless constraint force): F_w ẇ;
//! - stance leg torque F_θ1 (τ1, from the ground at the ankle): F_θ1 θ̇1;
//! - balance torque F_θ2 between leg and upper body: F_θ2 (θ̇2 − θ̇1);
//! - swing hip torque F_θ3 on the thigh: F_θ3 θ̇3 (the swing model's pelvis only translates, so
//!   the thigh's absolute rate is the joint rate of the model);
//! - swing knee torque F_θ4: F_θ4 θ̇4 (zero once the knee is locked).
//!
//! The *positive work* is Σ over actuators of ∫ max(Pᵢ, 0) dt: what the actuators deliver, with no
//! credit for the work they absorb (a muscle does not recover it). The *net work* is ∫ Σ Pᵢ dt.
//! Not included: the impulses (heel strike, knee locks), which are not actuators, and the hind
//! leg in double support, which is kinematic (no forces are modelled).
//!
//! Each segment is integrated by the composite Simpson rule on [`SAMPLES`] intervals. Within a
//! segment the powers are smooth except where the positive part or F_w ≥ 0 switches; there the
//! rule is first-order accurate locally, and the test `positive_work_converges_with_sampling`
//! bounds the sampling error.
use serde::Serialize;

use crate::control::stance::{StanceForces, StanceRun, StanceSetup};
use crate::control::swing::{Subphase, SwingForces, SwingSetup};
use crate::ode::Segment;

/// Simpson intervals per integration segment (even).
pub const SAMPLES: usize = 400;

/// Positive and net mechanical work (J).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Work {
    /// Σ ∫ max(Pᵢ, 0) dt over the actuators.
    pub positive: f64,
    /// ∫ Σ Pᵢ dt.
    pub net: f64,
}

impl std::ops::Add for Work {
    type Output = Work;
    fn add(self, o: Work) -> Work {
        Work {
            positive: self.positive + o.positive,
            net: self.net + o.net,
        }
    }
}

/// Composite Simpson rule for ∫ f over [a, b] on `n` intervals (`n` rounded up to even, ≥ 2).
pub fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
    let n = (n.max(2) + 1) & !1;
    let h = (b - a) / n as f64;
    let inner: f64 = (1..n)
        .map(|i| {
            let weight = if i % 2 == 1 { 4.0 } else { 2.0 };
            weight * f(a + i as f64 * h)
        })
        .sum();
    (f(a) + inner + f(b)) * h / 3.0
}

/// Work of `powers` (one entry per actuator) over [a, b]. The end points are sampled just inside
/// (1e-9 of the interval): a force that switches where a segment ends (the leg torque at
/// 0.4 t_step) counts with its value within the segment.
fn integrate<const K: usize>(powers: impl Fn(f64) -> [f64; K], a: f64, b: f64, n: usize) -> Work {
    if b <= a {
        return Work::default();
    }
    let inset = 1e-9 * (b - a);
    let n = (n.max(2) + 1) & !1;
    let h = (b - a) / n as f64;
    let mut sum = Work::default();
    for i in 0..=n {
        let weight = match i {
            0 => 1.0,
            i if i == n => 1.0,
            i if i % 2 == 1 => 4.0,
            _ => 2.0,
        };
        let p = powers((a + i as f64 * h).clamp(a + inset, b - inset));
        sum.positive += weight * p.iter().map(|p| p.max(0.0)).sum::<f64>();
        sum.net += weight * p.iter().sum::<f64>();
    }
    Work {
        positive: sum.positive * h / 3.0,
        net: sum.net * h / 3.0,
    }
}

/// Powers of the stance actuators at (t, y): [F_w ẇ, F_θ1 θ̇1, F_θ2 (θ̇2 − θ̇1)] (W).
pub fn stance_powers(
    forces: &StanceForces,
    t: f64,
    y: &crate::control::stance::StanceState,
) -> [f64; 3] {
    // Q = (F_w, F_θ1 − F_θ2, F_θ2)
    let q = forces.generalized(t, y);
    let (f_w, f_2) = (q[0], q[2]);
    let f_1 = q[1] + f_2;
    [f_w * y[3], f_1 * y[4], f_2 * (y[5] - y[4])]
}

/// Work of the stance actuators over a stance run, `n` Simpson intervals per segment.
pub fn stance_work(setup: &StanceSetup, run: &StanceRun, n: usize) -> Work {
    run.segments
        .iter()
        .map(|(seg, locked)| {
            let forces = StanceForces::new(setup, run.tau1, run.p, *locked);
            integrate(
                |t| stance_powers(&forces, t, &seg.state(t)),
                seg.t0,
                seg.t1,
                n,
            )
        })
        .fold(Work::default(), |a, b| a + b)
}

/// Powers of the swing hip and knee torques at (t, y): [F_θ3 θ̇3, F_θ4 θ̇4] (W).
pub fn swing_powers(
    forces: &SwingForces,
    t: f64,
    y: &crate::control::swing::SwingState,
) -> [f64; 2] {
    let tau = forces.torques(t, y);
    [tau[0] * y[2], tau[1] * y[3]]
}

/// Work of the swing torques over the subphases, `n` Simpson intervals per subphase.
pub fn swing_work(setup: &SwingSetup, subphases: &[(Subphase, &Segment<4>)], n: usize) -> Work {
    subphases
        .iter()
        .map(|(sub, seg)| {
            let forces = SwingForces { setup, sub: *sub };
            integrate(
                |t| swing_powers(&forces, t, &seg.state(t)),
                seg.t0,
                seg.t1,
                n,
            )
        })
        .fold(Work::default(), |a, b| a + b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn simpson_is_exact_for_cubics() {
        // ∫_1^3 (x³ − 2x + 1) dx = [x⁴/4 − x² + x]_1^3 = (81/4 − 9 + 3) − (1/4 − 1 + 1) = 14
        let v = simpson(|x| x * x * x - 2.0 * x + 1.0, 1.0, 3.0, 2);
        assert!((v - 14.0).abs() < 1e-12, "{v}");
        // odd n is rounded up to even
        let v = simpson(|x| x * x, 0.0, 1.0, 3);
        assert!((v - 1.0 / 3.0).abs() < 1e-14, "{v}");
    }

    #[test]
    fn positive_part_of_a_sine() {
        // P = sin t over [0, 2π]: positive work 2, net 0
        let w = integrate(|t| [t.sin()], 0.0, 2.0 * std::f64::consts::PI, 400);
        assert!((w.positive - 2.0).abs() < 1e-6, "{w:?}");
        assert!(w.net.abs() < 1e-12, "{w:?}");
        // two actuators do not cancel: +sin and −sin give positive work 4, net 0
        let w = integrate(
            |t| [t.sin(), -t.sin()],
            0.0,
            2.0 * std::f64::consts::PI,
            400,
        );
        assert!((w.positive - 4.0).abs() < 1e-6, "{w:?}");
        assert!(w.net.abs() < 1e-12, "{w:?}");
    }
}
