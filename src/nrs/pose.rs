//! The figure of an NRS at one instant (Ko & Badler 1993 §5.4): the centre site and its
//! orientation place the hip joints, the feet's configurations place the ankles, and the legs
//! follow as two-link chains whose knees bend towards the foot's heading. Everything is in the
//! world frame of [`crate::figure`]; a heading ψ points along (cos ψ, 0, −sin ψ).
use glam::{DMat3, DVec3};

use crate::figure::{ArmAngles, Landmarks, LegPoints};
use crate::kinematics::foot::Foot;
use crate::model::body::Body;
use crate::nrs::specs::Side;

/// The floor direction (x, z) of heading ψ.
#[inline]
pub fn direction(psi: f64) -> [f64; 2] {
    [psi.cos(), -psi.sin()]
}

/// The floor direction (x, z) to the right of heading ψ.
#[inline]
pub fn right_of(psi: f64) -> [f64; 2] {
    [psi.sin(), psi.cos()]
}

/// The heading of the floor direction (x, z).
#[inline]
pub fn heading_of(v: [f64; 2]) -> f64 {
    (-v[1]).atan2(v[0])
}

/// The angle b − a wrapped into (−π, π]: the shortest turn from heading a to heading b.
#[inline]
pub fn turn_between(a: f64, b: f64) -> f64 {
    let d = (b - a).rem_euclid(std::f64::consts::TAU);
    if d > std::f64::consts::PI {
        d - std::f64::consts::TAU
    } else {
        d
    }
}

/// A foot on the floor: where its ankle stands when it is flat (a floor point), its heading and
/// its pitch (heel up +; below 0 it stands on its heel, above 0 on its metatarsal joint and then
/// on its toe tip).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Planted {
    /// The flat foot's ankle, floor point (x, z) (m).
    pub flat: [f64; 2],
    /// Heading (rad, + left).
    pub heading: f64,
    /// Pitch (rad, heel up +).
    pub pitch: f64,
}

/// A foot anywhere: its ankle (world), heading, pitch and toe dorsiflexion θ6.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FootPose {
    /// Ankle joint centre (m, world).
    pub ankle: [f64; 3],
    /// Heading (rad).
    pub heading: f64,
    /// Pitch (rad, heel up +).
    pub pitch: f64,
    /// Toe dorsiflexion θ6 (rad).
    pub theta6: f64,
}

/// The ankle of a foot on the floor at pitch p relative to its flat position, (along the foot,
/// up), and θ6: about the heel for p < 0 (the heel rocker), about the metatarsal joint and then
/// the toe tip for p > 0 ([`Foot::rolling_ankle`], metatarsal limit `theta6_max`).
pub fn grounded_ankle(foot: &Foot, p: f64, theta6_max: f64) -> ([f64; 2], f64) {
    if p >= 0.0 {
        foot.rolling_ankle(foot.h12, p, theta6_max)
    } else {
        let (s, c) = p.sin_cos();
        // heel = ankle + pitch((−l8, −l9), p), the heel fixed at (−l8, 0)
        let v = [-foot.l8 * c - foot.l9 * s, foot.l8 * s - foot.l9 * c];
        ([-foot.l8 - v[0], -v[1]], 0.0)
    }
}

impl Planted {
    /// The foot's pose.
    pub fn pose(&self, foot: &Foot, theta6_max: f64) -> FootPose {
        let (a, theta6) = grounded_ankle(foot, self.pitch, theta6_max);
        let d = direction(self.heading);
        FootPose {
            ankle: [self.flat[0] + a[0] * d[0], a[1], self.flat[1] + a[0] * d[1]],
            heading: self.heading,
            pitch: self.pitch,
            theta6,
        }
    }
}

/// The pelvis and upper body at one instant: the values [`Landmarks`] takes, the pelvis's world
/// heading included (its `pelvis_rotation`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Upper {
    /// Pelvis centre (m, world).
    pub centre: [f64; 3],
    /// Pelvis heading (rad): `pelvis_rotation`.
    pub heading: f64,
    /// Pelvic tilt (rad).
    pub tilt: f64,
    /// Pelvic list (rad).
    pub list: f64,
    /// Lumbar extension (rad).
    pub lumbar_extension: f64,
    /// Lumbar bending (rad).
    pub lumbar_bending: f64,
    /// Lumbar rotation (rad).
    pub lumbar_rotation: f64,
    /// Neck rotation (rad).
    pub neck_rotation: f64,
    /// The right and the left arm.
    pub arms: [ArmAngles; 2],
}

/// The hip joint of `side` for the pelvis of `upper` (half width `half_width`): centre ± R·(0,
/// 0, l0/2), R = R_y(heading)·R_x(−list)·R_z(−tilt) ([`Landmarks`]).
pub fn hip_joint(upper: &Upper, side: Side, half_width: f64) -> DVec3 {
    let r = DMat3::from_rotation_y(upper.heading)
        * DMat3::from_rotation_x(-upper.list)
        * DMat3::from_rotation_z(-upper.tilt);
    DVec3::from_array(upper.centre) + r * DVec3::new(0.0, 0.0, side.sign() * half_width)
}

/// The knee of a two-link leg (thigh l3, shank l4) from `hip` to `ankle`, bending towards the
/// floor direction `forward`: the knee lies in the plane of the hip–ankle line and `forward`,
/// in front of the line. Returns the knee and the knee axis (to the figure's right), or the
/// hip–ankle distance when it exceeds l3 + l4.
pub fn knee(
    hip: DVec3,
    ankle: DVec3,
    forward: [f64; 2],
    l3: f64,
    l4: f64,
) -> Result<(DVec3, DVec3), f64> {
    let along = ankle - hip;
    let d = along.length();
    if d > l3 + l4 + 1e-9 {
        return Err(d);
    }
    let u = along / d;
    let f = DVec3::new(forward[0], 0.0, forward[1]);
    let n = (f - f.dot(u) * u).normalize();
    let a = (l3 * l3 - l4 * l4 + d * d) / (2.0 * d);
    let b = (l3 * l3 - a * a).max(0.0).sqrt();
    Ok((hip + a * u + b * n, u.cross(n)))
}

/// One leg's points for its hip and foot: the foot's heel, metatarsal joint and toe tip in its
/// sagittal plane, the knee by [`knee`] bending towards the floor heading `bend` (the foot's
/// heading, or that of `knee_heading`, docs/nrs.md). Err: the hip–ankle distance beyond
/// the leg's length.
pub fn leg_points(
    hip: DVec3,
    foot_pose: &FootPose,
    bend: f64,
    foot: &Foot,
    body: &Body,
) -> Result<LegPoints, f64> {
    let ankle = DVec3::from_array(foot_pose.ankle);
    let d = direction(foot_pose.heading);
    let (k, axis) = knee(hip, ankle, direction(bend), body.l3, body.l4)?;
    let pts = foot.points([0.0, foot_pose.ankle[1]], foot_pose.pitch, foot_pose.theta6);
    let world = |p: [f64; 2]| [ankle.x + p[0] * d[0], p[1], ankle.z + p[0] * d[1]];
    Ok(LegPoints {
        hip: hip.to_array(),
        knee: k.to_array(),
        ankle: foot_pose.ankle,
        heel: world(pts.heel),
        mtp: world(pts.meta),
        toe: world(pts.toe),
        knee_axis: axis.to_array(),
    })
}

/// The clinical ankle inversion (rad, eversion −) of a leg from `hip` to the foot `pose` whose
/// knee bends towards the floor heading `bend`, computed from the geometry: the shank's lateral
/// axis is the knee axis, the unit u × f of the hip → ankle direction u and the bending
/// direction f ([`knee`]), whatever the knee's flexion; the foot's frame has x heel → mtp and y
/// towards the ankle ([`crate::figure::skeleton`]); and in the ZXY decomposition of the foot in
/// the shank, R = R_z(a) R_x(b) R_y(c), the foot's y in the shank's frame is (−sin a cos b,
/// cos a cos b, sin b), so sin b = y_foot · z_shank; inversion = ±b (right/left).
pub(crate) fn ankle_inversion(
    hip: DVec3,
    pose: &FootPose,
    foot: &Foot,
    bend: f64,
    side: Side,
) -> f64 {
    let u = (DVec3::from_array(pose.ankle) - hip).normalize();
    let b = direction(bend);
    let z = u.cross(DVec3::new(b[0], 0.0, b[1])).normalize();
    let d = direction(pose.heading);
    let pts = foot.points([0.0, 0.0], pose.pitch, 0.0);
    let world = |p: [f64; 2]| DVec3::new(p[0] * d[0], p[1], p[0] * d[1]);
    let (heel, mtp) = (world(pts.heel), world(pts.meta));
    let x = (mtp - heel).normalize();
    let up = -heel - (-heel).dot(x) * x;
    side.sign() * up.normalize().dot(z).clamp(-1.0, 1.0).asin()
}

/// [ours] The floor heading towards which the knee of the leg from `hip` to the foot `pose`
/// bends: the foot's heading (the engine's rule: the foot turns with the shank) unless the
/// ankle would then evert beyond `eversion_max`; then the heading turned by the least angle
/// (up to 60°) that keeps the eversion at that bound. The leg's lateral lean over a foot turned
/// out everts the ankle, tan b = (the hip's offset along the foot's lateral axis) / (its height
/// above the ankle), whatever the knee (docs/nrs.md); turning the knee's plane towards the leg
/// moves part of the hip's axial rotation into the foot's rotation on the shank. The search:
/// the side that raises the inversion, 5° steps to bracket the bound, then bisection.
pub(crate) fn knee_heading(
    hip: DVec3,
    pose: &FootPose,
    foot: &Foot,
    side: Side,
    eversion_max: f64,
) -> f64 {
    let psi = pose.heading;
    let inversion = |phi: f64| ankle_inversion(hip, pose, foot, psi + phi, side);
    if inversion(0.0) >= -eversion_max {
        return psi;
    }
    let sign = if inversion(1e-4) >= inversion(-1e-4) {
        1.0
    } else {
        -1.0
    };
    let step = 5f64.to_radians();
    let (mut lo, mut hi) = (0.0, None);
    for k in 1..=12 {
        let phi = k as f64 * step;
        if inversion(sign * phi) >= -eversion_max {
            hi = Some(phi);
            break;
        }
        lo = phi;
    }
    let Some(mut hi) = hi else {
        return psi + sign * lo;
    };
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if inversion(sign * mid) >= -eversion_max {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    psi + sign * hi
}

/// The figure: the upper body, the right and the left foot, at `time` in step `step`, each
/// knee bending towards the heading of `knee_heading` for `eversion_max`.
/// Err((side, distance)): a leg that cannot reach its foot.
pub fn figure(
    upper: &Upper,
    feet: [&FootPose; 2],
    (body, foot): (&Body, &Foot),
    eversion_max: f64,
    time: f64,
    step: usize,
) -> Result<Landmarks, (Side, f64)> {
    let half = body.l0 / 2.0;
    let leg = |side: Side, f: &FootPose| {
        let hip = hip_joint(upper, side, half);
        let bend = knee_heading(hip, f, foot, side, eversion_max);
        leg_points(hip, f, bend, foot, body).map_err(|d| (side, d))
    };
    Ok(Landmarks {
        time,
        step,
        pelvis: upper.centre,
        pelvis_tilt: upper.tilt,
        pelvis_list: upper.list,
        pelvis_rotation: upper.heading,
        lumbar_extension: upper.lumbar_extension,
        lumbar_bending: upper.lumbar_bending,
        lumbar_rotation: upper.lumbar_rotation,
        neck_rotation: upper.neck_rotation,
        right: leg(Side::Right, feet[0])?,
        left: leg(Side::Left, feet[1])?,
        right_arm: upper.arms[0],
        left_arm: upper.arms[1],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn body() -> Body {
        Body::standard(1.8, 80.0).unwrap()
    }

    #[test]
    fn headings_and_directions_agree_with_the_world_frame() {
        // heading 90° (a left turn) faces −z, the figure's left at heading 0
        let d = direction(std::f64::consts::FRAC_PI_2);
        assert!(d[0].abs() < 1e-15 && (d[1] + 1.0).abs() < 1e-15);
        assert_eq!(right_of(0.0), [0.0, 1.0]);
        for psi in [0.3, -2.0, 3.0] {
            assert!((heading_of(direction(psi)) - psi).abs() < 1e-12);
        }
        assert!((turn_between(3.0, -3.0) - (std::f64::consts::TAU - 6.0)).abs() < 1e-12);
    }

    /// A grounded foot's pivot stays where it was: the heel for p < 0, the metatarsal joint for
    /// small p > 0, and the ankle is l9 above the floor when flat.
    #[test]
    fn a_grounded_foot_pivots_without_sliding() {
        let b = body();
        let foot = Foot::new(&b);
        let lim = 0.5;
        let (a, _) = grounded_ankle(&foot, 0.0, lim);
        assert!(a[0].abs() < 1e-12 && (a[1] - foot.l9).abs() < 1e-12);
        for p in [-0.3, -0.1, 0.1, 0.4] {
            let (a, t6) = grounded_ankle(&foot, p, lim);
            let pts = foot.points(a, p, t6);
            if p < 0.0 {
                assert!((pts.heel[0] + foot.l8).abs() < 1e-12 && pts.heel[1].abs() < 1e-12);
            } else {
                assert!((pts.meta[0] - foot.h12).abs() < 1e-12 && pts.meta[1].abs() < 1e-12);
            }
            assert!(pts.lowest() > -1e-12);
        }
    }

    /// The two-link leg keeps its segment lengths, bends its knee forward, and its knee axis is a
    /// unit vector normal to the thigh and the shank.
    #[test]
    fn the_leg_keeps_its_lengths_and_bends_forward() {
        let b = body();
        let hip = DVec3::new(0.1, 0.9, 0.05);
        for (ankle, psi) in [
            (DVec3::new(0.3, 0.1, 0.1), 0.0),
            (DVec3::new(0.0, 0.12, 0.2), 1.2),
        ] {
            let f = direction(psi);
            let (k, axis) = knee(hip, ankle, f, b.l3, b.l4).unwrap();
            assert!(((k - hip).length() - b.l3).abs() < 1e-12);
            assert!(((ankle - k).length() - b.l4).abs() < 1e-12);
            let mid = (hip + ankle) / 2.0;
            assert!(
                (k - mid).dot(DVec3::new(f[0], 0.0, f[1])) > 0.0,
                "the knee points forward"
            );
            assert!((axis.length() - 1.0).abs() < 1e-12);
            assert!(axis.dot(k - hip).abs() < 1e-12 && axis.dot(ankle - k).abs() < 1e-12);
        }
        assert!(knee(hip, DVec3::new(0.0, -0.5, 0.0), [1.0, 0.0], b.l3, b.l4).is_err());
    }

    use crate::figure::clinical::clinical;

    fn leg(side: Side) -> (Body, Foot, DVec3) {
        let body = Body::standard(1.9, 95.0).unwrap();
        let hip = DVec3::new(0.0, 0.9, side.sign() * body.l0 / 2.0);
        (body, Foot::new(&body), hip)
    }

    /// The figure of one leg (the other standing under its hip) for the eversion bound `max`
    /// ([`knee_heading`]), and its clinical ankle inversion.
    fn clinical_inversion(side: Side, pose: &FootPose, max: f64) -> f64 {
        let (body, foot, _) = leg(side);
        let upper = Upper {
            centre: [0.0, 0.9, 0.0],
            ..Upper::default()
        };
        let other = FootPose {
            ankle: [0.0, body.l9, -side.sign() * body.l0 / 2.0],
            heading: 0.0,
            pitch: 0.0,
            theta6: 0.0,
        };
        let feet = match side {
            Side::Right => [pose, &other],
            Side::Left => [&other, pose],
        };
        let lm = figure(&upper, feet, (&body, &foot), max, 0.0, 0).unwrap();
        let c = clinical(&lm, &body).unwrap();
        match side {
            Side::Right => c.right.ankle.adduction,
            Side::Left => c.left.ankle.adduction,
        }
    }

    /// The geometric inversion is the clinical one (the skeleton's frames and their Euler
    /// decomposition) for feet turned in and out, pitched, ahead of and behind the hip, either
    /// leg; a flat foot under a leg in its vertical plane has none; and tan b = offset / height
    /// for a flat foot whose hip is offset along the foot's lateral axis.
    #[test]
    fn the_ankle_inversion_is_the_clinical_one() {
        for side in [Side::Right, Side::Left] {
            let (body, foot, hip) = leg(side);
            for (x, heading, pitch) in [
                (0.3, -0.5, 0.0),
                (-0.35, 0.5, 0.25),
                (0.2, 0.3, -0.2),
                (0.0, 0.0, 0.0),
            ] {
                let ankle = [x, body.l9 + 0.05, hip.z + 0.03];
                let pose = FootPose {
                    ankle,
                    heading,
                    pitch,
                    theta6: 0.0,
                };
                let b = ankle_inversion(hip, &pose, &foot, heading, side);
                // no bound: the knee bends towards the foot's heading
                let c = clinical_inversion(side, &pose, f64::INFINITY);
                assert!((b - c).abs() < 1e-9, "{side:?} {x} {heading}: {b} vs {c}");
            }
            // the hip straight above the foot's sagittal plane, offset e along its lateral axis
            let ankle = [0.0, body.l9, hip.z];
            let pose = FootPose {
                ankle,
                heading: 0.4,
                pitch: 0.0,
                theta6: 0.0,
            };
            let r = crate::nrs::pose::right_of(0.4);
            let h = hip.y - body.l9;
            for e in [0.0, 0.1, -0.15] {
                let o = DVec3::new(ankle[0] + e * r[0], hip.y, ankle[2] + e * r[1]);
                let b = ankle_inversion(o, &pose, &foot, 0.4, side);
                // the hip out to the foot's right leans the shank right: right foot everted
                let expected = -side.sign() * (e / h).atan();
                assert!(
                    (b - expected).abs() < 1e-9,
                    "{side:?} {e}: {b} vs {expected}"
                );
            }
        }
    }

    /// Within the bound the knee bends towards the foot's heading; beyond it, the heading
    /// found puts the clinical eversion on the bound, and half that turn would not.
    #[test]
    fn the_knee_turns_as_little_as_keeps_the_eversion() {
        let max = 14f64.to_radians();
        for side in [Side::Right, Side::Left] {
            let (body, foot, hip) = leg(side);
            // a long step's landing foot turned out 30°: the hip behind it leans over it
            let out = -side.sign() * 30f64.to_radians();
            let pose = FootPose {
                ankle: [0.42, body.l9 + 0.04, hip.z],
                heading: out,
                pitch: 0.0,
                theta6: 0.0,
            };
            let free = ankle_inversion(hip, &pose, &foot, out, side);
            assert!(free < -max, "{side:?}: {}°", free.to_degrees());
            let bend = knee_heading(hip, &pose, &foot, side, max);
            let b = ankle_inversion(hip, &pose, &foot, bend, side);
            assert!((b + max).abs() < 1e-9, "{side:?}: {}°", b.to_degrees());
            let half = ankle_inversion(hip, &pose, &foot, out + 0.5 * (bend - out), side);
            assert!(half < -max);
            // the posed figure's clinical eversion is on the bound
            let c = clinical_inversion(side, &pose, max);
            assert!((c + max).abs() < 1e-9, "{side:?}: {}°", c.to_degrees());
            // the knee turns back towards the pelvis's heading (0), less than the foot's out-turn
            assert!(bend.abs() < out.abs() && bend * out > 0.0, "{bend}");
            // straight ahead: no turn
            let ahead = FootPose {
                heading: 0.0,
                ..pose
            };
            assert_eq!(knee_heading(hip, &ahead, &foot, side, max), 0.0);
        }
    }
}
