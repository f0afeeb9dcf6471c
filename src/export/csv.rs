//! The clinical-angle CSV (issue item 7): one row per frame, `time_s`, `step`, the pelvis centre
//! `pelvis_tx_m`, `pelvis_ty_m`, `pelvis_tz_m` (world frame, m), then [`angle_columns`]
//! in degrees as `*_deg`. Numbers as [`super::number`] writes them (shortest round-trip form).
use std::io::{self, Write};

use super::number::{push_f64, push_usize};
use super::{ExportError, FrameData, RowWriter};
use crate::figure::clinical::{AngleColumn, angle_columns};

/// The frame CSV writer.
pub(crate) struct FrameCsv {
    columns: Vec<AngleColumn>,
}

impl FrameCsv {
    pub(crate) fn new() -> Self {
        FrameCsv {
            columns: angle_columns(),
        }
    }
}

impl RowWriter for FrameCsv {
    fn counts_rows(&self) -> bool {
        false
    }

    fn row(&mut self, out: &mut Vec<u8>, frame: &FrameData) -> Result<(), ExportError> {
        let c = frame.clinical();
        push_f64(out, c.time);
        out.push(b',');
        push_usize(out, c.step);
        for v in c.pelvis {
            out.push(b',');
            push_f64(out, v);
        }
        for col in &self.columns {
            out.push(b',');
            push_f64(out, (col.get)(c).to_degrees());
        }
        out.push(b'\n');
        Ok(())
    }

    fn header(&self, out: &mut dyn Write, _rows: usize) -> io::Result<()> {
        write!(out, "time_s,step,pelvis_tx_m,pelvis_ty_m,pelvis_tz_m")?;
        for col in &self.columns {
            write!(out, ",{}_deg", col.name)?;
        }
        writeln!(out)
    }
}
