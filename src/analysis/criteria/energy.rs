//! C3, the mechanical power of a gait cycle per unit body mass (Pronost et al. 2006, eqs. 10–11),
//! from the energies of the body's five segments ([`super::segments`]) at the frames of a uniform
//! grid, their velocities by second-order finite differences (`numerics::sampled`).
//!
//! At each frame k: segment s has mass mₛ, centre-of-mass velocity vₛ, angular velocity ωₛ
//! (the axial part of Ṙ Rᵀ) and transverse inertia Iₛ, so its kinetic energy is
//! ½ mₛ |vₛ|² + ½ Iₛ (|ωₛ|² − (ωₛ · yₛ)²) (no inertia about its long axis yₛ). Sums over the
//! n intervals of the cycle, divided by M T (T = n h):
//! - `literal`: Σₖ |ΔE_k − M g Δh|, eq. 10 as printed (E_k the segments' kinetic energy in the
//!   world, h the height of the centre of mass), summed per eq. 11;
//! - `mechanical`: Σₖ |Δ(E_k + M g h)|, the same with the sign of the work–energy theorem (the
//!   changes of the body's total mechanical energy, Burdett et al. 1983's indirect method);
//! - `internal`: Willems, Cavagna & Heglund 1995's internal work: the kinetic energy of the
//!   segments relative to the centre of mass, E_int = Σ ½ mₛ |vₛ − v_G|² + rotation, summed over
//!   three groups (the upper body, each leg: energy moves freely between the segments of a leg,
//!   not between the legs and the trunk), its increases counted: Σ_groups Σₖ max(ΔE_int, 0);
//! - `external`: their external work, the increases of the centre of mass's energy
//!   ½ M |v_G|² + M g h: Σₖ max(ΔE_ext, 0).
use glam::{DMat3, DVec3};
use serde::Serialize;

use super::segments::{POSE, Placed, Segments};
use crate::model::GRAVITY;
use crate::numerics::sampled::first_derivative;

/// Mechanical power per unit mass over a cycle (W/kg); the module doc defines each.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Power {
    /// Eqs. 10–11 as printed: Σ |ΔE_k − M g Δh| / (M T).
    pub literal: f64,
    /// Σ |Δ(E_k + M g h)| / (M T): the work–energy theorem's sign.
    pub mechanical: f64,
    /// Willems et al. 1995's internal power.
    pub internal: f64,
    /// Willems et al. 1995's external power.
    pub external: f64,
}

/// The groups of segments between which no energy is transferred (Willems et al. 1995): the
/// upper body, the right leg, the left leg (indices of `SEGMENT_NAMES`).
const GROUPS: [&[usize]; 3] = [&[0], &[1, 2], &[3, 4]];

/// Energies of the body at one frame (J).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Energies {
    /// The segments' kinetic energy, translation and rotation, in the world.
    pub kinetic: f64,
    /// The segments' potential energy, M g h_G.
    pub potential: f64,
    /// Kinetic energy relative to the centre of mass, per group of [`GROUPS`].
    pub internal: [f64; 3],
    /// The centre of mass's kinetic and potential energy.
    pub external: f64,
}

/// The angular velocity ω of a frame turning at Ṙ: the axial vector of the skew part of Ṙ Rᵀ.
pub fn angular_velocity(axes: &DMat3, rate: &DMat3) -> DVec3 {
    let w = *rate * axes.transpose();
    // w.col(j)[i] is the entry (i, j)
    0.5 * DVec3::new(
        w.col(1).z - w.col(2).y,
        w.col(2).x - w.col(0).z,
        w.col(0).y - w.col(1).x,
    )
}

/// The energies at every frame of `poses` (spaced `h` apart) of the body of `segments`.
pub fn energies(poses: &[[f64; POSE]], h: f64, segments: &Segments) -> Vec<Energies> {
    let placed: Vec<[Placed; 5]> = poses.iter().map(|p| segments.place(p)).collect();
    let n = placed.len();
    // velocities: finite differences of every coordinate of every segment's centre and axes
    let derivative = |get: &dyn Fn(&[Placed; 5]) -> f64| {
        first_derivative(&placed.iter().map(get).collect::<Vec<_>>(), h)
    };
    let mut v = vec![[DVec3::ZERO; 5]; n];
    let mut rates = vec![[DMat3::ZERO; 5]; n];
    for s in 0..5 {
        for i in 0..3 {
            for (k, d) in derivative(&|p| p[s].com[i]).into_iter().enumerate() {
                v[k][s][i] = d;
            }
            for j in 0..3 {
                for (k, d) in derivative(&|p| p[s].axes.col(j)[i]).into_iter().enumerate() {
                    rates[k][s].col_mut(j)[i] = d;
                }
            }
        }
    }
    let total: f64 = segments.mass.iter().sum();
    (0..n)
        .map(|k| {
            let p = &placed[k];
            let rotation: [f64; 5] = std::array::from_fn(|s| {
                let w = angular_velocity(&p[s].axes, &rates[k][s]);
                let along = w.dot(p[s].axes.y_axis);
                0.5 * segments.inertia[s] * (w.length_squared() - along * along)
            });
            let momentum: DVec3 = (0..5).map(|s| segments.mass[s] * v[k][s]).sum();
            let v_g = momentum / total;
            let height: f64 = (0..5).map(|s| segments.mass[s] * p[s].com.y).sum::<f64>() / total;
            let kinetic = (0..5)
                .map(|s| 0.5 * segments.mass[s] * v[k][s].length_squared() + rotation[s])
                .sum();
            let potential = total * GRAVITY * height;
            let internal = GROUPS.map(|g| {
                g.iter()
                    .map(|&s| {
                        0.5 * segments.mass[s] * (v[k][s] - v_g).length_squared() + rotation[s]
                    })
                    .sum()
            });
            Energies {
                kinetic,
                potential,
                internal,
                external: 0.5 * total * v_g.length_squared() + potential,
            }
        })
        .collect()
}

/// C3 over the frames `e` (one cycle, `e.len() − 1` intervals of `h`) of a body of mass `mass`.
pub fn power(e: &[Energies], h: f64, mass: f64) -> Power {
    let mut sum = Power::default();
    for w in e.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        let (dk, dp) = (b.kinetic - a.kinetic, b.potential - a.potential);
        sum.literal += (dk - dp).abs();
        sum.mechanical += (dk + dp).abs();
        sum.internal += (0..3)
            .map(|g| (b.internal[g] - a.internal[g]).max(0.0))
            .sum::<f64>();
        sum.external += (b.external - a.external).max(0.0);
    }
    let scale = 1.0 / (mass * h * e.len().saturating_sub(1) as f64);
    Power {
        literal: sum.literal * scale,
        mechanical: sum.mechanical * scale,
        internal: sum.internal * scale,
        external: sum.external * scale,
    }
}
