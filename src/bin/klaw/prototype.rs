//! `klaw prototype`: walk data (Ko & Badler 1992) from one steady step of a walk the engine
//! simulates, or from a measured walk (docs/generalize.md).
use std::io::Write;
use std::path::PathBuf;

use clap::{ArgGroup, Args};
use klaw::generalize::extract::from_walk;
use klaw::generalize::measured;
use klaw::model::InputError;
use klaw::{Result, export};

use crate::args::GaitArgs;
use crate::outputs::{self, Output};

/// The extensions of a walk-data file.
pub(crate) const WALK_DATA: &[&str] = &["json", "csv"];

#[derive(Args)]
#[command(group(ArgGroup::new("source").required(true).args(["from_walk", "from_csv"])))]
pub(crate) struct PrototypeArgs {
    /// Take the prototype from a walk the engine simulates (the gait, body and attribute flags)
    #[arg(long)]
    from_walk: bool,

    /// Read the prototype from a measured walk: the landmark CSV of docs/generalize.md
    #[arg(long, value_name = "FILE.csv")]
    from_csv: Option<PathBuf>,

    /// With --from-walk: the step taken, 1 to steps − 2 [default: steps − 2]
    #[arg(long, value_name = "K", allow_negative_numbers = true)]
    step: Option<i64>,

    #[command(flatten)]
    gait: GaitArgs,

    /// The generalization's constants (reading a measured walk, extracting the sequences): a
    /// file in the layout of models/generalize.toml, checked before any work (docs/cli.md,
    /// "Model files") [default: models/generalize.toml]
    #[arg(long, value_name = "FILE.toml")]
    generalize_model: Option<PathBuf>,

    /// Walk data to write: .json or .csv (docs/generalize.md, "Walk data files")
    #[arg(long, value_name = "FILE.json|FILE.csv")]
    out: PathBuf,
}

pub(crate) fn run(args: &PrototypeArgs) -> Result<()> {
    outputs::check(&[Output::new("out", &args.out, WALK_DATA)])?;
    let params = crate::kinematic::generalize_parameters(args.generalize_model.as_deref())?;
    let data = match &args.from_csv {
        Some(_) if args.gait.engine_model.is_some() => {
            let reason = "applies to --from-walk only (a measured walk is not simulated)";
            return Err(InputError::bad_value("engine-model", reason).into());
        }
        Some(path) => {
            if args.step.is_some() {
                let reason =
                    "applies to --from-walk only (a measured walk's first whole step is taken)";
                return Err(InputError::bad_value("step", reason).into());
            }
            let text = std::fs::read_to_string(path).map_err(|source| klaw::Error::Io {
                action: "reading",
                path: path.clone(),
                source,
            })?;
            measured::from_csv(&text, &params)
                .map_err(|e| InputError::malformed("measured walk", path, e.to_string()))?
        }
        None => {
            let body = args.gait.body()?;
            let attrs = args.gait.attributes()?;
            let gaits = args.gait.gaits(&body, &attrs)?;
            let n = gaits.len();
            if n < 3 {
                let reason = format!(
                    "a prototype is a step with one before and one after it: at least 3 steps, not {n}"
                );
                return Err(InputError::bad_value("steps", reason).into());
            }
            let k = match args.step {
                Some(k) => crate::check_count("step", k, 1, n - 2, "")?,
                None => n - 2,
            };
            let parameters = args.gait.engine_parameters()?;
            let walk = klaw::engine::walker::simulate_with(body, attrs, &gaits, parameters)?;
            from_walk(&walk, k, &params)?
        }
    };
    export::write_walk_data(&args.out, &data)?;
    let size = std::fs::metadata(&args.out).map_or(0, |m| m.len());
    let mut out = std::io::stdout().lock();
    let _ = writeln!(out, "prototype: {}", data.source);
    let _ = writeln!(
        out,
        "step length {:.4} m (the one before {:.4} m), leg length {:.4} m; FGM {:.3}, heel-off {:.3}, MOM {:.3}, TOM {:.3}",
        data.step_length,
        data.step_length_before,
        data.body.leg_length(),
        data.phases.fgm,
        data.phases.heel_off,
        data.phases.mom,
        data.phases.tom
    );
    let _ = writeln!(out, "walk data: {} ({size} bytes)", args.out.display());
    Ok(())
}
