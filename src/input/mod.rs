//! Input files at the edge of the crate: step schedules and attribute files. No physics here.
pub mod attribute_file;
pub mod schedule;

use std::path::Path;

pub use attribute_file::read_attributes;
pub use schedule::{SCHEDULE_FIELDS, read_schedule};

use crate::error::{Error, Result};

/// The whole text of `path`; errors are `Error::Io { action: "reading", .. }`.
fn read_text(path: &Path) -> Result<String> {
    std::fs::read_to_string(path).map_err(|source| Error::Io {
        action: "reading",
        path: path.to_path_buf(),
        source,
    })
}
