//! The two-link leg in its own plane (KLAW 1989 §2.3, Table B-1: thigh l3, shank l4): the knee and
//! ankle of a leg hanging from its hip joint, and the chain that closes a hip and an ankle (knee
//! flexion from their distance, the thigh angle). A hip joint with lateral offset `dz` from the
//! ankle is at 3-D distance √(Δx² + Δy² + dz²); the leg's plane contains the forward axis, so the
//! in-plane drop from hip to ankle is √(Δy² + dz²).
use crate::kinematics::foot::FootPoints;
use crate::numerics::trig::{atan2, sin_cos};

/// A leg pose: sagittal points (x forward, y up, world heights; the foot in the vertical plane of
/// its ankle) and the in-plane angles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LegPose {
    /// Knee in the leg's plane, unfolded: x, and the in-plane height above the ankle added to the
    /// ankle's height (equal to the world height when the leg has no lateral offset).
    pub(crate) knee: [f64; 2],
    pub(crate) ankle: [f64; 2],
    pub(crate) foot: FootPoints,
    /// Thigh from the in-plane downward vertical (knee ahead −), rad.
    pub(crate) theta3: f64,
    /// Knee flexion, rad.
    pub(crate) theta4: f64,
    /// (sin, cos) of θ3 and of the shank's θ3 + θ4 (for [`leg_points_sc`] and the figure).
    pub(crate) sin_cos: [(f64, f64); 2],
    /// Foot pitch (heel up +) and toe dorsiflexion θ6, rad.
    pub pitch: f64,
    pub(crate) theta6: f64,
    /// By how much the straight leg falls short of the hip (m; 0 when the hip is reachable).
    pub(crate) gap: f64,
}

/// Knee and ankle (x, world y) of a leg hanging from a hip joint at `hip` with in-plane thigh
/// angle θ3 and knee flexion θ4, in a plane that contains the forward axis and is tilted by φ,
/// sin φ = dz / (in-plane drop), so that the ankle sits `dz` to the side of the hip. Also
/// returns the (sin, cos) of θ3 and of the shank's θ3 + θ4 it used (the figure places the leg
/// in 3-D with them).
pub(crate) fn leg_points(
    hip: [f64; 2],
    dz: f64,
    theta3: f64,
    theta4: f64,
    l3: f64,
    l4: f64,
) -> ([f64; 2], [f64; 2], [(f64, f64); 2]) {
    let sin_cos = [sin_cos(theta3), sin_cos(theta3 + theta4)];
    let (knee, ankle) = leg_points_sc(hip, dz, sin_cos, l3, l4);
    (knee, ankle, sin_cos)
}

/// [`leg_points`] from the (sin, cos) of θ3 and of θ3 + θ4 (a pose that has them already).
pub(crate) fn leg_points_sc(
    hip: [f64; 2],
    dz: f64,
    [(s3, c3), (ss, cs)]: [(f64, f64); 2],
    l3: f64,
    l4: f64,
) -> ([f64; 2], [f64; 2]) {
    let drop = l3 * c3 + l4 * cs;
    let cos_phi = (1.0 - (dz / drop).powi(2)).max(0.0).sqrt();
    let knee = [hip[0] - l3 * s3, hip[1] - l3 * c3 * cos_phi];
    let ankle = [knee[0] - l4 * ss, knee[1] - l4 * cs * cos_phi];
    (knee, ankle)
}

/// The (sin, cos) of a + b from those of a and of b.
#[inline]
fn add_angles((sa, ca): (f64, f64), (sb, cb): (f64, f64)) -> (f64, f64) {
    (sa * cb + ca * sb, ca * cb - sa * sb)
}

/// Hip–ankle distance of a leg with knee flexion κ, from cos κ.
pub(crate) fn reach(l3: f64, l4: f64, cos_kappa: f64) -> f64 {
    (l3 * l3 + l4 * l4 + 2.0 * l3 * l4 * cos_kappa).sqrt()
}

/// The leg chain for a hip at `hip` (with lateral offset `dz`) and an ankle at `ankle`: knee
/// flexion from the distance (0 and a gap when out of reach), thigh angle in the leg's plane.
pub(crate) struct Chain {
    pub(crate) kappa: f64,
    pub(crate) theta3: f64,
    pub(crate) knee: [f64; 2],
    pub(crate) gap: f64,
    /// (sin, cos) of θ3 and of κ.
    pub(crate) thigh: (f64, f64),
    pub(crate) knee_sc: (f64, f64),
}

impl Chain {
    /// The pose's (sin, cos) of θ3 and of θ3 + θ4 for knee flexion θ4 with (sin, cos) `knee`.
    pub(crate) fn sin_cos(&self, knee: (f64, f64)) -> [(f64, f64); 2] {
        [self.thigh, add_angles(self.thigh, knee)]
    }
}

/// [`Chain`] of a hip and an ankle. (The distances stay libm's `hypot`: near a straight knee κ
/// is the acos of nearly 1, which turns a last-bit change of d into ≈ 1e-8 rad.)
pub(crate) fn chain(l3: f64, l4: f64, hip: [f64; 2], dz: f64, ankle: [f64; 2]) -> Chain {
    let dx = hip[0] - ankle[0];
    let dv = (hip[1] - ankle[1]).hypot(dz);
    let d = dx.hypot(dv);
    let cos_k = ((d * d - l3 * l3 - l4 * l4) / (2.0 * l3 * l4)).clamp(-1.0, 1.0);
    let kappa = cos_k.acos();
    let gap = (d - (l3 + l4)).max(0.0);
    // (κ's own sine and cosine, not cos_k: the leg's points use the κ reported)
    let knee_sc = sin_cos(kappa);
    let a = reach(l3, l4, knee_sc.1);
    // thigh = hip–ankle line angle (from the downward vertical, ankle ahead −) minus β
    let line = atan2(dx, dv);
    let beta = (l4 * knee_sc.0 / a).clamp(-1.0, 1.0).asin();
    let theta3 = line - beta;
    let (s3, c3) = sin_cos(theta3);
    let knee = [hip[0] - l3 * s3, ankle[1] + dv - l3 * c3];
    Chain {
        kappa,
        theta3,
        knee,
        gap,
        thigh: (s3, c3),
        knee_sc,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::body::Body;

    /// The chain against its first form (the shank's sine and cosine from sin_cos(θ3 + κ), and
    /// libm's sin and cos) over hips near and out of reach, with and without a lateral offset:
    /// the same angles and knee to round-off.
    #[test]
    fn chain_agrees_with_hypot_and_the_shank_angle() {
        let b = Body::standard(1.8, 80.0).unwrap();
        let (l3, l4) = (b.l3, b.l4);
        let old = |hip: [f64; 2], dz: f64, ankle: [f64; 2]| {
            let dx = hip[0] - ankle[0];
            let dv = (hip[1] - ankle[1]).hypot(dz);
            let d = dx.hypot(dv);
            let cos_k = ((d * d - l3 * l3 - l4 * l4) / (2.0 * l3 * l4)).clamp(-1.0, 1.0);
            let kappa = cos_k.acos();
            let a = reach(l3, l4, kappa.cos());
            let theta3 = dx.atan2(dv) - (l4 * kappa.sin() / a).clamp(-1.0, 1.0).asin();
            let knee = [
                hip[0] - l3 * theta3.sin(),
                ankle[1] + dv - l3 * theta3.cos(),
            ];
            (kappa, theta3, knee, (d - (l3 + l4)).max(0.0))
        };
        let mut worst: f64 = 0.0;
        for i in 0..=40 {
            for j in 0..=40 {
                for dz in [0.0, 0.03, -0.08] {
                    let hip = [-0.5 + 0.025 * i as f64, 0.55 + 0.01 * j as f64];
                    let ankle = [0.05, 0.08];
                    let c = chain(l3, l4, hip, dz, ankle);
                    let (kappa, theta3, knee, gap) = old(hip, dz, ankle);
                    let [(s3, c3), (ss, cs)] = c.sin_cos(c.knee_sc);
                    let (s, co) = (theta3 + kappa).sin_cos();
                    for e in [
                        c.kappa - kappa,
                        c.theta3 - theta3,
                        c.knee[0] - knee[0],
                        c.knee[1] - knee[1],
                        c.gap - gap,
                        s3 - theta3.sin(),
                        c3 - theta3.cos(),
                        ss - s,
                        cs - co,
                    ] {
                        worst = worst.max(e.abs());
                    }
                }
            }
        }
        assert!(worst < 1e-14, "{worst}");
    }
}
