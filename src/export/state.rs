//! The engine-state CSV (`klaw walk --state-out`): one row per [`StateFrame`], the serde field names
//! as the header.
use std::path::Path;

use super::file::write_atomic;
use crate::engine::report::StateFrame;
use crate::error::Result;

/// The CSV header: the serde field names of `StateFrame`, in declaration order.
pub(crate) fn frame_header() -> Vec<String> {
    let mut w = csv::WriterBuilder::new()
        .has_headers(true)
        .from_writer(Vec::new());
    w.serialize(StateFrame::default())
        .expect("a default frame serializes");
    let bytes = w.into_inner().expect("writing to memory does not fail");
    let mut r = csv::ReaderBuilder::new()
        .has_headers(false)
        .from_reader(bytes.as_slice());
    let mut header = csv::StringRecord::new();
    r.read_record(&mut header)
        .expect("the header written above reads back");
    header.iter().map(str::to_string).collect()
}

/// Write the frames as CSV: a header of the `StateFrame` field names (written even when there are no
/// frames), then one row per frame; floats in their shortest exact (round-trip) form.
pub fn write_frames_csv(path: &Path, frames: &[StateFrame]) -> Result<()> {
    write_atomic(path, |out| {
        let mut w = csv::WriterBuilder::new()
            .has_headers(false)
            .from_writer(out);
        w.write_record(frame_header())?;
        for f in frames {
            w.serialize(f)?;
        }
        w.flush()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

    #[test]
    fn frames_csv_has_header_and_exact_floats() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("f.csv");
        write_frames_csv(&p, &[]).unwrap();
        let text = fs::read_to_string(&p).unwrap();
        assert_eq!(text.lines().count(), 1);
        let header: Vec<&str> = text.trim_end().split(',').collect();
        assert_eq!(header.len(), 22);
        assert_eq!(header[..3], ["time_s", "step", "phase"]);
        assert_eq!(header[21], "swing_toe_y_m");

        let f = StateFrame {
            time_s: 0.1 + 0.2,
            step: 3,
            phase: "swing2",
            stance_side: "left",
            stance_mode: "locked",
            hip_x_m: 1.0 / 3.0,
            swing_toe_y_m: -1e-12,
            ..StateFrame::default()
        };
        write_frames_csv(&p, &[f.clone(), f]).unwrap();
        let mut r = csv::Reader::from_path(&p).unwrap();
        let hdr = r.headers().unwrap().clone();
        let rows: Vec<csv::StringRecord> = r.records().map(|r| r.unwrap()).collect();
        assert_eq!(rows.len(), 2);
        let col = |name: &str| hdr.iter().position(|h| h == name).unwrap();
        let row = &rows[0];
        assert_eq!(row[col("time_s")].parse::<f64>().unwrap(), 0.1 + 0.2);
        assert_eq!(row[col("hip_x_m")].parse::<f64>().unwrap(), 1.0 / 3.0);
        assert_eq!(row[col("swing_toe_y_m")].parse::<f64>().unwrap(), -1e-12);
        assert_eq!(&row[col("phase")], "swing2");
        assert_eq!(&row[col("step")], "3");
    }
}
