//! `klaw generalize`: a prototype generalized to a body and a step length (Ko & Badler 1992,
//! §5), checked by posing it, written as walk data.
use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use klaw::generalize::{KinematicWalk, default_prototype};
use klaw::model::InputError;
use klaw::model::body::DEFAULT_BODY_TABLE;
use klaw::{Body, Gait, Result, export, input};

use crate::kinematic::read_walk_data;
use crate::outputs::{self, Output};
use crate::prototype::WALK_DATA;
use crate::{DEFAULT_HEIGHT, DEFAULT_MASS};

#[derive(Args)]
pub(crate) struct GeneralizeArgs {
    /// The prototype: walk data (.json or .csv) [default: the bundled one, klaw's default walk]
    #[arg(long, value_name = "FILE.json|FILE.csv")]
    prototype: Option<PathBuf>,

    /// The generalized step's length sl (m), within the attributes' limits
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    step_length: f64,

    /// Body height H in m, range [1.2, 2.2]
    #[arg(long, value_name = "M", default_value_t = DEFAULT_HEIGHT, allow_negative_numbers = true)]
    height: f64,

    /// Body mass M in kg, range [25, 200]
    #[arg(long, value_name = "KG", default_value_t = DEFAULT_MASS, allow_negative_numbers = true)]
    mass: f64,

    /// The body's anthropometric table: winter, deleva-male, deleva-female or a table file of
    /// your own (FILE.toml; docs/bodies.md)
    #[arg(long, value_name = "NAME|FILE.toml", default_value = DEFAULT_BODY_TABLE)]
    body_table: String,

    /// Style preset: normal, brisk, elderly, march, long-stride or paper (its pelvic rotation and step width place the hip)
    #[arg(long, value_name = "NAME")]
    style: Option<String>,

    /// The generalization's constants (the α slopes, the posing tolerances): a file in the
    /// layout of models/generalize.toml, checked before any work (docs/cli.md, "Model files")
    /// [default: models/generalize.toml]
    #[arg(long, value_name = "FILE.toml")]
    generalize_model: Option<PathBuf>,

    /// Walk data to write: .json or .csv (docs/generalize.md, "Walk data files")
    #[arg(long, value_name = "FILE.json|FILE.csv")]
    out: PathBuf,
}

pub(crate) fn run(args: &GeneralizeArgs) -> Result<()> {
    outputs::check(&[Output::new("out", &args.out, WALK_DATA)])?;
    let body = Body::from_table(&args.body_table, args.height, args.mass)?;
    let params = crate::kinematic::generalize_parameters(args.generalize_model.as_deref())?;
    let attrs = input::load_attributes(args.style.as_deref(), None)?;
    // the step's duration only paces the determinants of the check: the normalizing formula's,
    // sf = sl / (0.004 H), unchecked (walk data are in normalized time)
    let sl = InputError::check_range("step-length", args.step_length, 1e-3, 3.0 * body.l1, "m")?;
    let sf = sl / (0.004 * body.height);
    let gait = Gait {
        velocity: sl * sf / 60.0,
        step_length: sl,
        step_frequency: sf,
    };
    let prototype = match &args.prototype {
        Some(p) => read_walk_data(p)?,
        None => default_prototype(),
    };
    crate::kinematic::warn_alphas(args.generalize_model.as_deref(), &params, &prototype);
    let walk = KinematicWalk::new(&prototype, body, attrs, gait, 2, &params)?;
    export::write_walk_data(&args.out, &walk.step.data)?;
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "generalized {} to H {} m ({} table, leg length {:.4} m) at step length {:.4} m; the hip comes down {:.1} mm at most when posed",
        prototype.source,
        args.height,
        args.body_table,
        body.l1,
        walk.step.data.step_length,
        1e3 * walk.hip_drop
    );
    let _ = writeln!(out, "walk data: {}", args.out.display());
    Ok(())
}
