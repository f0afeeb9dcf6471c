//! The whole figure around the dynamic model (KLAW 1989 §4.2, spec §7): the virtual stance leg
//! with its foot rules, the swing foot, the determinants of gait (pelvic rotation, list and
//! lateral displacement) and the upper body. Everything here is kinematic: it reads a simulated
//! step and places the figure in 3-D at one instant as [`Landmarks`].
//!
//! World frame (OpenSim's): x forward (the walking direction), y up, z to the figure's right,
//! right-handed; the origin on the ground under the first stance ankle's flat-foot position, the
//! walk's sagittal plane at z = 0. Metres and radians.

/// One leg's joint centres and foot contact points, world frame (m).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct LegPoints {
    pub hip: [f64; 3],
    pub knee: [f64; 3],
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
/// + with the right side forward. The hip joints are `pelvis ± R · (0, 0, l0/2)` (right +).
/// The thorax relative to the pelvis is `R_y(lumbar_rotation) · R_x(lumbar_bending) ·
/// R_z(lumbar_extension)`.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Landmarks {
    /// Time since the first heel strike (s).
    pub time: f64,
    /// Index of the step (heel strike to heel strike) the instant belongs to.
    pub step: usize,
    /// Pelvis centre C, the dynamic model's hip (spec §7), midpoint of the hip joints.
    pub pelvis: [f64; 3],
    pub pelvis_tilt: f64,
    pub pelvis_list: f64,
    pub pelvis_rotation: f64,
    /// Thorax relative to the pelvis (rad): extension + (trunk back), bending + with the top of
    /// the trunk towards the right, rotation + with the right shoulder forward.
    pub lumbar_extension: f64,
    pub lumbar_bending: f64,
    pub lumbar_rotation: f64,
    pub right: LegPoints,
    pub left: LegPoints,
    pub right_arm: ArmAngles,
    pub left_arm: ArmAngles,
}
