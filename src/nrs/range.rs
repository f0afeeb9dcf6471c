//! Keeping an NRS⁻'s ankles within their range of motion [ours]: Ko & Badler (1993 §5.1) leave
//! the foot angles θ_foot to the animator; with both feet flat at HSM⁺ and the pelvis above the
//! ankles' midpoint, the hind ankle of a long step dorsiflexes beyond the normal 20° (AAOS 1965),
//! and a swing foot held flat in the air below a flexed knee does too (docs/nrs.md). The clinical
//! ankle dorsiflexion is measured on the posed figure ([`crate::figure::clinical`]). (A leg
//! leaning sideways over a turned foot everts the ankle; its knee then bends towards a heading
//! turned from the foot's: [`crate::nrs::pose::knee_heading`].)
use glam::DVec3;

use crate::figure::clinical::clinical;
use crate::kinematics::foot::Foot;
use crate::kinematics::leg::reach;
use crate::model::body::Body;
use crate::nrs::pose::{direction, knee};
use crate::nrs::segment::Segment;
use crate::nrs::specs::Side;
use crate::nrs::state::WalkerState;

/// The ankle dorsiflexion (rad) of `side` in `seg` at normalized time t; `None` where the pose
/// or its clinical angles are not defined.
pub(crate) fn dorsiflexion(seg: &Segment, t: f64, side: Side) -> Option<f64> {
    let lm = seg.pose(t).ok()?;
    let c = clinical(&lm, &seg.body).ok()?;
    Some(match side {
        Side::Right => c.right.ankle.flexion,
        Side::Left => c.left.ankle.flexion,
    })
}

/// The largest ankle dorsiflexion of `side` in `seg` at the normalized times `ts` (rad).
pub(crate) fn largest_dorsiflexion(
    seg: &Segment,
    side: Side,
    ts: impl Iterator<Item = f64>,
) -> f64 {
    ts.filter_map(|t| dorsiflexion(seg, t, side))
        .fold(f64::NEG_INFINITY, f64::max)
}

/// The airborne swing foot plantarflexes where its ankle would dorsiflex beyond `max`: each
/// airborne row of `swing` (ankle, heading, pitch, θ6) whose dorsiflexion in `seg` exceeds
/// `max` gets its pitch raised (heel up) by the excess, as far as the floor lets the toe go
/// (`Foot::clear_pitch`). The ankle's path, and so the legs, are unchanged: the pitch turns the
/// foot about the ankle, and the knee bends towards the foot's heading, not its pitch. Where the
/// toe tip has reached the floor (a backward step's foot landing toe first), the toes bend up
/// ([`toes_for`]) so that the foot can still plantarflex. The landing row (the last) is left to
/// the step's end angles. Returns whether a row changed.
pub(crate) fn plantarflex_in_air(
    seg: &Segment,
    swing: &mut [[f64; 6]],
    toe_off: usize,
    max: f64,
) -> bool {
    let n = swing.len() - 1;
    let side = seg.stance.other();
    let mut changed = false;
    for (i, row) in swing.iter_mut().enumerate().take(n).skip(toe_off + 1) {
        let Some(d) = dorsiflexion(seg, i as f64 / n as f64, side) else {
            continue;
        };
        if d > max {
            let want = row[4] + (d - max);
            let theta6 = toes_for(&seg.foot, want, row[1], row[5], seg.theta6_max);
            let (pitch, _) = seg.foot.clear_pitch(want, [0.0, row[1]], theta6, 0.0);
            if pitch > row[4] {
                row[4] = pitch;
                row[5] = theta6;
                changed = true;
            }
        }
    }
    changed
}

/// The toe angle θ6 (rad) at which a foot of pitch `pitch` with its ankle at height `ankle_y`
/// keeps its toe tip on or above the floor: `theta6` unless the tip would go below; then the
/// toe turned up to lie on the floor, θ6 = p − asin(m / l13) for the metatarsal joint at height
/// m = y − (h12 sin p + l9 cos p) (the tip at m − l13 sin(p − θ6)), at most `theta6_max`. The
/// pitch p is `pitch` or, where that would put the metatarsal joint itself below the floor
/// (no toe angle helps there), the pitch at which it touches, h12 sin p + l9 cos p =
/// r sin(p + α) = y with r = |(h12, l9)|, α = atan2(l9, h12).
pub(crate) fn toes_for(foot: &Foot, pitch: f64, ankle_y: f64, theta6: f64, theta6_max: f64) -> f64 {
    let r = foot.h12.hypot(foot.l9);
    let p = if ankle_y < r {
        pitch.min((ankle_y / r).asin() - foot.l9.atan2(foot.h12))
    } else {
        pitch
    };
    let (s, c) = p.sin_cos();
    let m = (ankle_y - (foot.h12 * s + foot.l9 * c)).max(0.0);
    let needed = p - (m / foot.l13).min(1.0).asin();
    theta6.max(needed.min(theta6_max))
}

/// The stance ankle's dorsiflexion (rad) in the leg's plane for the hip `hip` and the foot of
/// heading `heading` and pitch `pitch` with its ankle at `ankle`: 90° less the angle between
/// the shank (ankle to knee, [`knee`]) and the foot's axis heel → toe.
fn sagittal_dorsiflexion(
    body: &Body,
    hip: DVec3,
    ankle: [f64; 3],
    heading: f64,
    pitch: f64,
) -> Option<f64> {
    let a = DVec3::from_array(ankle);
    let d = direction(heading);
    let (k, _) = knee(hip, a, d, body.l3, body.l4).ok()?;
    let (sp, cp) = pitch.sin_cos();
    let axis = DVec3::new(cp * d[0], -sp, cp * d[1]);
    Some(std::f64::consts::FRAC_PI_2 - (k - a).angle_between(axis))
}

/// The centre height at a row (its hip `o` at centre height 0): `y` unless the stance ankle
/// would there dorsiflex beyond `ankle_dorsiflexion_max`; then the lowest height up to the
/// standing knee's reach at which it does not (bisection), or that reach. And the excess (rad)
/// that remains at that height (0 if none).
pub(crate) fn raised_height(
    state: &WalkerState,
    o: DVec3,
    ankle: [f64; 3],
    heading: f64,
    pitch: f64,
    y: f64,
) -> (f64, f64) {
    let body = &state.body;
    let max = state.params.ankle_dorsiflexion_max;
    let horiz2 = (o.x - ankle[0]).powi(2) + (o.z - ankle[2]).powi(2);
    let r = reach(body.l3, body.l4, state.params.stand_knee.cos());
    if horiz2 >= r * r {
        return (y, 0.0);
    }
    let top = ankle[1] - o.y + (r * r - horiz2).sqrt();
    let dorsi = |h: f64| {
        let hip = o + DVec3::new(0.0, h, 0.0);
        sagittal_dorsiflexion(body, hip, ankle, heading, pitch).unwrap_or(f64::NEG_INFINITY)
    };
    // above the straight leg's reach the centre is lowered to it later (`centre_path`)
    let l = body.l1 - 1e-7;
    let ym = y.min(ankle[1] - o.y + (l * l - horiz2).max(0.0).sqrt());
    if dorsi(ym) <= max {
        return (y, 0.0);
    }
    if top <= ym {
        return (y, dorsi(ym) - max);
    }
    if dorsi(top) > max {
        return (top, dorsi(top) - max);
    }
    let (mut lo, mut hi) = (y, top);
    for _ in 0..50 {
        let mid = 0.5 * (lo + hi);
        if dorsi(mid) > max { lo = mid } else { hi = mid }
    }
    (hi, 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A straight leg (hip l1 from the ankle) leaning forward by θ over a flat foot dorsiflexes
    /// its ankle by θ; a foot pitched heel up by p takes p off.
    #[test]
    fn the_sagittal_dorsiflexion_of_a_straight_leg_is_its_lean() {
        let body = Body::standard(1.8, 80.0).unwrap();
        let ankle = [0.0, body.l9, 0.0];
        for theta in [0.0f64, 0.1, 0.3] {
            let l = body.l1 * (1.0 - 1e-12);
            let hip = DVec3::new(l * theta.sin(), body.l9 + l * theta.cos(), 0.0);
            for p in [0.0, 0.2] {
                let d = sagittal_dorsiflexion(&body, hip, ankle, 0.0, p).unwrap();
                assert!((d - (theta - p)).abs() < 1e-5, "{theta} {p}: {d}");
            }
        }
    }

    fn leg(side: Side) -> (Body, Foot, DVec3) {
        let body = Body::standard(1.9, 95.0).unwrap();
        let hip = DVec3::new(0.0, 0.9, side.sign() * body.l0 / 2.0);
        (body, Foot::new(&body), hip)
    }

    /// The toes turned up by `toes_for` keep the toe tip on or above the floor at the pitch the
    /// floor then allows (`clear_pitch`): on the floor where it would have gone below, unless
    /// the metatarsal joint or the limit stops the foot first; a toe that clears the floor is
    /// left alone.
    #[test]
    fn the_toes_bend_up_onto_the_floor() {
        let (_, foot, _) = leg(Side::Right);
        let lim = 35f64.to_radians();
        let mut raised = 0;
        for (y, p) in [
            (0.09, 0.5),
            (0.1, 0.3),
            (0.12, 0.45),
            (0.2, 0.3),
            (0.11, 0.2),
        ] {
            let t6 = toes_for(&foot, p, y, 0.05, lim);
            let (q, pts) = foot.clear_pitch(p, [0.0, y], t6, 0.0);
            assert!(
                pts.toe[1] >= -1e-12 && pts.meta[1] >= -1e-12,
                "{y} {p}: {pts:?}"
            );
            if foot.points([0.0, y], p, 0.05).toe[1] >= 0.0 {
                assert_eq!(t6, 0.05);
            } else if q == p && t6 < lim {
                assert!(pts.toe[1].abs() < 1e-12, "{y} {p}: {pts:?}");
                raised += 1;
            } else {
                // stopped by the metatarsal joint on the floor or by the limit
                assert!(pts.meta[1].abs() < 1e-9 || t6 == lim, "{y} {p}: {pts:?}");
            }
        }
        assert!(raised > 0);
    }
}
