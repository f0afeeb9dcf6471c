//! `klaw bench`: the default walk timed, single-threaded.
use std::io::Write;
use std::path::Path;
use std::time::Instant;

use clap::Args;
use klaw::engine::walker::simulate;
use klaw::model::InputError;
use klaw::{AttributeTable, Attributes, Body, Gait, GaitRequest, Result, export};

use crate::{
    DEFAULT_FPS, DEFAULT_HEIGHT, DEFAULT_MASS, DEFAULT_STEPS, MAX_FPS, MAX_STEPS, MIN_FPS,
    check_count,
};

const MAX_REPEAT: usize = 100_000;

#[derive(Args)]
pub(crate) struct BenchArgs {
    /// Steps per walk, range [1, 1000000]
    #[arg(long, value_name = "N", default_value_t = DEFAULT_STEPS as i64, allow_negative_numbers = true)]
    steps: i64,
    /// Number of walks timed, range [1, 100000]
    #[arg(
        long,
        value_name = "R",
        default_value_t = 20,
        allow_negative_numbers = true
    )]
    repeat: i64,
    /// Also time the kinematics: the figure (landmarks) and the clinical angles of every frame
    #[arg(long)]
    frames: bool,
    /// Frames per second for --frames and --csv, range [0.001, 10000]
    #[arg(long, value_name = "FPS", default_value_t = DEFAULT_FPS)]
    fps: f64,
    /// Also time writing the frames' CSV (to a temporary file, removed afterwards)
    #[arg(long)]
    csv: bool,
}

/// What the timed walks took (wall-clock seconds) and did.
#[derive(Default)]
struct Timings {
    /// Simulating.
    wall: f64,
    /// Sampling the frames and their clinical angles (--frames).
    frames_wall: f64,
    /// Writing the frames' CSV (--csv).
    csv_wall: f64,
    frame_count: usize,
    /// Simulated seconds.
    simulated: f64,
    solves: usize,
    iterations: usize,
}

pub(crate) fn run(args: &BenchArgs) -> Result<()> {
    let steps = check_count("steps", args.steps, 1, MAX_STEPS, "steps")?;
    let repeat = check_count("repeat", args.repeat, 1, MAX_REPEAT, "walks")?;
    let body = Body::standard(DEFAULT_HEIGHT, DEFAULT_MASS)?;
    let attrs = AttributeTable::builtin().defaults();
    let gait = GaitRequest::preferred(&body, &attrs)?;
    let gaits = vec![gait; steps];
    let fps = InputError::check_range("fps", args.fps, MIN_FPS, MAX_FPS, "frames/s")?;
    let csv_path = std::env::temp_dir().join(format!("klaw-bench-{}.csv", std::process::id()));
    let mut t = Timings::default();
    for _ in 0..repeat {
        time_walk(args, &body, &attrs, &gaits, fps, &csv_path, &mut t)?;
    }
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "bench: {repeat} walks of {steps} steps at v = {:.2} m/s ({:.3} s wall)",
        gait.velocity, t.wall
    );
    print_rates(&mut out, args, fps, (steps * repeat) as f64, &t);
    Ok(())
}

/// Simulate one walk and, as asked, sample its frames and write their CSV; add the times to `t`.
fn time_walk(
    args: &BenchArgs,
    body: &Body,
    attrs: &Attributes,
    gaits: &[Gait],
    fps: f64,
    csv_path: &Path,
    t: &mut Timings,
) -> Result<()> {
    let start = Instant::now();
    let walk = simulate(*body, attrs.clone(), gaits)?;
    t.wall += start.elapsed().as_secs_f64();
    t.simulated += walk.duration();
    if args.frames {
        let start = Instant::now();
        for lm in klaw::figure::frames(&walk, fps) {
            let lm = lm?;
            std::hint::black_box(klaw::figure::clinical::clinical(&lm, body)?);
            t.frame_count += 1;
        }
        t.frames_wall += start.elapsed().as_secs_f64();
    }
    if args.csv {
        let start = Instant::now();
        let written = export::try_write(
            csv_path,
            export::Format::Csv,
            body,
            fps,
            klaw::figure::frames(&walk, fps),
            &export::Options::default(),
        );
        t.csv_wall += start.elapsed().as_secs_f64();
        let _ = std::fs::remove_file(csv_path);
        written?;
    }
    for s in &walk.report().steps {
        t.solves += s.solves.len();
        t.iterations += s.solves.iter().map(|r| r.report.iterations).sum::<usize>();
    }
    Ok(())
}

/// The rates: real time, steps per second, frames and CSV as asked, iterations per solve.
fn print_rates(out: &mut impl Write, args: &BenchArgs, fps: f64, total_steps: f64, t: &Timings) {
    let _ = writeln!(
        out,
        "real-time factor: {:.2} simulated s per wall s",
        t.simulated / t.wall
    );
    let _ = writeln!(out, "steps per second: {:.1}", total_steps / t.wall);
    if args.frames {
        let _ = writeln!(
            out,
            "with frames: {} frames at {fps} frames/s ({:.3} s wall, {:.1} us per frame)",
            t.frame_count,
            t.frames_wall,
            1e6 * t.frames_wall / t.frame_count.max(1) as f64
        );
        let _ = writeln!(
            out,
            "real-time factor with frames: {:.2} simulated s per wall s",
            t.simulated / (t.wall + t.frames_wall)
        );
    }
    if args.csv {
        let _ = writeln!(
            out,
            "real-time factor with CSV: {:.2} simulated s per wall s ({:.3} s wall writing)",
            t.simulated / (t.wall + t.csv_wall),
            t.csv_wall
        );
    }
    if t.solves > 0 {
        let _ = writeln!(
            out,
            "iterations per solve: {:.2} ({} solves)",
            t.iterations as f64 / t.solves as f64,
            t.solves
        );
    } else {
        let _ = writeln!(out, "iterations per solve: n/a (no solves recorded)");
    }
}
