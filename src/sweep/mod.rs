//! Parameter sweeps: the Cartesian product of value lists for the gait, the body and any
//! locomotion attribute, one independent walk per point, run in parallel (rayon) and summarized
//! one row per walk. Rows come out in product order whatever the thread count, and each walk is
//! deterministic, so the output is byte-identical for any `RAYON_NUM_THREADS`.
//!
//! Points are numbered 0.. in product order (the `point` column); a shard `K/N` is the points
//! with `point mod N = K − 1`. Writing and resuming the output files is [`output`], joining
//! shards [`merge`].
pub(crate) mod check;
pub mod file;
pub mod merge;
pub mod output;
pub mod product;
pub mod rows;
pub(crate) mod run;
pub mod shard;
pub mod spec;
pub(crate) mod tables;

pub use file::read_sweep_file;
pub use product::{Axis, Sweep};
pub use rows::RowFormat;
pub use shard::Shard;
pub use spec::{parse_attr, parse_body_tables, parse_spec, parse_styles};
