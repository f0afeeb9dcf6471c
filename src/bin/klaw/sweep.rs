//! `klaw sweep`: one walk per point of a product of gaits, bodies and attributes, one summary
//! row per walk.
use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use klaw::sweep::output::{self, RunStats};
use klaw::sweep::{self as sw, Axis, Shard, Sweep};
use klaw::{AttributeTable, Result};

use crate::outputs::{self, Output};
use crate::progress::Progress;

#[derive(Args)]
pub(crate) struct SweepArgs {
    /// Sweep file (TOML): `name = value` for any flag below or attribute; flags override it
    #[arg(
        long,
        value_name = "FILE.toml",
        long_help = "Sweep file: a flat TOML table whose keys are the value flags of this command\n\
            (velocity, step_length or step-length, step_frequency, height, mass, mass_per_height2,\n\
            steps) or locomotion attribute names (models/attributes.toml), each a number, a string\n\
            spec \"START:STOP:STEP\" or \"A,B,C\", or an array of numbers, e.g.\n\
            \n    velocity = \"0.6:2.0:0.1\"\n    height = [1.5, 1.7, 1.9]\n    bounciness = 0.5\n\
            \n\
            A flag given on the command line overrides the file's entry of the same name (and\n\
            --mass or --mass-per-height2 drops the file's mass and mass_per_height2 both)."
    )]
    file: Option<PathBuf>,
    /// Walking speeds v in m/s: X, START:STOP:STEP or A,B,C
    #[arg(long, value_name = "SPEC", allow_hyphen_values = true)]
    velocity: Option<String>,
    /// Step lengths sl in m: X, START:STOP:STEP or A,B,C
    #[arg(long, value_name = "SPEC", allow_hyphen_values = true)]
    step_length: Option<String>,
    /// Step frequencies sf in steps/min: X, START:STOP:STEP or A,B,C
    #[arg(long, value_name = "SPEC", allow_hyphen_values = true)]
    step_frequency: Option<String>,
    /// Body heights H in m [default: 1.8]
    #[arg(long, value_name = "SPEC", allow_hyphen_values = true)]
    height: Option<String>,
    /// Body masses M in kg [default: 80]
    #[arg(
        long,
        value_name = "SPEC",
        allow_hyphen_values = true,
        conflicts_with = "mass_per_height2"
    )]
    mass: Option<String>,
    /// Mass from height: M = K · H² (K in kg/m²), instead of --mass
    #[arg(long, value_name = "SPEC", allow_hyphen_values = true)]
    mass_per_height2: Option<String>,
    /// Steps per walk, whole numbers [default: 10]
    #[arg(long, value_name = "SPEC", allow_hyphen_values = true)]
    steps: Option<String>,
    /// Style presets A,B,C (normal, brisk, elderly, march, long-stride, paper); --attr overrides them
    #[arg(long, value_name = "NAMES")]
    style: Option<String>,
    /// Body tables A,B: winter, deleva-male, deleva-female or a table file of your own
    /// (FILE.toml, docs/bodies.md); names and files may mix
    #[arg(long, value_name = "NAMES|FILES")]
    body_table: Option<String>,
    /// A locomotion attribute to sweep, NAME=SPEC in the units of models/attributes.toml (repeatable)
    #[arg(long, value_name = "NAME=SPEC", allow_hyphen_values = true)]
    attr: Vec<String>,
    /// Run only the K-th of N interleaved slices (points with point mod N = K − 1), 1 ≤ K ≤ N
    #[arg(
        long,
        value_name = "K/N",
        allow_hyphen_values = true,
        long_help = "Run only the K-th of N disjoint slices of the sweep, 1-based: 1 ≤ K ≤ N (K = Slurm's\n\
            SLURM_ARRAY_TASK_ID with --array=1-N). Shard K holds the points whose index (the point\n\
            column) satisfies point mod N = K − 1, so every shard gets a like mix of fast and slow\n\
            walks. Join the shards' outputs with `klaw merge`."
    )]
    shard: Option<String>,
    /// Keep the rows already written (an interrupted run's partial file, the existing --out) and run only the rest
    #[arg(
        long,
        long_help = "Keep the rows already written and run only the missing points. While a sweep runs, its\n\
            rows go to .NAME.partial next to --out (renamed to --out when done); an interrupted run\n\
            leaves that file. --resume keeps its complete rows and those of an existing --out,\n\
            after checking they come from this sweep (same columns, same inputs per point, same\n\
            shard), and writes the union in point order: the same file an uninterrupted run\n\
            writes. Without --resume an existing partial file is an error."
    )]
    resume: bool,
    /// Output file: CSV (.csv) or JSON Lines (.jsonl)
    #[arg(long, value_name = "FILE.csv|FILE.jsonl", default_value = "sweep.csv")]
    out: PathBuf,
}

/// Run the sweep; `Ok(false)` when it ran and every walk failed (exit status 1: their reasons
/// are in the rows).
pub(crate) fn run(args: &SweepArgs) -> Result<bool> {
    outputs::check(&[Output::new("out", &args.out, outputs::SWEEP)])?;
    let shard = match &args.shard {
        Some(text) => Shard::parse(text)?,
        None => Shard::ALL,
    };
    let sweep = build(args)?;
    let total = sweep.len();
    let threads = rayon::current_num_threads();
    let shard_note = if shard == Shard::ALL {
        String::new()
    } else {
        format!(", shard {}/{}", shard.index, shard.count)
    };
    eprintln!("sweep: {total} walks{shard_note} on {threads} threads");
    let start = Instant::now();
    let stats = run_with_progress(&sweep, args, shard)?;
    let mut out = std::io::stdout().lock();
    let kept = if stats.kept > 0 {
        format!(" ({} rows kept from the earlier run)", stats.kept)
    } else {
        String::new()
    };
    let _ = writeln!(
        out,
        "swept {} walks in {:.2} s: {} converged, {} failed{kept}",
        stats.computed,
        start.elapsed().as_secs_f64(),
        stats.computed - stats.failed,
        stats.failed
    );
    let _ = writeln!(out, "rows: {}", args.out.display());
    let all_failed = stats.computed > 0 && stats.failed == stats.computed;
    if all_failed {
        eprintln!(
            "error: every walk of the sweep failed (the reasons are in the error column of {})",
            args.out.display()
        );
    }
    Ok(!all_failed)
}

/// The sweep of the sweep file's entries and the flags'.
fn build(args: &SweepArgs) -> Result<Sweep> {
    let table = AttributeTable::builtin();
    let file = match &args.file {
        Some(path) => sw::read_sweep_file(path, &table)?,
        None => Vec::new(),
    };
    let mut flags = Vec::new();
    for (axis, flag, spec) in [
        (Axis::Velocity, "velocity", &args.velocity),
        (Axis::StepLength, "step-length", &args.step_length),
        (Axis::StepFrequency, "step-frequency", &args.step_frequency),
        (Axis::Height, "height", &args.height),
        (Axis::Mass, "mass", &args.mass),
        (
            Axis::MassPerHeight2,
            "mass-per-height2",
            &args.mass_per_height2,
        ),
        (Axis::Steps, "steps", &args.steps),
    ] {
        if let Some(spec) = spec {
            flags.push((axis, sw::parse_spec(flag, spec)?));
        }
    }
    if let Some(spec) = &args.style {
        flags.push((Axis::Style, sw::parse_styles(spec)?));
    }
    if let Some(spec) = &args.body_table {
        flags.push((Axis::BodyTable, sw::parse_body_tables(spec, None)?));
    }
    for arg in &args.attr {
        let (name, values) = sw::parse_attr(arg, &table)?;
        flags.push((Axis::Attribute(name), values));
    }
    let sweep = Sweep::build(file, flags)?;
    sweep.check_values(&table)?;
    Ok(sweep)
}

/// Run the sweep into --out, with its progress ([`Progress`]).
fn run_with_progress(sweep: &Sweep, args: &SweepArgs, shard: Shard) -> Result<RunStats> {
    let progress = Progress::new("sweep", 0, "walks");
    let stats = output::run_to_file(sweep, &args.out, shard, args.resume, &|done, total| {
        progress.set(done as u64, total as u64)
    });
    progress.finish();
    stats
}
