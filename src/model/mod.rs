//! The model's data: the body (anthropometric tables in `models/`), the locomotion attributes
//! (defaults, units and ranges in `models/attributes.toml`, style presets) and physical constants.
pub mod attributes;
pub mod body;
pub mod error;
pub mod file;
pub mod pelvis_speed;
pub mod rom;
pub mod servos;

pub use error::{InputError, Shown};

/// Standard gravity (m/s²).
pub const GRAVITY: f64 = 9.81;
