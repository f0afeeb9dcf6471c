//! The exported skeleton (issue items 7 and 8; spec §7 "Clinical angles" and "Upper body"): the
//! world frame of every segment of the figure and the clinical joint angles, read off a
//! [`Landmarks`] and the [`Body`].
//!
//! Every segment frame is, at the anatomical zero pose (legs vertical, soles flat, arms hanging),
//! parallel to the world frame of [`crate::figure`]: x forward, y up (along the segment, distal to
//! proximal), z to the figure's right. The rotation of a joint is the child frame in the parent
//! frame, `R = Pᵀ · C`, and each joint angle set is its exact Euler decomposition
//!
//! `R = R_z(a) · R_x(b) · R_y(c)`
//!
//! (about the lateral axis first, then the forward axis, then the long axis: gait2392's hip order,
//! and the BVH channel order `Xrotation Zrotation Yrotation` once the BVH axes are mapped, see
//! `docs/export.md`). The clinical angles are those outputs with per-joint and per-side signs:
//! - flexion = `a` (hip and shoulder flexion, ankle and mtp dorsiflexion, elbow flexion) or `−a`
//!   (knee flexion: the shank turns backwards);
//! - adduction = `b` on the right and `−b` on the left (the distal segment towards the midline:
//!   hip adduction, knee varus, ankle inversion, shoulder adduction);
//! - rotation = `c` on the right and `−c` on the left (internal rotation).
//!
//! Segment frames from the points: the thigh's y axis runs knee → hip and its z axis is the knee
//! axis; the shank's y runs ankle → knee, z the knee axis; the foot's x runs heel → mtp (the
//! horizontal sole line at rest) and its y points to the ankle, so the ankle sits l9 above the
//! sole, the heel l8 behind and the mtp √(l12² − l9²) ahead of it; the toe's x runs mtp → toe
//! tip, its z is the foot's lateral axis. The pelvis and thorax frames are the angles of
//! [`Landmarks`] as its doc defines them; the arms are placed by forward kinematics from the
//! thorax: shoulders at (0, spine, ±shoulder_width/2) in the thorax frame (its origin is the
//! pelvis centre), upper arm `R_thorax · R_z(flexion) · R_x(∓abduction)` (right −, left +),
//! forearm and hand `R_upper · R_z(elbow flexion)`.
//!
//! [`clinical`] runs for every exported frame: its small helpers (the checked points, unit
//! vectors, the leg frames, the joint decompositions, the trunk and arm checks) are
//! `#[inline(always)]`. Out of line each returned its value inside a `Result` through memory and
//! passed its error closure's captures by reference, ≈ 40 instructions a call on top of the
//! arithmetic: inlined, the happy path is the arithmetic, and the error names are still built
//! only on error (5.1 → 4.5 M instructions for the default walk's 556 frames, landmarks
//! included).
use glam::{DMat3, DVec3};

use crate::error::{Error, Result};
use crate::figure::{ArmAngles, Landmarks, LegPoints};
use crate::model::body::Body;
use crate::numerics::trig::{atan2, sin_cos};

/// Largest disagreement (m) between the landmarks and the rigid segments of the body table that
/// the BVH export accepts: its offsets are the body's lengths, so beyond this the file could not
/// reproduce the landmarks.
pub const LENGTH_TOLERANCE: f64 = 1e-3;

/// `R_z(a) · R_x(b) · R_y(c)`.
pub fn zxy_matrix(a: f64, b: f64, c: f64) -> DMat3 {
    DMat3::from_rotation_z(a) * DMat3::from_rotation_x(b) * DMat3::from_rotation_y(c)
}

/// The angles `[a, b, c]` with `m = R_z(a) · R_x(b) · R_y(c)`, b in [−90°, 90°].
///
/// With `m = R_z R_x R_y`: m₂₁ = sin b, (m₀₁, m₁₁) = cos b (−sin a, cos a),
/// (m₂₀, m₂₂) = cos b (−sin c, cos c).
pub fn zxy_angles(m: &DMat3) -> [f64; 3] {
    zxy_from(|i, j| m.col(j)[i])
}

/// [`zxy_angles`] of the matrix whose entry (i, j) is `r(i, j)` (only five are read).
#[inline(always)]
fn zxy_from(r: impl Fn(usize, usize) -> f64) -> [f64; 3] {
    let b = r(2, 1).clamp(-1.0, 1.0).asin();
    let a = atan2(-r(0, 1), r(1, 1));
    let c = atan2(-r(2, 0), r(2, 2));
    [a, b, c]
}

/// Largest |angle| (rad) of the middle rotation, and of the outer ones, for which
/// [`zxy_angles`]`(`[`zxy_matrix`]`(a, b, c))` and its YXZ counterpart return (a, b, c) to
/// round-off: well inside b ∈ (−90°, 90°) (the decomposition loses accuracy near gimbal lock)
/// and a, c ∈ (−180°, 180°).
const ROUND_TRIP_MIDDLE: f64 = 1.5;
const ROUND_TRIP_OUTER: f64 = 3.0;

fn round_trips(a: f64, b: f64, c: f64) -> bool {
    b.abs() <= ROUND_TRIP_MIDDLE && a.abs() <= ROUND_TRIP_OUTER && c.abs() <= ROUND_TRIP_OUTER
}

/// [`zxy_angles`]`(&`[`zxy_matrix`]`(a, b, c))` without the matrix: (a, b, c) itself where
/// the decomposition returns it.
fn zxy_round_trip(a: f64, b: f64, c: f64) -> [f64; 3] {
    if round_trips(a, b, c) {
        [a, b, c]
    } else {
        zxy_angles(&zxy_matrix(a, b, c))
    }
}

/// [`yxz_angles`]`(&`[`yxz_matrix`]`(r, p, q))` without the matrix, as [`zxy_round_trip`].
fn yxz_round_trip(r: f64, p: f64, q: f64) -> [f64; 3] {
    if round_trips(r, p, q) {
        [r, p, q]
    } else {
        yxz_angles(&yxz_matrix(r, p, q))
    }
}

/// `R_y(r) · R_x(p) · R_z(q)`: the order of the pelvis and lumbar angles of [`Landmarks`].
/// Multiplied out (rows of the matrix, sₐ = sin a, cₐ = cos a):
/// (c_r c_q + s_r s_p s_q, s_r s_p c_q − c_r s_q, s_r c_p),
/// (c_p s_q, c_p c_q, −s_p),
/// (c_r s_p s_q − s_r c_q, s_r s_q + c_r s_p c_q, c_r c_p),
/// with [`sin_cos`] instead of libm's for each rotation and two matrix products (this is the
/// pelvis frame of every exported frame).
pub fn yxz_matrix(r: f64, p: f64, q: f64) -> DMat3 {
    let (sr, cr) = sin_cos(r);
    let (sp, cp) = sin_cos(p);
    let (sq, cq) = sin_cos(q);
    let (spsq, spcq) = (sp * sq, sp * cq);
    DMat3::from_cols(
        DVec3::new(cr * cq + sr * spsq, cp * sq, cr * spsq - sr * cq),
        DVec3::new(sr * spcq - cr * sq, cp * cq, sr * sq + cr * spcq),
        DVec3::new(sr * cp, -sp, cr * cp),
    )
}

/// The angles `[r, p, q]` with `m = R_y(r) · R_x(p) · R_z(q)`, p in [−90°, 90°].
///
/// With `m = R_y R_x R_z`: m₁₂ = −sin p, (m₀₂, m₂₂) = cos p (sin r, cos r),
/// (m₁₀, m₁₁) = cos p (sin q, cos q).
pub fn yxz_angles(m: &DMat3) -> [f64; 3] {
    let e = |i: usize, j: usize| m.col(j)[i];
    let p = (-e(1, 2)).clamp(-1.0, 1.0).asin();
    let r = atan2(e(0, 2), e(2, 2));
    let q = atan2(e(1, 0), e(1, 1));
    [r, p, q]
}

/// A segment's pose: its origin (a joint centre) and its axes (the columns), world frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    pub origin: DVec3,
    pub axes: DMat3,
}

impl Frame {
    /// The world position of a point given in this frame.
    pub fn point(&self, local: DVec3) -> DVec3 {
        self.origin + self.axes * local
    }
}

pub use crate::kinematics::pelvis::Side;

/// The frames of one leg: thigh (origin at the hip), shank (knee), foot (ankle), toe (mtp).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LegFrames {
    pub thigh: Frame,
    pub shank: Frame,
    pub foot: Frame,
    pub toe: Frame,
}

/// The frames of one arm: upper arm (origin at the shoulder), forearm (elbow), hand (wrist).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArmFrames {
    pub upper_arm: Frame,
    pub forearm: Frame,
    pub hand: Frame,
}

/// Every segment of the figure at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Skeleton {
    /// Origin at the pelvis centre (midpoint of the hip joints).
    pub pelvis: Frame,
    /// Origin at the pelvis centre too: the lumbar rotation is about that point.
    pub thorax: Frame,
    pub right: LegFrames,
    pub left: LegFrames,
    pub right_arm: ArmFrames,
    pub left_arm: ArmFrames,
}

/// The three rotations of one joint, clinical signs (rad); see the module doc for each joint's
/// meaning: flexion (knee flexion, dorsiflexion, …), adduction (towards the midline: adduction,
/// varus, inversion), rotation (internal +).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Joint3 {
    pub flexion: f64,
    pub adduction: f64,
    pub rotation: f64,
}

/// One leg's joints.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct LegAngles {
    pub hip: Joint3,
    pub knee: Joint3,
    /// flexion = dorsiflexion, adduction = inversion, rotation = adduction of the foot (toe-in).
    pub ankle: Joint3,
    /// flexion = dorsiflexion (toes up).
    pub mtp: Joint3,
}

/// One arm's joints.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct ArmJoints {
    /// adduction = −abduction of [`ArmAngles`].
    pub shoulder: Joint3,
    pub elbow: Joint3,
}

/// All clinical angles of one frame (rad; degrees only at the file edges).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Clinical {
    pub time: f64,
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
    pub lumbar_bending: f64,
    pub lumbar_rotation: f64,
    pub right: LegAngles,
    pub left: LegAngles,
    pub right_arm: ArmJoints,
    pub left_arm: ArmJoints,
}

impl Clinical {
    pub fn leg(&self, side: Side) -> &LegAngles {
        match side {
            Side::Right => &self.right,
            Side::Left => &self.left,
        }
    }

    pub fn arm(&self, side: Side) -> &ArmJoints {
        match side {
            Side::Right => &self.right_arm,
            Side::Left => &self.left_arm,
        }
    }
}

/// Whether `x` is finite: 0 · x is ±0 for a finite x and NaN for ±∞ and NaN. (One multiply and
/// one compare; `f64::is_finite` compiles here to integer masking, ≈ 4 instructions a number,
/// and these checks run for every number of every frame.)
#[inline(always)]
fn is_finite(x: f64) -> bool {
    x * 0.0 == 0.0
}

/// [`is_finite`] of the three coordinates at once.
#[inline(always)]
fn is_finite3(v: DVec3) -> bool {
    (v * 0.0).element_sum() == 0.0
}

#[inline(always)]
fn finite(name: &str, value: f64) -> Result<f64> {
    if is_finite(value) {
        Ok(value)
    } else {
        Err(Error::NotFinite {
            name: name.to_string(),
            value,
        })
    }
}

/// `p` as a vector, or [`Error::NotFinite`] naming `name().axis` (the name is only built on
/// error: this runs several times per frame, so the vector's own test comes first).
#[inline(always)]
fn point(name: impl FnOnce() -> String, p: [f64; 3]) -> Result<DVec3> {
    let v = DVec3::from_array(p);
    if is_finite3(v) {
        return Ok(v);
    }
    let (axis, value) = ["x", "y", "z"]
        .into_iter()
        .zip(p)
        .find(|(_, v)| !v.is_finite())
        .expect("a coordinate is not finite");
    Err(Error::NotFinite {
        name: format!("{}.{axis}", name()),
        value,
    })
}

/// [`finite`] with the name built only on error.
#[inline(always)]
fn finite_named(name: impl FnOnce() -> String, value: f64) -> Result<f64> {
    if is_finite(value) {
        Ok(value)
    } else {
        finite(&name(), value)
    }
}

fn geometry(time: f64, what: String) -> Error {
    Error::Geometry {
        what: format!("frame at t = {time} s: {what}"),
    }
}

/// `v / |v|`, or an error naming `what()` when v is (nearly) zero.
#[inline(always)]
fn unit(v: DVec3, time: f64, what: impl Fn() -> String) -> Result<DVec3> {
    let n = v.length();
    if n > 1e-9 {
        Ok(v / n)
    } else {
        Err(geometry(time, format!("{} has zero length", what())))
    }
}

/// The component of `hint` perpendicular to the unit vector `axis`, normalized.
#[inline(always)]
fn perpendicular(hint: DVec3, axis: DVec3, time: f64, what: impl Fn() -> String) -> Result<DVec3> {
    let hint = unit(hint, time, &what)?;
    let p = hint - hint.dot(axis) * axis;
    let n = p.length();
    if n < 1e-6 {
        return Err(geometry(
            time,
            format!("{} is parallel to the segment", what()),
        ));
    }
    // p.normalize(), without measuring p again
    Ok(p * n.recip())
}

/// The thigh, shank, foot and toe frames of one leg from its points (the module doc gives the
/// axes). Inlined: the frames are built in the caller's frame, not copied out of a `Result`.
#[inline(always)]
fn leg_frames(leg: &LegPoints, side: Side, time: f64) -> Result<LegFrames> {
    let s = side.suffix();
    let hip = point(|| format!("{s}.hip"), leg.hip)?;
    let knee = point(|| format!("{s}.knee"), leg.knee)?;
    let ankle = point(|| format!("{s}.ankle"), leg.ankle)?;
    let heel = point(|| format!("{s}.heel"), leg.heel)?;
    let mtp = point(|| format!("{s}.mtp"), leg.mtp)?;
    let toe = point(|| format!("{s}.toe"), leg.toe)?;
    let knee_axis = point(|| format!("{s}.knee_axis"), leg.knee_axis)?;

    // y along the segment, z the knee axis, x = y × z (forward); a function, not a closure, to
    // be inlined too
    #[inline(always)]
    fn y_z(origin: DVec3, [y, z]: [DVec3; 2], time: f64, s: &str, what: &str) -> Result<Frame> {
        let y = unit(y, time, || format!("the {what} of the {s} leg"))?;
        let z = perpendicular(z, y, time, || format!("the {s} knee axis"))?;
        Ok(Frame {
            origin,
            axes: DMat3::from_cols(y.cross(z), y, z),
        })
    }
    let thigh = y_z(hip, [hip - knee, knee_axis], time, s, "thigh")?;
    let shank = y_z(knee, [knee - ankle, knee_axis], time, s, "shank")?;
    // foot: x heel → mtp, y towards the ankle, z = x × y
    let x = unit(mtp - heel, time, || format!("the {s} foot's heel–mtp line"))?;
    let y = perpendicular(ankle - heel, x, time, || format!("the {s} heel–ankle line"))?;
    let foot = Frame {
        origin: ankle,
        axes: DMat3::from_cols(x, y, x.cross(y)),
    };
    // toe: x mtp → toe tip, z the foot's lateral axis, y = z × x
    let x = unit(toe - mtp, time, || format!("the {s} toe"))?;
    let z = perpendicular(foot.axes.z_axis, x, time, || {
        format!("the {s} foot's lateral axis")
    })?;
    let toe = Frame {
        origin: mtp,
        axes: DMat3::from_cols(x, z.cross(x), z),
    };
    Ok(LegFrames {
        thigh,
        shank,
        foot,
        toe,
    })
}

/// An arm's shoulder flexion, abduction and elbow flexion, or [`Error::NotFinite`] naming the
/// first that is not finite.
#[inline(always)]
fn arm_angles(arm: &ArmAngles, side: Side) -> Result<[f64; 3]> {
    let s = side.suffix();
    Ok([
        finite_named(|| format!("{s}.shoulder_flexion"), arm.shoulder_flexion)?,
        finite_named(|| format!("{s}.shoulder_abduction"), arm.shoulder_abduction)?,
        finite_named(|| format!("{s}.elbow_flexion"), arm.elbow_flexion)?,
    ])
}

/// The shoulder and elbow of an arm placed `R_thorax · R_z(flexion) · R_x(∓abduction)`, forearm
/// `· R_z(elbow)` ([`arm_frames`]): their angles are those it was built from (where the
/// decompositions return them, [`zxy_round_trip`]).
fn arm_joints([flexion, abduction, elbow]: [f64; 3], side: Side) -> ArmJoints {
    let s = side.sign();
    ArmJoints {
        shoulder: joint3(zxy_round_trip(flexion, -s * abduction, 0.0), s, 1.0),
        elbow: joint3(zxy_round_trip(elbow, 0.0, 0.0), s, 1.0),
    }
}

fn arm_frames(thorax: &Frame, arm: &ArmAngles, side: Side, body: &Body) -> Result<ArmFrames> {
    let [flexion, abduction, elbow] = arm_angles(arm, side)?;
    let f = &body.figure;
    let shoulder = thorax.point(DVec3::new(
        0.0,
        f.spine,
        side.sign() * f.shoulder_width / 2.0,
    ));
    let upper = thorax.axes * zxy_matrix(flexion, -side.sign() * abduction, 0.0);
    let upper_arm = Frame {
        origin: shoulder,
        axes: upper,
    };
    let fore = upper * DMat3::from_rotation_z(elbow);
    let forearm = Frame {
        origin: upper_arm.point(DVec3::new(0.0, -f.upper_arm, 0.0)),
        axes: fore,
    };
    let hand = Frame {
        origin: forearm.point(DVec3::new(0.0, -f.forearm, 0.0)),
        axes: fore,
    };
    Ok(ArmFrames {
        upper_arm,
        forearm,
        hand,
    })
}

impl Skeleton {
    /// The segment frames of `lm`. Errors: a non-finite number ([`Error::NotFinite`], naming the
    /// field), a degenerate segment or a knee axis along a segment ([`Error::Geometry`]).
    pub fn new(lm: &Landmarks, body: &Body) -> Result<Self> {
        let trunk = Trunk::new(lm)?;
        let (t, pelvis) = (trunk.time, trunk.pelvis);
        let [lr, lb, le] = trunk.lumbar;
        let thorax = Frame {
            origin: pelvis.origin,
            axes: pelvis.axes * yxz_matrix(lr, lb, le),
        };
        Ok(Skeleton {
            pelvis,
            thorax,
            right: leg_frames(&lm.right, Side::Right, t)?,
            left: leg_frames(&lm.left, Side::Left, t)?,
            right_arm: arm_frames(&thorax, &lm.right_arm, Side::Right, body)?,
            left_arm: arm_frames(&thorax, &lm.left_arm, Side::Left, body)?,
        })
    }

    pub fn leg(&self, side: Side) -> &LegFrames {
        match side {
            Side::Right => &self.right,
            Side::Left => &self.left,
        }
    }

    pub fn arm(&self, side: Side) -> &ArmFrames {
        match side {
            Side::Right => &self.right_arm,
            Side::Left => &self.left_arm,
        }
    }

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
        assemble(
            time,
            step,
            &self.pelvis,
            yxz_angles(&self.pelvis.axes),
            yxz_angles(&(self.pelvis.axes.transpose() * self.thorax.axes)),
            [&self.right, &self.left],
            [arm(Side::Right), arm(Side::Left)],
        )
    }

    /// The largest distance (m) between a landmark and where the body's rigid segments put it:
    /// hips at pelvis ± R (0, 0, l0/2), knee l3 below the hip and ankle l4 below the knee along
    /// their segments, heel (−l8, −l9, 0) and mtp (√(l12² − l9²), −l9, 0) in the foot frame, toe
    /// tip l13 along the toe. Returns the distance and the landmark's name.
    pub fn length_error(&self, lm: &Landmarks, body: &Body) -> (f64, String) {
        let h12 = body.ankle_to_metatarsal_horizontal();
        let mut worst = (0.0, String::new());
        for side in [Side::Right, Side::Left] {
            let (l, pts) = match side {
                Side::Right => (&self.right, &lm.right),
                Side::Left => (&self.left, &lm.left),
            };
            let hip = self
                .pelvis
                .point(DVec3::new(0.0, 0.0, side.sign() * body.l0 / 2.0));
            let checks = [
                ("hip", hip, pts.hip),
                (
                    "knee",
                    l.thigh.point(DVec3::new(0.0, -body.l3, 0.0)),
                    pts.knee,
                ),
                (
                    "ankle",
                    l.shank.point(DVec3::new(0.0, -body.l4, 0.0)),
                    pts.ankle,
                ),
                (
                    "heel",
                    l.foot.point(DVec3::new(-body.l8, -body.l9, 0.0)),
                    pts.heel,
                ),
                ("mtp", l.foot.point(DVec3::new(h12, -body.l9, 0.0)), pts.mtp),
                ("toe", l.toe.point(DVec3::new(body.l13, 0.0, 0.0)), pts.toe),
            ];
            for (name, model, given) in checks {
                let d = model.distance(DVec3::from_array(given));
                if d > worst.0 || d.is_nan() {
                    worst = (d, format!("{}.{name}", side.suffix()));
                }
            }
        }
        worst
    }
}

/// The clinical angles of the joint from `parent` to `child` axes.
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
/// from: the pelvis, lumbar and arm angles are the landmarks' own (the frames are built from
/// them, [`zxy_round_trip`]), and no arm is placed (the angles do not depend on `_body`).
pub fn clinical(lm: &Landmarks, _body: &Body) -> Result<Clinical> {
    let trunk = Trunk::new(lm)?;
    let right = leg_frames(&lm.right, Side::Right, trunk.time)?;
    let left = leg_frames(&lm.left, Side::Left, trunk.time)?;
    let right_arm = arm_joints(arm_angles(&lm.right_arm, Side::Right)?, Side::Right);
    let left_arm = arm_joints(arm_angles(&lm.left_arm, Side::Left)?, Side::Left);
    let [lr, lb, le] = trunk.lumbar;
    Ok(assemble(
        lm.time,
        lm.step,
        &trunk.pelvis,
        yxz_round_trip(trunk.rotation, -trunk.list, -trunk.tilt),
        yxz_round_trip(lr, lb, le),
        [&right, &left],
        [right_arm, left_arm],
    ))
}

/// The checked time and trunk angles of a frame, and its pelvis frame
/// `R_y(rotation) · R_x(−list) · R_z(−tilt)`.
struct Trunk {
    time: f64,
    tilt: f64,
    list: f64,
    rotation: f64,
    pelvis: Frame,
    /// Lumbar rotation, bending, extension.
    lumbar: [f64; 3],
}

impl Trunk {
    /// Errors: the first non-finite of time, pelvis, pelvis angles, lumbar angles.
    #[inline(always)]
    fn new(lm: &Landmarks) -> Result<Self> {
        let time = finite("time", lm.time)?;
        let origin = point(|| "pelvis".to_string(), lm.pelvis)?;
        let tilt = finite("pelvis_tilt", lm.pelvis_tilt)?;
        let list = finite("pelvis_list", lm.pelvis_list)?;
        let rotation = finite("pelvis_rotation", lm.pelvis_rotation)?;
        let lumbar = [
            finite("lumbar_rotation", lm.lumbar_rotation)?,
            finite("lumbar_bending", lm.lumbar_bending)?,
            finite("lumbar_extension", lm.lumbar_extension)?,
        ];
        Ok(Trunk {
            time,
            tilt,
            list,
            rotation,
            pelvis: Frame {
                origin,
                axes: yxz_matrix(rotation, -list, -tilt),
            },
            lumbar,
        })
    }
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
        right: leg(legs[0], Side::Right),
        left: leg(legs[1], Side::Left),
        right_arm,
        left_arm,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    fn close(a: DMat3, b: DMat3) -> bool {
        (a - b).to_cols_array().iter().all(|d| d.abs() < 1e-12)
    }

    /// The multiplied-out [`yxz_matrix`] against the product of glam's three rotations (its
    /// first implementation) over angles in every quadrant.
    #[test]
    fn yxz_matrix_is_the_product_of_its_rotations() {
        let mut worst: f64 = 0.0;
        for i in 0..20 {
            for j in 0..20 {
                for k in 0..20 {
                    let angle = |n: i32, scale: f64| (n as f64 - 9.7) * scale;
                    let (r, p, q) = (angle(i, 0.33), angle(j, 0.17), angle(k, 0.31));
                    let m = DMat3::from_rotation_y(r)
                        * DMat3::from_rotation_x(p)
                        * DMat3::from_rotation_z(q);
                    let d = (yxz_matrix(r, p, q) - m).to_cols_array();
                    worst = d.iter().fold(worst, |w, x| w.max(x.abs()));
                }
            }
        }
        assert!(worst < 1e-15, "{worst}");
    }

    /// The finiteness tests agree with `f64::is_finite` on the special values and beside them.
    #[test]
    fn finiteness_is_that_of_std() {
        let values = [
            0.0,
            -0.0,
            1.0,
            -2.5e-300,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            f64::MIN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            -f64::NAN,
        ];
        for x in values {
            assert_eq!(is_finite(x), x.is_finite(), "{x}");
            for y in values {
                for z in [0.3, f64::MAX, f64::NAN] {
                    let v = DVec3::new(x, y, z);
                    assert_eq!(is_finite3(v), v.is_finite(), "{v}");
                }
            }
        }
    }

    /// Decomposition inverts composition, checked against glam's own Euler conversion (an
    /// independent implementation): glam's intrinsic ZXY is R_z·R_x·R_y, its YXZ is R_y·R_x·R_z.
    #[test]
    fn euler_round_trips_and_matches_glam() {
        let angles = [
            (0.3, -0.4, 1.2),
            (-2.5, 1.1, -3.0),
            (1.0, 0.0, 0.0),
            (0.0, -1.5, 0.2),
        ];
        for (a, b, c) in angles {
            let m = zxy_matrix(a, b, c);
            let [x, y, z] = zxy_angles(&m);
            assert!((x - a).abs() < 1e-12 && (y - b).abs() < 1e-12 && (z - c).abs() < 1e-12);
            let g = DMat3::from_euler(glam::EulerRot::ZXY, a, b, c);
            assert!(close(m, g));
            let m = yxz_matrix(a, b, c);
            let [x, y, z] = yxz_angles(&m);
            assert!((x - a).abs() < 1e-12 && (y - b).abs() < 1e-12 && (z - c).abs() < 1e-12);
            assert!(close(m, DMat3::from_euler(glam::EulerRot::YXZ, a, b, c)));
        }
        // near gimbal lock the angles still recompose to the same matrix
        let m = zxy_matrix(0.4, FRAC_PI_2 - 1e-4, -0.3);
        let [a, b, c] = zxy_angles(&m);
        assert!(close(zxy_matrix(a, b, c), m));
    }
}
