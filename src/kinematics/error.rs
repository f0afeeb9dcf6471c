//! The geometric constructions of the lower body that can fail.

/// A pose the virtual stance leg cannot take (KLAW 1989 §4.2, the foot rules of spec §7).
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum GeometryError {
    /// After heel-off the rolling foot's pitch has no solution: neither about the metatarsal
    /// joint nor about the toe tip does the ankle come within `distance` (m), the hip–ankle
    /// distance of the prescribed knee flexion (rad), of the hip.
    #[error(
        "the rolling foot cannot reach the hip: hip–ankle distance {distance:.4} m for knee flexion {:.1}° is out of reach",
        knee_flexion.to_degrees()
    )]
    RollingFootOutOfReach {
        /// The hip–ankle distance the knee flexion gives (in m).
        distance: f64,
        /// The prescribed knee flexion (in rad).
        knee_flexion: f64,
    },
    /// The hip passes over the stance ankle `gap` (m) beyond the straight leg's reach from the
    /// flat foot: the foot cannot turn from its heel onto its metatarsal joint without its pitch
    /// jumping.
    #[error(
        "the straight stance leg cannot reach the hip from the flat foot: {gap:.3e} m short as the hip passes over the ankle"
    )]
    FlatFootOutOfReach {
        /// How far the straight leg falls short (in m).
        gap: f64,
    },
}
