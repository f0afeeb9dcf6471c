//! `klaw plot-sweep`: a heat map of a sweep's result column over two swept parameters.
use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use klaw::Result;
use klaw::plot::heat_map::heat_map;

use crate::font_note;
use crate::outputs::{self, Output};

#[derive(Args)]
pub(crate) struct PlotSweepArgs {
    /// Sweep output to read (.csv or .jsonl)
    input: PathBuf,
    /// Swept parameter on the horizontal axis (a column name, e.g. velocity)
    #[arg(long)]
    x: String,
    /// Swept parameter on the vertical axis (a column name, e.g. height)
    #[arg(long)]
    y: String,
    /// Result column to colour by: any numeric column, e.g. converged, mean_iterations (alias
    /// iterations), max_peak_swing_knee_flexion_deg (alias peak_knee), work_per_m
    #[arg(long)]
    column: String,
    /// Heat map to write: PNG or SVG by the extension
    #[arg(long, value_name = "FILE.png|FILE.svg")]
    out: PathBuf,
}

pub(crate) fn run(args: &PlotSweepArgs) -> Result<()> {
    outputs::check(&[Output::new("out", &args.out, outputs::FIGURE)])?;
    let map = heat_map(&args.input, &args.x, &args.y, &args.column, &args.out)?;
    let failed = map.cells.iter().filter(|c| c.failed()).count();
    let walks: usize = map.cells.iter().map(|c| c.rows).sum();
    let walks_failed: usize = map.cells.iter().map(|c| c.rows - c.converged).sum();
    let note = font_note();
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "heat map of {} over {} × {}: {} × {} values, {} cells, {failed} failed cells, \
         {walks_failed} of {walks} walks failed: {}{note}",
        map.column,
        map.x,
        map.y,
        map.xs.len(),
        map.ys.len(),
        map.cells.len(),
        args.out.display()
    );
    Ok(())
}
