//! Input files at the edge of the crate: step schedules and attribute files, read and turned
//! into the gaits and attributes of a walk.
pub mod attribute_file;
pub mod schedule;

use std::path::Path;

pub use attribute_file::{attributes_with, load_attributes};
pub use schedule::{read_schedule, schedule_gaits};

use crate::error::{Error, Result};

/// The whole text of `path`; errors are `Error::Io { action: "reading", .. }`.
fn read_text(path: &Path) -> Result<String> {
    std::fs::read_to_string(path).map_err(|source| Error::Io {
        action: "reading",
        path: path.to_path_buf(),
        source,
    })
}
