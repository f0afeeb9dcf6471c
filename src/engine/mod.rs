//! The engine: the step loop that walks a body step after step (KLAW 1989 Figure 1), the
//! streamed walk, the per-step report and the actuators' work.
pub mod measure;
pub mod parameters;
pub mod pose;
pub mod report;
pub mod stance;
pub mod startup;
pub mod step;
pub mod stream;
pub mod swing;
pub mod trials;
pub mod walker;
pub mod work;
