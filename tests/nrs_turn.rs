//! Turnarounds (Ko & Badler 1993 §6) against the section's own rules: the feet end 2λ apart in
//! the goal frame, turns over 100° split into equal parts, the timing is 2.5δ with the gaze at
//! the goal after δ, the twist is split 2/3 at the neck, the hip falls monotonically in the
//! first step and rises in the second; and no foot below the floor, no stance foot sliding, no
//! leg stretched.
use std::f64::consts::PI;

use klaw::Landmarks;
use klaw::figure::clinical::clinical;
use klaw::model::attributes::AttributeTable;
use klaw::model::body::Body;
use klaw::nrs::pose::{direction, right_of, turn_between};
use klaw::nrs::{Side, TurnKind, TurnSpecs, Turnaround, WalkerState};

fn standing(facing: f64) -> WalkerState {
    let body = Body::standard(1.8, 80.0).unwrap();
    WalkerState::standing(
        body,
        AttributeTable::builtin().defaults(),
        [0.5, -0.2],
        facing,
    )
}

fn turn(state: &WalkerState, deg: f64, side: Side, kind: TurnKind) -> Turnaround {
    let specs = TurnSpecs {
        angle: deg.to_radians(),
        side,
        kind,
    };
    Turnaround::initialize(state, &specs, None).unwrap()
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// `n + 1` frames over the whole turnaround.
fn frames(t: &Turnaround, n: usize) -> Vec<Landmarks> {
    (0..=n).map(|i| t.advance(i as f64 / n as f64)).collect()
}

/// The feet after a 90° turn, read in the goal frame: the stepping foot of the first step
/// 2λ back and 2λ to the turn's side of the pivot foot; then the other foot 2λ ahead (dynamic)
/// or level (stationary) and 2λ back across; both facing the goal direction.
#[test]
fn the_feet_end_two_lambda_apart_in_the_goal_frame() {
    for side in [Side::Left, Side::Right] {
        for kind in [TurnKind::Dynamic, TurnKind::Stationary] {
            let s = standing(0.3);
            let t = turn(&s, 90.0, side, kind);
            let sign = if side == Side::Left { 1.0 } else { -1.0 };
            let goal = 0.3 + sign * PI / 2.0;
            let end = t.end_state();
            let lambda2 = s.body.l0;
            let (f, r) = (direction(goal), right_of(goal));
            let frame = |from: [f64; 2], to: [f64; 2]| {
                let v = [to[0] - from[0], to[1] - from[1]];
                // (forward, towards the turn's side)
                (
                    v[0] * f[0] + v[1] * f[1],
                    -sign * (v[0] * r[0] + v[1] * r[1]),
                )
            };
            let pivot = s.foot(side.other()).flat;
            let first = end.foot(side).flat;
            let (a, b) = frame(pivot, first);
            assert!((a + lambda2).abs() < 1e-12 && (b - lambda2).abs() < 1e-12);
            let (a, b) = frame(first, end.foot(side.other()).flat);
            let ahead = if kind == TurnKind::Dynamic {
                lambda2
            } else {
                0.0
            };
            assert!((a - ahead).abs() < 1e-12 && (b + lambda2).abs() < 1e-12);
            for foot in end.feet {
                assert!(turn_between(foot.heading, goal).abs() < 1e-12);
                assert_eq!(foot.pitch, 0.0);
            }
            // the figure at t = 1 stands on them
            let last = t.advance(1.0);
            for (leg, foot) in [(last.right, end.feet[0]), (last.left, end.feet[1])] {
                assert!((leg.ankle[0] - foot.flat[0]).abs() < 1e-9);
                assert!((leg.ankle[2] - foot.flat[1]).abs() < 1e-9);
            }
            assert!(turn_between(last.pelvis_rotation, goal).abs() < 1e-9);
        }
    }
}

/// 250° is three turnarounds of 83.3°, 2.5δ each; 100° is one.
#[test]
fn large_turns_split_into_equal_parts() {
    let s = standing(0.0);
    let t = turn(&s, 250.0, Side::Left, TurnKind::Stationary);
    assert_eq!(t.parts(), 3);
    let delta = t.step_duration();
    assert!((t.duration() - 3.0 * 2.5 * delta).abs() < 1e-12);
    // the pelvis heading after each part
    for k in 1..=3 {
        let lm = t.advance(k as f64 / 3.0);
        let want = k as f64 * 250f64.to_radians() / 3.0;
        assert!(turn_between(lm.pelvis_rotation, want).abs() < 1e-9, "{k}");
    }
    assert_eq!(turn(&s, 100.0, Side::Right, TurnKind::Dynamic).parts(), 1);
    assert!(
        (t.end_state().time - s.time - t.duration()).abs() < 1e-12,
        "the end state's clock"
    );
}

/// §6's timing: the feet stand still for the first 0.5δ while the gaze turns; the gaze reaches
/// the goal at δ and stays; the neck takes 2/3 of the twist between gaze and pelvis, the lumbar
/// joint the rest; the first step ends at 1.5δ and the second at 2.5δ.
#[test]
fn timing_and_twist_shares() {
    let s = standing(0.0);
    let t = turn(&s, 80.0, Side::Left, TurnKind::Dynamic);
    let delta = t.step_duration();
    let span = t.duration();
    assert!((span - 2.5 * delta).abs() < 1e-12);
    let at = |tau: f64| t.advance(tau / span);
    let start = s.figure().unwrap();
    let goal = 80f64.to_radians();
    let gaze = |lm: &Landmarks| lm.pelvis_rotation + lm.lumbar_rotation + lm.neck_rotation;
    for tau in [0.1, 0.25, 0.45] {
        let lm = at(tau * delta);
        assert!(dist(lm.right.ankle, start.right.ankle) < 1e-12);
        assert!(dist(lm.left.ankle, start.left.ankle) < 1e-12);
        assert!(dist(lm.pelvis, start.pelvis) < 1e-12);
        assert!(gaze(&lm) > 0.0 && gaze(&lm) < goal);
    }
    for tau in [1.0, 1.3, 2.0, 2.5] {
        let lm = at(tau * delta);
        assert!(
            (gaze(&lm) - goal).abs() < 1e-3,
            "the gaze at the goal at {tau} δ"
        );
    }
    let lm = at(0.9 * delta);
    assert!(gaze(&lm) < goal - 1e-3, "not before δ");
    for tau in [0.3, 0.8, 1.2, 1.9] {
        let lm = at(tau * delta);
        let twist = lm.lumbar_rotation + lm.neck_rotation;
        assert!(twist.abs() > 1e-3);
        assert!((lm.neck_rotation - 2.0 / 3.0 * twist).abs() < 1e-3, "{tau}");
    }
    // the steps' ends: the first foot lands at 1.5 δ
    let steps: Vec<_> = t.steps().collect();
    assert!((steps[0].duration() - delta).abs() < 1e-12);
    let land = at(1.5 * delta);
    let f = t.end_state().foot(Side::Left).flat;
    assert!((land.left.ankle[0] - f[0]).abs() < 1e-9 && (land.left.ankle[2] - f[1]).abs() < 1e-9);
}

/// §6: the hip is lowered monotonically in the first step and raised in the second; nothing
/// goes below the floor, no stance foot slides, no leg is stretched; the hip's axial rotation
/// stays within 45° (AAOS 1965 normal range of hip internal and external rotation).
#[test]
fn the_hip_falls_then_rises_and_the_legs_hold() {
    for deg in [45.0, 80.0, 100.0] {
        for kind in [TurnKind::Dynamic, TurnKind::Stationary] {
            let s = standing(1.0);
            let t = turn(&s, deg, Side::Left, kind);
            let delta = t.step_duration();
            let n = 500;
            let fr = frames(&t, n);
            let tau = |i: usize| i as f64 / n as f64 * 2.5;
            let y: Vec<f64> = fr.iter().map(|lm| lm.pelvis[1]).collect();
            for i in 1..=n {
                if tau(i) > 0.5 && tau(i) <= 1.5 {
                    assert!(y[i] <= y[i - 1] + 1e-12, "falls in step 1 ({deg}°)");
                } else if tau(i - 1) >= 1.5 {
                    assert!(y[i] >= y[i - 1] - 1e-12, "rises in step 2 ({deg}°)");
                }
            }
            assert!(y[n / 5 * 3] < y[0] - 1e-3, "the hip is lowered");
            let body = s.body;
            let mut max_rotation: f64 = 0.0;
            for (i, lm) in fr.iter().enumerate() {
                for l in [lm.right, lm.left] {
                    for p in [l.heel, l.mtp, l.toe] {
                        assert!(p[1] > -1e-6, "below the floor");
                    }
                    assert!(dist(l.hip, l.ankle) <= body.l3 + body.l4 + 1e-9);
                }
                let c = clinical(lm, &body).unwrap();
                max_rotation = max_rotation
                    .max(c.right.hip.rotation.abs())
                    .max(c.left.hip.rotation.abs());
                // the pivot (right) foot stays put until it lifts in the second step
                if tau(i) < 1.5 + 0.05 {
                    assert!(
                        dist(lm.right.heel, fr[0].right.heel) < 1e-3,
                        "the pivot slides"
                    );
                }
            }
            eprintln!(
                "{deg}° {kind:?} turnaround (δ = {delta} s): max hip axial rotation {:.1}°",
                max_rotation.to_degrees()
            );
            assert!(max_rotation.to_degrees() < deg / 2.0 + 5.0);
            if deg <= 80.0 {
                assert!(max_rotation.to_degrees() < 45.0);
            }
        }
    }
}
