//! The body's segments placed from a frame's clinical angles (forward kinematics, the inverse of
//! [`crate::figure::clinical`]): the five rigid bodies of the body table (`models/`, KLAW 1989
//! Table B-1) that carry the whole mass: the upper body (head, arms and trunk, m2), the two
//! thighs (m3) and the two shanks with their feet (m4).
//!
//! The frames are those of the exported skeleton (`docs/export.md`): the pelvis
//! `R_y(rotation) · R_x(−list) · R_z(−tilt)` at the pelvis centre, the thorax the pelvis
//! `· R_y(lumbar rotation) · R_x(lumbar bending) · R_z(lumbar extension)`, a thigh the pelvis
//! `· R_z(hip flexion) · R_x(±adduction) · R_y(±rotation)` (+ right, − left) at the hip
//! `pelvis · (0, 0, ±l0/2)`, a shank the thigh `· R_z(−knee flexion)` at the knee, l3 down the
//! thigh; the ankle l4 down the shank. Centres of mass on the segments' long axes: the upper
//! body's r2 above the pelvis centre along the thorax, the thigh's r3 below the hip, the shank's
//! r4 below the knee. Each segment's inertia is the table's about its transverse axes,
//! I = m (γ l)², and 0 about its long axis (the table has no longitudinal radius of gyration).
use glam::{DMat3, DVec3};

use crate::figure::clinical::Clinical;
use crate::figure::euler::{yxz_matrix, zxy_matrix};
use crate::figure::skeleton::Side;
use crate::model::body::Body;

/// The quantities of a frame the criteria read, in the order of [`pose`]: pelvis centre x, y, z
/// (m), pelvis tilt, list, rotation, lumbar extension, bending, rotation, then per side (right,
/// left) hip flexion, adduction, rotation and knee flexion (rad, clinical signs).
pub const POSE: usize = 17;

/// The names of the [`POSE`] quantities, as the CSV columns without their unit.
pub const POSE_NAMES: [&str; POSE] = [
    "pelvis_tx",
    "pelvis_ty",
    "pelvis_tz",
    "pelvis_tilt",
    "pelvis_list",
    "pelvis_rotation",
    "lumbar_extension",
    "lumbar_bending",
    "lumbar_rotation",
    "hip_flexion_r",
    "hip_adduction_r",
    "hip_rotation_r",
    "knee_flexion_r",
    "hip_flexion_l",
    "hip_adduction_l",
    "hip_rotation_l",
    "knee_flexion_l",
];

/// The paper's eleven degrees of freedom (Pronost et al. 2006, Figure 1: pelvis 3, hips 3 each,
/// knees 1 each), as indices into the pose: the state vector of C1 and C2.
pub const DOFS: [usize; 11] = [3, 4, 5, 9, 10, 11, 12, 13, 14, 15, 16];

/// The pose of a frame (see [`POSE`]).
pub fn pose(c: &Clinical) -> [f64; POSE] {
    let [x, y, z] = c.pelvis;
    let (r, l) = (&c.right, &c.left);
    [
        x,
        y,
        z,
        c.pelvis_tilt,
        c.pelvis_list,
        c.pelvis_rotation,
        c.lumbar_extension,
        c.lumbar_bending,
        c.lumbar_rotation,
        r.hip.flexion,
        r.hip.adduction,
        r.hip.rotation,
        r.knee.flexion,
        l.hip.flexion,
        l.hip.adduction,
        l.hip.rotation,
        l.knee.flexion,
    ]
}

/// The segments, in the order of [`Segments::place`]'s output.
pub const SEGMENT_NAMES: [&str; 5] = [
    "upper body",
    "right thigh",
    "right shank",
    "left thigh",
    "left shank",
];

/// A segment at one instant: its centre of mass and its axes (columns; y along the segment,
/// towards its proximal end), world frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placed {
    /// Centre of mass (m).
    pub com: DVec3,
    /// Axes, x forward, y along the segment, z to the right at the anatomical zero.
    pub axes: DMat3,
}

/// The five segments of a body: masses, transverse moments of inertia about the centres of
/// mass, and the lengths that place them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segments {
    /// Masses (kg), in [`SEGMENT_NAMES`] order; they add up to the body mass.
    pub mass: [f64; 5],
    /// Moments of inertia about the transverse axes through the centre of mass (kg m²).
    pub inertia: [f64; 5],
    body: Body,
}

impl Segments {
    /// The segments of `body`.
    pub fn new(body: &Body) -> Self {
        Segments {
            mass: [body.m2, body.m3, body.m4, body.m3, body.m4],
            inertia: [body.i2, body.i3, body.i4, body.i3, body.i4],
            body: *body,
        }
    }

    /// The segments placed by `pose` (module doc), in [`SEGMENT_NAMES`] order.
    pub fn place(&self, pose: &[f64; POSE]) -> [Placed; 5] {
        let b = &self.body;
        let (pelvis, centre) = pelvis_frame(pose);
        let thorax = pelvis * yxz_matrix(pose[8], pose[7], pose[6]);
        let along = |axes: DMat3, from: DVec3, d: f64| from + axes * DVec3::new(0.0, d, 0.0);
        let [right, left] =
            [Side::Right, Side::Left].map(|side| leg(pose, side, pelvis, centre, b));
        let leg_segments = |(thigh, shank, hip, knee): (DMat3, DMat3, DVec3, DVec3)| {
            [
                Placed {
                    com: along(thigh, hip, -b.r3),
                    axes: thigh,
                },
                Placed {
                    com: along(shank, knee, -b.r4),
                    axes: shank,
                },
            ]
        };
        let [rt, rs] = leg_segments(right);
        let [lt, ls] = leg_segments(left);
        [
            Placed {
                com: along(thorax, centre, b.r2),
                axes: thorax,
            },
            rt,
            rs,
            lt,
            ls,
        ]
    }

    /// The ankle joint centres (right, left), world frame (m).
    pub fn ankles(&self, pose: &[f64; POSE]) -> [DVec3; 2] {
        let b = &self.body;
        let (pelvis, centre) = pelvis_frame(pose);
        [Side::Right, Side::Left].map(|side| {
            let (_, shank, _, knee) = leg(pose, side, pelvis, centre, b);
            knee + shank * DVec3::new(0.0, -b.l4, 0.0)
        })
    }
}

/// The pelvis axes and centre of a pose.
fn pelvis_frame(pose: &[f64; POSE]) -> (DMat3, DVec3) {
    (
        yxz_matrix(pose[5], -pose[4], -pose[3]),
        DVec3::new(pose[0], pose[1], pose[2]),
    )
}

/// A leg's thigh and shank axes, hip and knee centres.
fn leg(
    pose: &[f64; POSE],
    side: Side,
    pelvis: DMat3,
    centre: DVec3,
    b: &Body,
) -> (DMat3, DMat3, DVec3, DVec3) {
    let (i, s) = match side {
        Side::Right => (9, 1.0),
        Side::Left => (13, -1.0),
    };
    let hip = centre + pelvis * DVec3::new(0.0, 0.0, s * b.l0 / 2.0);
    let thigh = pelvis * zxy_matrix(pose[i], s * pose[i + 1], s * pose[i + 2]);
    let knee = hip + thigh * DVec3::new(0.0, -b.l3, 0.0);
    let shank = thigh * DMat3::from_rotation_z(-pose[i + 3]);
    (thigh, shank, hip, knee)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::clinical::clinical;

    /// The forward kinematics of the clinical angles read off the figure puts the knees and
    /// ankles back where the figure's own construction (`figure::landmarks`, from the dynamic
    /// model's points) put them.
    #[test]
    fn knees_and_ankles_come_back_from_the_clinical_angles() {
        let body = Body::standard(1.75, 70.0).unwrap();
        let walk = crate::simulation::Simulation::new(body)
            .velocity(1.3)
            .steps(3)
            .run()
            .unwrap();
        let segments = Segments::new(&body);
        let mut worst: f64 = 0.0;
        for lm in walk.frames(50.0).unwrap() {
            let c = clinical(&lm, &body).unwrap();
            let p = pose(&c);
            let ankles = segments.ankles(&p);
            for (a, leg) in ankles.iter().zip([&lm.right, &lm.left]) {
                worst = worst.max(a.distance(DVec3::from_array(leg.ankle)));
            }
            let placed = segments.place(&p);
            for (k, leg) in [(1, &lm.right), (3, &lm.left)] {
                // the thigh's centre of mass lies r3 from the hip towards the knee
                let hip = DVec3::from_array(leg.hip);
                let knee = DVec3::from_array(leg.knee);
                let com = hip + (knee - hip) * body.r3 / body.l3;
                worst = worst.max(placed[k].com.distance(com));
            }
        }
        assert!(worst < 1e-9, "{worst} m");
    }

    #[test]
    fn the_segments_carry_the_whole_mass() {
        let body = Body::standard(1.8, 80.0).unwrap();
        let s = Segments::new(&body);
        assert!((s.mass.iter().sum::<f64>() - 80.0).abs() < 1e-9);
    }
}
