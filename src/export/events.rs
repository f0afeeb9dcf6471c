//! The gait-event CSV (`klaw walk --events`).
use std::path::Path;

use serde::Serialize;

use super::file::write_atomic;
use crate::analysis::events::Event;
use crate::error::Result;

/// Write gait events as CSV: `time_s, side, event, step`, one row per event.
pub fn write_events_csv(path: &Path, events: &[Event]) -> Result<()> {
    write_rows_csv(path, &["time_s", "side", "event", "step"], events)
}

/// Write `rows` as CSV, one row per value with the columns of its fields (serde); `header` is
/// written alone when there are no rows.
pub fn write_rows_csv<T: Serialize>(path: &Path, header: &[&str], rows: &[T]) -> Result<()> {
    write_atomic(path, |out| {
        let mut w = csv::Writer::from_writer(out);
        if rows.is_empty() {
            w.write_record(header)?;
        }
        for r in rows {
            w.serialize(r)?;
        }
        w.flush()
    })
}
