//! The whole figure around the dynamic model (KLAW 1989 §4.2, spec §7): the virtual stance leg
//! with its foot rules, the swing foot, the determinants of gait (pelvic rotation, list and
//! lateral displacement) and the upper body. Everything here is kinematic: it reads a simulated
//! step and places the figure in 3-D at one instant as [`Landmarks`].
//!
//! World frame (OpenSim's): x forward (the walking direction), y up, z to the figure's right,
//! right-handed; the origin on the ground under the first stance ankle's flat-foot position, the
//! walk's sagittal plane at z = 0. Metres and radians.

use crate::engine::walker::Step;
use crate::figure::error::FigureError;
use crate::kinematics::foot::{Foot, FootPoints};
use crate::kinematics::pelvis::Side;
use crate::model::attributes::Attributes;
use crate::numerics::trig::atan2;

/// One leg's joint centres and foot contact points, world frame (m).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct LegPoints {
    /// Hip joint centre.
    pub hip: [f64; 3],
    /// Knee joint centre.
    pub knee: [f64; 3],
    /// Ankle joint centre.
    pub ankle: [f64; 3],
    /// Back of the heel at sole level (the heel contact point).
    pub heel: [f64; 3],
    /// 1st metatarsal joint, at sole level when the foot is flat.
    pub mtp: [f64; 3],
    /// Toe tip.
    pub toe: [f64; 3],
    /// Unit axis of knee flexion, the normal of the plane of hip, knee and ankle, pointing to the
    /// figure's right (world +z when the leg is in a sagittal plane). Defined even with a straight
    /// knee.
    pub knee_axis: [f64; 3],
}

/// Arm angles of one side relative to the thorax, clinical signs (rad).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct ArmAngles {
    /// Upper arm forward +.
    pub shoulder_flexion: f64,
    /// Upper arm away from the body +.
    pub shoulder_abduction: f64,
    /// Elbow flexion +.
    pub elbow_flexion: f64,
}

/// The figure at one instant.
///
/// The legs are given as points (the dynamics and the foot rules place them); the pelvis, trunk
/// and arms as angles. The pelvis orientation in the world is
/// `R = R_y(rotation) · R_x(−list) · R_z(−tilt)` (rotation about the vertical first, then list
/// about the forward axis, then tilt about the lateral axis), so that each angle has its clinical
/// sign: tilt + anterior (the front of the pelvis down), list + with the right side up, rotation
/// \+ with the right side forward. The hip joints are `pelvis ± R · (0, 0, l0/2)` (right +).
/// The thorax relative to the pelvis is `R_y(lumbar_rotation) · R_x(lumbar_bending) ·
/// R_z(lumbar_extension)`, and the head relative to the thorax `R_y(neck_rotation)` (about the
/// thorax's long axis, at the neck base on top of the spine).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Landmarks {
    /// Time since the first heel strike (s).
    pub time: f64,
    /// Index of the step (heel strike to heel strike) the instant belongs to.
    pub step: usize,
    /// Pelvis centre C, midpoint of the hip joints: the dynamic model's hip (spec §7) moved so
    /// that the stance hip joint keeps the paper's half-sine list while the pelvis lists as
    /// people do (docs/realism.md, "The list's shape").
    pub pelvis: [f64; 3],
    /// Pelvic tilt, + anterior (rad).
    pub pelvis_tilt: f64,
    /// Pelvic list, + with the right side up (rad).
    pub pelvis_list: f64,
    /// Pelvic rotation, + with the right side forward (rad).
    pub pelvis_rotation: f64,
    /// Thorax relative to the pelvis (rad): extension + (trunk back), bending + with the top of
    /// the trunk towards the right, rotation + with the right shoulder forward.
    pub lumbar_extension: f64,
    /// Lumbar bending (rad), + with the top of the trunk towards the right.
    pub lumbar_bending: f64,
    /// Lumbar rotation (rad), + with the right shoulder forward.
    pub lumbar_rotation: f64,
    /// Neck rotation (rad): the head relative to the thorax about the thorax's long (vertical)
    /// axis, + with the face turned to the figure's left (positive about +y, the sense of
    /// `lumbar_rotation` and `pelvis_rotation`). The walk does not twist the neck: 0 in its
    /// frames.
    pub neck_rotation: f64,
    /// The right leg's points.
    pub right: LegPoints,
    /// The left leg's points.
    pub left: LegPoints,
    /// The right arm's angles.
    pub right_arm: ArmAngles,
    /// The left arm's angles.
    pub left_arm: ArmAngles,
}

/// Place a leg in 3-D: hip joint `hip` (world), in-plane angles θ3 and θ4 — given by the (sin,
/// cos) of θ3 and of θ3 + θ4 — in a plane through the forward axis tilted so that the ankle lies
/// `dz` to the inside of the hip (dz = hip z − ankle z), and the sagittal foot points (world x,
/// y) carried with the ankle.
fn place_leg(
    hip: [f64; 3],
    dz: f64,
    [thigh, shank]: [(f64, f64); 2],
    (l3, l4): (f64, f64),
    ankle2: [f64; 2],
    foot: &FootPoints,
) -> LegPoints {
    let drop = l3 * thigh.1 + l4 * shank.1;
    let sin_phi = -dz / drop;
    let cos_phi = (1.0 - sin_phi * sin_phi).max(0.0).sqrt();
    // `len` down the segment at the angle whose (sin, cos) is `(s, c)`
    let down = |len: f64, (s, c): (f64, f64), from: [f64; 3]| {
        let along = len * c;
        [
            from[0] - len * s,
            from[1] - along * cos_phi,
            from[2] + along * sin_phi,
        ]
    };
    let knee = down(l3, thigh, hip);
    let ankle = down(l4, shank, knee);
    let carry = |p: [f64; 2]| {
        [
            ankle[0] + p[0] - ankle2[0],
            ankle[1] + p[1] - ankle2[1],
            ankle[2],
        ]
    };
    LegPoints {
        hip,
        knee,
        ankle,
        heel: carry(foot.heel),
        mtp: carry(foot.meta),
        toe: carry(foot.toe),
        knee_axis: [0.0, sin_phi, cos_phi],
    }
}

/// An arm following the opposite thigh's sagittal angle `thigh` (knee forward +; spec §7):
/// shoulder flexion half the attribute `arm_swing` when the thigh is at `reference` (the
/// leading thigh's angle at heel strike, −θ3*; at least 1e-3 rad), abduction 5°, elbow 20° +
/// ½ max(0, shoulder flexion).
pub(crate) fn arm_swing(thigh: f64, reference: f64, attrs: &Attributes) -> ArmAngles {
    let flexion = 0.5 * attrs.arm_swing * thigh / reference.max(1e-3);
    ArmAngles {
        shoulder_flexion: flexion,
        shoulder_abduction: 5f64.to_radians(),
        elbow_flexion: 20f64.to_radians() + 0.5 * flexion.max(0.0),
    }
}

/// The figure at world time `t` within `step` (spec §7): the pelvis centre from the stance
/// dynamics moved sideways by the lateral displacement; tilt tilt0 + θ2 − θ2_ref; list and
/// rotation from the determinants; the stance leg from its foot rules, the swing (or hind) leg
/// from the swing dynamics (or the hind leg's completion); lumbar bending −list, thorax rotation
/// −1.8 × pelvic rotation relative to the pelvis; each arm follows the opposite thigh with the
/// arm-swing range, elbow 20° + ½ max(0, shoulder flexion), shoulder abduction 5°.
pub fn landmarks(step: &Step, t: f64, attrs: &Attributes) -> Result<Landmarks, FigureError> {
    let c = &step.constraints;
    let tau = (t - step.t_start).clamp(0.0, c.timing.t_step);
    let x0 = step.x_ankle;
    let now = step.at(tau);
    let (state, p) = (now.state, now.pelvis);
    let (l3, l4) = (step.stance_leg.l3, step.stance_leg.l4);
    let pose = |source| FigureError::Pose {
        step: step.index,
        source,
    };
    let c3 = now.pelvis_centre();
    let hip3 = |side: Side| {
        let o = now.hip_offset(side);
        [x0 + c3[0] + o[0], c3[1] + o[1], c3[2] + o[2]]
    };
    let stance = step.stance_pose_at(&now).map_err(pose)?;
    let (_, dz_stance) = now.hip_joint(step.side);
    let stance_leg = place_leg(
        hip3(step.side),
        dz_stance,
        stance.sin_cos,
        (l3, l4),
        [x0 + stance.ankle[0], stance.ankle[1]],
        &shifted(&stance.foot, x0),
    );
    let foot: Foot = step.stance_leg.foot;
    let sw = step.swing_pose_at(&now, &foot);
    let swing_leg = place_leg(
        hip3(step.side.other()),
        sw.dz,
        sw.sin_cos,
        (l3, l4),
        [x0 + sw.ankle[0], sw.ankle[1]],
        &shifted(&sw.foot, x0),
    );
    let (right, left) = match step.side {
        Side::Right => (stance_leg, swing_leg),
        Side::Left => (swing_leg, stance_leg),
    };
    let theta2 = state[2];
    let tilt = attrs.pelvis_tilt + theta2 - attrs.trunk_lean;
    let arm = |opposite: &LegPoints| arm_swing(thigh_angle(opposite), -c.theta3, attrs);
    Ok(Landmarks {
        time: t,
        step: step.index,
        pelvis: [x0 + c3[0], c3[1], c3[2]],
        pelvis_tilt: tilt,
        pelvis_list: p.list,
        pelvis_rotation: p.rotation,
        lumbar_extension: tilt - theta2,
        // the spine undoes the list (spec §7 "spine compensates the pelvis"; its "−list" bent
        // the trunk the other way, 2 × the list off the vertical: docs/realism.md)
        lumbar_bending: p.list,
        lumbar_rotation: -1.8 * p.rotation,
        neck_rotation: 0.0,
        right_arm: arm(&left),
        left_arm: arm(&right),
        right,
        left,
    })
}

/// A thigh's sagittal angle from the downward vertical, the knee forward +.
pub(crate) fn thigh_angle(leg: &LegPoints) -> f64 {
    atan2(leg.knee[0] - leg.hip[0], leg.hip[1] - leg.knee[1])
}

fn shifted(f: &FootPoints, dx: f64) -> FootPoints {
    let s = |p: [f64; 2]| [p[0] + dx, p[1]];
    FootPoints {
        heel: s(f.heel),
        meta: s(f.meta),
        toe: s(f.toe),
    }
}

/// The figure at `fps` frames per second from t = 0 to the walk's last heel strike (inclusive),
/// one step at a time (nothing is collected).
pub fn frames<'a>(
    walk: &'a crate::engine::walker::Walk,
    fps: f64,
) -> impl Iterator<Item = Result<Landmarks, FigureError>> + 'a {
    let n = (walk.duration() * fps + 1e-9).floor() as usize;
    let mut i = 0;
    (0..=n).filter_map(move |k| {
        let t = k as f64 / fps;
        while i + 1 < walk.steps.len() && t >= walk.steps[i + 1].t_start {
            i += 1;
        }
        walk.steps.get(i).map(|s| landmarks(s, t, &walk.attrs))
    })
}
