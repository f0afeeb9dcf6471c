//! The engine: the step loop that walks a body step after step (KLAW 1989 Figure 1), the
//! streamed walk, the per-step report and the actuators' work.
pub mod report;
pub mod stream;
pub mod walker;
pub mod work;
