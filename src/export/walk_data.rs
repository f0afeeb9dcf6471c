//! Walk data (Ko & Badler 1992, `klaw prototype`, `klaw generalize`) as JSON or CSV by the
//! extension (docs/generalize.md, "Walk data files").
use std::path::Path;

use super::file::write_atomic;
use crate::error::Result;
use crate::generalize::{WalkData, text};

/// Write `w` to `path`: `.json` as JSON, anything else as the walk-data CSV; whole or not at all.
pub fn write_walk_data(path: &Path, w: &WalkData) -> Result<()> {
    let is_json = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"));
    let body = if is_json {
        text::to_json(w)?
    } else {
        text::to_csv(w)?
    };
    write_atomic(path, |out| out.write_all(body.as_bytes()))
}
