//! `klaw walk`: a walk simulated and written as motion, figure, report, state, events and cycle
//! files.
use std::io::Write;
use std::path::{Path, PathBuf};

use clap::Args;
use klaw::engine::report::Report;
use klaw::model::{InputError, Shown};
use klaw::simulation::stream::{Gather, WalkStream};
use klaw::{Body, Result, export, plot};

use crate::args::GaitArgs;
use crate::outputs::{self, Output};
use crate::progress::Progress;
use crate::{DEFAULT_FPS, MAX_FPS, MIN_FPS, count, font_note};

/// Frames held in memory until the walk ends (--state-out, --cycle-out; ≈ 200 bytes each): cap
/// the count.
const MAX_FRAMES: f64 = 5_000_000.0;

#[derive(Args)]
pub(crate) struct WalkArgs {
    #[command(flatten)]
    pub(crate) gait: GaitArgs,

    /// Output frame rate in frames/s, range [0.001, 10000]
    #[arg(
        long,
        value_name = "HZ",
        default_value_t = DEFAULT_FPS,
        allow_negative_numbers = true,
        long_help = "Frame rate of the CSV output in frames per second; valid range [0.001, 10000]. Frames\n\
            are sampled from t = 0 to the last heel strike, so a walk of duration T has\n\
            round(T · fps) + 1 rows."
    )]
    pub(crate) fps: f64,

    /// Motion of the whole figure: .csv, .mot/.sto (OpenSim) or .bvh by the extension
    #[arg(
        long,
        value_name = "FILE.csv|.mot|.sto|.bvh",
        default_value = "walk.csv",
        long_help = "Motion of the whole figure, one frame per 1/fps, in the format of the extension:\n\
            .csv: time_s, pelvis_tx/ty/tz_m (pelvis centre), pelvis tilt/list/rotation, and for each\n\
            side (_r, _l) hip flexion/adduction/rotation, knee flexion, ankle dorsiflexion, mtp\n\
            dorsiflexion, shoulder flexion/abduction, elbow flexion, lumbar angles, all *_deg with\n\
            clinical signs;\n\
            .mot/.sto: OpenSim storage with gait2392 coordinates (see --opensim-model);\n\
            .bvh: a skeleton for Blender and game engines (Y up, metres; see --in-place).\n\
            Frames are streamed: a walk of any length runs in bounded memory. docs/export.md has\n\
            the column and sign tables. Written whole or not at all."
    )]
    pub(crate) out: PathBuf,

    /// BVH: keep the root over the origin in the walking direction (only with a .bvh --out)
    #[arg(long)]
    pub(crate) in_place: bool,

    /// .mot/.sto: the OpenSim model whose coordinates are written [default: gait2392] (only
    /// with a .mot or .sto --out)
    #[arg(long, value_name = "MODEL", value_parser = ["gait2392", "rajagopal2015"])]
    pub(crate) opensim_model: Option<String>,

    /// The engine's state per frame (θ1..θ4, w, hip and swing-leg points) as CSV [default: none]
    #[arg(long, value_name = "FILE.csv")]
    pub(crate) state_out: Option<PathBuf>,

    /// Gait events (HS, FGM, heel_off, MOM, TO of each foot) at their exact times, as CSV
    #[arg(long, value_name = "FILE.csv")]
    pub(crate) events: Option<PathBuf>,

    /// Joint angles over the gait cycle (0..100 %, right heel strike at 0), averaged over the
    /// steady cycles (all but the first), as CSV
    #[arg(long, value_name = "FILE.csv")]
    pub(crate) cycle_out: Option<PathBuf>,

    /// Figure of the walk to write: PNG or SVG by the extension [default: --out with .png]
    #[arg(
        long,
        value_name = "FILE.png|FILE.svg",
        long_help = "Figure of the walk to write, 1600 × 1000 px, PNG or SVG by the extension (.png or .svg);\n\
            by default the --out path with the extension .png (walk.png for walk.csv). It shows the\n\
            first 12 steps (the title says so when the walk has more), so that its memory and its\n\
            panels stay bounded however long the walk:\n\
            a side view of the legs as stick figures every 0.1 s over the ground (metres, equal\n\
            aspect ratio; blue the right leg, red the left), the hip height against time and the\n\
            joint angles θ1..θ4 in degrees against time. Titles, tick labels and legends need a\n\
            TrueType font, read when the program runs from $KLAW_FONT or else DejaVu Sans\n\
            (/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf); without one the figure is drawn\n\
            without text. Written whole or not at all, after the CSV and the report."
    )]
    pub(crate) plot: Option<PathBuf>,

    /// Do not write the figure
    #[arg(long, conflicts_with = "plot")]
    pub(crate) no_plot: bool,

    /// How the walk is made: dynamic (the engine) or kinematic (a prototype generalized)
    #[arg(
        long,
        value_name = "MODE",
        default_value = "dynamic",
        value_parser = ["dynamic", "kinematic"],
        long_help = "How the walk is made: dynamic, the engine's simulation (KLAW 1989); or kinematic, a\n\
            prototype step generalized to the body and the step length (Ko & Badler 1992,\n\
            docs/generalize.md) and repeated: no shooting, every output but --report (exit 2), one\n\
            gait for every step (a --schedule of different gaits: exit 2)."
    )]
    pub(crate) mode: String,

    /// The kinematic mode's prototype: walk data (.json or .csv) [default: the bundled one, klaw's default walk]
    #[arg(long, value_name = "FILE.json|FILE.csv")]
    pub(crate) prototype: Option<PathBuf>,

    /// The kinematic mode's generalization constants: a file in the layout of
    /// models/generalize.toml (the α slopes, the posing tolerances), checked before any work
    /// (docs/cli.md, "Model files") [default: models/generalize.toml]
    #[arg(long, value_name = "FILE.toml")]
    pub(crate) generalize_model: Option<PathBuf>,

    /// Per-step report to write as JSON [default: none]
    #[arg(
        long,
        value_name = "FILE.json",
        long_help = "Per-step report to write as JSON: target and achieved gait, end-condition errors, and\n\
            the shooting solves (iterations, residual) of every step. Written whole or not at all.\n\
            [default: not written]"
    )]
    pub(crate) report: Option<PathBuf>,
}

/// `klaw walk --mode dynamic`: the engine's simulated walk, written out.
pub(crate) fn run(args: &WalkArgs) -> Result<()> {
    if args.prototype.is_some() {
        let reason = "applies to --mode kinematic only (the dynamic mode walks no prototype)";
        return Err(InputError::bad_value("prototype", reason).into());
    }
    if args.generalize_model.is_some() {
        let reason = "applies to --mode kinematic only (the dynamic mode generalizes nothing)";
        return Err(InputError::bad_value("generalize-model", reason).into());
    }
    let fps = InputError::check_range("fps", args.fps, MIN_FPS, MAX_FPS, "frames/s")?;
    let body = args.gait.body()?;
    let attrs = args.gait.attributes()?;
    let parameters = args.gait.engine_parameters()?;
    let gaits = args.gait.gaits(&body, &attrs)?;
    let plot = check_outputs(args, gaits.len())?;
    let format = export::Format::from_path(&args.out)?;
    let options = options(args, format)?;
    let gather = Gather {
        reports: args.report.is_some(),
        events: args.events.is_some(),
        state_frame_steps: match (&args.state_out, &plot) {
            (Some(_), _) => usize::MAX,
            (None, Some(_)) => plot::walk::FIGURE_STEPS,
            (None, None) => 0,
        },
        clinical: args.cycle_out.is_some(),
    };
    if args.state_out.is_some() || args.cycle_out.is_some() {
        // every frame's state or clinical angles are held until the walk ends: refuse a count
        // that would not fit in memory (the walk lasts Σ 60 / sf)
        let duration = klaw::plan::gait::walk_duration(&gaits);
        InputError::check_range(
            "frame count with --state-out or --cycle-out (duration · fps + 1)",
            (duration * fps).round() + 1.0,
            1.0,
            MAX_FRAMES,
            "frames",
        )?;
    }
    let mut stream = WalkStream::new(body, attrs, &gaits, fps, gather).with_parameters(parameters);
    let frames = stream.frames() as u64;
    let progress = Progress::new("walk", frames, "frames");
    let mut done = 0;
    let counted = stream.by_ref().inspect(|_| {
        done += 1;
        progress.set(done, frames);
    });
    let written = export::try_write(&args.out, format, &body, fps, counted, &options);
    progress.finish();
    written?;
    stream.finish();
    write_outputs(args, &body, &mut stream, plot.as_deref())?;
    print_summary(args, &stream, fps, plot.as_deref());
    Ok(())
}

/// Refuse, before anything is simulated, a cycle output of too short a walk and any output
/// that could not be written ([`outputs::check`]); the figure's path unless --no-plot (by
/// default the motion file's with `.png`).
pub(crate) fn check_outputs(args: &WalkArgs, steps: usize) -> Result<Option<PathBuf>> {
    let least = klaw::analysis::cycle::min_steps(false);
    if args.cycle_out.is_some() && steps < least {
        let reason = format!(
            "the gait cycle is averaged over the right heel strike to right heel strike cycles \
             after the first: at least {least} steps are needed, not {steps}"
        );
        return Err(InputError::bad_value("cycle-out", reason).into());
    }
    let plot = (!args.no_plot).then(|| {
        args.plot
            .clone()
            .unwrap_or_else(|| args.out.with_extension("png"))
    });
    let outputs = [
        Some(Output::new("out", &args.out, outputs::MOTION)),
        args.report
            .as_deref()
            .map(|p| Output::new("report", p, outputs::JSON)),
        plot.as_deref()
            .map(|p| Output::new("plot", p, outputs::FIGURE)),
        args.state_out
            .as_deref()
            .map(|p| Output::new("state-out", p, outputs::CSV)),
        args.events
            .as_deref()
            .map(|p| Output::new("events", p, outputs::CSV)),
        args.cycle_out
            .as_deref()
            .map(|p| Output::new("cycle-out", p, outputs::CSV)),
    ];
    let outputs: Vec<Output> = outputs.into_iter().flatten().collect();
    outputs::check(&outputs)?;
    Ok(plot)
}

/// The export choices of the flags; a choice the motion file's format does not use is refused.
pub(crate) fn options(args: &WalkArgs, format: export::Format) -> Result<export::Options> {
    use export::Format::{Bvh, Mot, Sto};
    if args.in_place && format != Bvh {
        let reason = "applies to a .bvh --out only (the root kept over the origin)";
        return Err(InputError::bad_value("in-place", reason).into());
    }
    if args.opensim_model.is_some() && !matches!(format, Mot | Sto) {
        let reason = "applies to a .mot or .sto --out only (the OpenSim model's coordinates)";
        return Err(InputError::bad_value("opensim-model", reason).into());
    }
    Ok(export::Options {
        in_place: args.in_place,
        opensim_model: match args.opensim_model.as_deref() {
            Some("rajagopal2015") => export::OpenSimModel::Rajagopal2015,
            _ => export::OpenSimModel::Gait2392,
        },
    })
}

/// Write what the walk gathered besides the motion: report, state, events, cycle and figure.
fn write_outputs(
    args: &WalkArgs,
    body: &Body,
    stream: &mut WalkStream,
    plot: Option<&Path>,
) -> Result<()> {
    if let Some(path) = &args.report {
        let report = Report {
            height: body.height,
            mass: body.mass,
            steps: std::mem::take(&mut stream.reports),
        };
        export::write_report_json(path, &report)?;
    }
    if let Some(path) = &args.state_out {
        export::write_frames_csv(path, &stream.state_frames)?;
    }
    if let Some(path) = &args.events {
        export::write_events_csv(path, &stream.events)?;
    }
    if let Some(path) = &args.cycle_out {
        let curves =
            klaw::analysis::cycle::cycle_average(&stream.clinical, &stream.right_heel_strikes, 1)?;
        export::write_cycle_csv(path, &curves)?;
    }
    if let Some(plot) = plot {
        plot::walk::walk_figure(&stream.state_frames, stream.steps, plot)?;
    }
    Ok(())
}

/// The summary on stdout: the walk, the shooting and every file written.
fn print_summary(args: &WalkArgs, stream: &WalkStream, fps: f64, plot: Option<&Path>) {
    let frames = stream.frames();
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "walked {}: {:.3} s simulated, {} at {} frames/s",
        count(stream.steps, "step"),
        stream.duration(),
        count(frames, "frame"),
        Shown(fps)
    );
    let _ = writeln!(
        out,
        "shooting: {}, {:.1} iterations per solve on average, {} at most",
        count(stream.solves, "solve"),
        stream.iterations as f64 / stream.solves.max(1) as f64,
        stream.max_iterations
    );
    print_files(&mut out, args, "engine state", plot);
}

/// The files a walk wrote, a line each (`state` names the state rows), for either mode.
pub(crate) fn print_files(out: &mut impl Write, args: &WalkArgs, state: &str, plot: Option<&Path>) {
    let _ = writeln!(out, "motion: {}", args.out.display());
    for (path, what) in [
        (&args.state_out, state),
        (&args.events, "events"),
        (&args.cycle_out, "gait cycle"),
        (&args.report, "report"),
    ] {
        if let Some(p) = path {
            let _ = writeln!(out, "{what}: {}", p.display());
        }
    }
    if let Some(path) = plot {
        let _ = writeln!(out, "plot: {}{}", path.display(), font_note());
    }
}
