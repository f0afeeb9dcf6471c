//! The `klaw` command line: parse the flags, call the library, write the files, print a summary.
//! No physics here. Errors print `error: <message>` and exit with `Error::exit_code()` (2 for bad
//! input, 1 for a simulation or output failure); clap's usage errors exit 2 as well.
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::{Args, Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};
use klaw::engine::report::Report;
use klaw::engine::stream::{Gather, WalkStream};
use klaw::engine::walker::simulate;
use klaw::sweep::output as swio;
use klaw::sweep::{self as sw, Axis};
use klaw::{
    AttributeTable, Attributes, Body, Error, Gait, GaitRequest, Result, export, input, plot,
};

const DEFAULT_HEIGHT: f64 = 1.8;
const DEFAULT_MASS: f64 = 80.0;
const DEFAULT_VELOCITY: f64 = 1.4;
const DEFAULT_STEPS: usize = 10;
const DEFAULT_FPS: f64 = 100.0;
const MAX_STEPS: usize = 1_000_000;
const MIN_FPS: f64 = 0.001;
const MAX_FPS: f64 = 10_000.0;
const MAX_REPEAT: usize = 100_000;
/// Frames are held in memory before they are written (≈ 200 bytes each): cap the count.
const MAX_FRAMES: f64 = 5_000_000.0;

#[derive(Parser)]
#[command(
    name = "klaw",
    version,
    about = "Goal-directed, dynamically simulated human walking (Bruderlin & Calvert's KLAW, 1989)",
    long_about = "Goal-directed, dynamically simulated human walking after Bruderlin & Calvert, \"Goal-directed,\n\
        dynamic animation of human walking\" (SIGGRAPH 1989).\n\
        \n\
        `klaw walk` simulates a walk and writes its frames as CSV and a figure of it (PNG or SVG);\n\
        `klaw bench` times the default walk.\n\
        \n\
        Exit status: 0 on success, 2 for bad input (a flag or file out of range or malformed), 1 when\n\
        the simulation or writing the output fails."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Simulate a walk and write its frames (CSV), a figure (PNG/SVG) and optionally a report (JSON)
    #[command(
        long_about = "Simulate a walk and write its frames (CSV), a figure of it (PNG or SVG) and optionally a\n\
            per-step report (JSON).\n\
            \n\
            The gait is given by any of --velocity (v, m/s), --step-length (sl, m) and --step-frequency (sf,\n\
            steps/min); the others are completed by KLAW's normalizing formula for a body of height H:\n\
            sl = 0.004 · sf · H and v = sl · sf / 60. Only v → sf = √(15000 · v / H), sl = 60 · v / sf; only\n\
            sf → sl = 0.004 · sf · H; only sl → sf = sl / (0.004 · H); two given → the third from\n\
            v = sl · sf / 60; all three → they must agree (v = sl · sf / 60 within 1 %). With none,\n\
            v = 1.4 m/s. The completed gait is checked against the\n\
            anatomical limits of the attributes (by default v in [0.4, 2.5] m/s, sf in [50, 182] steps/min,\n\
            sl in [0.2, 1.3] leg lengths, i.e. [0.1736, 1.1285] m for H = 1.8 m).\n\
            \n\
            Example: klaw walk --velocity 1.2 --steps 6 --out slow.csv --plot slow.svg --report slow.json"
    )]
    Walk(WalkArgs),
    /// Time the default walk (v = 1.4 m/s, H = 1.8 m, M = 80 kg), single-threaded
    #[command(
        long_about = "Time the default walk (v = 1.4 m/s, H = 1.8 m, M = 80 kg), single-threaded, and print the\n\
            real-time factor (simulated seconds per wall-clock second), steps per second and mean shooting\n\
            iterations per solve. Only the simulation is timed; no frames are sampled or written."
    )]
    Bench(BenchArgs),
    /// Run many walks over a grid of gaits, bodies and attributes; one summary row per walk
    #[command(
        long_about = "Run one walk per point of the Cartesian product of the given values, in parallel on all\n\
            cores (RAYON_NUM_THREADS sets the thread count), and write one summary row per walk as\n\
            CSV or JSON Lines (by the extension of --out).\n\
            \n\
            Every value flag takes a single number X, an inclusive range START:STOP:STEP (STOP is\n\
            included within 1e-9 relative) or a list A,B,C; a sweep file (--file) can give any of\n\
            them, and flags override it. Unswept quantities take the defaults of `klaw walk`\n\
            (H 1.8 m, M 80 kg, 10 steps, v 1.4 m/s when no gait flag is given).\n\
            \n\
            Rows come in product order (velocity, step_length, step_frequency, height, mass,\n\
            mass_per_height2, steps, then the attributes: the first varies slowest), numbered by\n\
            the point column, and are identical whatever the thread count. They are written as the\n\
            walks complete (memory does not grow with the sweep) to .NAME.partial next to --out,\n\
            renamed to --out at the end (see --resume). A point that fails (out of range, no\n\
            convergence) gets converged = false and the reason in the error column; the sweep\n\
            carries on. Columns after the inputs: converged, error, mean_iterations and\n\
            max_iterations (shooting trials per solve), achieved_velocity (m/s),\n\
            achieved_step_length (m), achieved_step_frequency (steps/min), mean_hip_excursion (m),\n\
            max_peak_swing_knee_flexion_deg, stance_pct and double_support_pct (% of the cycle),\n\
            min_toe_clearance (m), work_per_m (J/m: the actuators' positive mechanical work per\n\
            metre walked) and work_per_kg_m (J/(kg m)).\n\
            \n\
            A progress bar is drawn when stderr is a terminal, plain progress lines otherwise.\n\
            \n\
            Example: klaw sweep --velocity 0.6:2.0:0.1 --height 1.5,1.65,1.8,1.95 --mass-per-height2 23"
    )]
    Sweep(SweepArgs),
    /// Join sweep outputs (the shards of a sweep) into one file in point order
    #[command(
        long_about = "Join sweep outputs, typically the shards of one sweep (klaw sweep --shard K/N), into one\n\
            file with the rows in point order: byte-identical to the output of the unsharded sweep.\n\
            \n\
            The inputs must have the output's format and the same columns. A point found in more than\n\
            one input must have the same row in each (written once, with a warning); different rows\n\
            for a point are an error. Points missing below the largest point found are an error\n\
            unless --allow-missing (a missing shard would leave such gaps); points after the largest\n\
            cannot be detected. A cut-off last line (an interrupted run) is not merged (warning).\n\
            The output is written whole or not at all.\n\
            \n\
            Example: klaw merge all.csv part-*.csv"
    )]
    Merge(MergeArgs),
    /// Heat map (PNG/SVG) of a sweep's result column over two swept parameters
    #[command(
        long_about = "Draw a heat map of one result column of a sweep output (CSV or JSON Lines) over two swept\n\
            parameters: a cell per (x, y) pair, spanning halfway to the neighbouring values, coloured\n\
            on the viridis scale with a colour bar; points that failed are light grey with a dark\n\
            cross. If the sweep varies other parameters too, a cell shows the mean over its converged\n\
            walks (for converged: the fraction converged) and is failed when none converged.\n\
            1200 × 900 px, PNG or SVG by the extension of --out, written whole or not at all; text\n\
            needs a TrueType font (see klaw walk --help, --plot).\n\
            \n\
            Examples:\n\
            klaw plot-sweep grid.csv --x velocity --y height --column converged --out converged.png\n\
            klaw plot-sweep grid.csv --x velocity --y height --column mean_iterations --out it.svg\n\
            klaw plot-sweep grid.csv --x velocity --y height --column peak_knee --out knee.png"
    )]
    PlotSweep(PlotSweepArgs),
    /// Joint angle curves over the gait cycle with the normal ranges shaded (PNG/SVG)
    #[command(
        long_about = "Simulate a walk (the flags of `klaw walk`; default: v 1.4 m/s, H 1.8 m, M 80 kg, 10 steps)\n\
            and draw its joint angle curves over the gait cycle: hip flexion, knee flexion, ankle\n\
            dorsiflexion, pelvic list, pelvic rotation and pelvis height against 0-100 % of the cycle,\n\
            averaged over the steady cycles (the first cycle of each leg is left out, so at least 6\n\
            steps are needed: heel strikes start the even steps on the right, the odd ones on the\n\
            left; the walk is sampled at 200 frames/s). The right leg\n\
            and the pelvis run from right heel strike, the left leg (dashed) from left heel strike.\n\
            The published normal ranges of models/gait-norms.toml are shaded over their cycle\n\
            windows, and each is checked: the values are printed, outside ranges flagged.\n\
            1500 x 1000 px, PNG or SVG by the extension of --out, written whole or not at all.\n\
            \n\
            Example: klaw plot --velocity 1.2 --out slow-cycle.svg"
    )]
    Plot(PlotArgs),
    /// Stick-figure animation of a walk, side and front view (animated GIF)
    #[command(
        long_about = "Simulate a walk (the flags of `klaw walk`) and write a stick-figure animation of it as an\n\
            animated GIF: a side view (x forward, y up; the camera follows the pelvis, ticks on the\n\
            ground every 0.25 m) and a front view (the walker coming towards you: its right side on\n\
            the left of the picture). Legs (hip, knee, ankle, heel, metatarsal joint, toe), pelvis,\n\
            spine, shoulders, head and arms; the right side blue, the left red. A black dot marks\n\
            every foot point on the ground (heel, metatarsal joint or toe tip within 1 mm of it).\n\
            One GIF frame per 1/fps s of walk time, shown for 1/fps s (GIF delays are whole\n\
            hundredths of a second). Written whole or not at all.\n\
            \n\
            Example: klaw animate --velocity 1.2 --out slow.gif --fps 20 --size 600x300"
    )]
    Animate(AnimateArgs),
}

impl GaitArgs {
    /// Simulate the walk; also the title line of its parameters.
    fn simulate(&self) -> Result<(klaw::engine::walker::Walk, String)> {
        let body = Body::standard(self.height, self.mass)?;
        let attrs = load_attributes(self.style.as_deref(), self.attributes.as_deref())?;
        let gaits = gaits(self, &body, &attrs)?;
        let style = match (&self.style, &self.attributes) {
            (Some(s), Some(a)) => format!("{s} + {}", a.display()),
            (Some(s), None) => s.clone(),
            (None, Some(a)) => a.display().to_string(),
            (None, None) => "default".to_string(),
        };
        let title = klaw::plot::cycle::parameters_title(&gaits, &body, &style);
        Ok((simulate(body, attrs, &gaits)?, title))
    }
}

#[derive(Args)]
struct PlotArgs {
    #[command(flatten)]
    walk: GaitArgs,
    /// Figure to write: PNG or SVG by the extension
    #[arg(
        long,
        value_name = "FILE.png|FILE.svg",
        default_value = "plots/gait-cycle.png"
    )]
    out: PathBuf,
}

#[derive(Args)]
struct AnimateArgs {
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
    #[arg(long, value_name = "WxH", default_value = "900x450")]
    size: String,
}

#[derive(Args)]
struct SweepArgs {
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
    /// Style presets A,B,C (normal, brisk, elderly, march, long-stride); --attr overrides them
    #[arg(long, value_name = "NAMES")]
    style: Option<String>,
    /// A locomotion attribute to sweep, NAME=SPEC in the units of models/attributes.toml (repeatable)
    #[arg(long, value_name = "NAME=SPEC", allow_hyphen_values = true)]
    attr: Vec<String>,
    /// Run only the K-th of N interleaved slices (points with point mod N = K − 1), 1 ≤ K ≤ N
    #[arg(
        long,
        value_name = "K/N",
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

#[derive(Args)]
struct PlotSweepArgs {
    /// Sweep output to read (.csv or .jsonl)
    input: PathBuf,
    /// Swept parameter on the horizontal axis (a column name, e.g. velocity)
    #[arg(long)]
    x: String,
    /// Swept parameter on the vertical axis (a column name, e.g. height)
    #[arg(long)]
    y: String,
    /// Result column to colour by: any numeric column, e.g. converged, mean_iterations (alias
    /// iterations), max_peak_swing_knee_flexion_deg (alias peak_knee), work_per_m
    #[arg(long)]
    column: String,
    /// Heat map to write: PNG or SVG by the extension
    #[arg(long, value_name = "FILE.png|FILE.svg")]
    out: PathBuf,
}

#[derive(Args)]
struct MergeArgs {
    /// Output file: CSV (.csv) or JSON Lines (.jsonl), the inputs' format
    out: PathBuf,
    /// Sweep outputs to join (typically the shards of one sweep)
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    /// Write the rows even when points are missing (a warning instead of an error)
    #[arg(long)]
    allow_missing: bool,
}

/// The gait, body and attribute flags of `klaw walk`, `klaw plot` and `klaw animate`.
#[derive(Args)]
struct GaitArgs {
    /// Walking speed v in m/s, range [0.4, 2.5] [default: 1.4 if no gait flag is given]
    #[arg(
        long,
        value_name = "M/S",
        allow_negative_numbers = true,
        long_help = "Walking speed v in m/s; valid range [0.4, 2.5] m/s (attributes velocity_min/max). Given\n\
            alone, step frequency and step length follow from the normalizing formula:\n\
            sf = √(15000 · v / H) steps/min, sl = 60 · v / sf. [default: 1.4 when none of\n\
            --velocity, --step-length, --step-frequency is given]"
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

    /// Body height H in m, range [1.2, 2.2]
    #[arg(
        long,
        value_name = "M",
        default_value_t = DEFAULT_HEIGHT,
        allow_negative_numbers = true,
        long_help = "Body height H in m; valid range [1.2, 2.2] m. Segment lengths scale with H (Winter's\n\
            anthropometric table) and H enters the normalizing formula."
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

    /// Number of steps, range [1, 1000000] [default: 10, or the schedule's length]
    #[arg(
        long,
        value_name = "N",
        long_help = "Number of steps to simulate; valid range [1, 1000000]. With --schedule: the first N rows\n\
            are used, and if N exceeds the schedule's length the last row is held for the remaining\n\
            steps. [default: 10, or the schedule's length with --schedule]"
    )]
    steps: Option<usize>,

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

    /// Style preset: normal, brisk, elderly, march or long-stride
    #[arg(
        long,
        value_name = "NAME",
        long_help = "Style preset: an attribute file bundled from models/styles/ (normal, brisk, elderly,\n\
            march, long-stride). --attributes overrides the style's values name by name."
    )]
    style: Option<String>,
}

#[derive(Args)]
struct WalkArgs {
    #[command(flatten)]
    gait: GaitArgs,

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
    fps: f64,

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
    out: PathBuf,

    /// BVH: keep the root over the origin in the walking direction
    #[arg(long)]
    in_place: bool,

    /// .mot/.sto: the OpenSim model whose coordinates are written
    #[arg(long, value_name = "MODEL", default_value = "gait2392", value_parser = ["gait2392", "rajagopal2015"])]
    opensim_model: String,

    /// The engine's state per frame (θ1..θ4, w, hip and swing-leg points) as CSV [default: none]
    #[arg(long, value_name = "FILE.csv")]
    state_out: Option<PathBuf>,

    /// Gait events (HS, FGM, heel_off, MOM, TO of each foot) at their exact times, as CSV
    #[arg(long, value_name = "FILE.csv")]
    events: Option<PathBuf>,

    /// Joint angles over the gait cycle (0..100 %, right heel strike at 0), averaged over the
    /// steady cycles (all but the first), as CSV
    #[arg(long, value_name = "FILE.csv")]
    cycle_out: Option<PathBuf>,

    /// Figure of the walk to write: PNG or SVG by the extension
    #[arg(
        long,
        value_name = "FILE.png|FILE.svg",
        default_value = "walk.png",
        long_help = "Figure of the walk to write, 1600 × 1000 px, PNG or SVG by the extension (.png or .svg):\n\
            a side view of the legs as stick figures every 0.1 s over the ground (metres, equal\n\
            aspect ratio; blue the right leg, red the left), the hip height against time and the\n\
            joint angles θ1..θ4 in degrees against time. Titles, tick labels and legends need a\n\
            TrueType font, read when the program runs from $KLAW_FONT or else DejaVu Sans\n\
            (/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf); without one the figure is drawn\n\
            without text. Written whole or not at all, after the CSV and the report."
    )]
    plot: PathBuf,

    /// Do not write the figure
    #[arg(long, conflicts_with = "plot")]
    no_plot: bool,

    /// Per-step report to write as JSON [default: none]
    #[arg(
        long,
        value_name = "FILE.json",
        long_help = "Per-step report to write as JSON: target and achieved gait, end-condition errors, and\n\
            the shooting solves (iterations, residual) of every step. Written whole or not at all.\n\
            [default: not written]"
    )]
    report: Option<PathBuf>,
}

#[derive(Args)]
struct BenchArgs {
    /// Steps per walk, range [1, 1000000]
    #[arg(long, value_name = "N", default_value_t = DEFAULT_STEPS)]
    steps: usize,
    /// Number of walks timed, range [1, 100000]
    #[arg(long, value_name = "R", default_value_t = 20)]
    repeat: usize,
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

fn main() -> ExitCode {
    klaw::memory::keep_freed_memory();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Walk(args) => walk(&args),
        Command::Bench(args) => bench(&args),
        Command::Sweep(args) => sweep(&args),
        Command::Merge(args) => merge(&args),
        Command::PlotSweep(args) => plot_sweep(&args),
        Command::Plot(args) => plot_cycle(&args),
        Command::Animate(args) => animate(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(u8::try_from(e.exit_code()).unwrap_or(1))
        }
    }
}

fn check_count(name: &str, value: usize, min: usize, max: usize, unit: &str) -> Result<usize> {
    Error::check_range(name, value as f64, min as f64, max as f64, unit)?;
    Ok(value)
}

/// Fail before simulating if an output file could not be created: its directory must exist.
fn check_output_dir(path: &Path) -> Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if dir.is_dir() {
        Ok(())
    } else {
        Err(Error::Io {
            action: "writing",
            path: path.to_path_buf(),
            source: std::io::Error::new(
                std::io::ErrorKind::NotFound,
                format!("directory {} does not exist", dir.display()),
            ),
        })
    }
}

/// The gait of every step: the schedule's rows (the last one held) or the flags' one gait.
fn gaits(args: &GaitArgs, body: &Body, attrs: &Attributes) -> Result<Vec<Gait>> {
    if let Some(steps) = args.steps {
        check_count("steps", steps, 1, MAX_STEPS, "steps")?;
    }
    match &args.schedule {
        Some(path) => {
            let rows = input::read_schedule(path)?;
            let n = args.steps.unwrap_or(rows.len());
            check_count("steps", n, 1, MAX_STEPS, "steps")?;
            let completed = rows
                .iter()
                .take(n)
                .enumerate()
                .map(|(i, r)| {
                    r.complete(body, attrs).map_err(|e| Error::Malformed {
                        what: "schedule",
                        path: path.clone(),
                        reason: format!("step {}: {e}", i + 1),
                    })
                })
                .collect::<Result<Vec<_>>>()?;
            let last = *completed.last().expect("a schedule has at least one step");
            let mut gaits = completed;
            gaits.resize(n, last);
            Ok(gaits)
        }
        None => {
            let mut request = GaitRequest {
                velocity: args.velocity,
                step_length: args.step_length,
                step_frequency: args.step_frequency,
            };
            if request == GaitRequest::default() {
                request.velocity = Some(DEFAULT_VELOCITY);
            }
            let gait = request.complete(body, attrs)?;
            Ok(vec![gait; args.steps.unwrap_or(DEFAULT_STEPS)])
        }
    }
}

/// The defaults, then the style preset's values, then the attribute file's.
fn load_attributes(style: Option<&str>, path: Option<&Path>) -> Result<Attributes> {
    let table = AttributeTable::builtin();
    let mut overrides = match style {
        Some(name) => klaw::model::attributes::style(name)?,
        None => Default::default(),
    };
    let mut source = style.map_or(String::new(), |s| format!("style {s}"));
    if let Some(p) = path {
        overrides.extend(input::read_attributes(p)?);
        source = p.display().to_string();
    }
    table.resolve(&overrides, &source)
}

fn walk(args: &WalkArgs) -> Result<()> {
    let fps = Error::check_range("fps", args.fps, MIN_FPS, MAX_FPS, "frames/s")?;
    let body = Body::standard(args.gait.height, args.gait.mass)?;
    let attrs = load_attributes(args.gait.style.as_deref(), args.gait.attributes.as_deref())?;
    let gaits = gaits(&args.gait, &body, &attrs)?;
    // the walk lasts Σ 60 / sf
    let expected_duration: f64 = gaits.iter().map(|g| 60.0 / g.step_frequency).sum();
    let expected_frames = (expected_duration * fps).round() + 1.0;
    let format = export::Format::from_path(&args.out)?;
    if args.cycle_out.is_some() && gaits.len() < 5 {
        return Err(Error::BadSpec {
            flag: "cycle-out".into(),
            reason: format!(
                "the gait cycle is averaged over the right heel strike to right heel strike \
                 cycles after the first: at least 5 steps are needed, not {}",
                gaits.len()
            ),
        });
    }
    let plot = (!args.no_plot).then_some(args.plot.as_path());
    let outputs = [
        Some((args.out.as_path(), "--out")),
        args.report.as_deref().map(|p| (p, "--report")),
        plot.map(|p| (p, "--plot")),
        args.state_out.as_deref().map(|p| (p, "--state-out")),
        args.events.as_deref().map(|p| (p, "--events")),
        args.cycle_out.as_deref().map(|p| (p, "--cycle-out")),
    ];
    let outputs: Vec<(&Path, &str)> = outputs.into_iter().flatten().collect();
    if let Some(plot) = plot {
        plot::figure_format(plot)?;
    }
    for (i, (path, flag)) in outputs.iter().enumerate() {
        check_output_dir(path)?;
        if let Some((_, other)) = outputs[..i].iter().find(|(p, _)| p == path) {
            return Err(Error::Malformed {
                what: "output path",
                path: path.to_path_buf(),
                reason: format!("{other} and {flag} name the same file"),
            });
        }
    }
    let options = export::Options {
        in_place: args.in_place,
        opensim_model: match args.opensim_model.as_str() {
            "rajagopal2015" => export::OpenSimModel::Rajagopal2015,
            _ => export::OpenSimModel::Gait2392,
        },
    };
    let gather = Gather {
        reports: args.report.is_some(),
        events: args.events.is_some(),
        state_frames: plot.is_some() || args.state_out.is_some(),
        clinical: args.cycle_out.is_some(),
    };
    if gather.state_frames {
        // the state frames are kept for the figure: refuse a count that would not fit in memory
        Error::check_range(
            "frame count with --plot or --state-out (duration · fps + 1)",
            expected_frames,
            1.0,
            MAX_FRAMES,
            "frames; use --no-plot for longer walks",
        )?;
    }

    let mut stream = WalkStream::new(body, attrs, &gaits, fps, gather);
    export::try_write(&args.out, format, &body, fps, &mut stream, &options)?;
    stream.finish();
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
        let curves = export::cycle_average(&stream.clinical, &stream.right_heel_strikes, 1)?;
        export::write_cycle_csv(path, &curves)?;
    }
    if let Some(plot) = plot {
        plot::walk_figure(&stream.state_frames, plot)?;
    }
    let frames = (stream.duration() * fps + 1e-9).floor() as usize + 1;

    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "walked {} steps: {:.3} s simulated, {} frames at {} frames/s",
        stream.steps,
        stream.duration(),
        frames,
        fps
    );
    let _ = writeln!(
        out,
        "shooting: {} solves, {:.1} iterations per solve on average, {} at most",
        stream.solves,
        stream.iterations as f64 / stream.solves.max(1) as f64,
        stream.max_iterations
    );
    let _ = writeln!(out, "motion: {}", args.out.display());
    for (path, what) in [
        (&args.state_out, "engine state"),
        (&args.events, "events"),
        (&args.cycle_out, "gait cycle"),
    ] {
        if let Some(p) = path {
            let _ = writeln!(out, "{what}: {}", p.display());
        }
    }
    if let Some(path) = &args.report {
        let _ = writeln!(out, "report: {}", path.display());
    }
    if let Some(path) = plot {
        let note = if plot::text_available() {
            ""
        } else {
            " (no font found: drawn without text; set KLAW_FONT to a .ttf file)"
        };
        let _ = writeln!(out, "plot: {}{note}", path.display());
    }
    Ok(())
}

fn bench(args: &BenchArgs) -> Result<()> {
    let steps = check_count("steps", args.steps, 1, MAX_STEPS, "steps")?;
    let repeat = check_count("repeat", args.repeat, 1, MAX_REPEAT, "walks")?;
    let body = Body::standard(DEFAULT_HEIGHT, DEFAULT_MASS)?;
    let attrs = AttributeTable::builtin().defaults();
    let gait = GaitRequest {
        velocity: Some(DEFAULT_VELOCITY),
        ..GaitRequest::default()
    }
    .complete(&body, &attrs)?;
    let gaits = vec![gait; steps];

    let fps = Error::check_range("fps", args.fps, MIN_FPS, MAX_FPS, "frames/s")?;
    let csv_path = std::env::temp_dir().join(format!("klaw-bench-{}.csv", std::process::id()));

    let mut wall = 0.0;
    let mut frames_wall = 0.0;
    let mut csv_wall = 0.0;
    let mut frame_count = 0usize;
    let mut simulated = 0.0;
    let mut solves = 0usize;
    let mut iterations = 0usize;
    for _ in 0..repeat {
        let start = Instant::now();
        let walk = simulate(body, attrs.clone(), &gaits)?;
        wall += start.elapsed().as_secs_f64();
        simulated += walk.duration();
        if args.frames {
            let start = Instant::now();
            for lm in klaw::figure::frames(&walk, fps) {
                let lm = lm?;
                std::hint::black_box(klaw::figure::skeleton::clinical(&lm, &body)?);
                frame_count += 1;
            }
            frames_wall += start.elapsed().as_secs_f64();
        }
        if args.csv {
            let start = Instant::now();
            let written = export::try_write(
                &csv_path,
                export::Format::Csv,
                &body,
                fps,
                klaw::figure::frames(&walk, fps),
                &export::Options::default(),
            );
            csv_wall += start.elapsed().as_secs_f64();
            let _ = std::fs::remove_file(&csv_path);
            written?;
        }
        for s in &walk.report().steps {
            solves += s.solves.len();
            iterations += s.solves.iter().map(|r| r.report.iterations).sum::<usize>();
        }
    }
    let total_steps = (steps * repeat) as f64;
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "bench: {repeat} walks of {steps} steps at v = {:.2} m/s ({:.3} s wall)",
        gait.velocity, wall
    );
    let _ = writeln!(
        out,
        "real-time factor: {:.2} simulated s per wall s",
        simulated / wall
    );
    let _ = writeln!(out, "steps per second: {:.1}", total_steps / wall);
    if args.frames {
        let _ = writeln!(
            out,
            "with frames: {frame_count} frames at {fps} frames/s ({:.3} s wall, {:.1} us per frame)",
            frames_wall,
            1e6 * frames_wall / frame_count.max(1) as f64
        );
        let _ = writeln!(
            out,
            "real-time factor with frames: {:.2} simulated s per wall s",
            simulated / (wall + frames_wall)
        );
    }
    if args.csv {
        let _ = writeln!(
            out,
            "real-time factor with CSV: {:.2} simulated s per wall s ({:.3} s wall writing)",
            simulated / (wall + csv_wall),
            csv_wall
        );
    }
    if solves > 0 {
        let _ = writeln!(
            out,
            "iterations per solve: {:.2} ({solves} solves)",
            iterations as f64 / solves as f64
        );
    } else {
        let _ = writeln!(out, "iterations per solve: n/a (no solves recorded)");
    }
    Ok(())
}

fn sweep(args: &SweepArgs) -> Result<()> {
    sw::Format::from_path(&args.out)?;
    check_output_dir(&args.out)?;
    let shard = match &args.shard {
        Some(text) => sw::Shard::parse(text)?,
        None => sw::Shard::ALL,
    };
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
    for arg in &args.attr {
        let (name, values) = sw::parse_attr(arg, &table)?;
        flags.push((Axis::Attribute(name), values));
    }
    let sweep = sw::Sweep::build(file, flags)?;
    let total = sweep.len();
    let threads = rayon::current_num_threads();
    let shard_note = if shard == sw::Shard::ALL {
        String::new()
    } else {
        format!(", shard {}/{}", shard.index, shard.count)
    };
    eprintln!("sweep: {total} walks{shard_note} on {threads} threads");
    let start = Instant::now();
    let stats = if std::io::stderr().is_terminal() {
        let bar = ProgressBar::new(0).with_style(
            ProgressStyle::with_template(
                "{elapsed_precise} [{wide_bar}] {pos}/{len} walks, {per_sec}, ETA {eta}",
            )
            .expect("a valid template"),
        );
        let stats = swio::run_to_file(&sweep, &args.out, shard, args.resume, &|done, total| {
            bar.set_length(total as u64);
            bar.set_position(done as u64);
        });
        bar.finish_and_clear();
        stats?
    } else {
        swio::run_to_file(&sweep, &args.out, shard, args.resume, &|done, total| {
            // a line each time another 5 % is done
            if done * 20 / total != (done - 1) * 20 / total {
                eprintln!(
                    "sweep: {done}/{total} walks ({}%), {:.1} s",
                    done * 100 / total,
                    start.elapsed().as_secs_f64()
                );
            }
        })?
    };
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
    Ok(())
}

fn merge(args: &MergeArgs) -> Result<()> {
    check_output_dir(&args.out)?;
    let stats = klaw::sweep::merge::merge(&args.out, &args.inputs, args.allow_missing)?;
    for path in &stats.cut_off {
        eprintln!(
            "warning: the last line of {} is cut off (an interrupted run?): not merged",
            path.display()
        );
    }
    if stats.duplicates > 0 {
        eprintln!(
            "warning: {} rows were found in more than one input (identical: written once)",
            stats.duplicates
        );
    }
    if stats.missing > 0 {
        let list: Vec<String> = stats.first_missing.iter().map(|p| p.to_string()).collect();
        eprintln!(
            "warning: {} points are missing (first: {})",
            stats.missing,
            list.join(", ")
        );
    }
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "merged {} rows from {} files: {}",
        stats.rows,
        args.inputs.len(),
        args.out.display()
    );
    Ok(())
}

fn plot_sweep(args: &PlotSweepArgs) -> Result<()> {
    plot::figure_format(&args.out)?;
    check_output_dir(&args.out)?;
    let map =
        klaw::plot::heat_map::heat_map(&args.input, &args.x, &args.y, &args.column, &args.out)?;
    let failed = map.cells.iter().filter(|c| c.failed()).count();
    let note = if plot::text_available() {
        ""
    } else {
        " (no font found: drawn without text; set KLAW_FONT to a .ttf file)"
    };
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "heat map of {} over {} × {}: {} × {} values, {} cells, {failed} failed: {}{note}",
        map.column,
        map.x,
        map.y,
        map.xs.len(),
        map.ys.len(),
        map.cells.len(),
        args.out.display()
    );
    Ok(())
}

fn font_note() -> &'static str {
    if plot::text_available() {
        ""
    } else {
        " (no font found: drawn without text; set KLAW_FONT to a .ttf file)"
    }
}

fn plot_cycle(args: &PlotArgs) -> Result<()> {
    plot::figure_format(&args.out)?;
    check_output_dir(&args.out)?;
    let (walk, title) = args.walk.simulate()?;
    let cycle = klaw::plot::cycle::GaitCycle::from_walk(&walk)?;
    let norms = klaw::plot::cycle::NormTable::builtin();
    let figure = klaw::plot::cycle::write_cycle_figure(&cycle, &norms, &title, &args.out)?;
    let mut out = std::io::stdout().lock();
    let _ = writeln!(
        out,
        "gait cycle of {title}: mean of {} right / {} left cycles",
        cycle.cycles.0, cycle.cycles.1
    );
    for c in &figure.checks {
        let _ = writeln!(out, "  {}", c.describe());
    }
    let _ = writeln!(out, "plot: {}{}", args.out.display(), font_note());
    Ok(())
}

fn animate(args: &AnimateArgs) -> Result<()> {
    let options = klaw::plot::animation::Options::new(
        args.fps,
        klaw::plot::animation::parse_size(&args.size)?,
    )?;
    klaw::plot::animation::check_path(&args.out)?;
    check_output_dir(&args.out)?;
    let (walk, title) = args.walk.simulate()?;
    let summary = klaw::plot::animation::animate_walk(&walk, &title, &args.out, &options)?;
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
