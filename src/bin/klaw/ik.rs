//! `klaw ik`: lower-limb angles from a poulaine by inverse kinematics with biomechanical
//! secondary tasks (Pronost et al.; docs/ik.md), the whole figure written like `klaw walk`'s.
use std::io::Write;
use std::path::PathBuf;

use clap::{Args, ValueEnum};
use klaw::ik::{Angles, Ik, IkModel, Optimizer};
use klaw::model::InputError;
use klaw::model::attributes::AttributeTable;
use klaw::model::body::DEFAULT_BODY_TABLE;
use klaw::poulaine::database::clamp_to_reach;
use klaw::poulaine::{Database, Query, Trajectory};
use klaw::{Body, GaitRequest, Result, export};
use serde::Serialize;

use crate::outputs::{self, Output};
use crate::{DEFAULT_HEIGHT, DEFAULT_MASS, check_count};

#[derive(Clone, Copy, ValueEnum)]
enum Minimiser {
    /// Torczon's multi-directional search (the paper's)
    Mds,
    /// argmin's Nelder–Mead
    NelderMead,
}

#[derive(Args)]
pub(crate) struct IkArgs {
    /// The poulaine to follow (.csv of `klaw poulaine extract`: one cycle, uniform samples)
    #[arg(long, value_name = "FILE.csv", required_unless_present = "db")]
    poulaine: Option<PathBuf>,
    /// A poulaine database (.json of `klaw poulaine-db build`): the poulaine for the walker,
    /// and f3's reference angles; with --poulaine, only the reference angles
    #[arg(long, value_name = "FILE.json")]
    db: Option<PathBuf>,
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
    /// The secondary tasks' model: a file in the layout of models/ik.toml (joint limits, with
    /// an optional [leg_limits] in place of models/rom.toml's; rest posture; weights; inertias),
    /// checked before any work (docs/cli.md, "Model files") [default: models/ik.toml]
    #[arg(long, value_name = "FILE.toml")]
    ik_model: Option<PathBuf>,
    /// Walking speed (m/s) [with --poulaine: the poulaine's own; with --db: by klaw's
    /// normalizing formula from --step-length, or 1.4]
    #[arg(long, value_name = "M/S", allow_negative_numbers = true)]
    velocity: Option<f64>,
    /// --db: the step length (m) [default: by the normalizing formula]
    #[arg(
        long,
        value_name = "M",
        requires = "db",
        conflicts_with = "poulaine",
        allow_negative_numbers = true
    )]
    step_length: Option<f64>,
    /// --db: the feet's spacing in support, ankle to ankle (m) [default: the selected walk's]
    #[arg(
        long,
        value_name = "M",
        requires = "db",
        conflicts_with = "poulaine",
        allow_negative_numbers = true
    )]
    step_width: Option<f64>,
    /// --db: the pelvis-to-ankle height in support, a fraction of the leg, range [0.7, 1]
    /// [default: the selected walk's]
    #[arg(
        long,
        value_name = "FRACTION",
        requires = "db",
        conflicts_with = "poulaine",
        allow_negative_numbers = true
    )]
    stance: Option<f64>,
    /// --db: frames per second of the inverse kinematics and of --out, range [20, 500]
    #[arg(
        long,
        value_name = "HZ",
        default_value_t = 60.0,
        allow_negative_numbers = true
    )]
    fps: f64,
    /// --db: f3 (eq. 6) pulls towards the rest posture of models/ik.toml, as in the paper
    /// [default: towards the angles of the database's walks nearest in v / √(g l) at each
    /// phase, where it carries them, with the kinetic weight energy_with_reference]
    #[arg(long, requires = "db")]
    rest_posture: bool,
    /// --poulaine with --db: read the database's angles in phase with the poulaine's ankle
    /// paths, for a poulaine that does not start at its right heel strike [default: both
    /// cycles from their right heel strike, as `klaw poulaine extract` writes them]
    #[arg(
        long,
        requires = "poulaine",
        requires = "db",
        conflicts_with = "rest_posture"
    )]
    align_phase: bool,
    /// Gait cycles to write, range [1, 1000]
    #[arg(
        long,
        value_name = "N",
        default_value_t = 4,
        allow_negative_numbers = true
    )]
    cycles: i64,
    /// The secondary tasks' minimiser
    #[arg(long, value_enum, default_value = "mds")]
    minimiser: Minimiser,
    /// The figure's motion: .csv clinical angles, .mot/.sto OpenSim, .bvh
    #[arg(long, value_name = "FILE", default_value = "ik.csv")]
    out: PathBuf,
    /// A report (.json): the poulaine's source, the closed loop's residual, the minimiser's work
    #[arg(long, value_name = "FILE.json")]
    report: Option<PathBuf>,
}

#[derive(Serialize)]
struct Report {
    source: String,
    selected: Option<[String; 3]>,
    reference: String,
    query: Option<Query>,
    period_s: f64,
    velocity_m_s: f64,
    frames_per_cycle: usize,
    max_residual_m: f64,
    clamped_samples: usize,
    median_iterations: u64,
    median_evaluations: u64,
    within_limits: bool,
}

/// The poulaine of `klaw ik` and where it came from.
struct Source {
    poulaine: Trajectory,
    velocity: f64,
    name: String,
    selected: Option<[String; 3]>,
    query: Option<Query>,
    /// f3's reference posture per sample (the database's angles), if used, and its entries.
    reference: Option<(String, Vec<Angles>)>,
}

/// The database's poulaine for the walker of `a` (docs/ik.md, "Selection").
fn db_poulaine(a: &IkArgs, db_path: &std::path::Path, body: &Body) -> Result<Source> {
    InputError::check_range("fps", a.fps, 20.0, 500.0, "frames/s")?;
    if let Some(w) = a.step_width {
        InputError::check_range("step-width", w, 0.0, 0.4, "m")?;
    }
    if let Some(s) = a.stance {
        InputError::check_range("stance", s, 0.7, 1.0, "")?;
    }
    let db = Database::read(db_path)?;
    let attrs = AttributeTable::builtin().defaults();
    let velocity = match (a.velocity, a.step_length) {
        (None, None) => Some(1.4),
        (v, _) => v,
    };
    let gait = GaitRequest {
        velocity,
        step_length: a.step_length,
        step_frequency: None,
    }
    .complete(body, &attrs)?;
    let period = 120.0 / gait.step_frequency;
    let trace = db.trace_for_step(gait.step_length, body.l1);
    let nearest = db.select(&Query {
        trace,
        spacing: 0.0,
        stance: 0.0,
    });
    let axes = db.entries[nearest.x].axes;
    let q = Query {
        trace,
        spacing: a.step_width.map_or(axes.spacing, |w| w / 2.0 / body.l1),
        stance: a.stance.unwrap_or(axes.stance),
    };
    let (model, s) = db.poulaine(&q, body.l1, period);
    let n = (period * a.fps).round() as usize;
    let labels = [s.x, s.y, s.z].map(|i| db.entries[i].label.clone());
    let poulaine = model.sample(n);
    Ok(Source {
        reference: reference(a, &db, &poulaine, body),
        velocity: gait.velocity,
        name: db_path.display().to_string(),
        poulaine,
        selected: Some(labels),
        query: Some(q),
    })
}

/// f3's per-phase reference from `db`'s angles for `poulaine` ([`Database::reference`]) and the
/// entries it blends, unless --rest-posture.
fn reference(
    a: &IkArgs,
    db: &Database,
    poulaine: &Trajectory,
    body: &Body,
) -> Option<(String, Vec<Angles>)> {
    if a.rest_posture {
        return None;
    }
    let r = db.reference(poulaine, body.l1, a.align_phase)?;
    if !a.align_phase {
        let off = klaw::poulaine::database::alignment(&db.entries[r.blend[0].entry], poulaine);
        if off.abs() > 0.1 {
            eprintln!(
                "warning: the poulaine's ankle paths are {off:+.2} of a cycle out of phase with \
                 the database's walks, which start at their right heel strike; --align-phase \
                 reads the reference in phase"
            );
        }
    }
    let names: Vec<String> = r
        .blend
        .iter()
        .map(|b| {
            let label = &db.entries[b.entry].label;
            format!("{label} (weight {:.2}, phase {:+.3})", b.weight, b.shift)
        })
        .collect();
    Some((names.join(" and "), r.angles))
}

pub(crate) fn run(a: &IkArgs) -> Result<()> {
    let body = Body::from_table(&a.body_table, a.height, a.mass)?;
    let model = match &a.ik_model {
        Some(path) => Some(IkModel::read(path, &body)?),
        None => None,
    };
    let cycles = check_count("cycles", a.cycles, 1, 1000, "cycles")?;
    let mut outs = vec![Output::new("out", &a.out, outputs::MOTION)];
    if let Some(r) = &a.report {
        outs.push(Output::new("report", r, outputs::JSON));
    }
    outputs::check(&outs)?;
    let format = export::Format::from_path(&a.out)?;
    if let Some(v) = a.velocity {
        InputError::check_range("velocity", v, 0.1, 3.0, "m/s")?;
    }
    let mut ik = Ik::new(&body);
    if let Some(model) = model {
        ik.model = model;
    }
    ik.params.optimizer = match a.minimiser {
        Minimiser::Mds => Optimizer::MultiDirectional,
        Minimiser::NelderMead => Optimizer::NelderMead,
    };
    let Source {
        mut poulaine,
        velocity,
        name: source,
        selected,
        query,
        reference,
    } = match (&a.poulaine, &a.db) {
        (Some(p), db) => {
            let t = Trajectory::read_csv(p)?;
            let reference = match db {
                Some(d) => reference(a, &Database::read(d)?, &t, &body),
                None => None,
            };
            Source {
                velocity: a.velocity.unwrap_or_else(|| t.speed()),
                poulaine: t,
                name: p.display().to_string(),
                selected: None,
                query: None,
                reference,
            }
        }
        (None, Some(db_path)) => db_poulaine(a, db_path, &body)?,
        (None, None) => unreachable!("clap requires --poulaine or --db"),
    };
    if reference.is_some() {
        ik.model.weights.energy = ik.model.weights.energy_with_reference;
    }
    let clamped = clamp_to_reach(&mut poulaine, body.l0 / 2.0, ik.params.reach * body.l1);
    let dt = poulaine
        .uniform_step()
        .ok_or_else(|| InputError::bad_value("poulaine", "its samples are not uniform in time"))?;
    let per_phase = reference.as_ref().map(|(_, r)| r.as_slice());
    let sol = ik.solve_referenced(&poulaine.targets(), dt, true, per_phase)?;
    let angles: Vec<_> = sol.frames.iter().map(|f| f.theta).collect();
    let attrs = AttributeTable::builtin().defaults();
    let frames = klaw::ik::figure::frames((&body, &attrs), &angles, dt, velocity, cycles);
    export::write(
        &a.out,
        format,
        &body,
        1.0 / dt,
        frames,
        &export::Options::default(),
    )?;
    let median = |mut v: Vec<u64>| {
        v.sort_unstable();
        v[v.len() / 2]
    };
    let report = Report {
        source,
        selected,
        reference: reference.map_or("the rest posture".into(), |(label, _)| {
            format!("the angles of {label} at each phase")
        }),
        query,
        period_s: poulaine.period,
        velocity_m_s: velocity,
        frames_per_cycle: angles.len(),
        max_residual_m: sol.frames.iter().map(|f| f.residual).fold(0.0, f64::max),
        clamped_samples: clamped,
        median_iterations: median(sol.frames.iter().map(|f| f.iterations).collect()),
        median_evaluations: median(sol.frames.iter().map(|f| f.evaluations).collect()),
        within_limits: angles.iter().all(|t| ik.model.within_limits(t)),
    };
    if let Some(r) = &a.report {
        export::write_report_json(r, &report)?;
    }
    let _ = writeln!(
        std::io::stdout(),
        "ik: {} frames per cycle ({:.3} s, v {:.3} m/s), {cycles} cycles, ankles within {:.1e} m, \
         angles {} their limits, f3 towards {}: {}",
        report.frames_per_cycle,
        report.period_s,
        velocity,
        report.max_residual_m,
        if report.within_limits {
            "within"
        } else {
            "outside"
        },
        report.reference,
        a.out.display()
    );
    Ok(())
}
