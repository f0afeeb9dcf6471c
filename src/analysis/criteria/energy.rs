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
    /// Kinetic energy relative to the centre of mass, per group: the upper body, the right leg, the left leg.
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
    let differences = |xs: Vec<DVec3>| -> Vec<DVec3> {
        let d: [Vec<f64>; 3] = std::array::from_fn(|i| {
            first_derivative(&xs.iter().map(|x| x[i]).collect::<Vec<_>>(), h)
        });
        (0..n)
            .map(|k| DVec3::new(d[0][k], d[1][k], d[2][k]))
            .collect()
    };
    let v: [Vec<DVec3>; 5] =
        std::array::from_fn(|s| differences(placed.iter().map(|p| p[s].com).collect()));
    let rates: [Vec<DMat3>; 5] = std::array::from_fn(|s| {
        let cols: [Vec<DVec3>; 3] =
            std::array::from_fn(|j| differences(placed.iter().map(|p| p[s].axes.col(j)).collect()));
        (0..n)
            .map(|k| DMat3::from_cols(cols[0][k], cols[1][k], cols[2][k]))
            .collect()
    });
    let total: f64 = segments.mass.iter().sum();
    (0..n)
        .map(|k| {
            let p = &placed[k];
            let rotation: [f64; 5] = std::array::from_fn(|s| {
                let w = angular_velocity(&p[s].axes, &rates[s][k]);
                let along = w.dot(p[s].axes.y_axis);
                0.5 * segments.inertia[s] * (w.length_squared() - along * along)
            });
            let momentum: DVec3 = (0..5).map(|s| segments.mass[s] * v[s][k]).sum();
            let v_g = momentum / total;
            let height: f64 = (0..5).map(|s| segments.mass[s] * p[s].com.y).sum::<f64>() / total;
            let kinetic = (0..5)
                .map(|s| 0.5 * segments.mass[s] * v[s][k].length_squared() + rotation[s])
                .sum();
            let potential = total * GRAVITY * height;
            let internal = GROUPS.map(|g| {
                g.iter()
                    .map(|&s| {
                        0.5 * segments.mass[s] * (v[s][k] - v_g).length_squared() + rotation[s]
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

#[cfg(test)]
mod tests {
    use super::super::segments::pose;
    use super::*;
    use crate::figure::clinical::Clinical;
    use crate::model::body::Body;

    /// A frame turning about a fixed unit axis a at rate ω has angular velocity ω a, whatever
    /// its starting orientation (finite differences of the axes, to O(h²)).
    #[test]
    fn angular_velocity_of_a_steady_turn() {
        let a = DVec3::new(0.3, -0.5, 0.8).normalize();
        let (w, h) = (2.5, 1e-4);
        let start = DMat3::from_euler(glam::EulerRot::ZXY, 0.4, -0.2, 1.1);
        let at = |t: f64| DMat3::from_axis_angle(a, w * t) * start;
        let rate = (at(0.3 + h) - at(0.3 - h)) * (0.5 / h);
        let got = angular_velocity(&at(0.3), &rate);
        assert!((got - w * a).length() < 1e-6, "{got}");
    }

    /// A straight leg turning about its own long axis (hip rotation at 2 rad/s, everything else
    /// still) has no kinetic energy: the segments have no inertia about their long axes.
    #[test]
    fn a_leg_spinning_about_its_axis_has_no_energy() {
        let body = Body::standard(1.8, 80.0).unwrap();
        let h = 0.01;
        let poses: Vec<_> = (0..20)
            .map(|k| {
                let mut c = Clinical {
                    pelvis: [0.0, 1.0, 0.0],
                    ..Default::default()
                };
                c.right.hip.rotation = 2.0 * k as f64 * h;
                pose(&c)
            })
            .collect();
        for e in energies(&poses, h, &Segments::new(&body)) {
            assert!(e.kinetic.abs() < 1e-20, "{e:?}");
        }
        // turned about a transverse axis instead (hip flexion), it has ½ I ω² and more
        let poses: Vec<_> = (0..20)
            .map(|k| {
                let mut c = Clinical {
                    pelvis: [0.0, 1.0, 0.0],
                    ..Default::default()
                };
                c.right.hip.adduction = 2.0 * k as f64 * h;
                pose(&c)
            })
            .collect();
        let e = energies(&poses, h, &Segments::new(&body));
        assert!(
            e[10].kinetic > 0.5 * (body.i3 + body.i4) * 4.0,
            "{:?}",
            e[10]
        );
    }
}
