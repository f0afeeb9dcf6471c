//! Keeping an NRS⁻'s ankles within their range of motion [ours]: Ko & Badler (1993 §5.1) leave
//! the foot angles θ_foot to the animator; with both feet flat at HSM⁺ and the pelvis above the
//! ankles' midpoint, the hind ankle of a long step dorsiflexes beyond the normal 20° (AAOS 1965),
//! and a swing foot held flat in the air below a flexed knee does too (docs/nrs.md). The clinical
//! ankle dorsiflexion is measured on the posed figure ([`crate::figure::clinical`]).
use glam::DVec3;

use crate::figure::clinical::clinical;
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
/// foot about the ankle, and the knee bends towards the foot's heading, not its pitch. The
/// landing row (the last) is left to the step's end angles. Returns whether a row changed.
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
            let (pitch, _) = seg
                .foot
                .clear_pitch(row[4] + (d - max), [0.0, row[1]], row[5], 0.0);
            if pitch > row[4] {
                row[4] = pitch;
                changed = true;
            }
        }
    }
    changed
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
}
