//! `klaw poulaine extract|fit` and `klaw poulaine-db build`: poulaines of klaw's walks, their
//! curve model, and the database of them (Pronost et al.; docs/ik.md).
use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};

use clap::{Args, Subcommand};
use klaw::model::InputError;
use klaw::plot::poulaine::AnklePoulaine;
use klaw::poulaine::build::{Grid, synthetic};
use klaw::poulaine::curve::LegCurve;
use klaw::poulaine::{Database, Entry, Trajectory, fit};
use klaw::{GaitRequest, Result, Simulation, export};

use crate::args::GaitArgs;
use crate::outputs::{self, Output};

#[derive(Subcommand)]
pub(crate) enum PoulaineCommand {
    /// Simulate a walk and write its last gait cycle's poulaine (CSV)
    Extract(ExtractArgs),
    /// Model a poulaine (CSV) by four points and four Hermite curves; write the model (JSON)
    Fit(FitArgs),
}

#[derive(Args)]
pub(crate) struct ExtractArgs {
    #[command(flatten)]
    gait: GaitArgs,
    /// Samples per second of the poulaine, range [10, 1000]
    #[arg(long, value_name = "HZ", default_value_t = klaw::poulaine::trajectory::CAPTURE_RATE, allow_negative_numbers = true)]
    rate: f64,
    /// The poulaine to write (.csv: time_s, right_x/y/z_m, left_x/y/z_m)
    #[arg(long, value_name = "FILE.csv", default_value = "poulaine.csv")]
    out: PathBuf,
}

#[derive(Args)]
pub(crate) struct FitArgs {
    /// The poulaine (.csv, the layout of `klaw poulaine extract`: one cycle, uniform samples)
    #[arg(value_name = "POULAINE.csv")]
    poulaine: PathBuf,
    /// The model to write (.json); with --leg-length and --step-length, a database entry
    #[arg(long, value_name = "FILE.json", default_value = "poulaine-model.json")]
    out: PathBuf,
    /// The walker's leg length, hip to ankle (m): write a database entry (`measured`)
    #[arg(
        long,
        value_name = "M",
        requires = "step_length",
        allow_negative_numbers = true
    )]
    leg_length: Option<f64>,
    /// The walk's step length (m), for a database entry
    #[arg(
        long,
        value_name = "M",
        requires = "leg_length",
        allow_negative_numbers = true
    )]
    step_length: Option<f64>,
    /// The entry's label [default: the file's name]
    #[arg(long, value_name = "NAME")]
    label: Option<String>,
    /// A figure of the samples against the model, sagittal and frontal views (.png or .svg)
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
}

#[derive(Subcommand)]
pub(crate) enum DbCommand {
    /// Build a database: klaw walks over a grid (synthetic) and/or entries of `poulaine fit`
    Build(BuildArgs),
}

#[derive(Args)]
pub(crate) struct BuildArgs {
    /// Body heights (m), a list A,B,C; the mass is 23 H² kg
    #[arg(
        long,
        value_name = "M,…",
        value_delimiter = ',',
        allow_negative_numbers = true
    )]
    height: Vec<f64>,
    /// Step lengths (m), a list
    #[arg(
        long,
        value_name = "M,…",
        value_delimiter = ',',
        allow_negative_numbers = true
    )]
    step_length: Vec<f64>,
    /// An attribute and its values, NAME=A,B,C (units of models/attributes.toml); repeatable
    #[arg(long = "attr", value_name = "NAME=A,B")]
    attributes: Vec<String>,
    /// Database entries to add (.json of `klaw poulaine fit --leg-length … --step-length …`)
    #[arg(long, value_name = "FILE.json")]
    entry: Vec<PathBuf>,
    /// The database to write (.json)
    #[arg(long, value_name = "FILE.json", default_value = "poulaine-db.json")]
    out: PathBuf,
}

/// What `poulaine fit` writes without an entry's labels.
#[derive(serde::Serialize)]
struct Fitted<'a> {
    model: &'a klaw::poulaine::Model,
    fit_error: &'a klaw::poulaine::FitError,
    shape_error: &'a klaw::poulaine::FitError,
}

pub(crate) fn run(command: &PoulaineCommand) -> Result<()> {
    match command {
        PoulaineCommand::Extract(a) => extract(a),
        PoulaineCommand::Fit(a) => fit_file(a),
    }
}

pub(crate) fn run_db(command: &DbCommand) -> Result<()> {
    match command {
        DbCommand::Build(a) => build(a),
    }
}

fn extract(a: &ExtractArgs) -> Result<()> {
    InputError::check_range("rate", a.rate, 10.0, 1000.0, "samples/s")?;
    let body = a.gait.body()?;
    let attrs = a.gait.attributes()?;
    let gaits = a.gait.gaits(&body, &attrs)?;
    if gaits.len() < 2 {
        let reason = format!("{} step: a gait cycle needs at least 2", gaits.len());
        return Err(InputError::bad_value("steps", reason).into());
    }
    outputs::check(&[Output::new("out", &a.out, outputs::CSV)])?;
    let requests = gaits
        .iter()
        .map(|g| GaitRequest {
            velocity: Some(g.velocity),
            step_length: Some(g.step_length),
            step_frequency: Some(g.step_frequency),
        })
        .collect();
    let walk = Simulation::new(body)
        .engine_parameters(a.gait.engine_parameters()?)
        .attributes(attrs)
        .schedule(requests)
        .run()?;
    let (t, _) = Trajectory::from_walk(&walk, a.rate)?;
    t.write_csv(&a.out)?;
    let _ = writeln!(
        std::io::stdout(),
        "poulaine: {} samples over a cycle of {:.3} s (v {:.3} m/s): {}",
        t.time.len(),
        t.period,
        t.speed(),
        a.out.display()
    );
    Ok(())
}

fn fit_file(a: &FitArgs) -> Result<()> {
    if let Some(l) = a.leg_length {
        InputError::check_range("leg-length", l, 0.3, 1.5, "m")?;
    }
    if let Some(sl) = a.step_length {
        InputError::check_range("step-length", sl, 0.05, 2.0, "m")?;
    }
    let mut outs = vec![Output::new("out", &a.out, outputs::JSON)];
    if let Some(p) = &a.plot {
        outs.push(Output::new("plot", p, outputs::FIGURE));
    }
    outputs::check(&outs)?;
    let t = Trajectory::read_csv(&a.poulaine)?;
    let (model, error) = fit(&t)?;
    let shape = model.shape_error(&t);
    if let Some(p) = &a.plot {
        let leg = |samples: &[[f64; 3]], c: &LegCurve| AnklePoulaine {
            samples: samples.to_vec(),
            model: (0..400).map(|i| c.at(f64::from(i) / 400.0)).collect(),
            points: c.x.phase.map(|phi| c.at(phi)),
        };
        let title = format!(
            "{}: poulaine and its model (fit error {:.1} cm RMS, {:.1} cm at worst)",
            stem(&a.poulaine),
            100.0 * error.rms,
            100.0 * error.max
        );
        klaw::plot::poulaine::write(
            p,
            &[leg(&t.right, &model.right), leg(&t.left, &model.left)],
            &title,
        )?;
    }
    match (a.leg_length, a.step_length) {
        (Some(leg), Some(step)) => {
            let label = a.label.clone().unwrap_or_else(|| stem(&a.poulaine));
            let e = Entry::new(label, "measured", leg, step, model, error);
            export::write_report_json(&a.out, &e)?;
        }
        _ => export::write_report_json(
            &a.out,
            &Fitted {
                model: &model,
                fit_error: &error,
                shape_error: &shape,
            },
        )?,
    }
    let _ = writeln!(
        std::io::stdout(),
        "model of {}: fit error {:.4} m RMS, {:.4} m at worst (as shapes {:.4}, {:.4}): {}",
        a.poulaine.display(),
        error.rms,
        error.max,
        shape.rms,
        shape.max,
        a.out.display()
    );
    Ok(())
}

fn stem(p: &Path) -> String {
    p.file_stem()
        .map_or_else(|| "poulaine".into(), |s| s.to_string_lossy().into_owned())
}

/// `NAME=A,B,C` → (NAME, [A, B, C]).
fn attribute(text: &str) -> Result<(String, Vec<f64>)> {
    let bad = |why: &str| InputError::bad_value("attr", format!("`{text}`: {why}"));
    let (name, values) = text
        .split_once('=')
        .ok_or_else(|| bad("expected NAME=A,B,…"))?;
    let values = values
        .split(',')
        .map(|v| {
            v.trim()
                .parse::<f64>()
                .map_err(|_| bad("a value is not a number"))
        })
        .collect::<std::result::Result<Vec<_>, _>>()?;
    Ok((name.trim().to_string(), values))
}

fn build(a: &BuildArgs) -> Result<()> {
    let grid = Grid {
        heights: a.height.clone(),
        step_lengths: a.step_length.clone(),
        attributes: a
            .attributes
            .iter()
            .map(|t| attribute(t))
            .collect::<Result<_>>()?,
    };
    let gridded = !(grid.heights.is_empty() && grid.step_lengths.is_empty());
    if !gridded && a.entry.is_empty() {
        let reason = "give a grid (--height and --step-length) or --entry files";
        return Err(InputError::bad_value("height", reason).into());
    }
    if gridded {
        grid.check()?;
    }
    let mut added = Vec::new();
    for p in &a.entry {
        let text = std::fs::read_to_string(p).map_err(|source| klaw::Error::Io {
            action: "reading",
            path: p.clone(),
            source,
        })?;
        let wrapped = format!(r#"{{"description": "", "entries": [{text}]}}"#);
        added.extend(Database::parse(&wrapped, p)?.entries);
    }
    outputs::check(&[Output::new("out", &a.out, outputs::JSON)])?;
    let (mut db, skipped) = if gridded {
        synthetic(&grid)?
    } else {
        let d = Database {
            description: "measured: entries of `klaw poulaine fit`".into(),
            entries: Vec::new(),
        };
        (d, Vec::new())
    };
    let measured = added.len();
    db.entries.extend(added);
    if db.entries.is_empty() {
        return Err(klaw::poulaine::PoulaineError::Malformed {
            path: a.out.clone(),
            reason: format!(
                "no walk of the grid gave a poulaine ({} skipped)",
                skipped.len()
            ),
        }
        .into());
    }
    if measured > 0 {
        db.description
            .push_str(&format!("; {measured} measured entries added"));
    }
    // labels unique across the grid and the added entries
    let mut seen = BTreeMap::new();
    for e in &db.entries {
        if seen.insert(e.label.clone(), ()).is_some() {
            let reason = format!("the label {} is used twice", e.label);
            return Err(InputError::bad_value("entry", reason).into());
        }
    }
    export::write_report_json(&a.out, &db)?;
    let mut o = std::io::stdout().lock();
    let _ = writeln!(
        o,
        "poulaine database: {} entries ({} synthetic, {measured} measured), {} grid points skipped: {}",
        db.entries.len(),
        db.entries.len() - measured,
        skipped.len(),
        a.out.display()
    );
    for s in &skipped {
        let _ = writeln!(o, "skipped {}: {}", s.label, s.reason);
    }
    Ok(())
}
