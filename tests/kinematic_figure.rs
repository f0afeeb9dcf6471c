//! The kinematic walk's whole figure checked as `tests/figure.rs` checks the dynamic walk's, with
//! the same bounds (issue 38): no knee angle, foot pitch or joint position jumps at a phase
//! boundary (the values 1 µs either side), and stance contacts do not slide. For the bundled
//! prototype and for DeepMimic's clip (`models/prototypes/deepmimic-walk.csv`, read as
//! `klaw prototype --from-csv` reads it), each walked kinematically by Winter's body of H 1.8 m
//! and de Leva's male (H 1.85 m) and female (H 1.65 m) bodies at the default gait, as
//! `klaw walk --mode kinematic` walks them.
mod common;
use common::{d, foot_pitch, knee_angle, worst_contact_slide};

use klaw::figure::Landmarks;
use klaw::generalize::{
    GeneralizeParameters, KinematicWalk, WalkData, default_prototype, measured,
};
use klaw::{Body, Event};

const CLIP: &str = include_str!("../models/prototypes/deepmimic-walk.csv");

/// The two prototypes: the bundled one (klaw's own walk) and DeepMimic's clip.
fn prototypes() -> [(&'static str, WalkData); 2] {
    let clip = measured::from_csv(CLIP, &GeneralizeParameters::default()).unwrap();
    [("default", default_prototype()), ("DeepMimic", clip)]
}

/// The bodies: Winter H 1.8, de Leva male H 1.85, de Leva female H 1.65 (23 H² kg).
fn bodies() -> [Body; 3] {
    [
        common::body_of_height_in("winter", 1.8),
        common::body_of_height_in("deleva-male", 1.85),
        common::body_of_height_in("deleva-female", 1.65),
    ]
}

/// Every prototype walked by every body, 6 steps at the default gait (1.4 m/s), with a label.
fn walks() -> Vec<(String, Body, KinematicWalk)> {
    let mut out = Vec::new();
    for (name, w) in prototypes() {
        for body in bodies() {
            let gait = common::gait(&body, 1.4);
            let attrs = common::default_attributes();
            let params = GeneralizeParameters::default();
            let kin = KinematicWalk::new(&w, body, attrs, gait, 6, &params)
                .unwrap_or_else(|e| panic!("{name} on H {}: {e}", body.height));
            out.push((format!("{name} prototype, H {}", body.height), body, kin));
        }
    }
    out
}

fn figure(kin: &KinematicWalk, t: f64) -> Landmarks {
    kin.figure_at(t).unwrap()
}

/// The instants a leg becomes straight (its hip–ankle distance at thigh + shank, to 1 nm) or
/// bends again: the pose's own phase boundary where a leg's reach limits the hip. Found on a
/// 1 ms scan and bisected to 1e-11 s.
fn straightening(kin: &KinematicWalk, body: &Body) -> Vec<(&'static str, f64)> {
    let straight = |t: f64, right: bool| {
        let f = figure(kin, t);
        let leg = if right { f.right } else { f.left };
        d(leg.hip, leg.ankle) >= body.l1 - 1e-9
    };
    let n = (kin.duration() * 1000.0) as usize;
    let mut out = Vec::new();
    for right in [true, false] {
        let mut before = straight(0.0, right);
        for k in 1..=n {
            let t = k as f64 / 1000.0;
            let now = straight(t, right);
            if now != before {
                let (mut a, mut b) = (t - 1e-3, t);
                while b - a > 1e-11 {
                    let m = 0.5 * (a + b);
                    if straight(m, right) == before {
                        a = m
                    } else {
                        b = m
                    }
                }
                let name = match (right, now) {
                    (true, true) => "right leg straight",
                    (true, false) => "right leg bends",
                    (false, true) => "left leg straight",
                    (false, false) => "left leg bends",
                };
                out.push((name, 0.5 * (a + b)));
            }
            before = now;
        }
    }
    out
}

/// Across every phase boundary (heel strike, foot flat, heel-off, meta-off and toe-off of each
/// step, and each instant a leg straightens to its full reach or bends again) no knee angle,
/// foot pitch or joint position jumps: the values 1 µs either side differ by less than 0.05° and
/// 0.1 mm, and the figure at the boundary agrees with the one before (tests/figure.rs's bounds).
///
/// Before the fix (2026-12, issue 38): the bundled prototype's swing toe tip jumped 23.95 mm
/// (Winter H 1.8) at every toe-off, lifted in that instant to half the ball's height; on
/// DeepMimic's clip the swing leg, its ankle 15 mm out of reach in terminal swing, locked
/// straight and the knees snapped where it did (see the commit that fixed it).
#[test]
fn nothing_jumps_at_a_phase_boundary() {
    let e = 1e-6;
    let mut failures = Vec::new();
    for (label, body, kin) in walks() {
        let mut boundaries: Vec<(String, f64)> = kin
            .events()
            .iter()
            .map(|ev: &Event| (format!("{} {}", ev.side, ev.event), ev.time_s))
            .collect();
        boundaries.extend(
            straightening(&kin, &body)
                .into_iter()
                .map(|(n, t)| (n.to_string(), t)),
        );
        // the largest knee, foot and position change, and where
        let mut worst = [
            (0.0, String::new()),
            (0.0, String::new()),
            (0.0, String::new()),
        ];
        for (name, t) in boundaries {
            if t - e <= 0.0 || t + e >= kin.duration() {
                continue;
            }
            let (a, b, at) = (figure(&kin, t - e), figure(&kin, t + e), figure(&kin, t));
            for (la, lb) in [
                (&a.right, &b.right),
                (&a.left, &b.left),
                (&a.right, &at.right),
                (&a.left, &at.left),
            ] {
                let dk = (knee_angle(la) - knee_angle(lb)).abs().to_degrees();
                let dp = (foot_pitch(la) - foot_pitch(lb)).abs().to_degrees();
                let dx = [(la.knee, lb.knee), (la.ankle, lb.ankle), (la.toe, lb.toe)]
                    .map(|(p, q)| d(p, q))
                    .into_iter()
                    .fold(0.0, f64::max);
                for (w, v) in worst.iter_mut().zip([dk, dp, dx]) {
                    if v > w.0 {
                        *w = (v, format!("{name} at {t:.6} s"));
                    }
                }
            }
        }
        let [(dk, kat), (dp, pat), (dx, xat)] = worst;
        if dk >= 0.05 || dp >= 0.05 || dx >= 1e-4 {
            failures.push(format!(
                "{label}: knee {dk:.4}° ({kat}), foot {dp:.4}° ({pat}), a joint {:.4} mm ({xat})",
                1e3 * dx
            ));
        }
    }
    assert!(failures.is_empty(), "jumps:\n{}", failures.join("\n"));
}

/// A foot point on the ground stays where it is while it is on the ground (≤ 1 mm), over every
/// 1 ms interval of the walk (tests/figure.rs's bound).
#[test]
fn stance_contacts_do_not_slide() {
    for (label, _, kin) in walks() {
        let n = (kin.duration() * 1000.0) as usize;
        let worst = worst_contact_slide(n, |t| figure(&kin, t));
        assert!(worst < 1e-3, "{label}: a contact slides {worst} m in 1 ms");
    }
}
