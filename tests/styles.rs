//! Style presets (models/styles/): each converges over its speed range and body heights, and
//! the styles differ measurably from the normal walk in what they claim to change.
mod common;

use common::body_of_height;
use klaw::engine::walker as walk;
use klaw::figure::landmarks;
use klaw::model::attributes::{AttributeTable, STYLES, style};
use klaw::{Attributes, Simulation};

fn attrs_of(name: &str) -> Attributes {
    AttributeTable::builtin()
        .resolve(&style(name).unwrap(), name)
        .unwrap()
}

fn walk_with(name: &str, v: f64, h: f64) -> (Attributes, walk::Walk) {
    let w = Simulation::new(body_of_height(h))
        .style(name)
        .velocity(v)
        .steps(8)
        .run()
        .unwrap_or_else(|e| panic!("{name} v {v} H {h}: {e}"));
    (w.attributes().clone(), w.into_engine())
}

/// Each style over its own speed range [velocity_min, min(v_max, 2)] (5 speeds; v_max the
/// body's limit, velocity_max or the walk–run transition) and H = 1.65, 1.8 m: every step
/// converges.
#[test]
fn every_style_converges_over_its_speed_range() {
    for (name, _) in STYLES {
        let a = attrs_of(name);
        for h in [1.65, 1.8] {
            let limit = klaw::plan::gait::velocity_limit(&body_of_height(h), &a);
            let (lo, hi) = (a.velocity_min.max(0.6), limit.min(2.0));
            for k in 0..5 {
                // (the last is the limit itself, not lo + (hi − lo) rounded above it)
                let v = if k == 4 {
                    hi
                } else {
                    lo + (hi - lo) * k as f64 / 4.0
                };
                let (_, w) = walk_with(name, v, h);
                assert_eq!(w.steps.len(), 8);
            }
        }
    }
}

/// Step length, trunk lean, arm swing and step width, measured on the walk and its figure.
struct Measures {
    step_length: f64,
    trunk_lean: f64,
    arm_range: f64,
    step_width: f64,
}

fn measure(name: &str, v: f64) -> Measures {
    let (attrs, w) = walk_with(name, v, 1.8);
    let last = w.steps.last().unwrap();
    let (mut lean, mut n) = (0.0, 0);
    let (mut arm_lo, mut arm_hi) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut width: f64 = 0.0;
    for s in &w.steps[4..] {
        let t = s.constraints.timing.t_step;
        for k in 0..50 {
            let f = landmarks(s, s.t_start + t * k as f64 / 50.0, &attrs).unwrap();
            lean += f.pelvis_tilt - f.lumbar_extension; // the trunk's own lean
            n += 1;
            arm_lo = arm_lo.min(f.right_arm.shoulder_flexion);
            arm_hi = arm_hi.max(f.right_arm.shoulder_flexion);
            width = width.max(f.right.ankle[2] - f.left.ankle[2]);
        }
    }
    Measures {
        step_length: last.report.achieved.step_length,
        trunk_lean: lean / n as f64,
        arm_range: arm_hi - arm_lo,
        step_width: width,
    }
}

#[test]
fn styles_differ_from_normal_where_they_say() {
    let normal = measure("normal", 1.2);
    // the same speed with k = 1.2: sf ∝ 1/√k, so sl ∝ √k (by hand: √1.2 = 1.0954)
    let long = measure("long-stride", 1.2);
    assert!((long.step_length / normal.step_length - 1.0954).abs() < 0.005);
    // the elderly walk: shorter steps (√0.9), a stooped trunk, a wider base, less arm swing
    let elderly = measure("elderly", 1.0);
    let normal_slow = measure("normal", 1.0);
    assert!((elderly.step_length / normal_slow.step_length - 0.9f64.sqrt()).abs() < 0.005);
    assert!(elderly.trunk_lean > normal_slow.trunk_lean + 5f64.to_radians());
    assert!(elderly.step_width > normal_slow.step_width + 0.04);
    assert!(elderly.arm_range < 0.5 * normal_slow.arm_range);
    // the march: upright, with a large arm swing
    let march = measure("march", 1.2);
    assert!(march.trunk_lean < normal.trunk_lean - 1f64.to_radians());
    assert!(march.arm_range > 1.5 * normal.arm_range);
}

/// The paper's gait (`--style paper`: KLAW 1989 as published, the hip midway at heel strike, a
/// plastic heel strike, fixed pelvis amplitudes) walks Winter's table's valid box: H 1.2–2.2 m
/// by 0.2 × v from 0.4 m/s by 0.3 up to each body's walk–run transition, and the transition
/// itself (M = 23 H², 6 steps), with the hip midway between the ankles at every heel strike.
#[test]
fn the_papers_gait_walks_winters_box() {
    let a = attrs_of("paper");
    assert_eq!(a.hip_lead_slope, 0.0);
    let mut walks = 0;
    for i in 0..6 {
        let h = 1.2 + 0.2 * i as f64;
        let body = klaw::Body::standard(h, 23.0 * h * h).unwrap();
        let limit = klaw::plan::gait::velocity_limit(&body, &a);
        let speeds = (0..)
            .map(|k| 0.4 + 0.3 * k as f64)
            .take_while(|&v| v < limit)
            .chain([limit]);
        for v in speeds {
            let w = klaw::Simulation::new(body)
                .style("paper")
                .velocity(v)
                .steps(6)
                .run()
                .unwrap_or_else(|e| panic!("H {h:.1} v {v:.2}: {e}"));
            for s in &w.engine().steps {
                let c = &s.constraints;
                let phi = c.hip[0] / c.gait.step_length;
                assert!(
                    (phi - 0.5).abs() < 1e-12,
                    "H {h:.1} v {v:.2} step {}: φ {phi}",
                    s.index
                );
            }
            walks += 1;
        }
    }
    assert!(walks >= 30, "{walks} walks");
}
