//! `klaw merge`: sweep outputs (the shards of a sweep) joined into one file in point order.
use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use klaw::Result;

use crate::outputs::{self, Output};

#[derive(Args)]
pub(crate) struct MergeArgs {
    /// Output file: CSV (.csv) or JSON Lines (.jsonl), the inputs' format
    out: PathBuf,
    /// Sweep outputs to join (typically the shards of one sweep)
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    /// Write the rows even when points are missing (a warning instead of an error)
    #[arg(long)]
    allow_missing: bool,
}

pub(crate) fn run(args: &MergeArgs) -> Result<()> {
    outputs::check(&[Output::new("out", &args.out, outputs::SWEEP)])?;
    let stats = klaw::sweep::merge::merge(&args.out, &args.inputs, args.allow_missing)?;
    for path in &stats.cut_off {
        eprintln!(
            "warning: the last line of {} is cut off (an interrupted run?): not merged",
            path.display()
        );
    }
    if stats.duplicates > 0 {
        eprintln!(
            "warning: {} rows were found in more than one input (identical: written once)",
            stats.duplicates
        );
    }
    if stats.missing > 0 {
        let list: Vec<String> = stats.first_missing.iter().map(|p| p.to_string()).collect();
        eprintln!(
            "warning: {} points are missing (first: {})",
            stats.missing,
            list.join(", ")
        );
    }
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "merged {} rows from {} files: {}",
        stats.rows,
        args.inputs.len(),
        args.out.display()
    );
    Ok(())
}
