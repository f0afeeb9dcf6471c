//! Swing model (KLAW 1989 §2.3, Appendix A.2): a double pendulum (thigh, shank with the foot)
//! hanging from a hip that moves on a prescribed path (x_h(t), y_h(t)). Coordinates
//! q = (θ3, θ4): θ3 the thigh from the downward vertical (negative: knee ahead of the hip),
//! θ4 the knee flexion (relative); the shank's absolute angle is φ = θ3 + θ4.
//! Knee = hip + l3 (−sin θ3, −cos θ3); ankle = knee + l4 (−sin φ, −cos φ).
//!
//! With K = m3 r3 + m4 l3, C = m4 l3 r4 (r3, r4 absolute distances from the proximal joints),
//! Lagrange gives M q̈ + b = Q with
//!   a11 = I3 + m3 r3² + m4 l3² + I4 + m4 r4² + 2 C cos θ4   (as the scan of A.2 prints it),
//!   a12 = I4 + m4 r4² + C cos θ4,  a22 = I4 + m4 r4²,
//!   b1 = −C sin θ4 (2 θ̇3 θ̇4 + θ̇4²) + (g + ÿ_h)(K sin θ3 + m4 r4 sin φ) − ẍ_h (K cos θ3 + m4 r4 cos φ),
//!   b2 = C sin θ4 θ̇3² + (g + ÿ_h) m4 r4 sin φ − ẍ_h m4 r4 cos φ.
//! The hip terms are the scan's forcing K (ẍ_h cos θ3 − ÿ_h sin θ3) and −m3 g r3 sin θ3 moved to
//! the left-hand side, plus the shank's share.
use nalgebra::{Matrix2, Vector2};

use crate::dynamics::stance::solve2;
use crate::model::GRAVITY;
use crate::model::body::Body;
use crate::numerics::trig::sin_cos;

/// Inertial parameters of the swing leg.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SwingModel {
    /// Thigh mass m3 (kg).
    pub m3: f64,
    /// Shank and foot mass m4 (kg).
    pub m4: f64,
    /// Thigh length l3 (m).
    pub l3: f64,
    /// Shank length l4 (m).
    pub(crate) l4: f64,
    /// Hip to thigh centre of mass (m).
    pub r3: f64,
    /// Knee to shank centre of mass (m).
    pub r4: f64,
    /// Thigh moment of inertia about its centre of mass, I3 (kg m²).
    pub(crate) i3: f64,
    /// Shank moment of inertia about its centre of mass, I4 (kg m²).
    pub(crate) i4: f64,
    /// Gravity (m/s²).
    pub g: f64,
}

impl SwingModel {
    /// The swing leg of `body` (Table B-1 values; spec §5).
    pub fn new(body: &Body) -> Self {
        SwingModel {
            m3: body.m3,
            m4: body.m4,
            l3: body.l3,
            l4: body.l4,
            r3: body.r3,
            r4: body.r4,
            i3: body.i3,
            i4: body.i4,
            g: GRAVITY,
        }
    }

    /// Mass matrix in relative coordinates (θ3, θ4).
    pub fn mass_matrix(&self, q: &Vector2<f64>) -> Matrix2<f64> {
        self.mass_matrix_c4(q[1].cos())
    }

    fn mass_matrix_c4(&self, c4: f64) -> Matrix2<f64> {
        let c = self.m4 * self.l3 * self.r4 * c4;
        let shank = self.i4 + self.m4 * self.r4 * self.r4;
        let a11 =
            self.i3 + self.m3 * self.r3 * self.r3 + self.m4 * self.l3 * self.l3 + shank + 2.0 * c;
        Matrix2::new(a11, shank + c, shank + c, shank)
    }

    /// Bias terms for a hip accelerating at `hip_acc` = (ẍ_h, ÿ_h).
    pub fn bias(&self, q: &Vector2<f64>, qd: &Vector2<f64>, hip_acc: [f64; 2]) -> Vector2<f64> {
        self.bias_with(&Trig::new(q), qd, hip_acc)
    }

    fn bias_with(&self, tr: &Trig, qd: &Vector2<f64>, hip_acc: [f64; 2]) -> Vector2<f64> {
        let (s3, c3, s4, sp, cp) = (tr.s3, tr.c3, tr.s4, tr.sp, tr.cp);
        let (t3d, t4d) = (qd[0], qd[1]);
        let k = self.m3 * self.r3 + self.m4 * self.l3;
        let c = self.m4 * self.l3 * self.r4;
        let mr4 = self.m4 * self.r4;
        let gy = self.g + hip_acc[1];
        let ax = hip_acc[0];
        Vector2::new(
            -c * s4 * (2.0 * t3d * t4d + t4d * t4d) + gy * (k * s3 + mr4 * sp)
                - ax * (k * c3 + mr4 * cp),
            c * s4 * t3d * t3d + gy * mr4 * sp - ax * mr4 * cp,
        )
    }

    /// q̈ = M⁻¹ (Q − b). With `locked` the knee is held (θ̇4 = θ̈4 = 0): a single pendulum.
    /// Two `sin_cos` calls (θ3, θ4; the shank's angle by the addition formulas), no allocation.
    pub fn accelerations(
        &self,
        q: &Vector2<f64>,
        qd: &Vector2<f64>,
        torque: &Vector2<f64>,
        hip_acc: [f64; 2],
        locked: bool,
    ) -> Vector2<f64> {
        let tr = Trig::new(q);
        let m = self.mass_matrix_c4(tr.c4);
        let rhs = torque - self.bias_with(&tr, qd, hip_acc);
        if locked {
            // the reciprocal depends on q alone: ready before the torques
            Vector2::new(rhs[0] * (1.0 / m[(0, 0)]), 0.0)
        } else {
            solve2(&m, &rhs)
        }
    }

    /// Kinetic energy with the hip at rest.
    pub fn kinetic_energy(&self, q: &Vector2<f64>, qd: &Vector2<f64>) -> f64 {
        0.5 * qd.dot(&(self.mass_matrix(q) * qd))
    }

    /// Potential energy relative to the hip height.
    pub fn potential_energy(&self, q: &Vector2<f64>) -> f64 {
        let c3 = q[0].cos();
        let cp = (q[0] + q[1]).cos();
        -self.g * (self.m3 * self.r3 * c3 + self.m4 * (self.l3 * c3 + self.r4 * cp))
    }

    /// Knee and ankle for a hip at `hip`.
    pub fn joints(&self, hip: [f64; 2], q: &Vector2<f64>) -> ([f64; 2], [f64; 2]) {
        let (s3, c3) = sin_cos(q[0]);
        let (sp, cp) = sin_cos(q[0] + q[1]);
        let knee = [hip[0] - self.l3 * s3, hip[1] - self.l3 * c3];
        (knee, [knee[0] - self.l4 * sp, knee[1] - self.l4 * cp])
    }

    /// Ankle velocity relative to the hip: J(q) q̇.
    pub fn ankle_velocity(&self, q: &Vector2<f64>, qd: &Vector2<f64>) -> [f64; 2] {
        let j = self.ankle_jacobian(q);
        let v = j * qd;
        [v[0], v[1]]
    }

    /// Jacobian of the ankle position (relative to the hip) with respect to (θ3, θ4).
    pub fn ankle_jacobian(&self, q: &Vector2<f64>) -> Matrix2<f64> {
        let (s3, c3) = sin_cos(q[0]);
        let (sp, cp) = sin_cos(q[0] + q[1]);
        Matrix2::new(
            -self.l3 * c3 - self.l4 * cp,
            -self.l4 * cp,
            self.l3 * s3 + self.l4 * sp,
            self.l4 * sp,
        )
    }
}

/// sin and cos of θ3, θ4 and φ = θ3 + θ4 from two `sin_cos` calls.
struct Trig {
    s3: f64,
    c3: f64,
    s4: f64,
    c4: f64,
    sp: f64,
    cp: f64,
}

impl Trig {
    fn new(q: &Vector2<f64>) -> Self {
        let (s3, c3) = sin_cos(q[0]);
        let (s4, c4) = sin_cos(q[1]);
        Trig {
            s3,
            c3,
            s4,
            c4,
            sp: s3 * c4 + c3 * s4,
            cp: c3 * c4 - s3 * s4,
        }
    }
}
