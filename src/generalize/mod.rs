//! Walk data and its generalization (Ko & Badler, "Straight line walking animation based on
//! kinematic generalization that preserves the original characteristics", MS-CIS-92-79, 1992):
//! one step of a walk, the prototype, as walk data W(S, sl) = {H, F1, F2, F3, M, A} (eq. 4);
//! its generalization to any step length (φ_ρ, §2) and any body (ψ, §4) and both (§5), with the
//! paper's composition laws holding; extracted from a klaw walk or from a measured one; and
//! posed as the whole figure, the kinematic walk mode. The paper's errors and our decisions are
//! in docs/generalize.md.
pub mod condition;
pub mod error;
pub mod geometry;
pub mod parameters;
pub mod sequence;
pub mod transform;
pub mod walk_data;

pub use condition::BodyCondition;
pub use error::GeneralizeError;
pub use geometry::{Character, Pelvis};
pub use parameters::GeneralizeParameters;
pub use transform::{Target, combined, generalize, phi, psi, steady};
pub use walk_data::{Phases, Piece, WalkData};
pub mod extract;
pub mod pose;
pub mod walk;
pub use walk::KinematicWalk;
pub mod measured;
pub mod text;

/// The bundled prototype: step 8 of klaw's default walk (10 steps at 1.4 m/s, H 1.8 m, M 80 kg,
/// the default attributes), made by `klaw prototype --from-walk` and
/// regenerated with the other generated tables by `cargo run --release --example regenerate -- models`.
pub const DEFAULT_PROTOTYPE: &str = include_str!("../../models/prototype-default.csv");

/// The bundled prototype ([`DEFAULT_PROTOTYPE`]), read.
pub fn default_prototype() -> WalkData {
    text::from_csv(DEFAULT_PROTOTYPE).expect("the bundled prototype reads (tested)")
}
