//! The two Euler sequences of the exported skeleton (spec §7 "Clinical angles"), composed and
//! decomposed exactly:
//! - ZXY, `R = R_z(a) · R_x(b) · R_y(c)`: every joint of [`crate::figure::clinical`] (about the
//!   lateral axis first, then the forward axis, then the long axis: gait2392's hip order, and the
//!   BVH channel order `Xrotation Zrotation Yrotation` once the BVH axes are mapped, see
//!   `docs/export.md`);
//! - YXZ, `R = R_y(r) · R_x(p) · R_z(q)`: the pelvis and lumbar angles of
//!   [`crate::figure::Landmarks`].
//!
//! glam 0.30's `DMat3::to_euler(EulerRot::ZXY)` and `(EulerRot::YXZ)` follow these conventions
//! (they agree within 1e-13 rad, tested below), but they take the middle angle as
//! atan2(s, √(…)) rather than asin and use libm's atan2, so their last bits differ on most
//! rotations and the exported angles would change: the decompositions here are kept.
use glam::{DMat3, DVec3};

use crate::numerics::trig::{atan2, sin_cos};

/// `R_z(a) · R_x(b) · R_y(c)`.
pub(crate) fn zxy_matrix(a: f64, b: f64, c: f64) -> DMat3 {
    DMat3::from_rotation_z(a) * DMat3::from_rotation_x(b) * DMat3::from_rotation_y(c)
}

/// The angles `[a, b, c]` with `m = R_z(a) · R_x(b) · R_y(c)`, b in [−90°, 90°].
///
/// With `m = R_z R_x R_y`: m₂₁ = sin b, (m₀₁, m₁₁) = cos b (−sin a, cos a),
/// (m₂₀, m₂₂) = cos b (−sin c, cos c).
pub(crate) fn zxy_angles(m: &DMat3) -> [f64; 3] {
    zxy_from(|i, j| m.col(j)[i])
}

/// [`zxy_angles`] of the matrix whose entry (i, j) is `r(i, j)` (only five are read).
#[inline(always)]
pub(crate) fn zxy_from(r: impl Fn(usize, usize) -> f64) -> [f64; 3] {
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
pub(crate) fn zxy_round_trip(a: f64, b: f64, c: f64) -> [f64; 3] {
    if round_trips(a, b, c) {
        [a, b, c]
    } else {
        zxy_angles(&zxy_matrix(a, b, c))
    }
}

/// [`yxz_angles`]`(&`[`yxz_matrix`]`(r, p, q))` without the matrix, as [`zxy_round_trip`].
pub(crate) fn yxz_round_trip(r: f64, p: f64, q: f64) -> [f64; 3] {
    if round_trips(r, p, q) {
        [r, p, q]
    } else {
        yxz_angles(&yxz_matrix(r, p, q))
    }
}

/// `R_y(r) · R_x(p) · R_z(q)`: the order of the pelvis and lumbar angles of
/// [`crate::figure::Landmarks`]. Multiplied out (rows of the matrix, sₐ = sin a, cₐ = cos a):
/// (c_r c_q + s_r s_p s_q, s_r s_p c_q − c_r s_q, s_r c_p),
/// (c_p s_q, c_p c_q, −s_p),
/// (c_r s_p s_q − s_r c_q, s_r s_q + c_r s_p c_q, c_r c_p),
/// with [`sin_cos`] instead of libm's for each rotation and two matrix products (this is the
/// pelvis frame of every exported frame).
pub(crate) fn yxz_matrix(r: f64, p: f64, q: f64) -> DMat3 {
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
pub(crate) fn yxz_angles(m: &DMat3) -> [f64; 3] {
    let e = |i: usize, j: usize| m.col(j)[i];
    let p = (-e(1, 2)).clamp(-1.0, 1.0).asin();
    let r = atan2(e(0, 2), e(2, 2));
    let q = atan2(e(1, 0), e(1, 1));
    [r, p, q]
}

/// The angle equal to `angle` modulo 2π that lies nearest to `reference` (rad): a heading
/// decomposed into (−π, π] carried back to the turn count of a continuous `reference`, so that
/// a figure that turns past ±180° keeps a continuous rotation.
pub(crate) fn nearest_turn(angle: f64, reference: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    let turns = ((reference - angle) / tau).round();
    // untouched when no turn is added (so that −0 stays −0)
    if turns == 0.0 {
        angle
    } else {
        angle + tau * turns
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DQuat, EulerRot};
    use std::f64::consts::FRAC_PI_2;

    fn close(a: DMat3, b: DMat3) -> bool {
        (a - b).to_cols_array().iter().all(|d| d.abs() < 1e-12)
    }

    /// The multiplied-out [`yxz_matrix`] against the product of glam's three rotations over
    /// angles in every quadrant.
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
            let g = DMat3::from_euler(EulerRot::ZXY, a, b, c);
            assert!(close(m, g));
            let m = yxz_matrix(a, b, c);
            let [x, y, z] = yxz_angles(&m);
            assert!((x - a).abs() < 1e-12 && (y - b).abs() < 1e-12 && (z - c).abs() < 1e-12);
            assert!(close(m, DMat3::from_euler(EulerRot::YXZ, a, b, c)));
        }
        // near gimbal lock the angles still recompose to the same matrix
        let m = zxy_matrix(0.4, FRAC_PI_2 - 1e-4, -0.3);
        let [a, b, c] = zxy_angles(&m);
        assert!(close(zxy_matrix(a, b, c), m));
    }

    /// The decompositions against glam's `to_euler` on random rotations (uniform unit
    /// quaternions): the same angles within 1e-12 rad, and not the same bits on most of them
    /// (the reason the module doc gives for keeping ours).
    #[test]
    fn decompositions_match_glam_to_euler_on_random_rotations() {
        // xorshift64: a fixed, dependency-free sequence
        let mut s: u64 = 0x9E37_79B9_7F4A_7C15;
        let mut uniform = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let n = 10_000;
        let mut differ = 0;
        for _ in 0..n {
            let q = DQuat::from_xyzw(uniform(), uniform(), uniform(), uniform()).normalize();
            let m = DMat3::from_quat(q);
            for (ours, order) in [
                (zxy_angles(&m), EulerRot::ZXY),
                (yxz_angles(&m), EulerRot::YXZ),
            ] {
                let (a, b, c) = m.to_euler(order);
                for (x, g) in ours.into_iter().zip([a, b, c]) {
                    assert!((x - g).abs() < 1e-12, "{order:?} {q}: {x} vs {g}");
                }
                differ += usize::from(ours != [a, b, c]);
            }
        }
        assert!(differ > n, "{differ} of {} decompositions differ", 2 * n);
    }
}
