//! The primary task and the secondary tasks of Pronost et al. §5.
//!
//! Primary: the ankles follow their targets, Δθ_m = J⁺ ΔX (eq. 2) with the damped
//! pseudo-inverse J⁺ = Jᵀ (J Jᵀ + λ² I)⁻¹, and the step Δθ = Δθ_m + (I − J⁺J) δ (eq. 3) whose
//! second term leaves the ankles still to first order. \[ours\] δ is searched in an orthonormal
//! basis V of J's null space, Δθ = Δθ_m + V c: the same set of steps as (I − J⁺J) δ over all δ
//! (the undamped projector's range is that null space), in its 5 dimensions rather than 11.
//!
//! Secondary (α = θ_t + Δθ, the posture after the step):
//! - f1 (eq. 4), the joint limits: Σᵢ e^{ξ(αᵢ − bupᵢ)} + e^{ξ(blowᵢ − αᵢ)};
//! - f2 (eq. 5, garbled in the paper), the rotational kinetic energy of the five segments:
//!   Σ_b ½ ω_bᵀ (R_b I_b R_bᵀ) ω_b with ω_b = J_ω,b Δθ / Δt, i.e. ½ Δθᵀ M Δθ / Δt² with
//!   M = Σ_b J_ω,bᵀ R_b I_b R_bᵀ J_ω,b at θ_t;
//! - f3 (eq. 6), the distance to the rest posture: ‖α − θ_r‖²;
//!
//! and z = w_limits f1 + w_energy f2 + w_rest f3 with the weights of `models/ik.toml`.
//! \[ours\] f1 and f3 are scaled by Δt_ref / Δt (Δt_ref = 1/60 s, the paper's capture rate): the
//! per-frame trade-off between kinetic energy (∝ 1/Δt²) and the postural terms then moves the
//! posture in the null space at a rate that does not depend on the frame rate (`docs/ik.md`).
use argmin::core::{CostFunction, Error as ArgminError};
use nalgebra::{SMatrix, SymmetricEigen};

use crate::ik::chain::{Angles, Ankles, DOF, Jacobian, Pose};
use crate::ik::model::IkModel;

/// The null space's dimension: 11 rotations, 6 ankle coordinates.
pub const NULL: usize = DOF - 6;

/// An orthonormal basis of the null space (columns).
pub type NullBasis = SMatrix<f64, DOF, NULL>;
/// An 11 × 11 matrix.
pub type Matrix11 = SMatrix<f64, DOF, DOF>;
/// The pseudo-inverse's shape.
pub type Inverse = SMatrix<f64, DOF, 6>;

/// The damped pseudo-inverse Jᵀ (J Jᵀ + λ² I)⁻¹ (eq. 2; damped least squares). λ = 0 gives the
/// Moore–Penrose inverse of a J of full row rank. None: J Jᵀ + λ² I is singular.
pub fn pseudo_inverse(j: &Jacobian, damping: f64) -> Option<Inverse> {
    let g = j * j.transpose() + SMatrix::<f64, 6, 6>::identity() * (damping * damping);
    let chol = g.cholesky()?;
    Some(j.transpose() * chol.inverse())
}

/// The projector I − J⁺J of eq. 3 (J⁺ undamped). None: J is rank-deficient.
pub fn null_projector(j: &Jacobian) -> Option<Matrix11> {
    let p = pseudo_inverse(j, 0.0)?;
    Some(Matrix11::identity() - p * j)
}

/// An orthonormal basis of J's null space: the eigenvectors of JᵀJ with its 5 smallest
/// eigenvalues (0 for a J of full row rank).
pub fn null_basis(j: &Jacobian) -> NullBasis {
    let eig = SymmetricEigen::new(j.transpose() * j);
    let mut order: Vec<usize> = (0..DOF).collect();
    order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
    let mut v = NullBasis::zeros();
    for (k, &i) in order[..NULL].iter().enumerate() {
        v.set_column(k, &eig.eigenvectors.column(i));
    }
    v
}

/// f1 (eq. 4): the exponential joint-limit cost of posture α.
pub fn limits_cost(model: &IkModel, alpha: &Angles) -> f64 {
    let xi = model.weights.xi;
    (0..DOF)
        .map(|i| {
            (xi * (alpha[i] - model.upper[i])).exp() + (xi * (model.lower[i] - alpha[i])).exp()
        })
        .sum()
}

/// f3 (eq. 6): the squared distance of posture α to the rest posture (rad²).
pub fn rest_cost(model: &IkModel, alpha: &Angles) -> f64 {
    (alpha - model.rest).norm_squared()
}

/// M of f2 (eq. 5) at the pose: f2 = ½ Δθᵀ M Δθ / Δt² (J), the segments' inertia tensors turned
/// into the world, R_b I_b R_bᵀ, seen through their angular Jacobians.
pub fn energy_matrix(pose: &Pose, model: &IkModel) -> Matrix11 {
    let [ip, it, is] = model.inertia;
    let frames = [
        (pose.pelvis, ip),
        (pose.right.thigh, it),
        (pose.right.shank, is),
        (pose.left.thigh, it),
        (pose.left.shank, is),
    ];
    let mut m = Matrix11::zeros();
    for (jw, (r, i)) in pose.angular_jacobians().iter().zip(frames) {
        let w = r * i * r.transpose();
        let w = SMatrix::<f64, 3, 3>::from_fn(|a, b| w.col(b)[a]);
        m += jw.transpose() * w * jw;
    }
    m
}

/// f2 (eq. 5): ½ Δθᵀ M Δθ / Δt² (J).
pub fn energy_cost(m: &Matrix11, step: &Angles, dt: f64) -> f64 {
    0.5 * (step.transpose() * m * step)[(0, 0)] / (dt * dt)
}

/// One frame's secondary problem in the null space's coordinates c: z(θ_t + Δθ_m + V c).
#[derive(Clone, Debug)]
pub struct FrameProblem<'a> {
    /// The secondary tasks' data.
    pub model: &'a IkModel,
    /// θ_t, the previous frame's posture.
    pub previous: Angles,
    /// θ_t + Δθ_m, the posture after the primary step.
    pub base: Angles,
    /// V, the null space's basis at θ_t.
    pub basis: NullBasis,
    /// M of f2 at θ_t, or None for a posture with no motion (the first frame).
    pub energy: Option<Matrix11>,
    /// Δt (s).
    pub dt: f64,
    /// The scale of f1 and f3: Δt_ref / Δt (module doc).
    pub scale: f64,
}

impl FrameProblem<'_> {
    /// The posture α for coordinates c.
    pub fn posture(&self, c: &[f64]) -> Angles {
        let c = SMatrix::<f64, NULL, 1>::from_column_slice(c);
        self.base + self.basis * c
    }

    /// z at posture α: the weighted sum of f1, f2, f3 (module doc).
    pub fn z(&self, alpha: &Angles) -> f64 {
        let w = &self.model.weights;
        let potential =
            w.limits * limits_cost(self.model, alpha) + w.rest * rest_cost(self.model, alpha);
        let kinetic = match &self.energy {
            Some(m) => w.energy * energy_cost(m, &(alpha - self.previous), self.dt),
            None => 0.0,
        };
        self.scale * potential + kinetic
    }
}

impl CostFunction for FrameProblem<'_> {
    type Param = Vec<f64>;
    type Output = f64;
    fn cost(&self, c: &Vec<f64>) -> Result<f64, ArgminError> {
        Ok(self.z(&self.posture(c)))
    }
}

/// The ankles' error X* − f(θ), and its largest coordinate (m).
pub fn error(target: &Ankles, reached: &Ankles) -> (Ankles, f64) {
    let e = target - reached;
    (e, e.amax())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ik::chain::Chain;
    use crate::model::body::Body;
    use glam::{DMat3, DVec3};

    fn setup() -> (Chain, IkModel, Angles) {
        let b = Body::standard(1.75, 70.0).unwrap();
        let theta = Angles::from_row_slice(&[
            0.12, 0.04, -0.06, 0.35, 0.05, 0.08, 0.25, -0.15, -0.02, -0.04, 0.6,
        ]);
        (Chain::new(&b), IkModel::new(&b), theta)
    }

    /// J J⁺ = I for the undamped inverse; the projector is idempotent and symmetric, J N = 0; the
    /// basis is orthonormal with J V = 0 and spans N's range (N V = V); damping shrinks the step.
    #[test]
    fn the_projections_are_what_they_claim() {
        let (c, _, theta) = setup();
        let j = c.pose(&theta).jacobian();
        let p = pseudo_inverse(&j, 0.0).unwrap();
        assert!((j * p - SMatrix::<f64, 6, 6>::identity()).amax() < 1e-12);
        let n = null_projector(&j).unwrap();
        assert!((n * n - n).amax() < 1e-12 && (n - n.transpose()).amax() < 1e-12);
        assert!((j * n).amax() < 1e-12);
        let v = null_basis(&j);
        assert!((v.transpose() * v - SMatrix::<f64, NULL, NULL>::identity()).amax() < 1e-12);
        assert!((j * v).amax() < 1e-12);
        assert!((n * v - v).amax() < 1e-12);
        let e = Ankles::from_element(0.01);
        let damped = pseudo_inverse(&j, 0.05).unwrap() * e;
        assert!(damped.norm() < (p * e).norm());
    }

    /// A step in the null space leaves the ankles still to first order: the ankles move by
    /// O(h²) (the ratio of the motions at h and h/10 is ≈ 100), where a general step of the
    /// same size moves them by O(h).
    #[test]
    fn a_null_space_step_leaves_the_ankles_still_to_first_order() {
        let (c, _, theta) = setup();
        let j = c.pose(&theta).jacobian();
        let v = null_basis(&j);
        let x0 = c.ankles(&theta);
        let dir = v * SMatrix::<f64, NULL, 1>::from_column_slice(&[0.3, -0.5, 0.2, 0.6, -0.4]);
        let dir = dir / dir.norm();
        let moved = |h: f64| (c.ankles(&(theta + dir * h)) - x0).norm();
        let (a, b) = (moved(1e-2), moved(1e-3));
        assert!((a / b - 100.0).abs() < 5.0, "{a} {b}");
        assert!(a < 1e-3, "{a}");
        // a step of the same size along the primary direction moves them in proportion
        let any = pseudo_inverse(&j, 0.0).unwrap() * Ankles::from_element(1.0);
        let any = any / any.norm();
        let m = (c.ankles(&(theta + any * 1e-3)) - x0).norm();
        assert!(m > 100.0 * b, "{m} vs {b}");
    }

    /// f2 is the segments' rotational kinetic energy, each ω_b measured independently from the
    /// change of its frame over a small step, R(θ + Δθ) R(θ)ᵀ ≈ exp([ω Δt]×).
    #[test]
    fn f2_is_the_rotational_kinetic_energy_of_the_segments() {
        let (c, model, theta) = setup();
        let pose = c.pose(&theta);
        let m = energy_matrix(&pose, &model);
        let step =
            Angles::from_row_slice(&[0.2, -0.1, 0.3, 0.5, 0.1, -0.2, -0.4, 0.3, 0.2, 0.1, 0.6])
                * 1e-5;
        let dt = 1e-3;
        let after = c.pose(&(theta + step));
        let frames = |p: &Pose| {
            [
                p.pelvis,
                p.right.thigh,
                p.right.shank,
                p.left.thigh,
                p.left.shank,
            ]
        };
        let inertias = [
            model.inertia[0],
            model.inertia[1],
            model.inertia[2],
            model.inertia[1],
            model.inertia[2],
        ];
        let mut e = 0.0;
        for ((r0, r1), i) in frames(&pose).iter().zip(frames(&after)).zip(inertias) {
            let d: DMat3 = r1 * r0.transpose();
            // the small rotation's vector: the skew part of d
            let w = DVec3::new(
                d.y_axis.z - d.z_axis.y,
                d.z_axis.x - d.x_axis.z,
                d.x_axis.y - d.y_axis.x,
            ) * (0.5 / dt);
            let world = *r0 * i * r0.transpose();
            e += 0.5 * w.dot(world * w);
        }
        let f2 = energy_cost(&m, &step, dt);
        assert!((f2 - e).abs() < 1e-4 * e, "{f2} vs {e}");
        // M is symmetric positive definite
        let eig = SymmetricEigen::new(m);
        assert!(eig.eigenvalues.min() > 0.0 && (m - m.transpose()).amax() < 1e-12);
    }

    /// f1 is 2·e^{−ξ·half range} summed at mid-range, rises as e^{ξ d} past a limit, and f3 is
    /// the squared distance (hand-worked values).
    #[test]
    fn the_postural_costs_by_hand() {
        let (_, model, _) = setup();
        let mid = (model.lower + model.upper) / 2.0;
        let xi = model.weights.xi;
        let expect: f64 = (0..DOF)
            .map(|i| 2.0 * (-xi * (model.upper[i] - model.lower[i]) / 2.0).exp())
            .sum();
        assert!((limits_cost(&model, &mid) - expect).abs() < 1e-15);
        let mut past = model.rest;
        past[6] = -0.05; // the right knee 0.05 rad past full extension
        let f = limits_cost(&model, &past) - limits_cost(&model, &model.rest);
        assert!(f > (xi * 0.05).exp() - 1.0, "{f}");
        let mut off = model.rest;
        off[0] += 0.1;
        off[9] -= 0.2;
        assert!((rest_cost(&model, &off) - 0.05).abs() < 1e-15);
    }
}
