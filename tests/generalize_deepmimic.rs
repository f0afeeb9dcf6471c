//! The external prototype (issue 17): DeepMimic's walking clip, converted once by
//! `scripts/deepmimic_walk.py` into `models/prototypes/deepmimic-walk.csv` (its source, licence
//! and checksums in its header). Read as a measured walk, its events are where the clip's own
//! markers put them; generalized to klaw's bodies of both tables and to other step lengths it
//! keeps the walking constraints and the step length exactly; and at its own step length
//! (ρ = 1) its knee keeps the clip's knee curve.
mod common;
mod generalize_support;

use generalize_support::assert_walks;
use klaw::figure::LegPoints;
use klaw::generalize::measured::{self, columns};
use klaw::generalize::{GeneralizeError, GeneralizeParameters, KinematicWalk, WalkData};
use klaw::{Body, GaitRequest};

const CLIP: &str = include_str!("../models/prototypes/deepmimic-walk.csv");
/// The clip's stride, in its header (the root's advance over the clip, scripts/deepmimic_walk.py).
const STRIDE: f64 = 1.23859;

fn params() -> GeneralizeParameters {
    GeneralizeParameters::default()
}

fn prototype() -> WalkData {
    measured::from_csv(CLIP, &params()).unwrap()
}

/// The clip's frames: time and every column, by the layout's column names.
fn frames() -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = CLIP.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

/// The knee flexion (rad, 0 straight) of a hip, knee and ankle: the angle between the thigh and
/// the shank.
fn flexion(hip: &[f64], knee: &[f64], ankle: &[f64]) -> f64 {
    let u: Vec<f64> = (0..hip.len()).map(|i| knee[i] - hip[i]).collect();
    let v: Vec<f64> = (0..hip.len()).map(|i| ankle[i] - knee[i]).collect();
    let dot: f64 = u.iter().zip(&v).map(|(a, b)| a * b).sum();
    let n = |w: &[f64]| w.iter().map(|a| a * a).sum::<f64>().sqrt();
    (dot / (n(&u) * n(&v))).clamp(-1.0, 1.0).acos()
}

fn leg_flexion(leg: &LegPoints) -> f64 {
    flexion(&leg.hip, &leg.knee, &leg.ankle)
}

/// The times where `y` comes down through `level` (linear between the frames).
fn falls(t: &[f64], y: &[f64], level: f64) -> Vec<f64> {
    (1..y.len())
        .filter(|&i| y[i - 1] > level && y[i] <= level)
        .map(|i| t[i - 1] + (t[i] - t[i - 1]) * (y[i - 1] - level) / (y[i - 1] - y[i]))
        .collect()
}

/// A column of the clip by name.
fn column(name: &str) -> Vec<f64> {
    let (h, rows) = frames();
    let j = h.iter().position(|c| c == name).unwrap();
    rows.iter().map(|r| r[j]).collect()
}

/// The clip's heel strikes of the right and the left foot (s): where each heel comes down to
/// 1 mm above its lowest, computed here from the columns.
fn strikes() -> [Vec<f64>; 2] {
    let t = column("time_s");
    ["r", "l"].map(|side| {
        let y = column(&format!("heel_{side}_y_m"));
        let low = y.iter().copied().fold(f64::INFINITY, f64::min);
        falls(&t, &y, low + 1e-3)
    })
}

/// The clip reads: its step is half its stride, the heel strikes are where each heel comes
/// down to 1 mm above its lowest (computed here from the columns), and the toe-off of the hind
/// foot comes after the stance foot's heel strike (a double support), as the foot's toe tip
/// starts moving forward.
#[test]
fn the_clip_reads_as_a_step_with_its_own_events() {
    let w = prototype();
    assert_eq!(frames().0, columns());
    let t = column("time_s");
    let [r, l] = strikes();
    let period = l[0] - r[0];
    assert!(
        w.source
            .contains(&format!("{:.4} s to {:.4} s", r[0], l[0]))
    );
    // the step advances the body half a stride (to the clip's own ±1 mm of foot placement)
    assert!(
        (w.step_length - 0.5 * STRIDE).abs() < 1e-3,
        "{}",
        w.step_length
    );
    // half a stride later the other foot: the clip is periodic
    assert!((r[1] - l[0] - period).abs() < 2e-3, "{r:?} {l:?}");
    let tom = w.phases.tom;
    assert!(tom > 0.0 && tom < 0.1, "TOM {tom}");
    // the hind (left) toe tip stands still until its toe-off and moves on after it
    let x = column("toe_l_x_m");
    let at = |s: f64| klaw::generalize::sequence::interpolate(&t, &x, s);
    let off = r[0] + tom * period;
    assert!((at(off) - at(r[0])).abs() < 2e-3, "{}", at(off) - at(r[0]));
    assert!(
        at(off + 0.1) - at(off) > 0.02,
        "{}",
        at(off + 0.1) - at(off)
    );
}

/// The bodies: Winter's and de Leva's male and female tables.
fn bodies() -> [Body; 3] {
    [
        Body::from_table("winter", 1.75, 70.0).unwrap(),
        Body::from_table("deleva-male", 1.85, 82.0).unwrap(),
        Body::from_table("deleva-female", 1.62, 58.0).unwrap(),
    ]
}

/// The clip's step generalized to `body` at ρ times its step in leg lengths, 4 steps.
fn walk(w: &WalkData, body: Body, rho: f64) -> KinematicWalk {
    try_walk(w, body, rho).unwrap_or_else(|e| panic!("H {} ρ {rho}: {e}", body.height))
}

/// [`walk`], or why the generalization refuses it.
fn try_walk(w: &WalkData, body: Body, rho: f64) -> Result<KinematicWalk, GeneralizeError> {
    let attrs = common::default_attributes();
    let s = rho * w.character.step_length * body.l1;
    let gait = GaitRequest {
        step_length: Some(s),
        ..Default::default()
    }
    .complete(&body, &attrs)
    .unwrap();
    KinematicWalk::new(w, body, attrs, gait, 4, &params())
}

/// On three bodies of both tables, at 0.9, 1 and 1.2 times the clip's step in leg lengths (and
/// 0.8 where the check accepts it: [`a_sliding_heel_is_refused`]): the step is as long as asked
/// (to round-off), no foot slides, no leg stretches, nothing goes under the floor, and the figure
/// is continuous from step to step.
#[test]
fn generalized_to_klaw_bodies_it_keeps_the_walking_constraints() {
    let w = prototype();
    for body in bodies() {
        for rho in [0.8, 0.9, 1.0, 1.2] {
            let kin = match try_walk(&w, body, rho) {
                Ok(kin) => kin,
                // measured 1.18 mm (Winter H 1.75) and 1.04 mm (de Leva male H 1.85)
                Err(GeneralizeError::Slides { .. }) if rho < 0.9 => continue,
                Err(e) => panic!("H {} ρ {rho}: {e}", body.height),
            };
            let s = rho * w.character.step_length * body.l1;
            assert!((kin.step.data.step_length - s).abs() < 1e-12);
            let end = kin.figure_at(kin.duration()).unwrap();
            let start = kin.figure_at(0.0).unwrap();
            // after 4 steps the right heel (on the floor at both ends) has moved on two strides
            let moved = end.right.heel[0] - start.right.heel[0];
            assert!((moved - 4.0 * s).abs() < 1e-9, "{moved} vs {}", 4.0 * s);
            assert_walks(&kin, &body);
        }
    }
}

/// At 0.8 × the clip's step on Winter's body (H 1.75 m) the clip's swing heel, which moves back
/// 14 mm in its last frame before the strike, meets the floor a little before the heel strike and
/// slides back along it: the generalization refuses the step with a typed error naming the
/// slide, and the same step posed with the bound lifted slides more than 1 mm by the frames'
/// own measure (500 frames/s, `max_slide`), so the refusal is not spurious.
#[test]
fn a_sliding_heel_is_refused() {
    let w = prototype();
    let body = bodies()[0];
    let refused = try_walk(&w, body, 0.8);
    let Err(GeneralizeError::Slides { distance, max, .. }) = refused else {
        panic!("not refused for a slide: {:?}", refused.map(|_| ()));
    };
    assert!(distance > max && max == 1e-3, "{distance} {max}");
    let lifted = GeneralizeParameters {
        slide_max: 0.01,
        ..params()
    };
    let attrs = common::default_attributes();
    let s = 0.8 * w.character.step_length * body.l1;
    let gait = GaitRequest {
        step_length: Some(s),
        ..Default::default()
    }
    .complete(&body, &attrs)
    .unwrap();
    let kin = KinematicWalk::new(&w, body, attrs, gait, 4, &lifted).unwrap();
    let frames: Vec<_> = kin.frames(500.0).collect::<Result<_, _>>().unwrap();
    let (d, _, point) = generalize_support::max_slide(&frames);
    assert!(d > 1e-3 && point.ends_with("heel"), "{point} {d}");
}

/// At ρ = 1 on each body, the right knee's flexion over a stride follows the clip's own (the
/// angle between the thigh and the shank of the clip's markers, computed here) to 5.5° RMS
/// (measured 5.2°, 5.4° and 5.4°: the bodies' thigh : shank ratios and feet are not the
/// clip's; klaw's list, hung on the clip's pelvis, has people's timing since 2026-12-05,
/// which holds the stance hip joint 3 mm lower at mid-stance than the paper's half-sine did:
/// 4.0°, 4.2° and 4.2° with it; and since issue 38 the hip's drop for the swing leg in terminal
/// swing is planned over the whole step, which lowers it in stance too: 4.8°, 5.1° and 5.2°
/// before), and closer than at 1.2 × the clip's step (10.3–12.2°).
#[test]
fn at_its_own_step_the_knee_keeps_the_clips_curve() {
    let w = prototype();
    let (h, rows) = frames();
    let col = |name: &str| h.iter().position(|c| c == name).unwrap();
    let marker =
        |r: &[f64], m: &str| [r[col(&format!("{m}_r_x_m"))], r[col(&format!("{m}_r_y_m"))]];
    let [right, left] = strikes();
    let (strike, end) = (right[0], left[0]);
    let period = end - strike;
    // the clip's right knee over its first stride, at the stride's phase
    let clip: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r[0] >= strike && r[0] < strike + 2.0 * period)
        .map(|r| {
            let k = flexion(&marker(r, "hip"), &marker(r, "knee"), &marker(r, "ankle"));
            ((r[0] - strike) / (2.0 * period), k)
        })
        .collect();
    let rms = |kin: &KinematicWalk| {
        let d = 2.0 * kin.step.duration;
        let sq: f64 = clip
            .iter()
            .map(|&(phase, k)| {
                let lm = kin.figure_at(d + phase * d).unwrap();
                (leg_flexion(&lm.right) - k).powi(2)
            })
            .sum();
        (sq / clip.len() as f64).sqrt().to_degrees()
    };
    for body in bodies() {
        let kin = walk(&w, body, 1.0);
        let one = rms(&kin);
        let longer = rms(&walk(&w, body, 1.2));
        eprintln!(
            "H {} ({} leg): knee RMS {one:.2}° at ρ 1, {longer:.2}° at 1.2",
            body.height, body.l1
        );
        assert!(one < 5.5, "{one}");
        assert!(longer > one, "{longer} vs {one}");
    }
}
