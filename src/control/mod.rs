//! The middle level of the control hierarchy: subphase state machines, force and torque
//! profiles, and the shooting solvers that find their magnitudes.
pub mod shooting;
pub mod stance;
pub mod swing;
