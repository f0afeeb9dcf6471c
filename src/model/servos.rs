//! The servos' natural frequencies and damping ratios (spec §4, §5): model constants of
//! `models/engine.toml`'s `[servos]`, read with the engine's other constants
//! ([`crate::engine::parameters::EngineParameters`]). A spring written as a natural frequency
//! holds for every body: k = I (2π f)², d = 2 ζ I (2π f), I the inertia it moves.
use serde::Deserialize;

/// The servos of the stance leg axis, the trunk's balance and the swing hip and knee.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Servos {
    /// f_w (Hz): the telescopic leg axis, k_w = m2 (2π f_w)².
    pub leg_frequency: f64,
    /// ζ: the leg axis and the swing hip and knee servos.
    pub damping_ratio: f64,
    /// f_2 (Hz): the trunk's balance spring, k_2 = J2 (2π f_2)².
    pub trunk_frequency: f64,
    /// ζ_2: the balance torque's damper.
    pub trunk_damping_ratio: f64,
    /// f_h (Hz): swing2's hip servo, k_h = a11 (2π f_h)².
    pub swing_hip_frequency: f64,
}

impl Servos {
    /// The constants with their names, for checks and messages.
    pub fn named(&self) -> [(&'static str, f64); 5] {
        [
            ("leg_frequency", self.leg_frequency),
            ("damping_ratio", self.damping_ratio),
            ("trunk_frequency", self.trunk_frequency),
            ("trunk_damping_ratio", self.trunk_damping_ratio),
            ("swing_hip_frequency", self.swing_hip_frequency),
        ]
    }
}
