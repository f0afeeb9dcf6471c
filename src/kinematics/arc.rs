//! A foot turning rigidly about a pivot on the ground (its heel, its metatarsal joint, its toe
//! tip): the ankle's circle, where it meets a circle about the hip, and the first of those
//! pitches in a range. The closed forms the stance leg's foot rules steer their solvers with.
use std::f64::consts::TAU;

use crate::numerics::trig::atan2;

/// How far (rad) outside its range a root found in closed form may fall by round-off and still
/// count as in it (it is then clamped into the range).
const ROOT_SLACK: f64 = 1e-12;

/// The ankle of a foot turning rigidly about a pivot on the ground, as a function of the foot
/// pitch p (heel up +): `ankle + pitch(v, p) = pivot` for the foot-frame vector v from the
/// ankle to the pivot, i.e. `ankle(p) = pivot + radius · (−cos(p + phase), sin(p + phase))`
/// with `radius · (cos phase, −sin phase) = v`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Arc {
    pub(crate) pivot: [f64; 2],
    pub(crate) radius: f64,
    pub(crate) phase: f64,
}

impl Arc {
    pub(crate) fn new(pivot: [f64; 2], v: [f64; 2]) -> Self {
        Arc {
            pivot,
            radius: v[0].hypot(v[1]),
            phase: atan2(-v[1], v[0]),
        }
    }

    /// The two families of pitches at which the ankle is at in-plane distance `b` from `target`
    /// (a circle–circle intersection), each defined modulo 2π: with D = target − pivot,
    /// |D − radius · u(p + phase)|² = b² reads cos(p + phase − ψ) = c with ψ the direction of
    /// (−D_x, D_y) and c = (|D|² + radius² − b²) / (2 radius |D|). `None` when the circles do
    /// not meet (|c| > 1, or a NaN).
    pub(crate) fn pitches_at(&self, target: [f64; 2], b: f64) -> Option<[f64; 2]> {
        let dx = target[0] - self.pivot[0];
        let dy = target[1] - self.pivot[1];
        let d2 = dx * dx + dy * dy;
        let c = (d2 + self.radius * self.radius - b * b) / (2.0 * self.radius * d2.sqrt());
        // (NaN fails the test too)
        (c.abs() <= 1.0).then(|| {
            let base = atan2(dy, -dx) - self.phase;
            let half = c.acos();
            [base - half, base + half]
        })
    }
}

/// The smallest member of the families `roots` (each modulo 2π) in [lo, hi], a member up to
/// [`ROOT_SLACK`] outside the range clamped into it.
pub(crate) fn first_in(roots: [f64; 2], lo: f64, hi: f64) -> Option<f64> {
    let from = lo - ROOT_SLACK;
    let first = roots
        .map(|r| from + (r - from).rem_euclid(TAU))
        .into_iter()
        .fold(f64::INFINITY, f64::min);
    (first <= hi + ROOT_SLACK).then(|| first.clamp(lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The ankle at pitch p, turned about the pivot from the foot-frame vector v (the rotation of
    /// `kinematics::foot::pitch`, written out): ankle = pivot − R(p) v.
    fn ankle(pivot: [f64; 2], v: [f64; 2], p: f64) -> [f64; 2] {
        let (s, c) = p.sin_cos();
        [
            pivot[0] - (v[0] * c + v[1] * s),
            pivot[1] - (-v[0] * s + v[1] * c),
        ]
    }

    /// Both pitches `pitches_at` returns put the ankle at distance b from the target, by the
    /// rotation itself; circles that do not meet give none; `first_in` takes the smallest
    /// member in the range, moved by whole turns.
    #[test]
    fn the_pitches_put_the_ankle_on_the_circle() {
        let (pivot, v) = ([0.3, 0.0], [0.15, -0.08]);
        let arc = Arc::new(pivot, v);
        let target = [0.1, 0.85];
        for b in [0.75, 0.85, 0.95] {
            let roots = arc.pitches_at(target, b).unwrap();
            for p in roots {
                let a = ankle(pivot, v, p);
                let d = (a[0] - target[0]).hypot(a[1] - target[1]);
                assert!((d - b).abs() < 1e-12, "{b}: {d}");
            }
        }
        assert!(arc.pitches_at(target, 2.0).is_none());
        assert_eq!(first_in([0.5, -1.0], 0.0, 1.0), Some(0.5));
        let wrapped = first_in([0.5 - TAU, 3.0], 0.0, 1.0).unwrap();
        assert!((wrapped - 0.5).abs() < 1e-12);
        assert_eq!(first_in([2.0, 3.0], 0.0, 1.0), None);
    }
}
