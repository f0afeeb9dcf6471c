//! Non-rhythmic steps (Ko & Badler 1993) against independent facts: the goal reached, the
//! step types of Figure 2, no foot below the floor, no stance foot sliding, no leg stretched.
use klaw::Landmarks;
use klaw::model::attributes::AttributeTable;
use klaw::model::body::Body;
use klaw::nrs::pose::direction;
use klaw::nrs::state::WalkerState;
use klaw::nrs::step::NrsStep;
use klaw::nrs::{GoalReason, NrsError, Side, StepSpecs, StepType};

fn standing() -> WalkerState {
    let body = Body::standard(1.8, 80.0).unwrap();
    WalkerState::standing(body, AttributeTable::builtin().defaults(), [0.0, 0.0], 0.0)
}

fn specs(side: Side, position: [f64; 2], direction: f64) -> StepSpecs {
    StepSpecs {
        foot_position: position,
        foot_direction: direction,
        side,
        swing_height_factor: 1.0,
        gaze_direction: None,
        foot_angles: None,
    }
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The step's frames at 201 instants, and checks that hold at every one of them.
fn check_frames(step: &NrsStep, stance: Side, body: &Body) -> Vec<Landmarks> {
    let frames: Vec<Landmarks> = (0..=200).map(|i| step.advance(i as f64 / 200.0)).collect();
    let leg = |lm: &Landmarks, s: Side| match s {
        Side::Right => lm.right,
        Side::Left => lm.left,
    };
    let first = leg(&frames[0], stance);
    for lm in &frames {
        for l in [lm.right, lm.left] {
            for p in [l.heel, l.mtp, l.toe] {
                // 1 µm: the linear interpolation between table rows of a toe that clears the floor
                assert!(
                    p[1] > -1e-6,
                    "a foot point below the floor: {p:?} at {}",
                    lm.time
                );
            }
            assert!(dist(l.hip, l.knee) - body.l3 < 1e-9 && dist(l.knee, l.ankle) - body.l4 < 1e-9);
        }
        // the stance foot's contact points do not slide: the heel while it is down, the mtp
        let s = leg(lm, stance);
        if s.heel[1] < 1e-9 && first.heel[1] < 1e-9 {
            assert!(dist(s.heel, first.heel) < 1e-3, "the stance heel slides");
        }
        if s.mtp[1] < 1e-9 {
            assert!(dist(s.mtp, first.mtp) < 1e-3, "the stance mtp slides");
        }
    }
    frames
}

#[test]
fn a_forward_step_lands_on_its_goal() {
    let s = standing();
    let goal = [0.6, 0.04];
    let step = NrsStep::initialize(&s, &specs(Side::Right, goal, 0.1), None).unwrap();
    assert_eq!(step.kind(), StepType::Forward);
    let frames = check_frames(&step, Side::Left, &s.body);
    let end = step.end_state();
    assert!(
        (end.feet[0].flat[0] - goal[0]).abs() < 1e-12
            && (end.feet[0].flat[1] - goal[1]).abs() < 1e-12
    );
    // the foot lands flat (the default θ_HSM+^SW = 0): its ankle is l9 above the goal
    let last = frames.last().unwrap();
    assert!(
        dist(last.right.ankle, [goal[0], s.body.l9, goal[1]]) < 1e-9,
        "{:?}",
        last.right.ankle
    );
    let d = direction(0.1);
    let along = (last.right.mtp[0] - last.right.heel[0]) * d[0]
        + (last.right.mtp[2] - last.right.heel[2]) * d[1];
    assert!(along > 0.0);
    // the swing foot rose by about 5 cm · swhf above its take-off-to-landing line
    let peak = frames
        .iter()
        .map(|f| f.right.ankle[1])
        .fold(f64::MIN, f64::max);
    assert!(peak > s.body.l9 + 0.03, "peak {peak}");
    // the pelvis ends on the line between the ankles (docs/nrs.md): above their midpoint when
    // the stance foot ends flat, between them when its heel ends up (the highest point)
    let (a, b) = (last.left.ankle, last.right.ankle);
    let (u, v) = (
        [b[0] - a[0], b[2] - a[2]],
        [last.pelvis[0] - a[0], last.pelvis[2] - a[2]],
    );
    let along = (u[0] * v[0] + u[1] * v[1]) / (u[0] * u[0] + u[1] * u[1]);
    let off = (u[0] * v[1] - u[1] * v[0]) / (u[0] * u[0] + u[1] * u[1]).sqrt();
    assert!(
        off.abs() < 1e-9 && (0.0..=1.0).contains(&along),
        "{off} {along}"
    );
    if end.feet[1].pitch == 0.0 {
        assert!((along - 0.5).abs() < 1e-9, "{along}");
    }
}

#[test]
fn a_backward_and_a_lateral_step_too() {
    let s = standing();
    let back = NrsStep::initialize(&s, &specs(Side::Left, [-0.5, -0.04], 0.0), None).unwrap();
    assert_eq!(back.kind(), StepType::Backward);
    check_frames(&back, Side::Right, &s.body);
    let side = NrsStep::initialize(&s, &specs(Side::Left, [0.0, -0.35], 0.0), None).unwrap();
    assert_eq!(side.kind(), StepType::Lateral);
    check_frames(&side, Side::Right, &s.body);
}

/// Figure 2 with ν = 60°: the goal foot's heel around the stance heel, forward up to 60° towards the stepping side
/// and down to −30°, lateral 60°–120°, backward 120° to 210° (= −150°), illegal between −150°
/// and −30° (crossing the stance leg).
#[test]
fn step_types_by_the_angle_around_the_stance_heel() {
    let s = standing();
    let stance = s.feet[1]; // the left foot stands, the right steps (to +z)
    let p = &s.params;
    let l8 = klaw::kinematics::foot::Foot::new(&s.body).l8;
    let heel = [stance.flat[0] - l8, stance.flat[1]];
    let at = |deg: f64, foot_dir: f64| {
        let a = deg.to_radians();
        // the goal foot's heel at the angle: its ankle l8 ahead of it along the foot
        let d = direction(foot_dir);
        let goal = [
            heel[0] + 0.5 * a.cos() + l8 * d[0],
            heel[1] + 0.5 * a.sin() + l8 * d[1],
        ];
        klaw::nrs::step::classify(
            &stance,
            Side::Right,
            goal,
            foot_dir,
            (p.region_angle, p.boundary_tolerance, p.parallel_tolerance),
            l8,
        )
    };
    let oblique = 30f64.to_radians();
    use StepType::*;
    // 59°, 61°, 119° and 121° lie exactly 1° from a boundary: outside its band (docs/nrs.md), so
    // the foot's direction does not matter there
    for (deg, want) in [
        (29.0, Ok(Forward)),
        (31.0, Ok(Forward)),
        (59.0, Ok(Forward)),
        (61.0, Ok(Lateral)),
        (119.0, Ok(Lateral)),
        (121.0, Ok(Backward)),
        (-29.0, Ok(Forward)),
        (-149.0, Err(())),
        (-151.0, Ok(Backward)),
        (-31.0, Err(())),
        (-90.0, Err(())),
    ] {
        for foot in [oblique, 0.0] {
            assert_eq!(
                at(deg, foot).map_err(|_| ()),
                want,
                "{deg}°, foot at {foot} rad"
            );
        }
    }
    // on a boundary (within 1°) a foot parallel to the stance foot makes the step lateral
    assert_eq!(at(60.5, 0.05), Ok(Lateral));
    assert_eq!(at(60.5, oblique), Ok(Forward));
    assert_eq!(at(119.5, 0.0), Ok(Lateral));
    assert_eq!(at(119.5, oblique), Ok(Backward));
}

#[test]
fn illegal_goals_are_typed_errors() {
    let s = standing();
    let err = |spec: StepSpecs| NrsStep::initialize(&s, &spec, None).unwrap_err();
    assert!(matches!(
        err(specs(Side::Right, [0.0, -0.3], 0.0)),
        NrsError::Goal {
            reason: GoalReason::Illegal { .. },
            ..
        }
    ));
    assert!(matches!(
        err(specs(
            Side::Right,
            [s.feet[1].flat[0] + 0.01, s.feet[1].flat[1] + 0.03],
            0.0
        )),
        NrsError::Goal {
            reason: GoalReason::Overlap { .. },
            ..
        }
    ));
    assert!(matches!(
        err(specs(Side::Right, [0.12, 0.04], 0.0)),
        NrsError::Goal {
            reason: GoalReason::TooShort { .. },
            ..
        }
    ));
    assert!(matches!(
        err(specs(Side::Right, [1.6, 0.04], 0.0)),
        NrsError::Goal {
            reason: GoalReason::Unreachable { .. },
            ..
        } | NrsError::Input(_)
    ));
    let msg = err(specs(Side::Right, [0.0, -0.3], 0.0)).to_string();
    assert!(
        msg.contains("illegal region") && msg.contains("right foot"),
        "{msg}"
    );
}

/// `advance` is constant time and allocates nothing; two walkers do not share anything.
#[test]
fn several_walkers_are_independent() {
    let a = standing();
    let b = WalkerState::standing(
        Body::standard(1.6, 60.0).unwrap(),
        AttributeTable::builtin().defaults(),
        [3.0, 1.0],
        1.0,
    );
    let sa = NrsStep::initialize(&a, &specs(Side::Right, [0.5, 0.04], 0.0), None).unwrap();
    let before = sa.advance(0.4);
    let g = [
        3.0 + 0.45 * 1f64.cos() + 0.04 * 1f64.sin(),
        1.0 - 0.45 * 1f64.sin() + 0.04 * 1f64.cos(),
    ];
    let _sb = NrsStep::initialize(&b, &specs(Side::Right, g, 1.0), None).unwrap();
    assert_eq!(sa.advance(0.4), before);
}

/// Eq. 4 in a forward NRS⁻ from standing (§5.3): its centre-site height is the engine's hip
/// height h of the walking step of the same length, plus eq. 4's end correction (linear in t)
/// plus the Hermite end-slope terms t(1 − t)² and t²(t − 1) that bring it to rest: so
/// y(t) − h(t) is a cubic in t, whose fourth differences over the uniform table vanish (to
/// round-off), and it meets the standing height at t = 0 — away from the rows where the centre
/// rises [ours, docs/nrs.md]: where eq. 4 would dorsiflex the flat stance ankle beyond
/// `ankle_dorsiflexion_max`, which it then keeps. (In this 0.45 m step that is most of the
/// step: eq. 4 holds on 62 of the 253 windows of five rows, the first quarter; 73 before the
/// walking step's hip led at heel strike, whose higher hip dorsiflexes the stance ankle more.)
#[test]
fn a_forward_step_borrows_the_walking_steps_hip_height() {
    let s = standing();
    let length = 0.45;
    let goal = [s.feet[1].flat[0] + length, s.feet[0].flat[1]];
    let step = NrsStep::initialize(&s, &specs(Side::Right, goal, 0.0), None).unwrap();
    let n = s.params.table_intervals;
    let gait = klaw::GaitRequest {
        step_length: Some(length),
        ..Default::default()
    }
    .complete(&s.body, &s.attrs)
    .unwrap();
    let w = klaw::nrs::walking::WalkingStep::simulate(s.body, &s.attrs, gait, n).unwrap();
    let poses: Vec<Landmarks> = (0..=n).map(|i| step.advance(i as f64 / n as f64)).collect();
    // the stance (left) ankle's clinical dorsiflexion: where it is near its bound the centre
    // may have been raised (the rule measures it in the leg's plane, within a degree of this)
    let dorsi = |lm: &Landmarks| {
        klaw::figure::clinical::clinical(lm, &s.body)
            .unwrap()
            .left
            .ankle
            .flexion
    };
    let max = s.params.ankle_dorsiflexion_max;
    let raised: Vec<bool> = poses
        .iter()
        .map(|lm| dorsi(lm) > max - 1.5f64.to_radians())
        .collect();
    let d: Vec<f64> = (0..=n).map(|i| poses[i].pelvis[1] - w.height[i]).collect();
    assert!((d[0] + w.height[0] - s.upper.centre[1]).abs() < 1e-12);
    let mut windows = 0;
    let mut worst: f64 = 0.0;
    for i in 0..n - 3 {
        if raised[i..i + 5].iter().any(|r| *r) {
            continue;
        }
        let q = &d[i..i + 5];
        worst = worst.max((q[0] - 4.0 * q[1] + 6.0 * q[2] - 4.0 * q[3] + q[4]).abs());
        windows += 1;
    }
    eprintln!("eq. 4 on {windows} of {} windows", n - 3);
    // how much of the step eq. 4 holds on is the model's own output: a snapshot
    insta::assert_snapshot!(format!("eq. 4 holds on {windows} of {} windows", n - 3));
    assert!(
        worst < 1e-11,
        "y − h is not a cubic: fourth difference {worst}"
    );
}

/// Steps shorter than the engine can walk from a start (its start-up step drops the hip below
/// its heel-strike height for a 0.3 m walk of a 1.8 m figure) borrow a longer walking step at
/// the same cadence, its hip excursion scaled down (docs/nrs.md): they run, land on their goal
/// and keep every per-frame bound; below the engine's minimum step length they stay an error.
#[test]
fn short_steps_borrow_a_longer_walking_step() {
    let s = standing();
    let y = s.feet[0].flat[1];
    for (goal, kind) in [
        ([0.3, y], StepType::Forward),
        ([0.22, y], StepType::Forward),
        ([-0.3, y], StepType::Backward),
    ] {
        let step = NrsStep::initialize(&s, &specs(Side::Right, goal, 0.0), None)
            .unwrap_or_else(|e| panic!("{goal:?}: {e}"));
        assert_eq!(step.kind(), kind);
        let frames = check_frames(&step, Side::Left, &s.body);
        let ankle = frames.last().unwrap().right.ankle;
        assert!(
            dist(ankle, [goal[0], s.body.l9, goal[1]]) < 1e-9,
            "{goal:?}: {ankle:?}"
        );
    }
    let min = s.attrs.step_length_min * s.body.l1;
    assert!(NrsStep::initialize(&s, &specs(Side::Right, [min - 0.01, y], 0.0), None).is_err());
}
