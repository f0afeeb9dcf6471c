//! The lower-limb chain of Pronost et al. (§2, Figure 1): five rigid bodies (pelvis, two thighs,
//! two shanks) and eleven rotations: the pelvis's three about its centre, three at each hip, one
//! at each knee. Its forward kinematics gives the ankles relative to the pelvis centre, X = f(θ)
//! (§2), and its analytic Jacobian J = ∂f/∂θ (eq. 1), with glam.
//!
//! The root is klaw's pelvis centre C, the midpoint of the hip joints ([`crate::figure`]), not
//! the paper's midpoint of the anterior superior iliac spines: that point lies, in the pelvis
//! frame, about 0.14 PW forward and 0.30 PW up from C, PW the inter-ASIS width (Bell, Pedersen &
//! Brand 1990's hip-centre regression; PW ≈ l0 / 0.72 with their 36 % lateral offset), a fixed
//! offset in the pelvis frame (`docs/ik.md`).
//!
//! The axes are klaw's world axes carried along the walking direction (x forward, y up, z to the
//! right), and every angle has the clinical sign and Euler order of
//! [`crate::figure::clinical`], so that the chain's angles are the clinical angles of the figure
//! it poses:
//! - pelvis: `R_p = R_y(rotation) · R_x(−list) · R_z(−tilt)`, hips at `R_p · (0, 0, ±l0/2)`;
//! - hip of side s (+1 right, −1 left): thigh `R_t = R_p · R_z(flexion) · R_x(s adduction) ·
//!   R_y(s rotation)`, the knee `l3` down its y axis;
//! - knee: shank `R_s = R_t · R_z(−flexion)`, the ankle `l4` down its y axis.
use glam::{DMat3, DVec3};
use nalgebra::{SMatrix, SVector};

use crate::kinematics::pelvis::Side;
use crate::model::body::Body;

/// The number of rotations of the chain.
pub const DOF: usize = 11;

/// The chain's angles θ (rad), in the order of [`NAMES`].
pub type Angles = SVector<f64, DOF>;
/// The ankles relative to the pelvis centre, right then left (m), walking-direction axes.
pub type Ankles = SVector<f64, 6>;
/// The Jacobian ∂(ankles)/∂θ (eq. 1).
pub type Jacobian = SMatrix<f64, 6, DOF>;
/// A segment's angular Jacobian: its angular velocity (world, rad/s) per unit θ̇.
pub type AngularJacobian = SMatrix<f64, 3, DOF>;

/// The index of the pelvic tilt (anterior +), list (right side up +), rotation (right side
/// forward +).
pub const PELVIS_TILT: usize = 0;
/// Pelvic list.
pub const PELVIS_LIST: usize = 1;
/// Pelvic rotation.
pub const PELVIS_ROTATION: usize = 2;

/// The first of a leg's four angles: hip flexion, hip adduction, hip (internal) rotation, knee
/// flexion.
pub fn leg_offset(side: Side) -> usize {
    match side {
        Side::Right => 3,
        Side::Left => 7,
    }
}

/// The angles' names, as the clinical angles' (`_r` right, `_l` left).
pub const NAMES: [&str; DOF] = [
    "pelvis_tilt",
    "pelvis_list",
    "pelvis_rotation",
    "hip_flexion_r",
    "hip_adduction_r",
    "hip_rotation_r",
    "knee_flexion_r",
    "hip_flexion_l",
    "hip_adduction_l",
    "hip_rotation_l",
    "knee_flexion_l",
];

/// The chain's dimensions (m): hip joint to hip joint, thigh, shank.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Chain {
    /// l0, hip joint to hip joint.
    pub pelvis_width: f64,
    /// l3, hip to knee.
    pub thigh: f64,
    /// l4, knee to ankle.
    pub shank: f64,
}

/// A leg posed: joint centres and segment axes (columns), relative to the pelvis centre.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LegPose {
    /// Hip joint centre.
    pub hip: DVec3,
    /// Knee joint centre.
    pub knee: DVec3,
    /// Ankle joint centre.
    pub ankle: DVec3,
    /// Thigh axes `R_t`.
    pub thigh: DMat3,
    /// Shank axes `R_s`.
    pub shank: DMat3,
    /// The world axes of the leg's four rotations (hip flexion, adduction, rotation, knee
    /// flexion), signed so that a positive rate turns the distal segment about them.
    pub axes: [DVec3; 4],
}

/// The chain posed at θ: pelvis axes, the pelvis rotations' world axes, both legs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// Pelvis axes `R_p`.
    pub pelvis: DMat3,
    /// The world axes of tilt, list and rotation (signed as [`LegPose::axes`]).
    pub pelvis_axes: [DVec3; 3],
    /// The right leg.
    pub right: LegPose,
    /// The left leg.
    pub left: LegPose,
}

impl Pose {
    /// The leg of `side`.
    pub fn leg(&self, side: Side) -> &LegPose {
        match side {
            Side::Right => &self.right,
            Side::Left => &self.left,
        }
    }

    /// The ankles, right then left: X = f(θ).
    pub fn ankles(&self) -> Ankles {
        let (r, l) = (self.right.ankle, self.left.ankle);
        Ankles::new(r.x, r.y, r.z, l.x, l.y, l.z)
    }

    /// The Jacobian ∂X/∂θ (eq. 1), analytic: column j of a revolute joint is its world axis
    /// ω_j × (ankle − centre_j); a leg's ankle does not move with the other leg's joints.
    pub fn jacobian(&self) -> Jacobian {
        let mut j = Jacobian::zeros();
        for (row, side) in [(0, Side::Right), (3, Side::Left)] {
            let leg = self.leg(side);
            let mut set = |col: usize, v: DVec3| {
                j[(row, col)] = v.x;
                j[(row + 1, col)] = v.y;
                j[(row + 2, col)] = v.z;
            };
            for (k, axis) in self.pelvis_axes.iter().enumerate() {
                set(k, axis.cross(leg.ankle));
            }
            let o = leg_offset(side);
            for k in 0..3 {
                set(o + k, leg.axes[k].cross(leg.ankle - leg.hip));
            }
            set(o + 3, leg.axes[3].cross(leg.ankle - leg.knee));
        }
        j
    }

    /// The angular Jacobians of the five segments (pelvis, right thigh, right shank, left thigh,
    /// left shank): ω_b = Σ_j ω_j θ̇_j over the rotations between the root and the segment.
    pub fn angular_jacobians(&self) -> [AngularJacobian; 5] {
        let mut pelvis = AngularJacobian::zeros();
        for (k, a) in self.pelvis_axes.iter().enumerate() {
            pelvis.set_column(k, &to_na(*a));
        }
        let leg = |side: Side| {
            let o = leg_offset(side);
            let l = self.leg(side);
            let mut thigh = pelvis;
            for k in 0..3 {
                thigh.set_column(o + k, &to_na(l.axes[k]));
            }
            let mut shank = thigh;
            shank.set_column(o + 3, &to_na(l.axes[3]));
            (thigh, shank)
        };
        let (rt, rs) = leg(Side::Right);
        let (lt, ls) = leg(Side::Left);
        [pelvis, rt, rs, lt, ls]
    }
}

fn to_na(v: DVec3) -> nalgebra::Vector3<f64> {
    nalgebra::Vector3::new(v.x, v.y, v.z)
}

impl Chain {
    /// The chain of `body`: l0, l3, l4.
    pub fn new(body: &Body) -> Self {
        Chain {
            pelvis_width: body.l0,
            thigh: body.l3,
            shank: body.l4,
        }
    }

    /// The chain posed at θ (module doc).
    pub fn pose(&self, theta: &Angles) -> Pose {
        let ry = DMat3::from_rotation_y(theta[PELVIS_ROTATION]);
        let ryx = ry * DMat3::from_rotation_x(-theta[PELVIS_LIST]);
        let pelvis = ryx * DMat3::from_rotation_z(-theta[PELVIS_TILT]);
        let pelvis_axes = [-ryx.z_axis, -ry.x_axis, DVec3::Y];
        let leg = |side: Side| {
            let s = side.sign();
            let o = leg_offset(side);
            let (flexion, adduction, rotation, knee) =
                (theta[o], theta[o + 1], theta[o + 2], theta[o + 3]);
            let rz = pelvis * DMat3::from_rotation_z(flexion);
            let rzx = rz * DMat3::from_rotation_x(s * adduction);
            let thigh = rzx * DMat3::from_rotation_y(s * rotation);
            let shank = thigh * DMat3::from_rotation_z(-knee);
            let hip = pelvis * DVec3::new(0.0, 0.0, s * self.pelvis_width / 2.0);
            let knee_c = hip - self.thigh * thigh.y_axis;
            let ankle = knee_c - self.shank * shank.y_axis;
            LegPose {
                hip,
                knee: knee_c,
                ankle,
                thigh,
                shank,
                axes: [
                    pelvis.z_axis,
                    s * rz.x_axis,
                    s * thigh.y_axis,
                    -thigh.z_axis,
                ],
            }
        };
        Pose {
            pelvis,
            pelvis_axes,
            right: leg(Side::Right),
            left: leg(Side::Left),
        }
    }

    /// The ankles at θ: X = f(θ).
    pub fn ankles(&self, theta: &Angles) -> Ankles {
        self.pose(theta).ankles()
    }

    /// The whole leg's length l3 + l4.
    pub fn leg_length(&self) -> f64 {
        self.thigh + self.shank
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chain() -> Chain {
        Chain::new(&Body::standard(1.8, 80.0).unwrap())
    }

    /// Postures spread over the walking range and beyond (rad).
    fn postures() -> Vec<Angles> {
        let rows: [[f64; DOF]; 4] = [
            [0.0; DOF],
            [
                0.15, 0.05, -0.08, 0.4, 0.05, 0.1, 0.2, -0.2, -0.03, -0.05, 0.05,
            ],
            [
                -0.1, -0.07, 0.12, -0.3, -0.2, 0.3, 1.1, 0.9, 0.15, -0.4, 0.6,
            ],
            [0.3, 0.2, 0.5, 1.2, 0.4, -0.6, 1.5, -0.5, -0.3, 0.6, 0.01],
        ];
        rows.iter().map(|r| Angles::from_row_slice(r)).collect()
    }

    /// The segments keep their lengths, and the hips stay l0 apart about the pelvis centre.
    #[test]
    fn the_segments_keep_their_lengths() {
        let c = chain();
        for theta in postures() {
            let p = c.pose(&theta);
            for side in [Side::Right, Side::Left] {
                let l = p.leg(side);
                assert!(((l.knee - l.hip).length() - c.thigh).abs() < 1e-12);
                assert!(((l.ankle - l.knee).length() - c.shank).abs() < 1e-12);
            }
            assert!(((p.right.hip - p.left.hip).length() - c.pelvis_width).abs() < 1e-12);
            assert!((p.right.hip + p.left.hip).length() < 1e-12);
        }
    }

    /// Known postures, worked by hand: standing straight puts the ankles l1 under the hips; 90°
    /// of hip flexion puts the right ankle l1 in front of the hip; 90° of knee flexion with the
    /// thigh vertical puts it l3 down and l4 behind; 90° of pelvic rotation (right side forward)
    /// moves the right hip to x = +l0/2; 90° of hip abduction of the left leg (adduction −90°)
    /// puts its ankle l1 out to the left at hip height.
    #[test]
    fn hand_worked_postures() {
        let c = chain();
        let (h, l1) = (c.pelvis_width / 2.0, c.leg_length());
        let close = |a: DVec3, b: DVec3| assert!((a - b).length() < 1e-12, "{a} vs {b}");
        let p = c.pose(&Angles::zeros());
        close(p.right.ankle, DVec3::new(0.0, -l1, h));
        close(p.left.ankle, DVec3::new(0.0, -l1, -h));
        let q = std::f64::consts::FRAC_PI_2;
        let mut t = Angles::zeros();
        t[3] = q;
        close(c.pose(&t).right.ankle, DVec3::new(l1, 0.0, h));
        let mut t = Angles::zeros();
        t[6] = q;
        close(c.pose(&t).right.ankle, DVec3::new(-c.shank, -c.thigh, h));
        let mut t = Angles::zeros();
        t[PELVIS_ROTATION] = q;
        close(c.pose(&t).right.hip, DVec3::new(h, 0.0, 0.0));
        let mut t = Angles::zeros();
        t[8] = -q;
        close(c.pose(&t).left.ankle, DVec3::new(0.0, 0.0, -h - l1));
        // anterior tilt lowers the front: a hip flexed 90° (thigh forward) then points down-forward
        let mut t = Angles::zeros();
        t[PELVIS_TILT] = 0.3;
        t[3] = q;
        let a = c.pose(&t).right.ankle;
        assert!(a.y < -0.2 && a.x > 0.0, "{a}");
    }

    /// The analytic Jacobian is the central difference of the forward kinematics, column by
    /// column (O(h²) error, h = 1e-6: agreement to 1e-8).
    #[test]
    fn the_jacobian_is_the_derivative_of_the_forward_kinematics() {
        let c = chain();
        let h = 1e-6;
        for theta in postures() {
            let j = c.pose(&theta).jacobian();
            for k in 0..DOF {
                let mut plus = theta;
                let mut minus = theta;
                plus[k] += h;
                minus[k] -= h;
                let d = (c.ankles(&plus) - c.ankles(&minus)) / (2.0 * h);
                let err = (d - j.column(k)).amax();
                assert!(err < 1e-8, "column {} ({}): {err}", k, NAMES[k]);
            }
        }
    }

    /// The angular Jacobians are the derivatives of the segment frames: R(θ + h e_k) R(θ)ᵀ ≈ I +
    /// h [ω]×, ω the column k (central differences, to 1e-8).
    #[test]
    fn the_angular_jacobians_are_the_derivatives_of_the_frames() {
        let c = chain();
        let h = 1e-6;
        let frames = |p: &Pose| {
            [
                p.pelvis,
                p.right.thigh,
                p.right.shank,
                p.left.thigh,
                p.left.shank,
            ]
        };
        for theta in postures() {
            let p = c.pose(&theta);
            let js = p.angular_jacobians();
            for k in 0..DOF {
                let mut plus = theta;
                let mut minus = theta;
                plus[k] += h;
                minus[k] -= h;
                let (fp, fm) = (frames(&c.pose(&plus)), frames(&c.pose(&minus)));
                for (b, r) in frames(&p).iter().enumerate() {
                    // dR/dθ Rᵀ = [ω]×
                    let w = ((fp[b] - fm[b]) * (1.0 / (2.0 * h))) * r.transpose();
                    let omega = DVec3::new(w.y_axis.z, w.z_axis.x, w.x_axis.y);
                    let expect = DVec3::new(js[b][(0, k)], js[b][(1, k)], js[b][(2, k)]);
                    assert!(
                        (omega - expect).length() < 1e-8,
                        "segment {b}, angle {}: {omega} vs {expect}",
                        NAMES[k]
                    );
                }
            }
        }
    }
}
