//! The gait, body and attribute flags shared by `klaw walk`, `klaw plot` and `klaw animate`;
//! the body and attribute flags also by `klaw step` and `klaw turn`.
use std::path::PathBuf;

use clap::Args;
use klaw::engine::parameters::EngineParameters;
use klaw::engine::walker::{Walk, simulate_with};
use klaw::model::body::DEFAULT_BODY_TABLE;
use klaw::{Attributes, Body, Gait, GaitRequest, Result, input};

use crate::{DEFAULT_HEIGHT, DEFAULT_MASS, DEFAULT_STEPS, MAX_STEPS, check_count};

/// The gait, body and attribute flags of `klaw walk`, `klaw plot` and `klaw animate`.
#[derive(Args)]
pub(crate) struct GaitArgs {
    /// Walking speed v in m/s, range [0.4, √(0.5 g l1)]: 2.06 m/s for H = 1.8 m [default: the style's speed, 1.4 if no gait flag is given]
    #[arg(
        long,
        value_name = "M/S",
        allow_negative_numbers = true,
        long_help = "Walking speed v in m/s; valid range [0.4, v_max] m/s, v_max the body's walk–run\n\
            transition: Froude number v² / (g · l1) ≤ 0.5, l1 the leg length (0.48225 H), so\n\
            v_max = √(0.5 · 9.81 · l1) = 1.68 m/s for H = 1.2 m, 2.06 m/s for H = 1.8 m, 2.28 m/s\n\
            for H = 2.2 m (attributes velocity_min, froude_max; velocity_max = 2.5 caps it). Given\n\
            alone, step frequency and step length follow from the normalizing formula:\n\
            sf = √(15000 · v / H) steps/min, sl = 60 · v / sf. [default when none of --velocity,\n\
            --step-length, --step-frequency is given: the attribute preferred_velocity, 1.4 m/s;\n\
            --style brisk 1.7, --style elderly 0.8]"
    )]
    velocity: Option<f64>,

    /// Step length sl in m (heel strike to heel strike of the two feet)
    #[arg(
        long,
        value_name = "M",
        allow_negative_numbers = true,
        long_help = "Step length sl in m: the distance the body advances in one step. Its limits are\n\
            fractions of the leg length (attributes step_length_min/max, by default [0.2, 1.3] leg\n\
            lengths: [0.1736, 1.1285] m for H = 1.8 m). Given alone, sf = sl / (0.004 · H) and\n\
            v = sl · sf / 60. [default: from the normalizing formula]"
    )]
    step_length: Option<f64>,

    /// Step frequency sf in steps/min, range [50, 182]
    #[arg(
        long,
        value_name = "STEPS/MIN",
        allow_negative_numbers = true,
        long_help = "Step frequency sf in steps per minute (each step is 60 / sf s). Valid range [50, 182]\n\
            steps/min (attributes step_frequency_min/max); walking needs a double-support phase, so\n\
            sf < 181.75 steps/min. Given alone, sl = 0.004 · sf · H and v = sl · sf / 60. [default:\n\
            from the normalizing formula]"
    )]
    step_frequency: Option<f64>,

    /// Number of steps, range [1, 1000000] [default: 10, or the schedule's length]
    #[arg(
        long,
        value_name = "N",
        allow_negative_numbers = true,
        long_help = "Number of steps to simulate; valid range [1, 1000000]. With --schedule: the first N rows\n\
            are used, and if N exceeds the schedule's length the last row is held for the remaining\n\
            steps. [default: 10, or the schedule's length with --schedule]"
    )]
    steps: Option<i64>,

    /// Per-step gait requests from a .toml or .csv file (instead of the gait flags)
    #[arg(
        long,
        value_name = "FILE",
        conflicts_with_all = ["velocity", "step_length", "step_frequency"],
        long_help = "Per-step gait requests, one per step, each completed by the normalizing formula like the\n\
            gait flags (so each row needs at least one value). Either a TOML file of [[step]] tables\n\
            with any of the keys velocity (m/s), step_length (m), step_frequency (steps/min), or a\n\
            CSV file (extension .csv) whose header names any of those columns, one row per step,\n\
            empty cells allowed, # starts a comment line. Cannot be combined with --velocity,\n\
            --step-length or --step-frequency."
    )]
    schedule: Option<PathBuf>,

    #[command(flatten)]
    body: BodyArgs,

    /// The engine's model constants: a file in the layout of models/engine.toml (servos, solve
    /// tolerances, fallback limits), checked before any work (docs/cli.md, "Model files")
    /// [default: models/engine.toml]
    #[arg(long, value_name = "FILE.toml")]
    pub(crate) engine_model: Option<PathBuf>,
}

/// The body and style flags of every command that moves a figure.
#[derive(Args)]
pub(crate) struct BodyArgs {
    /// Body height H in m, range [1.2, 2.2]
    #[arg(
        long,
        value_name = "M",
        default_value_t = DEFAULT_HEIGHT,
        allow_negative_numbers = true,
        long_help = "Body height H in m; valid range [1.2, 2.2] m. Segment lengths scale with H (the\n\
            --body-table) and H enters the normalizing formula."
    )]
    height: f64,

    /// Body mass M in kg, range [25, 200]
    #[arg(
        long,
        value_name = "KG",
        default_value_t = DEFAULT_MASS,
        allow_negative_numbers = true,
        long_help = "Body mass M in kg; valid range [25, 200] kg. Segment masses and inertias scale with M."
    )]
    mass: f64,

    /// Locomotion attribute overrides: a TOML file `name = value`
    #[arg(
        long,
        value_name = "FILE",
        long_help = "Locomotion attribute overrides: a flat TOML file of `name = value` lines in the units of\n\
            models/attributes.toml (angles in degrees), e.g. `bounciness = 0.5`. Each value is\n\
            checked against its range; unknown names are an error. Unnamed attributes keep their\n\
            defaults."
    )]
    attributes: Option<PathBuf>,

    /// Style preset: normal, brisk, elderly, march, long-stride or paper (KLAW 1989 as published)
    #[arg(
        long,
        value_name = "NAME",
        long_help = "Style preset: an attribute file bundled from models/styles/ (normal, brisk, elderly,\n\
            march, long-stride, paper: KLAW 1989 as published). --attributes overrides the style's values name by name."
    )]
    style: Option<String>,

    /// Anthropometric table: winter, deleva-male, deleva-female or a table file of your own (FILE.toml)
    #[arg(
        long,
        value_name = "NAME|FILE.toml",
        default_value = DEFAULT_BODY_TABLE,
        long_help = "Anthropometric table the segments scale from with H and M: winter (Winter's / Dempster's\n\
            data, KLAW Table B-1; the default), deleva-male or deleva-female (de Leva 1996, Table 4:\n\
            other proportions, e.g. a women's thigh 0.212 H against Winter's 0.237 H), or a table\n\
            file of your own in the layout of models/body-*.toml (a value ending in .toml or\n\
            containing a /), checked before any work: docs/bodies.md, \"Your own table\"."
    )]
    body_table: String,
}

impl BodyArgs {
    /// The body of the flags.
    pub(crate) fn body(&self) -> Result<Body> {
        Ok(Body::from_table(&self.body_table, self.height, self.mass)?)
    }

    /// The defaults, then the style preset's values, then the attribute file's.
    pub(crate) fn attributes(&self) -> Result<Attributes> {
        input::load_attributes(self.style.as_deref(), self.attributes.as_deref())
    }
}

impl GaitArgs {
    /// The engine's model constants: the file's (`--engine-model`), or the bundled ones.
    pub(crate) fn engine_parameters(&self) -> Result<EngineParameters> {
        Ok(match &self.engine_model {
            Some(path) => EngineParameters::read(path)?,
            None => EngineParameters::default(),
        })
    }

    /// The body of the flags.
    pub(crate) fn body(&self) -> Result<Body> {
        self.body.body()
    }

    /// The defaults, then the style preset's values, then the attribute file's.
    pub(crate) fn attributes(&self) -> Result<Attributes> {
        self.body.attributes()
    }

    /// The gait of every step: the schedule's rows (the last one held) or the flags' one gait.
    pub(crate) fn gaits(&self, body: &Body, attrs: &Attributes) -> Result<Vec<Gait>> {
        let steps = match self.steps {
            Some(n) => Some(check_count("steps", n, 1, MAX_STEPS, "steps")?),
            None => None,
        };
        match &self.schedule {
            Some(path) => {
                let rows = input::read_schedule(path)?;
                let n = self.steps.unwrap_or(rows.len() as i64);
                let n = check_count("steps", n, 1, MAX_STEPS, "steps")?;
                Ok(input::schedule_gaits(path, &rows, n, body, attrs)?)
            }
            None => {
                let request = GaitRequest {
                    velocity: self.velocity,
                    step_length: self.step_length,
                    step_frequency: self.step_frequency,
                };
                let gait = if request == GaitRequest::default() {
                    GaitRequest::preferred(body, attrs)?
                } else {
                    request.complete(body, attrs)?
                };
                Ok(vec![gait; steps.unwrap_or(DEFAULT_STEPS)])
            }
        }
    }

    /// The walk of the flags, refused before any work when it has fewer than `min_steps`
    /// steps or more than `max_steps` (the commands that hold the whole walk in memory bound
    /// it), with the title line of its parameters.
    pub(crate) fn plan(&self, min_steps: usize, max_steps: usize) -> Result<Planned> {
        let body = self.body()?;
        let attrs = self.attributes()?;
        let parameters = self.engine_parameters()?;
        let gaits = self.gaits(&body, &attrs)?;
        if gaits.len() < min_steps {
            let reason = format!(
                "the gait cycle of both legs is averaged over their cycles after the first: at \
                 least {min_steps} steps are needed, not {}",
                gaits.len()
            );
            return Err(klaw::model::InputError::bad_value("steps", reason).into());
        }
        if gaits.len() > max_steps {
            let reason = format!(
                "{} steps: this command holds the whole walk in memory, at most {max_steps} \
                 steps (klaw walk streams any number)",
                gaits.len()
            );
            return Err(klaw::model::InputError::bad_value("steps", reason).into());
        }
        let style = match (&self.body.style, &self.body.attributes) {
            (Some(s), Some(a)) => format!("{s} + {}", a.display()),
            (Some(s), None) => s.clone(),
            (None, Some(a)) => a.display().to_string(),
            (None, None) => "default".to_string(),
        };
        let title = klaw::plot::parameters_title(&gaits, &body, &style);
        Ok(Planned {
            body,
            attrs,
            parameters,
            gaits,
            title,
        })
    }
}

/// A walk checked and ready to simulate ([`GaitArgs::plan`]).
pub(crate) struct Planned {
    body: Body,
    attrs: Attributes,
    parameters: EngineParameters,
    /// The completed gait of every step.
    pub gaits: Vec<Gait>,
    title: String,
}

impl Planned {
    /// Simulate the walk; also the title line of its parameters.
    pub(crate) fn simulate(self) -> Result<(Walk, String)> {
        let walk = simulate_with(self.body, self.attrs, &self.gaits, self.parameters)?;
        Ok((walk, self.title))
    }
}
