//! Keeping an NRS⁻'s ankles within their range of motion [ours]: Ko & Badler (1993 §5.1) leave
//! the foot angles θ_foot to the animator; with both feet flat at HSM⁺ and the pelvis above the
//! ankles' midpoint, the hind ankle of a long step dorsiflexes beyond the normal 20° (AAOS 1965),
//! and a swing foot held flat in the air below a flexed knee does too (docs/nrs.md). The clinical
//! ankle dorsiflexion is measured on the posed figure ([`crate::figure::clinical`]).
use crate::figure::clinical::clinical;
use crate::nrs::segment::Segment;
use crate::nrs::specs::Side;

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
