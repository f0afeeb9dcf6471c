//! The clinical joint angles of the exported skeleton (issue items 7 and 8; spec §7 "Clinical
//! angles"), read off the segment frames of [`crate::figure::skeleton`].
//!
//! The rotation of a joint is the child frame in the parent frame, `R = Pᵀ · C`, and each joint
//! angle set is its exact Euler decomposition
//!
//! `R = R_z(a) · R_x(b) · R_y(c)`
//!
//! (`figure::euler`, which says why glam's conversion is not used). The clinical angles
//! are those outputs with per-joint and per-side signs:
//! - flexion = `a` (hip and shoulder flexion, ankle and mtp dorsiflexion, elbow flexion) or `−a`
//!   (knee flexion: the shank turns backwards);
//! - adduction = `b` on the right and `−b` on the left (the distal segment towards the midline:
//!   hip adduction, knee varus, ankle inversion, shoulder adduction);
//! - rotation = `c` on the right and `−c` on the left (internal rotation).
//!
//! The pelvis angles are the YXZ decomposition of the pelvis frame, the lumbar angles that of the
//! thorax in the pelvis (the order of [`Landmarks`]), the neck rotation the first (vertical-axis)
//! angle of the YXZ decomposition of the head in the thorax (the head is turned about that axis
//! alone, so it is the whole rotation).
use glam::DMat3;

use crate::figure::Landmarks;
use crate::figure::error::Result;
use crate::figure::euler::{nearest_turn, yxz_angles, yxz_round_trip, zxy_from, zxy_round_trip};
use crate::figure::skeleton::{Frame, LegFrames, Side, Skeleton, Trunk, arm_angles, leg_frames};
use crate::model::body::Body;

/// The three rotations of one joint, clinical signs (rad); see the module doc for each joint's
/// meaning: flexion (knee flexion, dorsiflexion, …), adduction (towards the midline: adduction,
/// varus, inversion), rotation (internal +).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Joint3 {
    /// Rotation about the lateral axis: flexion + (the knee's flexion, the ankle's and mtp's
    /// dorsiflexion) (rad).
    pub flexion: f64,
    /// Rotation about the forward axis: towards the midline + (adduction, varus, inversion)
    /// (rad).
    pub adduction: f64,
    /// Rotation about the segment's long axis: internal + (rad).
    pub rotation: f64,
}

/// One leg's joints.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct LegAngles {
    /// The hip: thigh in pelvis.
    pub hip: Joint3,
    /// The knee: shank in thigh; one degree of freedom, so adduction and rotation are 0.
    pub knee: Joint3,
    /// flexion = dorsiflexion, adduction = inversion, rotation = adduction of the foot (toe-in).
    pub ankle: Joint3,
    /// flexion = dorsiflexion (toes up).
    pub mtp: Joint3,
}

/// One arm's joints.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct ArmJoints {
    /// adduction = −abduction of [`crate::figure::ArmAngles`].
    pub shoulder: Joint3,
    /// The elbow: flexion only.
    pub elbow: Joint3,
}

/// All clinical angles of one frame (rad; degrees only at the file edges).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Clinical {
    /// Time of the frame since the first heel strike (s).
    pub time: f64,
    /// Index of the step the frame falls in.
    pub step: usize,
    /// Pelvis centre, world frame (m).
    pub pelvis: [f64; 3],
    /// Anterior +.
    pub pelvis_tilt: f64,
    /// Right side up +.
    pub pelvis_list: f64,
    /// Right side forward +.
    pub pelvis_rotation: f64,
    /// Thorax relative to the pelvis: extension + (trunk back), bending + to the right, rotation +
    /// with the right shoulder forward.
    pub lumbar_extension: f64,
    /// Lumbar bending, + to the right.
    pub lumbar_bending: f64,
    /// Lumbar rotation, + with the right shoulder forward.
    pub lumbar_rotation: f64,
    /// The head relative to the thorax about the thorax's long axis, + with the face turned to
    /// the figure's left (the sense of the lumbar rotation).
    pub neck_rotation: f64,
    /// The right leg's joints.
    pub right: LegAngles,
    /// The left leg's joints.
    pub left: LegAngles,
    /// The right arm's joints.
    pub right_arm: ArmJoints,
    /// The left arm's joints.
    pub left_arm: ArmJoints,
}

impl Clinical {
    pub(crate) fn leg(&self, side: Side) -> &LegAngles {
        match side {
            Side::Right => &self.right,
            Side::Left => &self.left,
        }
    }

    pub(crate) fn arm(&self, side: Side) -> &ArmJoints {
        match side {
            Side::Right => &self.right_arm,
            Side::Left => &self.left_arm,
        }
    }
}

/// The shoulder and elbow of an arm placed `R_thorax · R_z(flexion) · R_x(∓abduction)`, forearm
/// `· R_z(elbow)` (as [`Skeleton::new`] places it): their angles are those it was built from
/// (where the decompositions return them, [`zxy_round_trip`]).
fn arm_joints([flexion, abduction, elbow]: [f64; 3], side: Side) -> ArmJoints {
    let s = side.sign();
    ArmJoints {
        shoulder: joint3(zxy_round_trip(flexion, -s * abduction, 0.0), s, 1.0),
        elbow: joint3(zxy_round_trip(elbow, 0.0, 0.0), s, 1.0),
    }
}

impl Skeleton {
    /// The clinical angles of these frames (the module doc gives the definitions).
    pub fn clinical(&self, time: f64, step: usize) -> Clinical {
        let arm = |side: Side| {
            let a = self.arm(side);
            let s = side.sign();
            ArmJoints {
                shoulder: joint(&self.thorax.axes, &a.upper_arm.axes, s, 1.0),
                elbow: joint(&a.upper_arm.axes, &a.forearm.axes, s, 1.0),
            }
        };
        let [neck_rotation, _, _] = yxz_angles(&self.neck);
        Clinical {
            neck_rotation,
            ..assemble(
                time,
                step,
                &self.pelvis,
                yxz_angles(&self.pelvis.axes),
                yxz_angles(&(self.pelvis.axes.transpose() * self.thorax.axes)),
                [&self.right, &self.left],
                [arm(Side::Right), arm(Side::Left)],
            )
        }
    }
}

/// The clinical angles of the joint from `parent` to `child` axes (inlined, as the helpers of
/// [`crate::figure::skeleton`]: it runs for every joint of every exported frame).
#[inline(always)]
fn joint(parent: &DMat3, child: &DMat3, side: f64, flexion_sign: f64) -> Joint3 {
    // (Pᵀ C)ᵢⱼ = Pᵢ · Cⱼ (columns): only the entries the decomposition reads
    joint3(
        zxy_from(|i, j| parent.col(i).dot(child.col(j))),
        side,
        flexion_sign,
    )
}

/// The clinical signs of the ZXY angles `[a, b, c]` of a joint.
fn joint3([a, b, c]: [f64; 3], side: f64, flexion_sign: f64) -> Joint3 {
    Joint3 {
        flexion: flexion_sign * a,
        adduction: side * b,
        rotation: side * c,
    }
}

/// The clinical angles of one frame: those of [`Skeleton::new`] then [`Skeleton::clinical`]
/// (the same errors, the same angles to round-off), without the frames the angles are read back
/// from: the pelvis, lumbar, neck and arm angles are the landmarks' own (the frames are built
/// from them, and `figure::euler`'s round trips return them), and no arm or head is placed (the
/// angles do not depend on `_body`).
pub fn clinical(lm: &Landmarks, _body: &Body) -> Result<Clinical> {
    let trunk = Trunk::new(lm)?;
    let right = leg_frames(&lm.right, Side::Right, trunk.time)?;
    let left = leg_frames(&lm.left, Side::Left, trunk.time)?;
    let right_arm = arm_joints(arm_angles(&lm.right_arm, Side::Right)?, Side::Right);
    let left_arm = arm_joints(arm_angles(&lm.left_arm, Side::Left)?, Side::Left);
    let [lr, lb, le] = trunk.lumbar;
    let [neck_rotation, _, _] = yxz_round_trip(trunk.neck, 0.0, 0.0);
    let mut pelvis = yxz_round_trip(trunk.rotation, -trunk.list, -trunk.tilt);
    // continuous with the landmarks' heading past ±180°, as the exporters write it
    pelvis[0] = nearest_turn(pelvis[0], lm.pelvis_rotation);
    Ok(Clinical {
        neck_rotation,
        ..assemble(
            lm.time,
            lm.step,
            &trunk.pelvis,
            pelvis,
            yxz_round_trip(lr, lb, le),
            [&right, &left],
            [right_arm, left_arm],
        )
    })
}

/// The clinical angles from the pelvis frame and its YXZ angles `[r, p, q]`, the lumbar YXZ
/// angles, the legs' frames and the arms' joints. (Inlined: the angles are written in place,
/// not copied into the caller's `Result`.)
#[inline(always)]
fn assemble(
    time: f64,
    step: usize,
    pelvis: &Frame,
    [r, p, q]: [f64; 3],
    [lr, lb, le]: [f64; 3],
    legs: [&LegFrames; 2],
    [right_arm, left_arm]: [ArmJoints; 2],
) -> Clinical {
    let leg = |l: &LegFrames, side: Side| {
        let s = side.sign();
        LegAngles {
            hip: joint(&pelvis.axes, &l.thigh.axes, s, 1.0),
            knee: joint(&l.thigh.axes, &l.shank.axes, s, -1.0),
            ankle: joint(&l.shank.axes, &l.foot.axes, s, 1.0),
            mtp: joint(&l.foot.axes, &l.toe.axes, s, 1.0),
        }
    };
    Clinical {
        time,
        step,
        pelvis: pelvis.origin.to_array(),
        pelvis_tilt: -q,
        pelvis_list: -p,
        pelvis_rotation: r,
        lumbar_extension: le,
        lumbar_bending: lb,
        lumbar_rotation: lr,
        neck_rotation: 0.0,
        right: leg(legs[0], Side::Right),
        left: leg(legs[1], Side::Left),
        right_arm,
        left_arm,
    }
}

/// A named clinical angle (rad) of a frame.
pub struct AngleColumn {
    /// Column name without unit suffix, e.g. `hip_flexion_r`.
    pub name: String,
    /// The angle's value in a frame (rad).
    pub get: Box<dyn Fn(&Clinical) -> f64 + Send + Sync>,
}

/// The clinical angle columns of the CSV exports, in order: pelvis tilt / list / rotation, lumbar
/// extension / bending / rotation, neck rotation, then per side (`_r`, then `_l`) hip flexion / adduction /
/// rotation, knee flexion, ankle dorsiflexion, mtp dorsiflexion, shoulder flexion / abduction,
/// elbow flexion. Signs as in [`Clinical`]; shoulder abduction is + away from the body.
pub fn angle_columns() -> Vec<AngleColumn> {
    fn col(name: &str, get: impl Fn(&Clinical) -> f64 + Send + Sync + 'static) -> AngleColumn {
        AngleColumn {
            name: name.to_string(),
            get: Box::new(get),
        }
    }
    let mut cols = vec![
        col("pelvis_tilt", |c| c.pelvis_tilt),
        col("pelvis_list", |c| c.pelvis_list),
        col("pelvis_rotation", |c| c.pelvis_rotation),
        col("lumbar_extension", |c| c.lumbar_extension),
        col("lumbar_bending", |c| c.lumbar_bending),
        col("lumbar_rotation", |c| c.lumbar_rotation),
        col("neck_rotation", |c| c.neck_rotation),
    ];
    for side in [Side::Right, Side::Left] {
        let s = side.suffix();
        cols.extend([
            col(&format!("hip_flexion_{s}"), move |c| {
                c.leg(side).hip.flexion
            }),
            col(&format!("hip_adduction_{s}"), move |c| {
                c.leg(side).hip.adduction
            }),
            col(&format!("hip_rotation_{s}"), move |c| {
                c.leg(side).hip.rotation
            }),
            col(&format!("knee_flexion_{s}"), move |c| {
                c.leg(side).knee.flexion
            }),
            col(&format!("ankle_dorsiflexion_{s}"), move |c| {
                c.leg(side).ankle.flexion
            }),
            col(&format!("mtp_dorsiflexion_{s}"), move |c| {
                c.leg(side).mtp.flexion
            }),
            col(&format!("shoulder_flexion_{s}"), move |c| {
                c.arm(side).shoulder.flexion
            }),
            col(&format!("shoulder_abduction_{s}"), move |c| {
                -c.arm(side).shoulder.adduction
            }),
            col(&format!("elbow_flexion_{s}"), move |c| {
                c.arm(side).elbow.flexion
            }),
        ]);
    }
    cols
}
