//! The whole figure posed from the inverse kinematics' angles, for the exporters (as
//! [`crate::nrs::pose`] poses a non-rhythmic step): the legs by the chain's forward kinematics
//! about the pelvis centre, the pelvis carried forward at the walk's speed, its height set by the
//! stance ankle on the ground, the feet by klaw's foot rules, the trunk and arms by klaw's walk
//! rules ([`crate::figure::landmarks()`]).
//!
//! - A leg is in support from its ankle's most forward point to its most backward (relative to
//!   the pelvis: heel strike to toe-off, Pronost et al.'s characteristic points 2 to 4).
//! - The supporting foot is planted where its ankle passes under the pelvis (point 3): it pivots
//!   on its heel before, rolls over its metatarsal joint and toe after ([`grounded_ankle`], the
//!   engine's heel rocker and rolling foot), its pitch the one that puts the ankle at its
//!   horizontal place. The pelvis's height is the one that puts the supporting ankle at the
//!   height that pitch gives it (the higher of the two in double support: no foot goes
//!   through the floor), raised where a swinging ankle would come nearer the floor than the
//!   foot's ankle height l9 (the chain's ankle path from a poulaine can pass a millimetre
//!   under it at the heel strike the supports' first frame does not yet count; the swinging
//!   foot then rests flat on the floor).
//! - A swinging foot stays square to its shank (the ankle at 0° of dorsiflexion), clamped to
//!   keep the heel and the toe above the floor (`Foot::clear_pitch`).
//! - The trunk keeps its lean (attribute `trunk_lean`): lumbar extension = tilt − lean, bending
//!   = list (the spine undoes the pelvis's list), rotation = −1.8 × pelvic rotation; each arm
//!   swings with the opposite thigh, half the attribute `arm_swing` at that thigh's largest
//!   forward angle.
use glam::DVec3;

use crate::figure::landmarks::arm_swing;
use crate::figure::{Landmarks, LegPoints};
use crate::ik::chain::{Angles, Chain, LegPose, Pose};
use crate::kinematics::foot::Foot;
use crate::kinematics::pelvis::Side;
use crate::model::attributes::Attributes;
use crate::model::body::Body;
use crate::nrs::pose::grounded_ankle;

/// Which frames of a periodic cycle a leg supports the body in: from the frame of its ankle's
/// largest x (forward) to the frame of its smallest, cyclically.
pub fn support(x: &[f64]) -> Vec<bool> {
    let n = x.len();
    let arg = |better: fn(f64, f64) -> bool| {
        (0..n).fold(0, |b, i| if better(x[i], x[b]) { i } else { b })
    };
    let (front, back) = (arg(|a, b| a > b), arg(|a, b| a < b));
    (0..n)
        .map(|i| {
            let from_front = (i + n - front) % n;
            let to_back = (back + n - front) % n;
            from_front <= to_back
        })
        .collect()
}

/// The pitch (heel up +) at which a grounded foot's ankle is `d` ahead of its flat place:
/// bisection of the monotonic [`grounded_ankle`] on [−60°, 80°] (clamped there).
fn pitch_for(foot: &Foot, d: f64, theta6_max: f64) -> f64 {
    let (mut lo, mut hi) = (-60f64.to_radians(), 80f64.to_radians());
    let x = |p: f64| grounded_ankle(foot, p, theta6_max).0[0];
    if d <= x(lo) {
        return lo;
    }
    if d >= x(hi) {
        return hi;
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if x(mid) < d {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The swinging foot's pitch: square to the shank (its x axis), clamped above the floor.
fn swing_pitch(foot: &Foot, leg: &LegPose, ankle_world: [f64; 2]) -> f64 {
    let y = leg.shank.y_axis;
    foot.clear_pitch(y.x.atan2(y.y), ankle_world, 0.0, 0.0).0
}

/// One cycle of the chain posed, with each leg's support phases.
struct Cycle<'a> {
    angles: &'a [Angles],
    poses: Vec<Pose>,
    supports: [Vec<bool>; 2],
    dt: f64,
    speed: f64,
}

const SIDES: [Side; 2] = [Side::Right, Side::Left];

impl Cycle<'_> {
    fn len(&self) -> usize {
        self.angles.len()
    }

    /// Leg `s`'s ankle x in the world at unrolled frame k.
    fn world_x(&self, k: usize, s: usize) -> f64 {
        self.speed * k as f64 * self.dt + self.poses[k % self.len()].leg(SIDES[s]).ankle.x
    }

    /// For each unrolled frame and leg in support, where its foot lies flat: the world x of its
    /// ankle at the run's frame nearest under the pelvis (point 3); NaN out of support.
    fn flat_places(&self, total: usize) -> Vec<[f64; 2]> {
        let n = self.len();
        let mut flat = vec![[f64::NAN; 2]; total];
        for s in 0..2 {
            let mut k = 0;
            while k < total {
                if !self.supports[s][k % n] {
                    k += 1;
                    continue;
                }
                let start = k;
                while k < total && self.supports[s][k % n] {
                    k += 1;
                }
                let under = |i: usize| self.poses[i % n].leg(SIDES[s]).ankle.x.abs();
                let mid = (start..k)
                    .min_by(|&a, &b| under(a).total_cmp(&under(b)))
                    .expect("a run has frames");
                let x_flat = self.world_x(mid, s);
                for f in flat.iter_mut().take(k).skip(start) {
                    f[s] = x_flat;
                }
            }
        }
        flat
    }
}

/// A thigh's sagittal angle, knee forward + (klaw's arm rule, [`crate::figure::landmarks()`]).
fn thigh(l: &LegPose) -> f64 {
    (l.knee.x - l.hip.x).atan2(l.hip.y - l.knee.y)
}

/// The figure's frames for `cycles` repetitions of one periodic cycle of the chain's `angles`
/// (frame period `dt`), the pelvis moving forward at `speed` (m/s).
pub fn frames(
    (body, attrs): (&Body, &Attributes),
    angles: &[Angles],
    dt: f64,
    speed: f64,
    cycles: usize,
) -> Vec<Landmarks> {
    let chain = Chain::new(body);
    let poses: Vec<Pose> = angles.iter().map(|a| chain.pose(a)).collect();
    let support_of = |s: Side| support(&poses.iter().map(|p| p.leg(s).ankle.x).collect::<Vec<_>>());
    let cycle = Cycle {
        angles,
        supports: [support_of(Side::Right), support_of(Side::Left)],
        poses,
        dt,
        speed,
    };
    let n = cycle.len();
    let total = n * cycles;
    let flat = cycle.flat_places(total);
    // the steps: a new one at each support's first frame, numbered as klaw numbers a walk's
    // (the right foot's even, the left's odd), the frames before the first the other foot's
    let starts: Vec<usize> = (0..total)
        .filter(|&k| {
            (0..2).any(|s| cycle.supports[s][k % n] && !cycle.supports[s][(k + n - 1) % n])
        })
        .collect();
    let first_right = starts
        .first()
        .is_some_and(|&k| cycle.supports[0][k % n] && !cycle.supports[0][(k + n - 1) % n]);
    let shift = match (starts.first(), first_right) {
        (Some(0), true) => 0,
        (_, true) => 2,
        _ => 1,
    };
    // the thighs' largest forward angle, the arms' reference
    let reference = cycle
        .poses
        .iter()
        .flat_map(|p| [thigh(&p.right), thigh(&p.left)])
        .fold(1e-3, f64::max);
    let foot = Foot::new(body);
    (0..total)
        .map(|k| {
            let mut f = pose_frame(&cycle, k, flat[k], (attrs, &foot), reference);
            f.step = starts.partition_point(|&s| s <= k) + shift - 1;
            f
        })
        .collect()
}

/// Unrolled frame k of the cycle: the supporting feet planted at `flat`, the pelvis's height
/// from them (module doc).
fn pose_frame(
    cycle: &Cycle,
    k: usize,
    flat: [f64; 2],
    (attrs, foot): (&Attributes, &Foot),
    reference: f64,
) -> Landmarks {
    let n = cycle.len();
    let pose = &cycle.poses[k % n];
    let theta = &cycle.angles[k % n];
    let theta6_max = attrs.metatarsal_limit;
    // the supporting ankles' pitches, grounded heights and toe angles
    let grounded: [Option<(f64, f64, f64)>; 2] = [0, 1].map(|s| {
        (!flat[s].is_nan()).then(|| {
            let p = pitch_for(foot, cycle.world_x(k, s) - flat[s], theta6_max);
            let (a, t6) = grounded_ankle(foot, p, theta6_max);
            (p, a[1], t6)
        })
    });
    // each supporting ankle at its grounded height, and each swinging one at least its foot's
    // height l9 above the floor (lower, no pitch keeps both heel and toe above it)
    let y_pelvis = (0..2)
        .map(|s| grounded[s].map_or(foot.l9, |g| g.1) - pose.leg(SIDES[s]).ankle.y)
        .fold(f64::NEG_INFINITY, f64::max);
    let origin = DVec3::new(cycle.speed * k as f64 * cycle.dt, y_pelvis, 0.0);
    let leg = |s: usize| {
        let l = pose.leg(SIDES[s]);
        let ankle = origin + l.ankle;
        let (p, t6) = match grounded[s] {
            Some((p, _, t6)) => (p, t6),
            None => (swing_pitch(foot, l, [ankle.x, ankle.y]), 0.0),
        };
        let pts = foot.points([ankle.x, ankle.y], p, t6);
        let at = |q: [f64; 2]| [q[0], q[1], ankle.z];
        LegPoints {
            hip: (origin + l.hip).to_array(),
            knee: (origin + l.knee).to_array(),
            ankle: ankle.to_array(),
            heel: at(pts.heel),
            mtp: at(pts.meta),
            toe: at(pts.toe),
            knee_axis: l.thigh.z_axis.to_array(),
        }
    };
    let arm = |opposite: &LegPose| arm_swing(thigh(opposite), reference, attrs);
    Landmarks {
        time: k as f64 * cycle.dt,
        step: 0,
        pelvis: origin.to_array(),
        pelvis_tilt: theta[0],
        pelvis_list: theta[1],
        pelvis_rotation: theta[2],
        lumbar_extension: theta[0] - attrs.trunk_lean,
        lumbar_bending: theta[1],
        lumbar_rotation: -1.8 * theta[2],
        neck_rotation: 0.0,
        right: leg(0),
        left: leg(1),
        right_arm: arm(&pose.left),
        left_arm: arm(&pose.right),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn support_runs_from_the_most_forward_to_the_most_backward_sample() {
        // a cycle: forward at 2, backward at 6 of 10
        let x = [0.1, 0.3, 0.4, 0.2, 0.0, -0.2, -0.4, -0.3, -0.1, 0.0];
        let s = support(&x);
        assert_eq!(
            s,
            [
                false, false, true, true, true, true, true, false, false, false
            ]
        );
        // wrapping around the cycle's end
        let x = [-0.3, -0.1, 0.1, 0.3, 0.2, 0.0, -0.2, -0.4];
        let s = support(&x);
        assert_eq!(s, [false, false, false, true, true, true, true, true]);
    }

    /// The pitch for a place inverts the grounded foot's ankle: back on the heel rocker, flat,
    /// forward on the metatarsal joint.
    #[test]
    fn the_pitch_puts_the_grounded_ankle_at_its_place() {
        let body = Body::standard(1.8, 80.0).unwrap();
        let foot = Foot::new(&body);
        let lim = 35f64.to_radians();
        for d in [-0.02, -0.005, 0.0, 0.01, 0.05, 0.12] {
            let p = pitch_for(&foot, d, lim);
            let a = grounded_ankle(&foot, p, lim).0;
            assert!((a[0] - d).abs() < 1e-12, "{d}: {}", a[0]);
            if d == 0.0 {
                assert!(p.abs() < 1e-12, "flat: {p}");
            } else {
                assert_eq!(p < 0.0, d < 0.0, "{d}: {p}");
            }
        }
    }
}
