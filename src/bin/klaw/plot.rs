//! `klaw plot`: the joint angle curves of a walk over the gait cycle, with the normal ranges.
use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use klaw::Result;
use klaw::analysis::cycle::{GaitCycle, min_steps};
use klaw::analysis::norms::{NormTable, WalkSpeed};
use klaw::plot::cycle::write_cycle_figure;

use crate::args::GaitArgs;
use crate::outputs::{self, Output};
use crate::progress::Spinner;
use crate::{count, font_note};

/// The most steps `klaw plot` walks: the whole walk is held for the cycle average, which has
/// long converged by then.
const MAX_STEPS: usize = 1000;

#[derive(Args)]
pub(crate) struct PlotArgs {
    #[command(flatten)]
    walk: GaitArgs,
    /// Figure to write: PNG or SVG by the extension
    #[arg(
        long,
        value_name = "FILE.png|FILE.svg",
        default_value = "gait-cycle.png"
    )]
    out: PathBuf,
}

pub(crate) fn run(args: &PlotArgs) -> Result<()> {
    outputs::check(&[Output::new("out", &args.out, outputs::FIGURE)])?;
    let spinner = Spinner::new("simulating the walk and drawing its gait cycle".into());
    let (walk, title) = args.walk.plan(min_steps(true), MAX_STEPS)?.simulate()?;
    let cycle = GaitCycle::from_walk(&walk)?;
    let norms = NormTable::builtin();
    let speed = WalkSpeed::of_walk(&walk);
    let figure = write_cycle_figure(&cycle, &norms, speed, &title, &args.out)?;
    drop(spinner);
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "gait cycle of {title}: mean of {} right / {} left",
        count(cycle.cycles.0, "cycle"),
        count(cycle.cycles.1, "cycle")
    );
    let _ = writeln!(
        out,
        "speed-dependent norms taken at v/√(g l1) = {:.3} (v {:.3} m/s, l1 {:.3} m)",
        speed.dimensionless(),
        speed.velocity,
        speed.leg_length
    );
    for c in &figure.checks {
        let _ = writeln!(out, "  {}", c.describe());
    }
    let _ = writeln!(out, "plot: {}{}", args.out.display(), font_note());
    Ok(())
}
