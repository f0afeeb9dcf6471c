//! The `klaw` command line: parse the flags, call the library, write the files, print a summary;
//! one module per subcommand with its flags and its `run`. No physics here. Errors print
//! `error: <message>` and exit with the status of `failure::exit_code` (2 for bad input, 1 for a
//! simulation or output failure); clap's usage errors exit 2 as well.
mod animate;
mod args;
mod bench;
mod evaluate;
mod failure;
mod generalize;
mod ik;
mod kinematic;
mod merge;
mod one_action;
mod outputs;
mod plot;
mod plot_sweep;
mod poulaine;
mod progress;
mod prototype;
mod scenario;
mod signals;
mod sweep;
mod walk;

use std::process::ExitCode;

use clap::{Parser, Subcommand};
use klaw::Result;
use klaw::model::InputError;

const DEFAULT_HEIGHT: f64 = 1.8;
const DEFAULT_MASS: f64 = 80.0;
const DEFAULT_STEPS: usize = 10;
const DEFAULT_FPS: f64 = 100.0;
const MAX_STEPS: usize = 1_000_000;
const MIN_FPS: f64 = 0.001;
const MAX_FPS: f64 = 10_000.0;

#[derive(Parser)]
#[command(
    name = "klaw",
    version,
    about = "Goal-directed, dynamically simulated human walking (Bruderlin & Calvert's KLAW, 1989)",
    long_about = "Goal-directed, dynamically simulated human walking after Bruderlin & Calvert, \"Goal-directed,\n\
        dynamic animation of human walking\" (SIGGRAPH 1989).\n\
        \n\
        The dynamic walk: `klaw walk` simulates a walk and writes its frames (CSV, OpenSim .mot / .sto,\n\
        BVH), events, report and a figure; `klaw bench` times the default walk; `klaw sweep` runs\n\
        many walks over a grid, `klaw merge` joins a sweep's shards, `klaw plot-sweep` draws a heat map.\n\
        Figures: `klaw plot` (joint angles over the gait cycle, normal ranges shaded), `klaw animate`\n\
        (a stick-figure GIF).\n\
        Stepping (Ko & Badler 1993): `klaw step`, `klaw turn`, and `klaw scenario` (stand, walk, step,\n\
        turn and pause in the world).\n\
        Walking from data (Ko & Badler 1992): `klaw prototype` (walk data from a walk or a measured\n\
        CSV), `klaw generalize` (to another step length and body), `klaw walk --mode kinematic`.\n\
        Inverse kinematics (Pronost et al.): `klaw poulaine`, `klaw poulaine-db`, `klaw ik`.\n\
        Evaluation: `klaw evaluate` (quality criteria and published ranges of a walk in a file).\n\
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
            v = the style's speed (attribute preferred_velocity, 1.4 m/s). The completed gait is checked against the\n\
            anatomical limits of the attributes (by default v from 0.4 m/s up to the body's walk–run\n\
            transition, Froude number v² / (g · l1) ≤ 0.5 with l1 the leg length: 2.0634 m/s for\n\
            H = 1.8 m; sf in [50, 182] steps/min; sl in [0.2, 1.3] leg lengths, i.e. [0.1736, 1.1285] m\n\
            for H = 1.8 m). A faster request exits with status 2 naming the body's limit.\n\
            \n\
            Example: klaw walk --velocity 1.2 --steps 6 --out slow.csv --plot slow.svg --report slow.json"
    )]
    Walk(walk::WalkArgs),
    /// Time the default walk (v = 1.4 m/s, H = 1.8 m, M = 80 kg), single-threaded
    #[command(
        long_about = "Time the default walk (v = 1.4 m/s, H = 1.8 m, M = 80 kg), single-threaded, and print the\n\
            real-time factor (simulated seconds per wall-clock second), steps per second and mean shooting\n\
            iterations per solve. Only the simulation is timed; no frames are sampled or written."
    )]
    Bench(bench::BenchArgs),
    /// Run many walks over a grid of gaits, bodies and attributes; one summary row per walk
    #[command(
        long_about = "Run one walk per point of the Cartesian product of the given values, in parallel on all\n\
            cores (RAYON_NUM_THREADS sets the thread count), and write one summary row per walk as\n\
            CSV or JSON Lines (by the extension of --out).\n\
            \n\
            Every value flag takes a single number X, an inclusive range START:STOP:STEP (STOP is\n\
            included within 1e-9 relative) or a list A,B,C; a sweep file (--file) can give any of\n\
            them, and flags override it. Unswept quantities take the defaults of `klaw walk`\n\
            (H 1.8 m, M 80 kg, 10 steps; with no gait flag, the style's preferred velocity, 1.4 m/s by\n\
            default).\n\
            \n\
            Rows come in product order (velocity, step_length, step_frequency, height, mass,\n\
            mass_per_height2, steps, then the attributes: the first varies slowest), numbered by\n\
            the point column, and are identical whatever the thread count. They are written as the\n\
            walks complete (memory does not grow with the sweep) to .NAME.partial next to --out,\n\
            renamed to --out at the end (see --resume). Every value is checked against its range\n\
            before any walk (out of it: exit 2). A point whose values do not go together (a\n\
            derived value outside the point's limits, a speed beyond the point's walk–run\n\
            transition, Froude number v² / (g · l1) > 0.5) or whose walk does not converge gets\n\
            converged = false and the reason in the error column, and the sweep carries on; when\n\
            every walk failed, the rows are written and the exit status is 1. Columns after the inputs: converged, error, mean_iterations and\n\
            max_iterations (shooting trials per solve), achieved_velocity (m/s),\n\
            achieved_step_length (m), achieved_step_frequency (steps/min), mean_hip_excursion (m),\n\
            max_peak_swing_knee_flexion_deg, stance_pct and double_support_pct (% of the cycle),\n\
            min_toe_clearance (m), work_per_m (J/m: the actuators' positive mechanical work per\n\
            metre walked), work_per_kg_m (J/(kg m)) and repaired_steps (steps that walked with a\n\
            fallback's change of their plan: the report's repairs).\n\
            \n\
            A progress bar is drawn when stderr is a terminal; otherwise a plain line at most every 10 s.\n\
            \n\
            Example: klaw sweep --velocity 0.6:2.0:0.1 --height 1.5,1.65,1.8,1.95 --mass-per-height2 23"
    )]
    Sweep(sweep::SweepArgs),
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
    Merge(merge::MergeArgs),
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
    PlotSweep(plot_sweep::PlotSweepArgs),
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
            windows (those that change with speed at the walk's v/sqrt(g l1), light blue), and\n\
            each is checked: the values are printed, outside ranges flagged.\n\
            1500 x 1000 px, PNG or SVG by the extension of --out, written whole or not at all.\n\
            \n\
            Example: klaw plot --velocity 1.2 --out slow-cycle.svg"
    )]
    Plot(plot::PlotArgs),
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
    Animate(animate::AnimateArgs),
    /// Run a scenario file: stand, walk, step, turn and pause in the world (CSV/.mot/.sto/.bvh)
    #[command(
        long_about = "Run the actions of a scenario file one after the other, from quiet standing: stand,\n\
            walk (the dynamic engine, with a start from standing and a stop into standing around\n\
            it), step (a non-rhythmic forward, backward or lateral step, Ko & Badler 1993), turn (a\n\
            turnaround on the spot, split into turns of at most 100°) and pause; and write the\n\
            figure's frames in the world frame to --out (.csv clinical angles, .mot/.sto OpenSim\n\
            coordinates, .bvh), optionally a stick-figure animation (--animate). The file format\n\
            and the method's decisions are in docs/nrs.md. A bad file, an unknown action or field,\n\
            an illegal step goal exit 2 naming the action (from 0) and the field; nothing is written.\n\
            \n\
            Example: klaw scenario examples/scenarios/table.toml --out table.bvh"
    )]
    Scenario(scenario::ScenarioArgs),
    /// One non-rhythmic step from quiet standing (forward, backward or lateral; Ko & Badler 1993)
    #[command(
        long_about = "Take one non-rhythmic step from quiet standing (Ko & Badler 1993): the stepping foot goes\n\
            --forward / --left metres from where it stands, turned by --turn degrees; the step is\n\
            forward, backward or lateral by where the goal lies around the stance heel (docs/nrs.md).\n\
            A goal in the illegal region (crossing the stance leg), out of the legs' reach, on the\n\
            stance foot or shorter than the engine's shortest walking step exits 2 naming the goal\n\
            and the reason; nothing is written. The outputs are those of `klaw scenario`.\n\
            \n\
            Example: klaw step --side right --forward -0.5 --out back.bvh --animate back.gif"
    )]
    Step(one_action::StepArgs),
    /// One turnaround on the spot from quiet standing (Ko & Badler 1993)
    #[command(
        long_about = "Turn on the spot from quiet standing (Ko & Badler 1993, §6): two steps per turnaround of at\n\
            most 100°, larger turns split into equal turnarounds; dynamic (the second foot lands\n\
            ahead, ready to walk on) or stationary (feet side by side). The outputs are those of\n\
            `klaw scenario`.\n\
            \n\
            Example: klaw turn --angle 180 --side right --kind stationary --out turn.csv --events turn-events.csv"
    )]
    Turn(one_action::TurnArgs),
    /// Biomechanical quality criteria of a walk in a file: jerk, cyclicity, power (Pronost et al. 2006)
    #[command(
        long_about = "Read a walk (klaw's frame CSV from klaw walk --out, a measured walk in its columns, or\n\
            OpenSim storage .mot/.sto with gait2392's coordinates) and print, over each gait cycle\n\
            (heel strike to the next of the same foot; from the step column, else the ankle's\n\
            foremost position), Pronost et al. 2006's criteria at 60 frames/s: C1 the total jerk\n\
            (rad²/s⁶) and the mean squared jerk, C2 the cyclicity (rad), C3 the power per kg as\n\
            printed (eqs. 10-11) with Willems et al. 1995's internal and external power; with\n\
            --against the mean-shifted RMS of each angle (eq. 7); with --report the actuators'\n\
            work per metre; and the published ranges of models/gait-norms.toml met or missed.\n\
            docs/criteria.md defines each and compares klaw's walks with the paper's Table 1.\n\
            A malformed file exits 2 naming the file and line; nothing is written.\n\
            \n\
            Example: klaw walk --out w.csv --report w.json --no-plot && klaw evaluate w.csv --report w.json --json c.json"
    )]
    Evaluate(evaluate::EvaluateArgs),
    /// Poulaines (ankles relative to the pelvis over a gait cycle): extract one from a walk, model it
    #[command(
        subcommand,
        long_about = "Poulaines (Pronost et al.): the ankles relative to the pelvis centre over one gait\n\
            cycle, in the walking direction's frame (x forward, y up, z right).\n\
            `extract` simulates a walk (the flags of `klaw walk`) and writes its last gait cycle's\n\
            poulaine as CSV; `fit` models a poulaine by its four characteristic points and four C¹\n\
            cubic Hermite curves, prints the fit error and writes the model (JSON; a database entry\n\
            with --leg-length and --step-length). Layouts in docs/ik.md.\n\
            \n\
            Example: klaw poulaine extract --velocity 1.2 --out p.csv && klaw poulaine fit p.csv --out m.json"
    )]
    Poulaine(poulaine::PoulaineCommand),
    /// Build a database of poulaines from klaw walks over a grid, and measured entries
    #[command(
        subcommand,
        name = "poulaine-db",
        long_about = "Build a database of modelled poulaines (Pronost et al. §3): one klaw walk per point of\n\
            the grid of --height, --step-length and --attr NAME=A,B values (labelled synthetic), and\n\
            the entries of `klaw poulaine fit --leg-length … --step-length …` (measured). JSON,\n\
            written whole or not at all; its layout is in docs/ik.md.\n\
            \n\
            Example: klaw poulaine-db build --height 1.6,1.8,2.0 --step-length 0.6,0.75,0.9 --attr step_width=0.05,0.1 --out db.json"
    )]
    PoulaineDb(poulaine::DbCommand),
    /// Lower-limb angles from a poulaine by inverse kinematics; the whole figure (CSV/.mot/.sto/.bvh)
    #[command(
        long_about = "Recover the lower limbs' angles from a poulaine by inverse kinematics whose null space\n\
            serves biomechanical secondary tasks (joint limits, rotational kinetic energy, the rest\n\
            posture; Pronost et al., docs/ik.md), and write the whole figure like `klaw walk`: the\n\
            pelvis carried at the walk's speed, its height from the supporting ankle on the floor.\n\
            The poulaine is a file (--poulaine) or the database's for the walker (--db with --height,\n\
            --step-length or --velocity, --step-width, --stance). A target beyond the leg's reach is\n\
            clamped to it; a frame the closed loop cannot bring within 1e-5 m exits 1.\n\
            \n\
            Example: klaw ik --db db.json --height 1.75 --step-length 0.7 --out ik.bvh"
    )]
    Ik(ik::IkArgs),
    /// Walk data of one step (Ko & Badler 1992) from a simulated walk or a measured one
    #[command(
        long_about = "Write the walk data W = {H, F1, F2, F3, M, A} of one step (Ko & Badler 1992,\n\
            docs/generalize.md): with --from-walk, step K of a walk the engine simulates (the gait,\n\
            body and attribute flags of `klaw walk`); with --from-csv, the first whole step of a\n\
            measured walk in the sagittal-landmark layout of docs/generalize.md. JSON or CSV by the\n\
            extension of --out, written whole or not at all.\n\
            \n\
            Example: klaw prototype --from-walk --out prototype.json"
    )]
    Prototype(prototype::PrototypeArgs),
    /// A prototype generalized to a body and a step length (Ko & Badler 1992)
    #[command(
        long_about = "Generalize a prototype (the bundled one by default) to a body and a step length (Ko &\n\
            Badler 1992 §5: ψ then φ; docs/generalize.md), pose it to check that no leg stretches and\n\
            no foot goes under the floor, and write the walk data. A step too long or too short for\n\
            the body exits 2 naming the longest or shortest that works.\n\
            \n\
            Example: klaw generalize --step-length 0.7 --height 1.6 --out short.json"
    )]
    Generalize(generalize::GeneralizeArgs),
}

fn main() -> ExitCode {
    klaw::memory::keep_freed_memory();
    let cli = Cli::parse();
    signals::clean_up_on_interruption();
    let result = match cli.command {
        Command::Walk(args) if args.mode == "kinematic" => kinematic::run(&args),
        Command::Walk(args) => walk::run(&args),
        Command::Bench(args) => bench::run(&args),
        Command::Sweep(args) => match sweep::run(&args) {
            Ok(false) => return ExitCode::FAILURE,
            other => other.map(|_| ()),
        },
        Command::Merge(args) => merge::run(&args),
        Command::PlotSweep(args) => plot_sweep::run(&args),
        Command::Plot(args) => plot::run(&args),
        Command::Animate(args) => animate::run(&args),
        Command::Scenario(args) => scenario::run(&args),
        Command::Step(args) => one_action::step(&args),
        Command::Turn(args) => one_action::turn(&args),
        Command::Evaluate(args) => evaluate::run(&args),
        Command::Poulaine(command) => poulaine::run(&command),
        Command::PoulaineDb(command) => poulaine::run_db(&command),
        Command::Ik(args) => ik::run(&args),
        Command::Prototype(args) => prototype::run(&args),
        Command::Generalize(args) => generalize::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", failure::message(&e));
            ExitCode::from(failure::exit_code(&e))
        }
    }
}

/// `value` if it lies in [min, max], else an `InputError::OutOfRange` naming it (counts are
/// parsed signed, so that `--steps -5` gets the range rather than clap's "unexpected argument").
fn check_count(name: &str, value: i64, min: usize, max: usize, unit: &str) -> Result<usize> {
    InputError::check_range(name, value as f64, min as f64, max as f64, unit)?;
    Ok(value as usize)
}

/// `n` and the noun, singular for one: `1 step`, `2 steps`.
fn count(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

/// What a figure's summary line adds when no font was found.
fn font_note() -> &'static str {
    if klaw::plot::text_available() {
        ""
    } else {
        " (no font found: drawn without text; set KLAW_FONT to a .ttf file)"
    }
}
