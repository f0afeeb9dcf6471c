//! BVH (Biovision hierarchy) export, parser and forward kinematics (issue item 7).
//!
//! File axes: Y up, +Z forward (the walking direction), +X to the figure's left, metres; a klaw
//! world vector (x forward, y up, z right) is written as (−z, y, x). The rest pose is the
//! anatomical zero of [`crate::figure::skeleton`] (legs vertical, soles flat, arms hanging), so every
//! joint channel is ± a clinical angle (`docs/export.md` has the table).
//!
//! Hierarchy: `Hips` (root, the pelvis centre) → `Spine` (the lumbar joint, at the pelvis centre)
//! → `Chest` → `Neck` → `Head`; `Chest` → `{Left,Right}Shoulder` → `Arm` → `ForeArm` → `Hand`;
//! `Hips` → `{Left,Right}UpLeg` → `Leg` → `Foot` → `ToeBase` → End Site (the toe tip). Offsets
//! from the body table: hips ±l0/2, knee l3 below the hip, ankle l4 below the knee, mtp
//! √(l12² − l9²) ahead of and l9 below the ankle, toe tip l13 ahead of the mtp; the spine
//! (hip-joint level to shoulder level) is split in two equal halves (`Spine` → `Chest` →
//! `Neck`), shoulders ±shoulder_width/2, then neck, head, upper arm, forearm, hand.
//!
//! Channels: the root has `Xposition Yposition Zposition Yrotation Zrotation Xrotation` and
//! `Spine` `Yrotation Zrotation Xrotation` (the order of the pelvis and lumbar angles of
//! [`crate::figure::Landmarks`], so these channels are exactly the landmarks' angles); every other
//! joint has `Xrotation Zrotation Yrotation` (flexion, ab/adduction, axial rotation); `Neck`'s
//! `Yrotation` is the neck rotation (the head's turn about the thorax's long axis). A joint's
//! rotation is the product of its channels in file order, each about the parent's (rest) axes;
//! the joint sits at its offset in the parent's frame.
mod parse;
mod write;

use glam::DVec3;

pub use parse::{Bvh, BvhJoint, JointPose, ParseError, parse};
pub(crate) use write::BvhWriter;

/// A klaw world vector (x forward, y up, z right) in BVH axes (X left, Y up, Z forward).
pub fn to_bvh(v: DVec3) -> DVec3 {
    DVec3::new(-v.z, v.y, v.x)
}

/// A BVH vector in klaw world axes; the inverse of [`to_bvh`].
pub fn from_bvh(v: DVec3) -> DVec3 {
    DVec3::new(v.z, v.y, -v.x)
}

/// A BVH channel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Channel {
    /// Translation along X (left), file units.
    Xposition,
    /// Translation along Y (up), file units.
    Yposition,
    /// Translation along Z (forward), file units.
    Zposition,
    /// Rotation about X (left), degrees.
    Xrotation,
    /// Rotation about Y (up), degrees.
    Yrotation,
    /// Rotation about Z (forward), degrees.
    Zrotation,
}

impl Channel {
    fn name(self) -> &'static str {
        match self {
            Channel::Xposition => "Xposition",
            Channel::Yposition => "Yposition",
            Channel::Zposition => "Zposition",
            Channel::Xrotation => "Xrotation",
            Channel::Yrotation => "Yrotation",
            Channel::Zrotation => "Zrotation",
        }
    }

    fn parse(s: &str) -> Option<Channel> {
        Some(match s {
            "Xposition" => Channel::Xposition,
            "Yposition" => Channel::Yposition,
            "Zposition" => Channel::Zposition,
            "Xrotation" => Channel::Xrotation,
            "Yrotation" => Channel::Yrotation,
            "Zrotation" => Channel::Zrotation,
            _ => return None,
        })
    }
}
