//! The gait-event CSV (`klaw walk --events`).
use std::path::Path;

use super::file::write_atomic;
use crate::analysis::events::Event;
use crate::error::Result;

/// Write gait events as CSV: `time_s, side, event, step`, one row per event.
pub fn write_events_csv(path: &Path, events: &[Event]) -> Result<()> {
    write_atomic(path, |out| {
        let mut w = csv::Writer::from_writer(out);
        if events.is_empty() {
            w.write_record(["time_s", "side", "event", "step"])?;
        }
        for e in events {
            w.serialize(e)?;
        }
        w.flush()
    })
}
