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
//! Each segment is integrated by 5-point Gauss–Legendre quadrature (order 10: DOP853's steps are
//! long) on the integrator's accepted steps (on each, the state is one polynomial and the powers
//! are smooth functions of it), every step split into equal panels so that a segment has at
//! least `n` of them, and a panel split again where an actuator's power changes sign (seen at
//! its ends and midpoint). Where F_w ≥ 0 switches inside a panel the rule is first-order
//! accurate locally; the test `positive_work_converges_with_sampling` bounds that error.
use serde::Serialize;

use crate::control::stance::{StanceForces, StanceRun, StanceSetup};
use crate::control::swing::{Subphase, SwingForces, SwingSetup};
use nalgebra::SVector;

use crate::numerics::ode::Segment;

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

/// Work of `powers` (one entry per actuator) over the segment `seg`: 5-point Gauss–Legendre on
/// its integrator steps, each split into equal panels so that there are at least `n`. The nodes
/// are inside the panels: a force that switches where a segment ends (the leg torque at
/// 0.4 t_step) counts with its value within the segment. Where an actuator's power changes sign
/// between a panel's ends and its midpoint, the crossing is located on the dense output and the
/// panel is split there, so that every max(Pᵢ, 0) is smooth on each part (without it the rule is
/// first-order accurate around the crossing, and the integrator's steps are long).
fn integrate<const N: usize, const K: usize>(
    powers: impl Fn(f64, &SVector<f64, N>) -> [f64; K],
    seg: &Segment<N>,
    n: usize,
) -> Work {
    // nodes on [0, 1] and weights: (1 ± xᵢ)/2 and wᵢ/2 with x = 0, ⅓√(5 ∓ 2√(10/7)),
    // w = 128/225, (322 ± 13√70)/900
    let r = (10.0_f64 / 7.0).sqrt();
    let (x1, x2) = ((5.0 - 2.0 * r).sqrt() / 3.0, (5.0 + 2.0 * r).sqrt() / 3.0);
    let s70 = 70.0_f64.sqrt();
    let (w1, w2) = ((322.0 + 13.0 * s70) / 1800.0, (322.0 - 13.0 * s70) / 1800.0);
    let gauss = [
        (0.5 * (1.0 - x2), w2),
        (0.5 * (1.0 - x1), w1),
        (0.5, 64.0 / 225.0),
        (0.5 * (1.0 + x1), w1),
        (0.5 * (1.0 + x2), w2),
    ];
    let power = |t: f64| powers(t, &seg.state(t));
    // the rule on [a, b]; its middle node's powers when already known
    let rule = |a: f64, b: f64, mid: Option<[f64; K]>, sum: &mut Work| {
        for (i, (x, w)) in gauss.into_iter().enumerate() {
            let p = match mid {
                Some(m) if i == 2 => m,
                _ => power(a + x * (b - a)),
            };
            sum.positive += w * (b - a) * p.iter().map(|p| p.max(0.0)).sum::<f64>();
            sum.net += w * (b - a) * p.iter().sum::<f64>();
        }
    };
    // the crossing of actuator k's power in [a, b] (signs differ at the ends)
    let crossing = |k: usize, a: f64, b: f64, ga: f64, gb: f64| {
        let (a, b) = crate::numerics::roots::illinois(
            |t| power(t)[k],
            (a, ga),
            (b, gb),
            1e-10 * (b - a),
            60,
        );
        0.5 * (a + b)
    };
    let split = n.div_ceil(seg.steps().count().max(1)).max(1);
    let mut sum = Work::default();
    // the powers where the last panel ended (the steps are contiguous)
    let mut g0 = power(seg.t0);
    for (a, b) in seg.steps() {
        let h = (b - a) / split as f64;
        for i in 0..split {
            let p0 = a + i as f64 * h;
            let p1 = if i + 1 == split { b } else { p0 + h };
            let pm = 0.5 * (p0 + p1);
            let (gm, g1) = (power(pm), power(p1));
            let mut cuts = Vec::new();
            for k in 0..K {
                let pos = [g0[k] > 0.0, gm[k] > 0.0, g1[k] > 0.0];
                if pos[0] != pos[1] {
                    cuts.push(crossing(k, p0, pm, g0[k], gm[k]));
                }
                if pos[1] != pos[2] {
                    cuts.push(crossing(k, pm, p1, gm[k], g1[k]));
                }
            }
            if cuts.is_empty() {
                rule(p0, p1, Some(gm), &mut sum);
            } else {
                cuts.sort_by(f64::total_cmp);
                let mut from = p0;
                for &c in cuts.iter().chain(std::iter::once(&p1)) {
                    if c > from {
                        rule(from, c, None, &mut sum);
                        from = c;
                    }
                }
            }
            g0 = g1;
        }
    }
    sum
}

/// Powers of the stance actuators at (t, y): [F_w ẇ, F_θ1 θ̇1, F_θ2 (θ̇2 − θ̇1)] (W).
fn stance_powers(
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

/// Work of the stance actuators over a stance run, at least `n` quadrature panels per segment.
pub fn stance_work(setup: &StanceSetup, run: &StanceRun, n: usize) -> Work {
    run.segments
        .iter()
        .map(|(seg, locked)| {
            // the segment's own torque at its ends (the switch at 0.4 t_step ends a segment)
            let on = seg.t0 < setup.torque_off * setup.t_step;
            let forces = StanceForces::new(setup, run.tau1, run.p, *locked).with_torque(on);
            integrate(|t, y| stance_powers(&forces, t, y), seg, n)
        })
        .fold(Work::default(), |a, b| a + b)
}

/// Powers of the swing hip and knee torques at (t, y): [F_θ3 θ̇3, F_θ4 θ̇4] (W).
fn swing_powers(forces: &SwingForces, t: f64, y: &crate::control::swing::SwingState) -> [f64; 2] {
    let tau = forces.torques(t, y);
    [tau[0] * y[2], tau[1] * y[3]]
}

/// Work of the swing torques over the subphases, at least `n` quadrature panels per subphase.
pub fn swing_work(setup: &SwingSetup, subphases: &[(Subphase, &Segment<4>)], n: usize) -> Work {
    subphases
        .iter()
        .map(|(sub, seg)| {
            let forces = SwingForces {
                setup,
                sub: *sub,
                piece: None,
            };
            integrate(|t, y| swing_powers(&forces, t, y), seg, n)
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

    /// x'' = −x from (1, 0): x = cos t, integrated by the engine's integrator.
    fn cosine(t1: f64) -> Segment<2> {
        struct Oscillator;
        impl crate::numerics::ode::Phase<2, 0> for Oscillator {
            fn rhs(&self, _t: f64, y: &SVector<f64, 2>) -> SVector<f64, 2> {
                SVector::<f64, 2>::new(y[1], -y[0])
            }
        }
        let y0 = SVector::<f64, 2>::new(1.0, 0.0);
        crate::numerics::ode::integrate_with(&Oscillator, 0.0, y0, t1, 1e-10)
            .unwrap()
            .segment
    }

    #[test]
    fn positive_part_of_a_cosine() {
        // P = cos t over [0, 2π]: positive work 2, net 0, on the integrator's steps alone and
        // split into panels
        let seg = cosine(2.0 * std::f64::consts::PI);
        for n in [1, 400] {
            let w = integrate(|_, y| [y[0]], &seg, n);
            assert!((w.positive - 2.0).abs() < 1e-8, "{n}: {w:?}");
            assert!(w.net.abs() < 1e-9, "{n}: {w:?}");
            // two actuators do not cancel: +cos and −cos give positive work 4, net 0
            let w = integrate(|_, y| [y[0], -y[0]], &seg, n);
            assert!((w.positive - 4.0).abs() < 2e-8, "{n}: {w:?}");
            assert!(w.net.abs() < 1e-12, "{n}: {w:?}");
        }
        // smooth powers: ∫ cos² over [0, 1] = 1/2 + sin 2 / 4, to the integration's accuracy
        let w = integrate(|_, y| [y[0] * y[0]], &cosine(1.0), 1);
        assert!((w.net - (0.5 + 2.0_f64.sin() / 4.0)).abs() < 1e-9, "{w:?}");
    }
}
