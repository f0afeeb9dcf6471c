//! `klaw scenario`: run a scenario file (stand, walk, step, turn, pause; docs/nrs.md) and write
//! its frames, contacts, report, footprint plot and animation; the outputs are shared with `klaw step` and
//! `klaw turn`, which run a one-action scenario.
use std::io::Write;
use std::path::{Path, PathBuf};

use clap::Args;
use klaw::Result;
use klaw::export::{self, Options};
use klaw::model::InputError;
use klaw::nrs::NrsParameters;
use klaw::plot::animation;
use klaw::scenario::{
    Contact, Footprint, Motion, Scenario, Span, read_scenario_with, run as run_scenario,
};
use serde::Serialize;

use crate::outputs::{self, Output};
use crate::{DEFAULT_FPS, MAX_FPS, MIN_FPS, count};

#[derive(Args)]
pub(crate) struct ScenarioArgs {
    /// The scenario file (TOML: [body], [attributes], [[action]] tables; docs/nrs.md)
    #[arg(value_name = "FILE.toml")]
    file: PathBuf,
    #[command(flatten)]
    nrs: NrsModelArg,
    #[command(flatten)]
    outputs: MotionOutputs,
}

/// The NRS model flag of the commands that run a scenario.
#[derive(Args)]
pub(crate) struct NrsModelArg {
    /// The NRS constants: a file in the layout of models/nrs.toml (ν, the swing's peak rise,
    /// the largest turn, the defaults and bounds of a step's values, …), checked before any work
    /// (docs/cli.md, "Model files") [default: models/nrs.toml]
    #[arg(long, value_name = "FILE.toml")]
    nrs_model: Option<PathBuf>,
}

impl NrsModelArg {
    /// The file's constants, or the bundled ones.
    pub(crate) fn parameters(&self) -> Result<NrsParameters> {
        Ok(match &self.nrs_model {
            Some(path) => NrsParameters::read(path)?,
            None => NrsParameters::default(),
        })
    }
}

/// The output flags of the commands that run a scenario.
#[derive(Args)]
pub(crate) struct MotionOutputs {
    /// Frames to write (.csv clinical angles, .mot/.sto OpenSim, .bvh), world frame [default:
    /// the command's name, .csv]
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Frames per second of --out, range [0.001, 10000]
    #[arg(long, value_name = "HZ", default_value_t = DEFAULT_FPS, allow_negative_numbers = true)]
    fps: f64,
    /// Foot contacts as CSV: time_s, side, event (foot_strike, foot_off), action, kind
    #[arg(long, value_name = "FILE.csv")]
    events: Option<PathBuf>,
    /// Report as JSON: the actions' time spans, the footprints and the contacts
    #[arg(long, value_name = "FILE.json")]
    report: Option<PathBuf>,
    /// Also write a stick-figure animation (.gif: side, front and top view)
    #[arg(long, value_name = "FILE.gif")]
    animate: Option<PathBuf>,
    /// The animation's frames per second of scenario time (also its playback rate), range [1, 100]
    #[arg(
        long,
        value_name = "HZ",
        default_value_t = 25.0,
        allow_negative_numbers = true
    )]
    animate_fps: f64,
    /// The animation's size in pixels, WIDTHxHEIGHT
    #[arg(
        long,
        value_name = "WxH",
        default_value = "1200x450",
        allow_hyphen_values = true
    )]
    animate_size: String,
    /// Also write the footprints seen from above (.png or .svg): feet, pelvis path, gaze
    #[arg(long, value_name = "FILE.png|.svg")]
    footprints: Option<PathBuf>,
}

/// What `--report` writes.
#[derive(Serialize)]
struct Report<'a> {
    /// What ran (the file, or the command's action).
    scenario: &'a str,
    height_m: f64,
    mass_kg: f64,
    duration_s: f64,
    /// The actions as they ran, with the starts and stops added around walks.
    actions: &'a [Span],
    /// Every footprint: ankle (x, z) in m, direction in rad (+ left).
    footprints: &'a [Footprint],
    contacts: &'a [Contact],
}

pub(crate) fn run(args: &ScenarioArgs) -> Result<()> {
    let o = &args.outputs;
    let out = o.out_path("scenario");
    o.check(&out)?;
    let scenario = read_scenario_with(&args.file, args.nrs.parameters()?)?;
    o.write(
        &scenario,
        &out,
        &format!("scenario {}", args.file.display()),
    )
}

impl MotionOutputs {
    /// `--out`, or `<name>.csv`.
    pub(crate) fn out_path(&self, name: &str) -> PathBuf {
        self.out
            .clone()
            .unwrap_or_else(|| format!("{name}.csv").into())
    }

    /// Refuse a bad frame rate and any output that could not be written, before any work.
    pub(crate) fn check(&self, out: &Path) -> Result<()> {
        InputError::check_range("fps", self.fps, MIN_FPS, MAX_FPS, "frames/s")?;
        self.animation()?;
        let mut outs = vec![Output::new("out", out, outputs::MOTION)];
        for (flag, path, ext) in [
            ("events", &self.events, outputs::CSV),
            ("report", &self.report, outputs::JSON),
            ("animate", &self.animate, &["gif"][..]),
            ("footprints", &self.footprints, outputs::FIGURE),
        ] {
            if let Some(p) = path {
                outs.push(Output::new(flag, p, ext));
            }
        }
        outputs::check(&outs)?;
        export::Format::from_path(out)?;
        Ok(())
    }

    /// Run `scenario` and write every output asked for, then the summary; `what` names it in
    /// the report, the animation's title and the summary.
    pub(crate) fn write(&self, scenario: &Scenario, out: &Path, what: &str) -> Result<()> {
        let format = export::Format::from_path(out)?;
        let motion = run_scenario(scenario, self.fps)?;
        let anim = match &self.animate {
            Some(_) => {
                let options = self.animation()?;
                let m = run_scenario(scenario, options.fps)?;
                let t = m.frames.last().map_or(0.0, |f| f.time);
                animation::check_frame_count(t, options.fps)?;
                Some((m, options))
            }
            None => None,
        };
        let body = scenario.body;
        let frames = motion.frames.iter().copied();
        export::write(out, format, &body, self.fps, frames, &Options::default())?;
        if let Some(path) = &self.events {
            let header = ["time_s", "side", "event", "action", "kind"];
            export::write_rows_csv(path, &header, &motion.contacts)?;
        }
        let duration = motion.frames.last().map_or(0.0, |f| f.time);
        if let Some(path) = &self.report {
            let report = Report {
                scenario: what,
                height_m: body.height,
                mass_kg: body.mass,
                duration_s: duration,
                actions: &motion.spans,
                footprints: &motion.footprints,
                contacts: &motion.contacts,
            };
            export::write_report_json(path, &report)?;
        }
        if let (Some(path), Some((m, options))) = (&self.animate, &anim) {
            animation::write_scenario_gif(m, &body, what, path, options)?;
        }
        if let Some(path) = &self.footprints {
            klaw::plot::footprints::write(path, &motion, &body, what)?;
        }
        self.summary(scenario, &motion, out, what, duration);
        Ok(())
    }

    /// The animation's frame rate and size.
    fn animation(&self) -> Result<animation::AnimationOptions> {
        let (lo, hi) = (1.0, 100.0);
        InputError::check_range("animate-fps", self.animate_fps, lo, hi, "frames/s")?;
        let size = animation::parse_size(&self.animate_size)?;
        Ok(animation::AnimationOptions::new(self.animate_fps, size)?)
    }

    fn summary(&self, scenario: &Scenario, motion: &Motion, out: &Path, what: &str, t: f64) {
        let mut o = std::io::stdout().lock();
        let _ = writeln!(
            o,
            "{what}: {}, {t:.2} s, {}, {}: {}",
            count(scenario.actions.len(), "action"),
            count(motion.footprints.len(), "footprint"),
            count(motion.frames.len(), "frame"),
            out.display()
        );
        for (path, name) in [
            (&self.events, "events"),
            (&self.report, "report"),
            (&self.animate, "animation"),
            (&self.footprints, "footprints"),
        ] {
            if let Some(p) = path {
                let _ = writeln!(o, "{name}: {}", p.display());
            }
        }
    }
}
