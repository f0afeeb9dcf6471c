//! Checks shared by the kinematic-walk tests: the walking constraints of a figure, frame by
//! frame.
#![allow(dead_code)]

use klaw::generalize::KinematicWalk;
use klaw::{Body, Landmarks};

/// The farthest any foot point moves while it stays on the floor (within 1e-7 m) from where it
/// met it, over the frames: (distance, time, which point).
pub fn max_slide(frames: &[Landmarks]) -> (f64, f64, String) {
    // contact: (first x, z) of each foot point while it stays on the floor
    let mut contact: [Option<[f64; 2]>; 6] = [None; 6];
    let mut slide: (f64, f64, usize) = (0.0, 0.0, 0);
    for lm in frames {
        for (i, leg) in [lm.right, lm.left].iter().enumerate() {
            for (j, p) in [leg.heel, leg.mtp, leg.toe].iter().enumerate() {
                let c = &mut contact[3 * i + j];
                if p[1] <= 1e-7 {
                    let at = *c.get_or_insert([p[0], p[2]]);
                    let d = (p[0] - at[0]).hypot(p[2] - at[1]);
                    if d > slide.0 {
                        slide = (d, lm.time, 3 * i + j);
                    }
                } else {
                    *c = None;
                }
            }
        }
    }
    let (d, t, k) = slide;
    let point = ["heel", "ball", "toe tip"][k % 3];
    let side = ["right", "left"][k / 3];
    (d, t, format!("{side} {point}"))
}

/// The distance between two points.
pub fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The constraints of a walking figure, frame by frame: a foot point on the floor stays where it
/// touched (≤ 1 mm over its contact), no hip–ankle distance exceeds thigh + shank, no point is
/// under the floor, and the figure is continuous through every heel strike.
pub fn assert_walks(kin: &KinematicWalk, body: &Body) {
    let frames: Vec<Landmarks> = kin.frames(500.0).collect::<Result<_, _>>().unwrap();
    for lm in &frames {
        for leg in [lm.right, lm.left] {
            assert!(
                distance(leg.hip, leg.ankle) <= body.l1 + 1e-9,
                "stretched at {}",
                lm.time
            );
            for p in [leg.heel, leg.mtp, leg.toe] {
                assert!(p[1] >= -1e-6, "under the floor at {}: {p:?}", lm.time);
            }
        }
    }
    let (d, t, point) = max_slide(&frames);
    assert!(d <= 1e-3, "the {point} slides {d} m by {t} s");
    for k in 1..kin.steps {
        let t = k as f64 * kin.step.duration;
        let (a, b) = (
            kin.figure_at(t - 1e-9).unwrap(),
            kin.figure_at(t + 1e-9).unwrap(),
        );
        for (x, y) in [(a.right, b.right), (a.left, b.left)] {
            for (p, q) in [
                (x.hip, y.hip),
                (x.knee, y.knee),
                (x.ankle, y.ankle),
                (x.toe, y.toe),
            ] {
                assert!(distance(p, q) < 1e-6, "jump at step {k}: {p:?} {q:?}");
            }
        }
    }
}
