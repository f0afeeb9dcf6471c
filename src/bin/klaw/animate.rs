//! `klaw animate`: a stick-figure animation of a walk as an animated GIF.
use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use klaw::Result;
use klaw::plan::gait::walk_duration;
use klaw::plot::animation::{self, AnimationOptions};

use crate::args::GaitArgs;
use crate::font_note;
use crate::outputs::{self, Output};
use crate::progress::Spinner;

/// The most steps `klaw animate` walks: the whole walk is held while its frames are drawn, and
/// an animation has at most 20 000 frames (about 2 000 steps at 20 frames/s).
const MAX_STEPS: usize = 2000;

#[derive(Args)]
pub(crate) struct AnimateArgs {
    #[command(flatten)]
    walk: GaitArgs,
    /// Animation to write (.gif)
    #[arg(long, value_name = "FILE.gif", default_value = "walk.gif")]
    out: PathBuf,
    /// Frames per second of walk time (also the playback rate), range [1, 100]
    #[arg(
        long,
        value_name = "HZ",
        default_value_t = 25.0,
        allow_negative_numbers = true
    )]
    fps: f64,
    /// Image size in pixels, WIDTHxHEIGHT (not --height: that is the body height)
    #[arg(
        long,
        value_name = "WxH",
        default_value = "900x450",
        allow_hyphen_values = true
    )]
    size: String,
}

pub(crate) fn run(args: &AnimateArgs) -> Result<()> {
    let options = AnimationOptions::new(args.fps, animation::parse_size(&args.size)?)?;
    outputs::check(&[Output::new("out", &args.out, &["gif"])])?;
    let planned = args.walk.plan(1, MAX_STEPS)?;
    // the frame count is known from the gait before anything is simulated
    animation::check_frame_count(walk_duration(&planned.gaits), options.fps)?;
    let spinner = Spinner::new("simulating the walk and drawing its animation".into());
    let (walk, title) = planned.simulate()?;
    let summary = animation::animate_walk(&walk, &title, &args.out, &options)?;
    drop(spinner);
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "animation of {title}: {} frames at {} frames/s, {} x {} px: {}{}",
        summary.frames,
        options.fps,
        options.size.0,
        options.size.1,
        args.out.display(),
        font_note()
    );
    Ok(())
}
