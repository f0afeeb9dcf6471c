//! `klaw scenario`: run a scenario file (stand, walk, step, turn, pause; docs/nrs.md) and write
//! its frames, and optionally a stick-figure animation of it and a plot of its footprints.
use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use klaw::Result;
use klaw::export::{self, Options};
use klaw::model::InputError;
use klaw::plot::animation;
use klaw::scenario::{read_scenario, run as run_scenario};

use crate::outputs::{self, Output};
use crate::{DEFAULT_FPS, MAX_FPS, MIN_FPS};

#[derive(Args)]
pub(crate) struct ScenarioArgs {
    /// The scenario file (TOML: [body], [attributes], [[action]] tables; docs/nrs.md)
    #[arg(value_name = "FILE.toml")]
    file: PathBuf,
    /// Frames to write (.csv clinical angles, .mot/.sto OpenSim, .bvh), world frame
    #[arg(long, value_name = "FILE", default_value = "scenario.csv")]
    out: PathBuf,
    /// Frames per second of --out
    #[arg(long, value_name = "HZ", default_value_t = DEFAULT_FPS, allow_negative_numbers = true)]
    fps: f64,
    /// Also write a stick-figure animation (.gif, 25 frames/s, side, front and top view)
    #[arg(long, value_name = "FILE.gif")]
    animate: Option<PathBuf>,
    /// Also write the footprints seen from above (.png or .svg): feet, pelvis path, gaze
    #[arg(long, value_name = "FILE.png|.svg")]
    footprints: Option<PathBuf>,
}

pub(crate) fn run(args: &ScenarioArgs) -> Result<()> {
    let fps = InputError::check_range("fps", args.fps, MIN_FPS, MAX_FPS, "frames/s")?;
    let mut outs = vec![Output::new("out", &args.out, outputs::MOTION)];
    if let Some(p) = &args.animate {
        outs.push(Output::new("animate", p, &["gif"]));
    }
    if let Some(p) = &args.footprints {
        outs.push(Output::new("footprints", p, outputs::FIGURE));
    }
    outputs::check(&outs)?;
    let format = export::Format::from_path(&args.out)?;
    let scenario = read_scenario(&args.file)?;
    let motion = run_scenario(&scenario, fps)?;
    let anim = match &args.animate {
        Some(_) => {
            let options = animation::Options::new(25.0, (1200, 450))?;
            Some((run_scenario(&scenario, options.fps)?, options))
        }
        None => None,
    };
    let body = scenario.body;
    export::write(
        &args.out,
        format,
        &body,
        fps,
        motion.frames.iter().copied(),
        &Options::default(),
    )?;
    let title = format!("scenario {}", args.file.display());
    if let (Some(path), Some((m, options))) = (&args.animate, &anim) {
        animation::write_scenario_gif(m, &body, &title, path, options)?;
    }
    if let Some(path) = &args.footprints {
        klaw::plot::footprints::write(path, &motion, &body, &title)?;
    }
    let mut out = std::io::stdout().lock();
    let duration = motion.frames.last().map_or(0.0, |f| f.time);
    let _ = writeln!(
        out,
        "scenario {}: {} actions, {:.2} s, {} footprints, {} frames: {}",
        args.file.display(),
        scenario.actions.len(),
        duration,
        motion.footprints.len(),
        motion.frames.len(),
        args.out.display()
    );
    if let Some(p) = &args.animate {
        let _ = writeln!(out, "animation: {}", p.display());
    }
    if let Some(p) = &args.footprints {
        let _ = writeln!(out, "footprints: {}", p.display());
    }
    Ok(())
}
