//! Parameter sweeps: the Cartesian product of value lists for the gait, the body and any
//! locomotion attribute, one independent walk per point, run in parallel (rayon) and summarized
//! one row per walk. Rows come out in product order whatever the thread count, and each walk is
//! deterministic, so the output is byte-identical for any `RAYON_NUM_THREADS`.
//!
//! Points are numbered 0.. in product order (the `point` column); a shard `K/N` is the points
//! with `point mod N = K − 1`. Writing and resuming the output files is [`output`], joining
//! shards [`merge`].
pub mod file;
pub mod merge;
pub mod output;
pub mod product;
pub mod rows;
pub mod run;
pub mod shard;
pub mod spec;

pub use file::{parse_sweep_toml, read_sweep_file};
pub use product::{Axis, Entry, Inputs, MAX_POINTS, QUANTITIES, Sweep};
pub use rows::{Cell, Format, OUTPUT_COLUMNS, Row, Summary};
pub use run::{CHUNK_PER_THREAD, MAX_STEPS, run_walk};
pub use shard::{MAX_SHARDS, Shard};
pub use spec::{MAX_VALUES, parse_attr, parse_spec, parse_styles};
