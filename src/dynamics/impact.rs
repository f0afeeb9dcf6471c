//! Collisions: the heel-strike impulse (KLAW 1989 §4: the new stance leg's initial conditions
//! "from the conservation of momentum", made precise in the spec §7) and the knee lock at the end
//! of swing2 (spec §5).
use nalgebra::{Vector2, Vector3};
use serde::Serialize;

use crate::dynamics::stance::{StanceModel, solve3};
use crate::dynamics::swing::SwingModel;

/// What a heel strike did.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ImpactReport {
    /// Kinetic energy lost, ½ ẇ⁻² / (M⁻¹)_ww (J).
    pub energy_lost: f64,
    /// Hip speed after / before the impact.
    pub speed_ratio: f64,
}

/// Stance-model rates of a hip moving at `hip_velocity` about a pivot, in the coordinates
/// q = (w, θ1, θ2) of that pivot: ẇ = v·(s1, c1), θ̇1 = v·(c1, −s1)/w; the trunk rate is kept.
pub fn rates_about_pivot(
    q: &Vector3<f64>,
    hip_velocity: [f64; 2],
    trunk_rate: f64,
) -> Vector3<f64> {
    let (s1, c1) = q[1].sin_cos();
    let [vx, vy] = hip_velocity;
    Vector3::new(vx * s1 + vy * c1, (vx * c1 - vy * s1) / q[0], trunk_rate)
}

/// Heel-strike impulse along the new stance leg (spec §7, \[ours\]: a fraction of the plastic
/// one): with the pre-impact rates q̇⁻ written about the new pivot,
/// q̇⁺ = q̇⁻ − ρ M⁻¹ e_w ẇ⁻ / (e_wᵀ M⁻¹ e_w), e_w = (1, 0, 0), 0 ≤ ρ ≤ 1 (`fraction`, the
/// attribute heel_strike_impulse). Afterwards ẇ⁺ = (1 − ρ) ẇ⁻, and p_θ1, p_θ2 (components of
/// M q̇) are unchanged; the energy lost is ρ (2 − ρ) · ½ ẇ⁻² / (M⁻¹)_ww. ρ = 1 is the plastic
/// impulse that stops the leg axis (ẇ⁺ = 0); with ρ < 1 the leg keeps shortening into the
/// loading response, where the stance servo absorbs the rest (KLAW 1989 §4: the new stance
/// from the conservation of momentum).
pub fn heel_strike(
    model: &StanceModel,
    q: &Vector3<f64>,
    qd_minus: &Vector3<f64>,
    fraction: f64,
) -> (Vector3<f64>, ImpactReport) {
    let m = model.mass_matrix(q);
    let minv_ew = solve3(&m, &Vector3::new(1.0, 0.0, 0.0));
    let wd = qd_minus[0];
    let qd_plus = qd_minus - minv_ew * (fraction * wd / minv_ew[0]);
    let speed = |qd: &Vector3<f64>| {
        let [x, y] = model.hip_velocity(q, qd);
        x.hypot(y)
    };
    let report = ImpactReport {
        energy_lost: fraction * (2.0 - fraction) * 0.5 * wd * wd / minv_ew[0],
        speed_ratio: speed(&qd_plus) / speed(qd_minus),
    };
    (qd_plus, report)
}

/// Knee lock at θ4 = κ_hs (spec §5 swing2 → swing3): θ̇4 → 0 and
/// θ̇3 → (a11 θ̇3 + a12 θ̇4) / a11, which keeps the leg's angular momentum about the hip.
pub fn knee_lock(model: &SwingModel, q: &Vector2<f64>, qd: &Vector2<f64>) -> Vector2<f64> {
    let m = model.mass_matrix(q);
    Vector2::new((m[(0, 0)] * qd[0] + m[(0, 1)] * qd[1]) / m[(0, 0)], 0.0)
}
