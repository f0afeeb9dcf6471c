//! The gait-cycle CSV (issue item 8, `klaw walk --cycle-out`): the averaged cycle of
//! [`crate::analysis::cycle::cycle_average`], one row per 1 % of the cycle.
use std::path::Path;

use super::number::Number;
use crate::analysis::cycle::CycleCurves;
use crate::error::Result;

/// Write the curves as CSV: `cycle_pct` (0…100), then each column as `*_deg`; 101 rows, numbers
/// as the motion files write them (`docs/export.md`, "Numbers in the files").
pub fn write_cycle_csv(path: &Path, curves: &CycleCurves) -> Result<()> {
    super::file::write_atomic(path, |out| {
        write!(out, "cycle_pct")?;
        for c in &curves.columns {
            write!(out, ",{c}_deg")?;
        }
        writeln!(out)?;
        for (p, row) in curves.rows.iter().enumerate() {
            write!(out, "{p}")?;
            for v in row {
                write!(out, ",{}", Number(v.to_degrees()))?;
            }
            writeln!(out)?;
        }
        Ok(())
    })
}
