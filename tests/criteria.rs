//! The quality criteria of `analysis::criteria` (Pronost et al. 2006, eqs. 7–11) on motions with
//! known answers: sinusoids with an analytic jerk, a rigid pendulum that keeps its energy,
//! periodic and drifting walks, and klaw's own walk.
use std::f64::consts::TAU;

use klaw::analysis::criteria::energy::{Energies, energies, power};
use klaw::analysis::criteria::heel_strikes::{from_kinematics, from_steps};
use klaw::analysis::criteria::segments::{POSE, Segments, pose};
use klaw::analysis::criteria::{
    CriteriaError, CriteriaFrames, CriteriaParameters, HeelStrikes, compare, evaluate,
};
use klaw::{Body, Clinical};

mod common;
use common::{default_body, default_walk};

/// The eleven angles of a frame, in the order of `segments::DOFS`.
fn set_dofs(c: &mut Clinical, v: [f64; 11]) {
    c.pelvis_tilt = v[0];
    c.pelvis_list = v[1];
    c.pelvis_rotation = v[2];
    c.right.hip.flexion = v[3];
    c.right.hip.adduction = v[4];
    c.right.hip.rotation = v[5];
    c.right.knee.flexion = v[6];
    c.left.hip.flexion = v[7];
    c.left.hip.adduction = v[8];
    c.left.hip.rotation = v[9];
    c.left.knee.flexion = v[10];
}

/// Frames at `fps` over [t0, t1] whose eleven angles are `angles(t)`, the pelvis position
/// unknown (NaN), heel strikes every second from 0 (right) and 0.5 (left) to 3.5 s.
fn synthetic(fps: f64, t0: f64, t1: f64, angles: impl Fn(f64) -> [f64; 11]) -> CriteriaFrames {
    let n = ((t1 - t0) * fps).round() as usize;
    let frames = (0..=n)
        .map(|k| {
            let time = t0 + k as f64 / fps;
            let mut c = Clinical {
                time,
                pelvis: [f64::NAN; 3],
                ..Default::default()
            };
            set_dofs(&mut c, angles(time));
            c
        })
        .collect();
    CriteriaFrames {
        frames,
        heel_strikes: HeelStrikes {
            right: vec![0.0, 1.0, 2.0, 3.0],
            left: vec![0.5, 1.5, 2.5, 3.5],
        },
    }
}

const AMPLITUDES: [f64; 11] = [
    0.05, 0.08, 0.07, 0.4, 0.1, 0.08, 0.6, 0.45, 0.09, 0.07, 0.55,
];

fn sines(t: f64) -> [f64; 11] {
    std::array::from_fn(|i| AMPLITUDES[i] * (TAU * t + 0.3 * i as f64).sin())
}

fn no_skip() -> CriteriaParameters {
    CriteriaParameters {
        skip: 0,
        ..Default::default()
    }
}

/// Sinusoids of period 1 s: the third difference of A sin(ωt + φ) at 60 frames/s is
/// −A ω³ g cos(ωt + φ) with g = 4 sin x sin²(x/2) / x³, x = ω/60, so over a cycle's 61 frames
/// (both heel strikes) C1 = (1/11) Σᵢ Aᵢ² ω⁶ g² (30 + cos² θᵢ), θᵢ the phase at the cycle's
/// start, and the mean squared jerk is (1/11) Σᵢ Aᵢ² ω⁶ g² / 2; whether the frames come at 60
/// frames/s or at 100 (and are resampled).
#[test]
fn total_jerk_of_sinusoids_is_analytic() {
    let w = TAU;
    let x = w / 60.0;
    let g = 4.0 * x.sin() * (x / 2.0).sin().powi(2) / x.powi(3);
    for fps in [60.0, 100.0] {
        let motion = synthetic(fps, -0.5, 4.0, sines);
        let c = evaluate(&motion, &default_body(), &no_skip()).unwrap();
        assert_eq!(c.cycles.len(), 6);
        for cc in &c.cycles {
            assert_eq!(cc.frames, 61);
            let c1: f64 = (0..11)
                .map(|i| {
                    let theta = w * cc.cycle.start + 0.3 * i as f64;
                    AMPLITUDES[i].powi(2) * w.powi(6) * g * g * (30.0 + theta.cos().powi(2))
                })
                .sum::<f64>()
                / 11.0;
            let rel = (cc.total_jerk - c1).abs() / c1;
            assert!(
                rel < 1e-5,
                "{fps} fps, cycle at {}: {rel:e}",
                cc.cycle.start
            );
            let msj: f64 = AMPLITUDES.iter().map(|a| a * a).sum::<f64>() * w.powi(6) * g * g / 22.0;
            let rel = (cc.mean_squared_jerk - msj).abs() / msj;
            assert!(rel < 1e-5, "{fps} fps: {rel:e}");
            // a sinusoid of one period returns to its start
            assert!(cc.cyclicity < 1e-9, "{}", cc.cyclicity);
            assert!(cc.power.is_none());
        }
    }
}

/// The finite differences' error is second order: against the exact mean squared jerk
/// (1/11) Σ Aᵢ² ω⁶ / 2, doubling the rate divides it by 4 (g² = 1 − x²/2 + …).
#[test]
fn the_jerk_converges_at_second_order() {
    let exact = AMPLITUDES.iter().map(|a| a * a).sum::<f64>() * TAU.powi(6) / 22.0;
    let motion = synthetic(480.0, -0.5, 4.0, sines);
    let error = |rate: f64| {
        let p = CriteriaParameters { rate, ..no_skip() };
        let c = evaluate(&motion, &default_body(), &p).unwrap();
        (c.mean.mean_squared_jerk - exact) / exact
    };
    let (e60, e120) = (error(60.0), error(120.0));
    // x²/2 with x = 2π/60: 5.5e-3
    assert!((e60 + (TAU / 60.0).powi(2) / 2.0).abs() < 2e-4, "{e60}");
    assert!((e60 / e120 - 4.0).abs() < 0.05, "{e60} / {e120}");
}

/// A periodic motion of several harmonics has C2 = 0 at every cycle; adding a drift rᵢ t to
/// each angle makes C2 = T ‖r‖ exactly (T = 1 s).
#[test]
fn cyclicity_of_periodic_and_drifting_walks() {
    let periodic = |t: f64| -> [f64; 11] {
        std::array::from_fn(|i| {
            let p = 0.2 * i as f64;
            0.3 * (TAU * t + p).sin()
                + 0.1 * (2.0 * TAU * t).cos()
                + 0.02 * (5.0 * TAU * t + p).sin()
        })
    };
    let c = evaluate(
        &synthetic(100.0, 0.0, 3.5, periodic),
        &default_body(),
        &no_skip(),
    )
    .unwrap();
    for cc in &c.cycles {
        assert!(cc.cyclicity < 1e-9, "{cc:?}");
    }
    let drift: [f64; 11] = std::array::from_fn(|i| 0.01 * (i as f64 - 4.0));
    let drifting = |t: f64| -> [f64; 11] {
        let p = periodic(t);
        std::array::from_fn(|i| p[i] + drift[i] * t)
    };
    let c = evaluate(
        &synthetic(100.0, 0.0, 3.5, drifting),
        &default_body(),
        &no_skip(),
    )
    .unwrap();
    let expected = drift.iter().map(|r| r * r).sum::<f64>().sqrt();
    for cc in &c.cycles {
        assert!(
            (cc.cyclicity - expected).abs() < 1e-9,
            "{} vs {expected}",
            cc.cyclicity
        );
    }
    assert_eq!(c.cycles.len(), 6);
    // with the first cycle of each foot left out
    let c = evaluate(
        &synthetic(100.0, 0.0, 3.5, drifting),
        &default_body(),
        &CriteriaParameters::default(),
    )
    .unwrap();
    assert_eq!(c.cycles.len(), 4);
    assert_eq!(c.mean.cycles, 4);
}

/// The right leg swinging as a rigid pendulum about a fixed hip (knee straight, everything else
/// at rest), integrated by RK4: I θ̈ = −μ g sin θ with I = I3 + m3 r3² + I4 + m4 (l3 + r4)² and
/// μ = m3 r3 + m4 (l3 + r4). Its kinetic + potential energy, as the criteria compute it from
/// the angles (forward kinematics, finite differences), is constant; its kinetic energy is
/// ½ I θ̇²; so the literal eq. 10, |ΔE_k − M g Δh| = 2 |ΔE_k|, is twice the kinetic energy's
/// total variation, the work–energy form |Δ(E_k + M g h)| is 0, and the internal and external
/// works are those of the same motion computed in the plane by hand.
#[test]
fn a_rigid_pendulum_keeps_its_energy() {
    let body = default_body();
    let (g, b) = (9.81, &body);
    let inertia = b.i3 + b.m3 * b.r3.powi(2) + b.i4 + b.m4 * (b.l3 + b.r4).powi(2);
    let mu = b.m3 * b.r3 + b.m4 * (b.l3 + b.r4);
    let accel = |th: f64| -mu * g * th.sin() / inertia;
    let (theta0, fps) = (0.6, 500.0);
    // RK4 at 20 substeps per frame, for 1.6 s (more than a period, ≈ 1.3 s)
    let frames = 800;
    let mut states = vec![(theta0, 0.0)];
    let dt = 1.0 / fps / 20.0;
    let (mut th, mut om) = (theta0, 0.0);
    for _ in 0..frames {
        for _ in 0..20 {
            let k1 = (om, accel(th));
            let k2 = (om + 0.5 * dt * k1.1, accel(th + 0.5 * dt * k1.0));
            let k3 = (om + 0.5 * dt * k2.1, accel(th + 0.5 * dt * k2.0));
            let k4 = (om + dt * k3.1, accel(th + dt * k3.0));
            th += dt / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
            om += dt / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
        }
        states.push((th, om));
    }
    let poses: Vec<[f64; POSE]> = states
        .iter()
        .map(|&(th, _)| {
            let mut c = Clinical {
                pelvis: [0.0, 1.0, 0.0],
                ..Default::default()
            };
            c.right.hip.flexion = th;
            pose(&c)
        })
        .collect();
    let h = 1.0 / fps;
    let e = energies(&poses, h, &Segments::new(&body));
    let total = |e: &Energies| e.kinetic + e.potential;
    let e_max = mu * g * (1.0 - theta0.cos());
    for (k, (ek, &(_, om))) in e.iter().zip(&states).enumerate() {
        assert!((total(ek) - total(&e[0])).abs() < 1e-4 * e_max, "frame {k}");
        assert!(
            (ek.kinetic - 0.5 * inertia * om * om).abs() < 1e-4 * e_max,
            "frame {k}"
        );
    }
    // inside the frames (the finite differences are one-sided at the ends)
    let inner = &e[1..e.len() - 1];
    let p = power(inner, h, body.mass);
    let duration = h * (inner.len() - 1) as f64;
    let variation: f64 = states[1..states.len() - 1]
        .windows(2)
        .map(|w| 0.5 * inertia * (w[1].1 * w[1].1 - w[0].1 * w[0].1).abs())
        .sum();
    let literal = 2.0 * variation / (body.mass * duration);
    assert!(
        (p.literal - literal).abs() < 1e-3 * literal,
        "{} vs {literal}",
        p.literal
    );
    // the kinetic energy swings between 0 and E_max, four times a period (≈ 1.6 s)
    assert!(
        variation > 3.5 * e_max && variation < 6.0 * e_max,
        "{variation} {e_max}"
    );
    assert!(p.mechanical < 1e-3 * p.literal, "{}", p.mechanical);
    // by hand in the plane: the thigh's centre moves at θ̇ r3, the shank's at θ̇ (l3 + r4),
    // perpendicular to the leg; the centre of mass at their weighted sum over M
    let (mass, m3, m4) = (body.mass, b.m3, b.m4);
    let by_hand: Vec<([f64; 3], f64)> = states[1..states.len() - 1]
        .iter()
        .map(|&(th, om)| {
            let dir = [th.cos(), th.sin()];
            let v3 = [om * b.r3 * dir[0], om * b.r3 * dir[1]];
            let v4 = [om * (b.l3 + b.r4) * dir[0], om * (b.l3 + b.r4) * dir[1]];
            let vg = [
                (m3 * v3[0] + m4 * v4[0]) / mass,
                (m3 * v3[1] + m4 * v4[1]) / mass,
            ];
            let sq = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2);
            let zero = [0.0, 0.0];
            let internal = [
                0.5 * b.m2 * sq(zero, vg),
                0.5 * m3 * sq(v3, vg) + 0.5 * m4 * sq(v4, vg) + 0.5 * (b.i3 + b.i4) * om * om,
                0.5 * (m3 + m4) * sq(zero, vg),
            ];
            let height = -(mu * th.cos()) / mass;
            (internal, 0.5 * mass * sq(vg, zero) + mass * g * height)
        })
        .collect();
    let internal: f64 = by_hand
        .windows(2)
        .map(|w| {
            (0..3)
                .map(|i| (w[1].0[i] - w[0].0[i]).max(0.0))
                .sum::<f64>()
        })
        .sum::<f64>()
        / (mass * duration);
    let external: f64 = by_hand
        .windows(2)
        .map(|w| (w[1].1 - w[0].1).max(0.0))
        .sum::<f64>()
        / (mass * duration);
    assert!(
        (p.internal - internal).abs() < 1e-3 * internal,
        "{} vs {internal}",
        p.internal
    );
    assert!(
        (p.external - external).abs() < 1e-3 * external,
        "{} vs {external}",
        p.external
    );
}

/// Klaw's default walk: the criteria from its exact heel strikes, from its step index at 100
/// frames/s and from the ankle's foremost positions agree on C1 and C3 (they sample the same
/// motion), and the internal power is of the published order (Willems et al. 1995: 0.2–0.6
/// W/kg at 1.4 m/s).
#[test]
fn klaw_walk_criteria_from_every_heel_strike_source() {
    let walk = default_walk(10);
    let body = default_body();
    let exact = CriteriaFrames::from_walk(&walk, 100.0).unwrap();
    let params = CriteriaParameters::default();
    let c = evaluate(&exact, &body, &params).unwrap();
    // 10 steps: 6 right heel strikes (the last ends the walk at 5.5549 s, after the last frame
    // at 5.55 s), 5 left; the first cycle of each foot left out
    assert_eq!(c.cycles.len(), 6, "{:?}", c.cycles);
    let p = c.mean.power.unwrap();
    assert!((0.2..1.0).contains(&p.internal), "{p:?}");
    assert!(p.literal > p.internal, "{p:?}");
    // the steady walk repeats itself: small C2
    assert!(c.mean.cyclicity < 0.02, "{}", c.mean.cyclicity);
    // the step index gives the heel strikes to the frame
    let by_steps = CriteriaFrames {
        heel_strikes: from_steps(&exact.frames),
        ..exact.clone()
    };
    for (a, b) in exact
        .heel_strikes
        .right
        .iter()
        .zip(&by_steps.heel_strikes.right)
    {
        assert!(b - a >= 0.0 && b - a < 0.01 + 1e-9, "{a} {b}");
    }
    let s = evaluate(&by_steps, &body, &params).unwrap();
    let close = |a: f64, b: f64, tol: f64| (a - b).abs() <= tol * a.abs().max(b.abs());
    assert!(close(s.mean.total_jerk, c.mean.total_jerk, 0.1), "{s:?}");
    // from the kinematics: one strike per cycle of each foot, a fixed lead on the heel strike
    let kin = from_kinematics(&exact.frames, &body, params.heel_strike_window);
    assert_eq!(
        kin.right.len(),
        exact.heel_strikes.right.len() - 1,
        "{kin:?}"
    );
    let leads: Vec<f64> = kin
        .right
        .iter()
        .zip(&exact.heel_strikes.right[1..])
        .map(|(k, e)| e - k)
        .collect();
    let spread = leads
        .iter()
        .fold(0.0f64, |m, l| m.max((l - leads[1]).abs()));
    assert!(spread < 2e-3 && (0.0..0.1).contains(&leads[1]), "{leads:?}");
    let by_kinematics = CriteriaFrames {
        heel_strikes: kin,
        ..exact.clone()
    };
    let k = evaluate(&by_kinematics, &body, &params).unwrap();
    assert!(
        close(k.mean.power.unwrap().internal, p.internal, 0.1),
        "{k:?}"
    );
    // a walk against itself: zero everywhere
    for a in compare::compare(&exact, &exact, 1) {
        assert!(a.rms.unwrap() < 1e-12, "{a:?}");
    }
}

#[test]
fn frames_the_criteria_cannot_use_are_errors() {
    let body: Body = default_body();
    let mut m = synthetic(60.0, 0.0, 2.0, sines);
    m.frames[5].right.knee.flexion = f64::NAN;
    let e = evaluate(&m, &body, &no_skip()).unwrap_err();
    assert!(
        matches!(
            e,
            CriteriaError::NotFinite {
                frame: 5,
                name: "knee_flexion_r",
                ..
            }
        ),
        "{e}"
    );
    let mut m = synthetic(60.0, 0.0, 2.0, sines);
    m.frames[7].time = m.frames[6].time;
    let e = evaluate(&m, &body, &no_skip()).unwrap_err();
    assert!(matches!(e, CriteriaError::Times { frame: 7 }), "{e}");
    let m = synthetic(60.0, 0.0, 0.9, sines);
    let e = evaluate(&m, &body, &no_skip()).unwrap_err();
    assert!(e.to_string().contains("no complete gait cycle"), "{e}");
    let mut m = synthetic(60.0, 0.0, 2.0, sines);
    m.heel_strikes.left = vec![1.0, 0.5];
    let e = evaluate(&m, &body, &no_skip()).unwrap_err();
    assert!(
        matches!(e, CriteriaError::HeelStrikes { side: "left" }),
        "{e}"
    );
    let m = synthetic(60.0, 0.0, 2.0, sines);
    let p = CriteriaParameters {
        rate: 0.0,
        ..no_skip()
    };
    assert!(matches!(
        evaluate(&m, &body, &p).unwrap_err(),
        CriteriaError::Parameter { name: "rate", .. }
    ));
}
