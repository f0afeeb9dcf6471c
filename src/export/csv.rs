//! The clinical-angle CSV (issue item 7): one row per frame, `time_s`, `step`, the pelvis centre
//! `pelvis_tx_m`, `pelvis_ty_m`, `pelvis_tz_m` (world frame, m), then [`angle_columns`]
//! in degrees as `*_deg`. Numbers in their shortest round-trip form.
use std::io::{self, Write};

use super::{FrameData, RowError, RowWriter};
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
    fn row(&mut self, out: &mut dyn Write, frame: &FrameData) -> Result<(), RowError> {
        let c = &frame.clinical;
        write!(
            out,
            "{},{},{},{},{}",
            c.time, c.step, c.pelvis[0], c.pelvis[1], c.pelvis[2]
        )?;
        for col in &self.columns {
            write!(out, ",{}", (col.get)(c).to_degrees())?;
        }
        writeln!(out)?;
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
