//! Analysis of a walk's motion: gait events.
pub mod events;
