//! `klaw evaluate`: the biomechanical quality criteria of a walk in a file (Pronost et al. 2006,
//! `docs/criteria.md`), its mean-shifted RMS against another walk, the actuators' work from its
//! report and the published ranges met or missed.
use std::io::Write;
use std::path::{Path, PathBuf};

use clap::Args;
use klaw::analysis::criteria::compare::{AngleRms, compare};
use klaw::analysis::criteria::heel_strikes::from_kinematics;
use klaw::analysis::criteria::{
    Criteria, CriteriaFrames, CriteriaParameters, PAPER_TABLE_1, evaluate,
};
use klaw::analysis::cycle::GaitCycle;
use klaw::analysis::norms::{self, NormCheck, NormTable, WalkSpeed};
use klaw::export::read::report::{WalkWork, read_walk_work};
use klaw::export::read::{MotionFile, read_motion};
use klaw::model::InputError;
use klaw::{Body, Result};
use serde_json::json;

use crate::outputs::{self, Output};
use crate::{DEFAULT_HEIGHT, DEFAULT_MASS, check_count};

#[derive(Args)]
pub(crate) struct EvaluateArgs {
    /// The walk: klaw's frame CSV (klaw walk --out x.csv, or a measured walk in its columns) or OpenSim storage (.mot/.sto)
    file: PathBuf,
    /// Another walk to compare with: the mean-shifted RMS of each angle (eq. 7) over the averaged gait cycle
    #[arg(long, value_name = "FILE")]
    against: Option<PathBuf>,
    /// Body height H in m, range [1.2, 2.2] [default: the report's, else 1.8]
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    height: Option<f64>,
    /// Body mass M in kg, range [25, 200] [default: the report's, else 80]
    #[arg(long, value_name = "KG", allow_negative_numbers = true)]
    mass: Option<f64>,
    /// The walk's report (klaw walk --report): the actuators' work per metre; it must be the same walk
    #[arg(long, value_name = "FILE.json")]
    report: Option<PathBuf>,
    /// Gait cycles of each foot left out at the start (a klaw walk's first starts from its initial conditions)
    #[arg(
        long,
        value_name = "N",
        default_value_t = 1,
        allow_negative_numbers = true
    )]
    skip_cycles: i64,
    /// Write the criteria, the comparison, the work and the norms as JSON
    #[arg(long, value_name = "OUT.json")]
    json: Option<PathBuf>,
}

/// The most cycles that may be skipped.
const MAX_SKIP: usize = 1000;

pub(crate) fn run(args: &EvaluateArgs) -> Result<()> {
    if let Some(json) = &args.json {
        outputs::check(&[Output::new("json", json, outputs::JSON)])?;
    }
    let skip = check_count("skip-cycles", args.skip_cycles, 0, MAX_SKIP, "cycles")?;
    let work = args.report.as_deref().map(read_walk_work).transpose()?;
    let height = args
        .height
        .or(work.map(|w| w.height))
        .unwrap_or(DEFAULT_HEIGHT);
    let mass = args.mass.or(work.map(|w| w.mass)).unwrap_or(DEFAULT_MASS);
    let body = Body::standard(height, mass)?;
    let params = CriteriaParameters {
        skip,
        ..Default::default()
    };
    let file = read_motion(&args.file, &body, &params)?;
    let against = args
        .against
        .as_deref()
        .map(|p| read_motion(p, &body, &params))
        .transpose()?;
    if let (Some(w), Some(path)) = (&work, &args.report) {
        same_walk(w, path, &file, &args.file, &body)?;
    }
    // a walk the criteria cannot use is a bad input file, named
    let criteria_of = |m: &MotionFile, path: &Path| {
        evaluate(&m.motion, &body, &params)
            .map_err(|e| InputError::malformed("motion file", path, e))
    };
    let criteria = criteria_of(&file, &args.file)?;
    let other = against
        .as_ref()
        .zip(args.against.as_deref())
        .map(|(a, p)| criteria_of(a, p))
        .transpose()?;
    let rms = against.as_ref().map(|a| {
        // both walks' cycles start at the same kind of event: the ankle's foremost position
        // unless both files have a step column
        let alike = |m: &MotionFile| match (file.steps, a.steps) {
            (Some(_), Some(_)) => m.motion.clone(),
            _ => CriteriaFrames {
                heel_strikes: from_kinematics(&m.motion.frames, &body, params.heel_strike_window),
                ..m.motion.clone()
            },
        };
        let events = match (file.steps, a.steps) {
            (Some(_), Some(_)) => "the step columns' heel strikes",
            _ => "the ankle's foremost positions in both files",
        };
        (compare(&alike(&file), &alike(a), skip), events)
    });
    let h = &file.motion.heel_strikes;
    let speed = WalkSpeed {
        velocity: pelvis_speed(&file.motion.frames),
        leg_length: body.l1,
    };
    let checks: Vec<NormCheck> =
        GaitCycle::from_clinical(&file.motion.frames, &h.right, &h.left, skip)
            .map(|cycle| norms::check(&cycle, &NormTable::builtin(), speed))
            .unwrap_or_default()
            .into_iter()
            .filter(|c| c.value.is_finite())
            .collect();
    let e = Evaluation {
        args,
        body,
        params,
        file,
        criteria,
        against: against.zip(other),
        rms,
        work,
        checks,
    };
    print(&e);
    if let Some(path) = &args.json {
        klaw::export::write_report_json(path, &to_json(&e))?;
        let _ = writeln!(std::io::stdout(), "json: {}", path.display());
    }
    Ok(())
}

/// Everything `klaw evaluate` found.
struct Evaluation<'a> {
    args: &'a EvaluateArgs,
    body: Body,
    params: CriteriaParameters,
    file: MotionFile,
    criteria: Criteria,
    against: Option<(MotionFile, Criteria)>,
    /// Eq. 7 per angle, and the events the cycles were cut at.
    rms: Option<(Vec<AngleRms>, &'static str)>,
    work: Option<WalkWork>,
    checks: Vec<NormCheck>,
}

/// The evaluation for people, on stdout.
fn print(e: &Evaluation) {
    let mut out = std::io::stdout().lock();
    let _ = writeln!(out, "{}", describe(&e.args.file, &e.file));
    let _ = writeln!(
        out,
        "body: H {} m, M {} kg; criteria at {} frames/s over each gait cycle (heel strike to the \
         next of the same foot), the first {} of each foot left out",
        e.body.height, e.body.mass, e.params.rate, e.params.skip
    );
    let _ = writeln!(out, "{}", table(&e.criteria));
    if let (Some((a, c)), Some(path)) = (&e.against, &e.args.against) {
        let _ = writeln!(out, "{}", describe(path, a));
        let _ = writeln!(out, "{}", table(c));
    }
    if let (Some((rms, events)), Some(path)) = (&e.rms, &e.args.against) {
        let _ = writeln!(
            out,
            "mean-shifted RMS against {} (eq. 7, over the gait cycle averaged between {events}):",
            path.display()
        );
        for a in rms {
            let v = a.rms.map_or("not available".to_string(), |r| {
                format!("{r:.4} rad ({:.2}°)", r.to_degrees())
            });
            let _ = writeln!(out, "  {:<22} {v}", a.angle);
        }
    }
    let _ = match &e.work {
        Some(w) => writeln!(
            out,
            "actuator work: {:.1} J/m ({:.3} J/(kg m)), positive work over {} steps, {:.2} m",
            w.per_metre(),
            w.per_metre() / w.mass,
            w.steps,
            w.distance
        ),
        None => writeln!(
            out,
            "actuator work: not available (the file holds no forces; give the walk's klaw walk --report)"
        ),
    };
    let inside = e.checks.iter().filter(|c| c.inside()).count();
    let _ = writeln!(
        out,
        "published ranges (models/gait-norms.toml): {inside} of {} met",
        e.checks.len()
    );
    for c in &e.checks {
        let _ = writeln!(out, "  {}", c.describe());
    }
}

/// The evaluation as JSON.
fn to_json(e: &Evaluation) -> serde_json::Value {
    let f = &e.file;
    json!({
        "file": e.args.file,
        "format": f.format,
        "heel_strikes_from": f.heel_strikes_from,
        "absent": f.absent,
        "heel_strikes": f.motion.heel_strikes,
        "body": {"height": e.body.height, "mass": e.body.mass},
        "criteria": e.criteria,
        "paper_table_1": {
            "total_jerk": PAPER_TABLE_1[0],
            "cyclicity": PAPER_TABLE_1[1],
            "internal_power_literal": PAPER_TABLE_1[2],
        },
        "against": e.args.against.as_ref().map(|p| json!({
            "file": p,
            "criteria": e.against.as_ref().map(|(_, c)| c),
            "rms": e.rms.as_ref().map(|(r, _)| rms_json(r)),
            "cycles_between": e.rms.as_ref().map(|(_, events)| events),
        })),
        "actuator_work": e.work.map(|w| json!({
            "per_metre": w.per_metre(),
            "per_kg_metre": w.per_metre() / w.mass,
            "report": w,
        })),
        "norms": e.checks.iter().map(norm_json).collect::<Vec<_>>(),
    })
}

/// The report must be the same walk as the file: the same step count (by the file's `step`
/// column) and a last frame within one step's end of the report's duration.
fn same_walk(
    w: &WalkWork,
    report: &Path,
    file: &MotionFile,
    path: &Path,
    body: &Body,
) -> Result<()> {
    let bad = |reason: String| -> Result<()> {
        Err(InputError::bad_value("report", format!("{}: {reason}", report.display())).into())
    };
    let Some(steps) = file.steps else {
        return bad(format!(
            "{} has no step column: it is not a klaw walk's frames",
            path.display()
        ));
    };
    let last = file.motion.frames.last().map_or(0.0, |f| f.time);
    let step = w.duration / w.steps as f64;
    if steps != w.steps || (last - w.duration).abs() > step {
        return bad(format!(
            "a walk of {} steps and {:.3} s, but {} holds {steps} steps and {last:.3} s: not the same walk",
            w.steps,
            w.duration,
            path.display()
        ));
    }
    if (w.height - body.height).abs() > 1e-9 || (w.mass - body.mass).abs() > 1e-9 {
        return bad(format!(
            "the walk's body is H {} m, M {} kg, not the --height {} m, --mass {} kg given",
            w.height, w.mass, body.height, body.mass
        ));
    }
    Ok(())
}

/// One line on what a file is and where its heel strikes come from.
fn describe(path: &Path, f: &MotionFile) -> String {
    let frames = &f.motion.frames;
    let span = frames.last().map_or(0.0, |l| l.time) - frames[0].time;
    let rate = (frames.len() - 1) as f64 / span;
    let mut s = format!(
        "{}: {}, {} frames over {:.3} s ({rate:.4} frames/s); heel strikes from {}: {} right, {} left",
        path.display(),
        f.format,
        frames.len(),
        span,
        f.heel_strikes_from,
        f.motion.heel_strikes.right.len(),
        f.motion.heel_strikes.left.len()
    );
    for a in &f.absent {
        s.push_str(&format!("\n  without {a}"));
    }
    s
}

/// The criteria as a table: one row per cycle, the mean, the paper's Table 1.
fn table(c: &Criteria) -> String {
    let mut s = format!(
        "{:<6} {:<5} {:>7} {:>7} {:>12} {:>12} {:>8} {:>8} {:>8} {:>8}\n",
        "cycle",
        "foot",
        "start s",
        "end s",
        "C1 rad²/s⁶",
        "msj rad²/s⁶",
        "C2 rad",
        "C3 W/kg",
        "int W/kg",
        "ext W/kg"
    );
    let power = |p: Option<klaw::analysis::criteria::Power>| match p {
        Some(p) => format!("{:>8.3} {:>8.3} {:>8.3}", p.literal, p.internal, p.external),
        None => format!("{:>8} {:>8} {:>8}", "–", "–", "–"),
    };
    for (i, cc) in c.cycles.iter().enumerate() {
        let side = format!("{:?}", cc.cycle.side).to_lowercase();
        s.push_str(&format!(
            "{:<6} {:<5} {:>7.3} {:>7.3} {:>12.3e} {:>12.3e} {:>8.4} {}\n",
            i + 1,
            side,
            cc.cycle.start,
            cc.cycle.end,
            cc.total_jerk,
            cc.mean_squared_jerk,
            cc.cyclicity,
            power(cc.power)
        ));
    }
    let m = &c.mean;
    s.push_str(&format!(
        "{:<6} {:<21} {:>12.3e} {:>12.3e} {:>8.4} {}\n",
        "mean",
        format!("{} cycles", m.cycles),
        m.total_jerk,
        m.mean_squared_jerk,
        m.cyclicity,
        power(m.power)
    ));
    s.push_str(&format!(
        "{:<28} {:>12.3e} {:>12} {:>8.4} {:>8.3}   (Pronost et al. 2006, Table 1, mean of 7 subjects)",
        "paper", PAPER_TABLE_1[0], "", PAPER_TABLE_1[1], PAPER_TABLE_1[2]
    ));
    s
}

fn rms_json(rms: &[AngleRms]) -> serde_json::Value {
    rms.iter()
        .map(|a| (a.angle.to_string(), json!(a.rms)))
        .collect::<serde_json::Map<_, _>>()
        .into()
}

fn norm_json(c: &NormCheck) -> serde_json::Value {
    json!({
        "name": c.name,
        "side": c.side.map(|s| format!("{s:?}").to_lowercase()),
        "value": c.value,
        "at_pct": c.at_pct,
        "speed": c.speed.map(|(v, _)| v),
        "speed_scale": c.speed.map(|(_, scale)| scale),
        "low": c.low,
        "high": c.high,
        "unit": c.unit,
        "inside": c.inside(),
    })
}

/// The walk's mean horizontal speed from its pelvis centre, first frame to last (m/s): the speed
/// the speed-dependent norms are read at; NaN when the file has no pelvis position (those norms
/// are then not checked).
fn pelvis_speed(frames: &[klaw::Clinical]) -> f64 {
    match (frames.first(), frames.last()) {
        (Some(a), Some(b)) if b.time > a.time => {
            let (dx, dz) = (b.pelvis[0] - a.pelvis[0], b.pelvis[2] - a.pelvis[2]);
            dx.hypot(dz) / (b.time - a.time)
        }
        _ => f64::NAN,
    }
}
