//! Stance model (KLAW 1989 §2.3, Appendix A.1, Figure 2): an inverted pendulum with a telescopic
//! leg of length w pivoting at the ankle, and the upper body (head, arms, trunk) on top at the hip.
//! Generalized coordinates q = (w, θ1, θ2): θ1 the leg from the upward vertical (hip ahead of the
//! ankle +), θ2 the upper body from the upward vertical (leaning forward +).
//!
//! With s = sin, c = cos, s12 = sin(θ1 − θ2), c12 = cos(θ1 − θ2), a = r2 (hip to upper-body
//! centre of mass), J1 = m1 r1² + I1 (leg about the ankle), J2 = m2 a² + I2 (upper body about the
//! hip), the Lagrangian L = T − V with
//!   T = ½ J1 θ̇1² + ½ m2 (ẇ² + w² θ̇1² + a² θ̇2² + 2 a ẇ θ̇2 s12 + 2 a w θ̇1 θ̇2 c12) + ½ I2 θ̇2²,
//!   V = m1 g (l9 + r1 c1) + m2 g (l9 + w c1 + a c2)
//! gives M q̈ + b = Q with
//!   M = [[m2, 0, m2 a s12], [0, J1 + m2 w², m2 a w c12], [m2 a s12, m2 a w c12, J2]],
//!   b1 = −m2 w θ̇1² − m2 a c12 θ̇2² + m2 g c1,
//!   b2 = 2 m2 w ẇ θ̇1 + m2 a w s12 θ̇2² − (m1 r1 + m2 w) g s1,
//!   b3 = 2 m2 a c12 ẇ θ̇1 − m2 a w s12 θ̇1² − m2 g a s2.
use nalgebra::{Matrix2, Matrix3, Vector2, Vector3};

use crate::model::GRAVITY;
use crate::model::body::Body;
use crate::numerics::trig::sin_cos;

/// Inertial parameters of the stance model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StanceModel {
    /// Leg mass m1 = m3 + m4 (kg).
    pub(crate) m1: f64,
    /// Upper-body mass m2 (kg).
    pub m2: f64,
    /// Leg centre of mass from the ankle, r1 (m).
    pub(crate) r1: f64,
    /// Leg moment of inertia about the ankle, J1 = m1 r1² + I1 (kg m²).
    pub(crate) j1: f64,
    /// Hip to upper-body centre of mass, a = r2 (m).
    pub a: f64,
    /// Upper-body moment of inertia about its centre of mass, I2 (kg m²).
    pub(crate) i2: f64,
    /// Ankle pivot height l9 (m).
    pub(crate) l9: f64,
    /// Gravity (m/s²).
    pub g: f64,
}

impl StanceModel {
    /// The stance model of `body` (Table B-1 values; spec §4).
    pub fn new(body: &Body) -> Self {
        StanceModel {
            m1: body.m1,
            m2: body.m2,
            r1: body.r1,
            j1: body.m1 * body.r1 * body.r1 + body.i1,
            a: body.r2,
            i2: body.i2,
            l9: body.l9,
            g: GRAVITY,
        }
    }

    /// Upper-body moment of inertia about the hip, J2 = m2 a² + I2.
    pub(crate) fn trunk_inertia(&self) -> f64 {
        self.m2 * self.a * self.a + self.i2
    }

    /// Mass matrix M(q) of the telescopic model.
    pub fn mass_matrix(&self, q: &Vector3<f64>) -> Matrix3<f64> {
        let tr = Trig::new(q[1], q[2]);
        let (w, s12, c12) = (q[0], tr.s12, tr.c12);
        let m2a = self.m2 * self.a;
        Matrix3::new(
            self.m2,
            0.0,
            m2a * s12,
            0.0,
            self.j1 + self.m2 * w * w,
            m2a * w * c12,
            m2a * s12,
            m2a * w * c12,
            self.trunk_inertia(),
        )
    }

    /// Bias terms b(q, q̇): centrifugal, Coriolis and gravity, M q̈ + b = Q.
    pub fn bias(&self, q: &Vector3<f64>, qd: &Vector3<f64>) -> Vector3<f64> {
        self.bias_with(&Trig::new(q[1], q[2]), q, qd)
    }

    fn bias_with(&self, tr: &Trig, q: &Vector3<f64>, qd: &Vector3<f64>) -> Vector3<f64> {
        let w = q[0];
        let (wd, t1d, t2d) = (qd[0], qd[1], qd[2]);
        let (s1, c1, s2, s12, c12) = (tr.s1, tr.c1, tr.s2, tr.s12, tr.c12);
        let (m2, a, g) = (self.m2, self.a, self.g);
        Vector3::new(
            -m2 * w * t1d * t1d - m2 * a * c12 * t2d * t2d + m2 * g * c1,
            2.0 * m2 * w * wd * t1d + m2 * a * w * s12 * t2d * t2d
                - (self.m1 * self.r1 + m2 * w) * g * s1,
            2.0 * m2 * a * c12 * wd * t1d - m2 * a * w * s12 * t1d * t1d - m2 * g * a * s2,
        )
    }

    /// Accelerations q̈ = M⁻¹ (Q − b). With `locked` the leg length is held (ẇ = ẅ = 0; the
    /// paper's locked-leg edit: the w row and column drop out) and q̈\[0\] = 0.
    pub fn accelerations(
        &self,
        q: &Vector3<f64>,
        qd: &Vector3<f64>,
        force: &Vector3<f64>,
        locked: bool,
    ) -> Vector3<f64> {
        let (s1, c1) = sin_cos(q[1]);
        self.accelerations_with(s1, c1, q, qd, force, locked)
    }

    /// [`Self::accelerations`] with sin θ1 and cos θ1 already known (the stance right-hand side
    /// needs them for its forces too). M is solved by its structure — M[0][1] = 0 — with the
    /// Schur complement of the θ2 row: three reciprocals, no factorization, no allocation.
    pub(crate) fn accelerations_with(
        &self,
        s1: f64,
        c1: f64,
        q: &Vector3<f64>,
        qd: &Vector3<f64>,
        force: &Vector3<f64>,
        locked: bool,
    ) -> Vector3<f64> {
        let tr = Trig::with(s1, c1, q[2]);
        let r = force - self.bias_with(&tr, q, qd);
        let w = q[0];
        let m2a = self.m2 * self.a;
        let (m02, m12) = (m2a * tr.s12, m2a * w * tr.c12);
        let m11 = self.j1 + self.m2 * w * w;
        let j2 = self.trunk_inertia();
        // the reciprocals depend on q alone, so they are ready before the forces: one division
        // waits for them (the unlocked t2dd), where three did in a chain
        if locked {
            // rows θ1, θ2 of M (Cramer's rule)
            let inv_det = 1.0 / (m11 * j2 - m12 * m12);
            Vector3::new(
                0.0,
                (r[1] * j2 - m12 * r[2]) * inv_det,
                (m11 * r[2] - m12 * r[1]) * inv_det,
            )
        } else {
            let (inv_m2, inv_m11) = (1.0 / self.m2, 1.0 / m11);
            let (e0, e1) = (m02 * inv_m2, m12 * inv_m11);
            let t2dd = (r[2] - e0 * r[0] - e1 * r[1]) / (j2 - e0 * m02 - e1 * m12);
            Vector3::new(
                (r[0] - m02 * t2dd) * inv_m2,
                (r[1] - m12 * t2dd) * inv_m11,
                t2dd,
            )
        }
    }

    /// Kinetic energy T(q, q̇).
    pub fn kinetic_energy(&self, q: &Vector3<f64>, qd: &Vector3<f64>) -> f64 {
        0.5 * qd.dot(&(self.mass_matrix(q) * qd))
    }

    /// Gravitational potential energy V(q), ground at y = 0.
    pub fn potential_energy(&self, q: &Vector3<f64>) -> f64 {
        let (w, c1, c2) = (q[0], q[1].cos(), q[2].cos());
        self.g * (self.m1 * (self.l9 + self.r1 * c1) + self.m2 * (self.l9 + w * c1 + self.a * c2))
    }

    /// Hip relative to the ankle pivot's x, absolute height: (w sin θ1, l9 + w cos θ1).
    pub fn hip(&self, q: &Vector3<f64>) -> [f64; 2] {
        let (s1, c1) = sin_cos(q[1]);
        [q[0] * s1, self.l9 + q[0] * c1]
    }

    /// Hip velocity ẇ (s1, c1) + w θ̇1 (c1, −s1).
    pub fn hip_velocity(&self, q: &Vector3<f64>, qd: &Vector3<f64>) -> [f64; 2] {
        let (s1, c1) = sin_cos(q[1]);
        [
            qd[0] * s1 + q[0] * qd[1] * c1,
            qd[0] * c1 - q[0] * qd[1] * s1,
        ]
    }

    /// Hip acceleration from q, q̇ and q̈ (second derivative of [`Self::hip`]).
    pub fn hip_acceleration(
        &self,
        q: &Vector3<f64>,
        qd: &Vector3<f64>,
        qdd: &Vector3<f64>,
    ) -> [f64; 2] {
        let (s1, c1) = sin_cos(q[1]);
        self.hip_acceleration_with(s1, c1, q, qd, qdd)
    }

    /// [`Self::hip_acceleration`] with sin θ1 and cos θ1 already known.
    pub(crate) fn hip_acceleration_with(
        &self,
        s1: f64,
        c1: f64,
        q: &Vector3<f64>,
        qd: &Vector3<f64>,
        qdd: &Vector3<f64>,
    ) -> [f64; 2] {
        let (w, wd, wdd) = (q[0], qd[0], qdd[0]);
        let (t1d, t1dd) = (qd[1], qdd[1]);
        [
            wdd * s1 + 2.0 * wd * t1d * c1 + w * t1dd * c1 - w * t1d * t1d * s1,
            wdd * c1 - 2.0 * wd * t1d * s1 - w * t1dd * s1 - w * t1d * t1d * c1,
        ]
    }
}

/// sin and cos of θ1, θ2 and θ1 − θ2 from two `sin_cos` calls.
struct Trig {
    s1: f64,
    c1: f64,
    s2: f64,
    s12: f64,
    c12: f64,
}

impl Trig {
    fn new(theta1: f64, theta2: f64) -> Self {
        let (s1, c1) = sin_cos(theta1);
        Self::with(s1, c1, theta2)
    }

    fn with(s1: f64, c1: f64, theta2: f64) -> Self {
        let (s2, c2) = sin_cos(theta2);
        Trig {
            s1,
            c1,
            s2,
            s12: s1 * c2 - c1 * s2,
            c12: c1 * c2 + s1 * s2,
        }
    }
}

/// Solve a symmetric positive definite 3×3 system (stack only: the right-hand side of the
/// integrator must not allocate).
pub(crate) fn solve3(m: &Matrix3<f64>, rhs: &Vector3<f64>) -> Vector3<f64> {
    match m.cholesky() {
        Some(ch) => ch.solve(rhs),
        None => Vector3::repeat(f64::NAN),
    }
}

/// Solve a 2×2 system by Cramer's rule (the determinant's reciprocal needs only `m`, so in a
/// right-hand side it is ready before `rhs`).
pub(crate) fn solve2(m: &Matrix2<f64>, rhs: &Vector2<f64>) -> Vector2<f64> {
    let inv_det = 1.0 / (m[(0, 0)] * m[(1, 1)] - m[(0, 1)] * m[(1, 0)]);
    Vector2::new(
        (rhs[0] * m[(1, 1)] - m[(0, 1)] * rhs[1]) * inv_det,
        (m[(0, 0)] * rhs[1] - m[(1, 0)] * rhs[0]) * inv_det,
    )
}
