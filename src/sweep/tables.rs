//! The body tables of a sweep's `body_table` axis, by index: the bundled tables of
//! [`BODY_TABLES`] first, then the table files the sweeps of this process have named, each read
//! and checked once per distinct path when its spec is parsed (before any walk), so that every
//! walk of the sweep scales the same reading and no walk reads a file.
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError};

use crate::model::InputError;
use crate::model::body::{BODY_TABLES, BodyTable, unknown_body_table};
use crate::model::file::names_a_file;

/// The table files read so far, at indices `BODY_TABLES.len()` on.
static FILES: Mutex<Vec<BodyTable>> = Mutex::new(Vec::new());

fn files() -> MutexGuard<'static, Vec<BodyTable>> {
    FILES.lock().unwrap_or_else(PoisonError::into_inner)
}

/// The index of the table `spec`: a bundled name, or a file ([`names_a_file`]), a relative one
/// relative to `base` when given (a sweep file's folder).
pub(crate) fn index(spec: &str, base: Option<&Path>) -> Result<usize, InputError> {
    if !names_a_file(spec) {
        return BODY_TABLES
            .iter()
            .position(|(n, _)| *n == spec)
            .ok_or_else(|| InputError::bad_value("body-table", unknown_body_table(spec)));
    }
    let path = match base {
        Some(dir) => dir.join(spec),
        None => PathBuf::from(spec),
    };
    let name = path.display().to_string();
    let mut files = files();
    let i = match files.iter().position(|t| t.name() == name) {
        Some(i) => i,
        None => {
            files.push(BodyTable::read(&path)?);
            files.len() - 1
        }
    };
    Ok(BODY_TABLES.len() + i)
}

/// The table of index `i` (of [`index`]).
pub(crate) fn table(i: usize) -> BodyTable {
    match BODY_TABLES.get(i) {
        Some((name, _)) => BodyTable::named(name).expect("the bundled body tables parse (tested)"),
        None => files()[i - BODY_TABLES.len()].clone(),
    }
}

/// The name of the table of index `i`: the bundled name or the file's path.
pub(crate) fn name(i: usize) -> &'static str {
    match BODY_TABLES.get(i) {
        Some((name, _)) => name,
        None => files()[i - BODY_TABLES.len()].name(),
    }
}
