//! The segment frames of the exported skeleton (issue items 7 and 8; spec §7 "Clinical angles"
//! and "Upper body"): the world frame of every segment of the figure, read off a [`Landmarks`]
//! and the [`Body`]; [`crate::figure::clinical`] reads the joint angles off them.
//!
//! Every segment frame is, at the anatomical zero pose (legs vertical, soles flat, arms hanging),
//! parallel to the world frame of [`crate::figure`]: x forward, y up (along the segment, distal to
//! proximal), z to the figure's right.
//!
//! Segment frames from the points: the thigh's y axis runs knee → hip and its z axis is the knee
//! axis; the shank's y runs ankle → knee, z the knee axis; the foot's x runs heel → mtp (the
//! horizontal sole line at rest) and its y points to the ankle, so the ankle sits l9 above the
//! sole, the heel l8 behind and the mtp √(l12² − l9²) ahead of it; the toe's x runs mtp → toe
//! tip, its z is the foot's lateral axis. The pelvis and thorax frames are the angles of
//! [`Landmarks`] as its doc defines them; the arms are placed by forward kinematics from the
//! thorax: shoulders at (0, spine, ±shoulder_width/2) in the thorax frame (its origin is the
//! pelvis centre), upper arm `R_thorax · R_z(flexion) · R_x(∓abduction)` (right −, left +),
//! forearm and hand `R_upper · R_z(elbow flexion)`. The head's frame has its origin at the neck
//! base, (0, spine, 0) in the thorax frame (the top of the spine, the level of the shoulders),
//! and axes `R_thorax · R_y(neck_rotation)`.
//!
//! The small helpers (the checked points, unit vectors, the leg frames, the trunk and arm checks)
//! are `#[inline(always)]`: they run for every exported frame, and inlined the happy path is the
//! arithmetic while the error names are still built only on error (`docs/engine.md`, "Figures
//! and analysis").
use glam::{DMat3, DVec3};

use crate::figure::error::{FigureError, Result};
use crate::figure::euler::{yxz_matrix, zxy_matrix};
use crate::figure::{ArmAngles, Landmarks, LegPoints};
use crate::model::body::Body;

/// Largest disagreement (m) between the landmarks and the rigid segments of the body table that
/// the BVH export accepts: its offsets are the body's lengths, so beyond this the file could not
/// reproduce the landmarks.
pub(crate) const LENGTH_TOLERANCE: f64 = 1e-3;

/// A segment's pose: its origin (a joint centre) and its axes (the columns), world frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Frame {
    pub origin: DVec3,
    pub axes: DMat3,
}

impl Frame {
    /// The world position of a point given in this frame.
    pub(crate) fn point(&self, local: DVec3) -> DVec3 {
        self.origin + self.axes * local
    }
}

pub use crate::kinematics::pelvis::Side;

/// The frames of one leg: thigh (origin at the hip), shank (knee), foot (ankle), toe (mtp).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LegFrames {
    pub thigh: Frame,
    pub shank: Frame,
    pub foot: Frame,
    pub toe: Frame,
}

/// The frames of one arm: upper arm (origin at the shoulder), forearm (elbow), hand (wrist).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ArmFrames {
    pub upper_arm: Frame,
    pub forearm: Frame,
    pub hand: Frame,
}

/// Every segment of the figure at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Skeleton {
    /// Origin at the pelvis centre (midpoint of the hip joints).
    pub(crate) pelvis: Frame,
    /// Origin at the pelvis centre too: the lumbar rotation is about that point.
    pub(crate) thorax: Frame,
    /// Head and neck: origin at the neck base on top of the spine, turned about the thorax's
    /// long axis by the neck rotation.
    pub(crate) head: Frame,
    /// The head's axes in the thorax's, `R_y(neck_rotation)`: kept as made, so that the neck's
    /// angles are read off it without the round-off of `R_thoraxᵀ · R_head` (a walk's zero neck
    /// rotation is written as 0).
    pub(crate) neck: DMat3,
    pub(crate) right: LegFrames,
    pub(crate) left: LegFrames,
    pub(crate) right_arm: ArmFrames,
    pub(crate) left_arm: ArmFrames,
}

/// Whether `x` is finite: 0 · x is ±0 for a finite x and NaN for ±∞ and NaN (one multiply and
/// one compare, cheaper than `f64::is_finite` for a check that runs on every number of every
/// frame).
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
        Err(FigureError::NotFinite {
            name: name.to_string(),
            value,
        })
    }
}

/// `p` as a vector, or [`FigureError::NotFinite`] naming `name().axis` (the name is only built
/// on error: this runs several times per frame, so the vector's own test comes first).
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
    Err(FigureError::NotFinite {
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

/// `v / |v|`, or an error naming `what()` when v is (nearly) zero.
#[inline(always)]
fn unit(v: DVec3, time: f64, what: impl Fn() -> String) -> Result<DVec3> {
    let n = v.length();
    if n > 1e-9 {
        Ok(v / n)
    } else {
        Err(FigureError::ZeroLength { time, what: what() })
    }
}

/// The component of `hint` perpendicular to the unit vector `axis`, normalized.
#[inline(always)]
fn perpendicular(hint: DVec3, axis: DVec3, time: f64, what: impl Fn() -> String) -> Result<DVec3> {
    let hint = unit(hint, time, &what)?;
    let p = hint - hint.dot(axis) * axis;
    let n = p.length();
    if n < 1e-6 {
        return Err(FigureError::Parallel { time, what: what() });
    }
    // p.normalize(), without measuring p again
    Ok(p * n.recip())
}

/// The thigh, shank, foot and toe frames of one leg from its points (the module doc gives the
/// axes). Inlined: the frames are built in the caller's frame, not copied out of a `Result`.
#[inline(always)]
pub(super) fn leg_frames(leg: &LegPoints, side: Side, time: f64) -> Result<LegFrames> {
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

/// An arm's shoulder flexion, abduction and elbow flexion, or [`FigureError::NotFinite`] naming
/// the first that is not finite.
#[inline(always)]
pub(super) fn arm_angles(arm: &ArmAngles, side: Side) -> Result<[f64; 3]> {
    let s = side.suffix();
    Ok([
        finite_named(|| format!("{s}.shoulder_flexion"), arm.shoulder_flexion)?,
        finite_named(|| format!("{s}.shoulder_abduction"), arm.shoulder_abduction)?,
        finite_named(|| format!("{s}.elbow_flexion"), arm.elbow_flexion)?,
    ])
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
    /// The segment frames of `lm`. Errors: a non-finite number ([`FigureError::NotFinite`],
    /// naming the field), a degenerate segment or a knee axis along a segment
    /// ([`FigureError::ZeroLength`], [`FigureError::Parallel`]).
    pub fn new(lm: &Landmarks, body: &Body) -> Result<Self> {
        let trunk = Trunk::new(lm)?;
        let (t, pelvis) = (trunk.time, trunk.pelvis);
        let [lr, lb, le] = trunk.lumbar;
        let thorax = Frame {
            origin: pelvis.origin,
            axes: pelvis.axes * yxz_matrix(lr, lb, le),
        };
        let neck = DMat3::from_rotation_y(trunk.neck);
        let head = Frame {
            origin: thorax.point(DVec3::new(0.0, body.figure.spine, 0.0)),
            axes: thorax.axes * neck,
        };
        Ok(Skeleton {
            pelvis,
            thorax,
            head,
            neck,
            right: leg_frames(&lm.right, Side::Right, t)?,
            left: leg_frames(&lm.left, Side::Left, t)?,
            right_arm: arm_frames(&thorax, &lm.right_arm, Side::Right, body)?,
            left_arm: arm_frames(&thorax, &lm.left_arm, Side::Left, body)?,
        })
    }

    pub(crate) fn leg(&self, side: Side) -> &LegFrames {
        match side {
            Side::Right => &self.right,
            Side::Left => &self.left,
        }
    }

    pub(crate) fn arm(&self, side: Side) -> &ArmFrames {
        match side {
            Side::Right => &self.right_arm,
            Side::Left => &self.left_arm,
        }
    }

    /// The largest distance (m) between a landmark and where the body's rigid segments put it:
    /// hips at pelvis ± R (0, 0, l0/2), knee l3 below the hip and ankle l4 below the knee along
    /// their segments, heel (−l8, −l9, 0) and mtp (√(l12² − l9²), −l9, 0) in the foot frame, toe
    /// tip l13 along the toe. Returns the distance and the landmark's name.
    pub(crate) fn length_error(&self, lm: &Landmarks, body: &Body) -> (f64, String) {
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

/// The checked time and trunk angles of a frame, and its pelvis frame
/// `R_y(rotation) · R_x(−list) · R_z(−tilt)`.
pub(super) struct Trunk {
    pub(super) time: f64,
    pub(super) tilt: f64,
    pub(super) list: f64,
    pub(super) rotation: f64,
    pub(super) pelvis: Frame,
    /// Lumbar rotation, bending, extension.
    pub(super) lumbar: [f64; 3],
    /// Neck rotation.
    pub(super) neck: f64,
}

impl Trunk {
    /// Errors: the first non-finite of time, pelvis, pelvis angles, lumbar angles, neck rotation.
    #[inline(always)]
    pub(super) fn new(lm: &Landmarks) -> Result<Self> {
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
        let neck = finite("neck_rotation", lm.neck_rotation)?;
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
            neck,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
