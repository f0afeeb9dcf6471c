//! The low level: equations of motion only, no control. Each model is derived by Lagrange
//! (derivations in `docs/dynamics.md`); each exposes its mass matrix M(q) and bias terms b(q, q̇)
//! so that M q̈ + b = Q, its energy, and the points it defines.
pub mod impact;
pub mod stance;
pub mod swing;

pub use stance::StanceModel;
pub use swing::SwingModel;
