//! Parameter sweeps: the Cartesian product of value lists for the gait, the body and any
//! locomotion attribute, one independent walk per point, run in parallel (rayon) and summarized
//! one row per walk. Rows come out in product order whatever the thread count, and each walk is
//! deterministic, so the output is byte-identical for any `RAYON_NUM_THREADS`.
//!
//! Points are numbered 0.. in product order (the `point` column); a shard `K/N` is the points
//! with `point mod N = K − 1`. Writing, resuming and merging the output files is [`output`].
pub mod output;

use std::collections::BTreeMap;
use std::path::Path;

use rayon::prelude::*;

use crate::engine::walker::simulate;
use crate::error::{Error, Result};
use crate::model::attributes::{AttributeTable, STYLES};
use crate::model::body::Body;
use crate::plan::Timing;
use crate::plan::gait::GaitRequest;

/// Largest number of values one flag may expand to.
pub const MAX_VALUES: usize = 1_000_000;
/// Largest number of points (walks) of a sweep.
pub const MAX_POINTS: usize = 10_000_000;
/// Steps per walk: valid range.
pub const MAX_STEPS: usize = 1_000_000;
/// Relative tolerance with which a range's STOP is included.
const RANGE_TOLERANCE: f64 = 1e-9;

fn bad(flag: &str, reason: impl Into<String>) -> Error {
    Error::BadSpec {
        flag: flag.to_string(),
        reason: reason.into(),
    }
}

/// Round to 12 significant digits, so that `0.6 + 3 · 0.1` is written `0.9`.
fn tidy(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    format!("{x:.11e}").parse().unwrap_or(x)
}

fn number(flag: &str, text: &str) -> Result<f64> {
    let t = text.trim();
    let v: f64 = t
        .parse()
        .map_err(|_| bad(flag, format!("`{t}` is not a number")))?;
    if !v.is_finite() {
        return Err(bad(flag, format!("`{t}` is not a finite number")));
    }
    Ok(v)
}

/// Parse a value specification for `--flag`: a single number `X`, an inclusive range
/// `START:STOP:STEP` (STOP included within 1e-9 relative; STEP may be negative when
/// STOP < START) or a list `A,B,C`. Errors name the flag.
pub fn parse_spec(flag: &str, spec: &str) -> Result<Vec<f64>> {
    let spec = spec.trim();
    if spec.is_empty() {
        return Err(bad(flag, "empty value"));
    }
    if spec.contains(':') {
        let parts: Vec<&str> = spec.split(':').collect();
        if parts.len() != 3 {
            return Err(bad(
                flag,
                format!("range `{spec}` must be START:STOP:STEP (three numbers)"),
            ));
        }
        let start = number(flag, parts[0])?;
        let stop = number(flag, parts[1])?;
        let step = number(flag, parts[2])?;
        if step == 0.0 {
            return Err(bad(flag, format!("range `{spec}`: STEP must not be 0")));
        }
        let span = (stop - start) / step;
        if span < 0.0 {
            let dir = if step > 0.0 { "below" } else { "above" };
            return Err(bad(
                flag,
                format!("range `{spec}`: STOP is {dir} START for this STEP's sign"),
            ));
        }
        let n = (span + RANGE_TOLERANCE * span.max(1.0)).floor();
        if !n.is_finite() || n + 1.0 > MAX_VALUES as f64 {
            return Err(bad(
                flag,
                format!("range `{spec}` has more than {MAX_VALUES} values"),
            ));
        }
        let n = n as usize;
        return Ok((0..=n)
            .map(|i| {
                if i == n && (span - n as f64).abs() <= RANGE_TOLERANCE * span.max(1.0) {
                    stop
                } else {
                    tidy(start + i as f64 * step)
                }
            })
            .collect());
    }
    let values = spec
        .split(',')
        .map(|t| {
            if t.trim().is_empty() {
                Err(bad(flag, format!("empty item in list `{spec}`")))
            } else {
                number(flag, t)
            }
        })
        .collect::<Result<Vec<_>>>()?;
    if values.len() > MAX_VALUES {
        return Err(bad(flag, format!("more than {MAX_VALUES} values")));
    }
    Ok(values)
}

/// Parse `NAME=SPEC` of `--attr`; the name must be a locomotion attribute.
pub fn parse_attr(arg: &str, table: &AttributeTable) -> Result<(String, Vec<f64>)> {
    let (name, spec) = arg
        .split_once('=')
        .ok_or_else(|| bad("attr", format!("`{arg}` must be NAME=SPEC")))?;
    let name = name.trim();
    if !table.0.contains_key(name) {
        let known: Vec<&str> = table.0.keys().map(String::as_str).collect();
        return Err(bad(
            "attr",
            format!(
                "unknown attribute `{name}`; known attributes: {}",
                known.join(", ")
            ),
        ));
    }
    let values = parse_spec(&format!("attr {name}"), spec)?;
    Ok((name.to_string(), values))
}

/// What a swept dimension sets.
#[derive(Clone, Debug, PartialEq)]
pub enum Axis {
    Velocity,
    StepLength,
    StepFrequency,
    Height,
    Mass,
    /// M = K · H².
    MassPerHeight2,
    Steps,
    /// A style preset of `models/styles/`, by its index in `attributes::STYLES`.
    Style,
    Attribute(String),
}

/// The quantities a sweep names besides the attributes, in product order.
pub const QUANTITIES: [&str; 8] = [
    "velocity",
    "step_length",
    "step_frequency",
    "height",
    "mass",
    "mass_per_height2",
    "steps",
    "style",
];

/// Parse a list of style names `A,B,C` into their indices in `attributes::STYLES`.
pub fn parse_styles(spec: &str) -> Result<Vec<f64>> {
    spec.split(',')
        .map(|name| {
            let name = name.trim();
            STYLES
                .iter()
                .position(|(n, _)| *n == name)
                .map(|i| i as f64)
                .ok_or_else(|| {
                    bad(
                        "style",
                        format!(
                            "unknown style `{name}`; the styles are {}",
                            STYLES
                                .iter()
                                .map(|(n, _)| *n)
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    )
                })
        })
        .collect()
}

impl Axis {
    /// The column name.
    pub fn name(&self) -> &str {
        match self {
            Axis::Velocity => "velocity",
            Axis::StepLength => "step_length",
            Axis::StepFrequency => "step_frequency",
            Axis::Height => "height",
            Axis::Mass => "mass",
            Axis::MassPerHeight2 => "mass_per_height2",
            Axis::Steps => "steps",
            Axis::Style => "style",
            Axis::Attribute(n) => n,
        }
    }

    /// The axis of a flag or sweep-file key (`step-length` or `step_length`), or of a locomotion
    /// attribute of `table`; `None` for an unknown name.
    pub fn from_name(name: &str, table: &AttributeTable) -> Option<Axis> {
        let key = name.trim().replace('-', "_");
        Some(match key.as_str() {
            "velocity" => Axis::Velocity,
            "step_length" => Axis::StepLength,
            "step_frequency" => Axis::StepFrequency,
            "height" => Axis::Height,
            "mass" => Axis::Mass,
            "mass_per_height2" => Axis::MassPerHeight2,
            "steps" => Axis::Steps,
            "style" => Axis::Style,
            _ if table.0.contains_key(&key) => Axis::Attribute(key),
            _ => return None,
        })
    }

    /// Position in the product order: the quantities in `QUANTITIES` order, then the attributes.
    fn rank(&self) -> usize {
        QUANTITIES
            .iter()
            .position(|q| *q == self.name() && !matches!(self, Axis::Attribute(_)))
            .unwrap_or(QUANTITIES.len())
    }
}

/// A sweep: axes in product order (the first varies slowest, the last fastest).
#[derive(Clone, Debug, Default)]
pub struct Sweep {
    pub axes: Vec<(Axis, Vec<f64>)>,
}

/// A swept axis with its values, as a flag or a sweep file gives it.
pub type Entry = (Axis, Vec<f64>);

/// Read a sweep file: a flat TOML table whose keys are the quantities of `klaw sweep`
/// (`velocity`, `step_length` or `step-length`, …, `steps`) or locomotion attribute names, and
/// whose values are a number, a string spec (`"0.6:2.0:0.1"`, `"1.5,1.7"`) or an array of numbers.
/// Entries come in key order (alphabetical).
pub fn read_sweep_file(path: &Path, table: &AttributeTable) -> Result<Vec<Entry>> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::Io {
        action: "reading",
        path: path.to_path_buf(),
        source: e,
    })?;
    parse_sweep_toml(&text, table).map_err(|reason| Error::Malformed {
        what: "sweep file",
        path: path.to_path_buf(),
        reason,
    })
}

/// `read_sweep_file` on text; errors are the reason only.
pub fn parse_sweep_toml(
    text: &str,
    table: &AttributeTable,
) -> std::result::Result<Vec<Entry>, String> {
    let doc: toml::Table =
        toml::from_str(text).map_err(|e| e.to_string().trim_end().to_string())?;
    let mut entries: Vec<Entry> = Vec::new();
    for (key, value) in &doc {
        let axis = Axis::from_name(key, table).ok_or_else(|| {
            format!(
                "unknown key `{key}`: a key is one of {} or a locomotion attribute of \
                 models/attributes.toml",
                QUANTITIES.join(", ")
            )
        })?;
        if entries.iter().any(|(a, _)| *a == axis) {
            return Err(format!("`{key}` is given twice (as `{}`)", axis.name()));
        }
        let shape = || {
            format!(
                "`{key}` must be a number, a string \"START:STOP:STEP\" or \"A,B,C\", or an array \
                 of numbers"
            )
        };
        let as_number = |v: &toml::Value| match v {
            toml::Value::Integer(i) => Some(*i as f64),
            toml::Value::Float(x) => Some(*x),
            _ => None,
        };
        let values = match value {
            toml::Value::String(spec) if axis == Axis::Style => {
                parse_styles(spec).map_err(|e| format!("`{key}`: {e}"))?
            }
            toml::Value::Array(items) if axis == Axis::Style => {
                let names: Option<Vec<&str>> = items.iter().map(|v| v.as_str()).collect();
                let names = names.ok_or_else(|| format!("`{key}` must be style names"))?;
                parse_styles(&names.join(",")).map_err(|e| format!("`{key}`: {e}"))?
            }
            toml::Value::String(spec) => {
                parse_spec(axis.name(), spec).map_err(|e| format!("`{key}`: {e}"))?
            }
            toml::Value::Array(items) => {
                if items.is_empty() {
                    return Err(format!("`{key}` is an empty array"));
                }
                items
                    .iter()
                    .map(|v| as_number(v).ok_or_else(shape))
                    .collect::<std::result::Result<Vec<_>, _>>()?
            }
            v => vec![as_number(v).ok_or_else(shape)?],
        };
        if let Some(x) = values.iter().find(|x| !x.is_finite()) {
            return Err(format!("`{key}`: {x} is not a finite number"));
        }
        entries.push((axis, values));
    }
    Ok(entries)
}

impl Sweep {
    /// The sweep of a sweep file's entries and the flags' entries: a flag replaces the file's
    /// entry of the same axis, and a flag `mass` or `mass_per_height2` drops the file's entries
    /// of both. The axes are put in product order: the quantities in `QUANTITIES` order, then
    /// the attributes (the file's, then the flags' new ones, each in their given order).
    pub fn build(file: Vec<Entry>, flags: Vec<Entry>) -> Result<Sweep> {
        let mut axes: Vec<Entry> = Vec::new();
        for (i, (axis, _)) in flags.iter().enumerate() {
            if flags[..i].iter().any(|(a, _)| a == axis) {
                return Err(bad(axis.name(), "given twice"));
            }
        }
        let flags_mass = flags
            .iter()
            .any(|(a, _)| matches!(a, Axis::Mass | Axis::MassPerHeight2));
        for entry in file {
            if flags_mass && matches!(entry.0, Axis::Mass | Axis::MassPerHeight2) {
                continue;
            }
            axes.push(entry);
        }
        for (axis, values) in flags {
            match axes.iter_mut().find(|(a, _)| *a == axis) {
                Some(slot) => slot.1 = values,
                None => axes.push((axis, values)),
            }
        }
        if axes.iter().any(|(a, _)| *a == Axis::Mass)
            && axes.iter().any(|(a, _)| *a == Axis::MassPerHeight2)
        {
            return Err(bad(
                "mass-per-height2",
                "mass and mass_per_height2 exclude each other (M = K · H²): give one",
            ));
        }
        for (axis, values) in &axes {
            if values.is_empty() {
                return Err(bad(axis.name(), "no values"));
            }
            if *axis == Axis::Steps
                && let Some(x) = values.iter().find(|x| x.fract() != 0.0)
            {
                return Err(bad("steps", format!("{x} is not a whole number of steps")));
            }
        }
        // stable: attributes keep their order
        axes.sort_by_key(|(a, _)| a.rank());
        let sweep = Sweep { axes };
        let total = sweep.len();
        if total > MAX_POINTS {
            return Err(Error::OutOfRange {
                name: "sweep size (product of the value counts)".into(),
                value: total as f64,
                min: 1.0,
                max: MAX_POINTS as f64,
                unit: "walks".into(),
            });
        }
        Ok(sweep)
    }
}

/// The K-th of N disjoint slices of a sweep (1 ≤ K ≤ N): the points with `point mod N = K − 1`.
/// Interleaved rather than contiguous so that every shard gets a like mix of fast and slow walks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// K, 1-based (Slurm's `SLURM_ARRAY_TASK_ID` with `--array=1-N`).
    pub index: usize,
    /// N.
    pub count: usize,
}

/// Largest shard count.
pub const MAX_SHARDS: usize = 1_000_000;

impl Shard {
    /// The whole sweep, 1/1.
    pub const ALL: Shard = Shard { index: 1, count: 1 };

    /// Parse `K/N` with 1 ≤ K ≤ N ≤ 1 000 000.
    pub fn parse(text: &str) -> Result<Shard> {
        let range = format!("K/N with whole numbers 1 ≤ K ≤ N ≤ {MAX_SHARDS}");
        let (k, n) = text
            .split_once('/')
            .ok_or_else(|| bad("shard", format!("`{text}` must be {range}")))?;
        let whole = |t: &str| {
            t.trim().parse::<usize>().map_err(|_| {
                bad(
                    "shard",
                    format!("`{text}`: `{}` is not a whole number; {range}", t.trim()),
                )
            })
        };
        let (index, count) = (whole(k)?, whole(n)?);
        if index < 1 || count < 1 || index > count || count > MAX_SHARDS {
            return Err(bad("shard", format!("`{text}` is out of range: {range}")));
        }
        Ok(Shard { index, count })
    }

    /// Whether point `p` belongs to this shard.
    pub fn contains(&self, p: usize) -> bool {
        p % self.count == self.index - 1
    }

    /// The shard's points of a sweep of `total` points, increasing, from `from` on.
    pub fn points(&self, total: usize, from: usize) -> impl Iterator<Item = usize> + use<> {
        let first = self.index - 1;
        let start = if from <= first {
            first
        } else {
            first + (from - first).div_ceil(self.count) * self.count
        };
        (start..total).step_by(self.count)
    }
}

/// One cell of an output row.
#[derive(Clone, Debug, PartialEq)]
pub enum Cell {
    Empty,
    Num(f64),
    Int(usize),
    Bool(bool),
    Text(String),
}

/// What one walk of the sweep produced.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Summary {
    pub mean_iterations: f64,
    pub max_iterations: usize,
    pub achieved_velocity: f64,
    pub achieved_step_length: f64,
    pub achieved_step_frequency: f64,
    pub mean_hip_excursion: f64,
    pub max_peak_swing_knee_flexion_deg: f64,
    pub stance_pct: f64,
    pub double_support_pct: f64,
    pub min_toe_clearance: f64,
    /// Positive mechanical work of the actuators per metre walked (J/m), and per kg of body mass.
    pub work_per_m: f64,
    pub work_per_kg_m: f64,
}

/// The output columns after the inputs.
pub const OUTPUT_COLUMNS: [&str; 14] = [
    "converged",
    "error",
    "mean_iterations",
    "max_iterations",
    "achieved_velocity",
    "achieved_step_length",
    "achieved_step_frequency",
    "mean_hip_excursion",
    "max_peak_swing_knee_flexion_deg",
    "stance_pct",
    "double_support_pct",
    "min_toe_clearance",
    "work_per_m",
    "work_per_kg_m",
];

/// The inputs of one walk, decoded from a point of the product.
#[derive(Clone, Debug, PartialEq)]
pub struct Inputs {
    /// The point's index in product order.
    pub point: usize,
    pub request: GaitRequest,
    pub height: f64,
    pub mass_per_height2: Option<f64>,
    pub mass: f64,
    pub steps: f64,
    /// The style preset (index in `attributes::STYLES`), when swept.
    pub style: Option<usize>,
    pub attributes: Vec<(String, f64)>,
}

/// The row of one walk: its inputs and its outcome (a summary, or the reason it failed).
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    pub inputs: Inputs,
    pub outcome: std::result::Result<Summary, String>,
}

/// Walks run in parallel per chunk, for each thread: rows are written chunk by chunk, so memory
/// holds at most a chunk of rows whatever the size of the sweep.
pub const CHUNK_PER_THREAD: usize = 32;

impl Sweep {
    /// Number of points (walks): the product of the axis lengths.
    pub fn len(&self) -> usize {
        self.axes
            .iter()
            .try_fold(1usize, |n, (_, v)| n.checked_mul(v.len()))
            .unwrap_or(usize::MAX)
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Point `k` of the product (row-major: the last axis varies fastest).
    pub fn point(&self, mut k: usize) -> Vec<f64> {
        let mut p = vec![0.0; self.axes.len()];
        for (i, (_, values)) in self.axes.iter().enumerate().rev() {
            p[i] = values[k % values.len()];
            k /= values.len();
        }
        p
    }

    /// Every point, in product order.
    pub fn points(&self) -> Vec<Vec<f64>> {
        (0..self.len()).map(|k| self.point(k)).collect()
    }

    /// The inputs of the walk of point `k`; unswept quantities take the `klaw walk` defaults
    /// (H 1.8 m, M 80 kg, 10 steps, v 1.4 m/s when no gait quantity is swept).
    pub fn inputs(&self, k: usize) -> Inputs {
        let point = self.point(k);
        let mut inputs = Inputs {
            point: k,
            request: GaitRequest::default(),
            height: 1.8,
            mass_per_height2: None,
            mass: 80.0,
            steps: 10.0,
            style: None,
            attributes: Vec::new(),
        };
        let mut mass = None;
        for ((axis, _), &x) in self.axes.iter().zip(&point) {
            match axis {
                Axis::Velocity => inputs.request.velocity = Some(x),
                Axis::StepLength => inputs.request.step_length = Some(x),
                Axis::StepFrequency => inputs.request.step_frequency = Some(x),
                Axis::Height => inputs.height = x,
                Axis::Mass => mass = Some(x),
                Axis::MassPerHeight2 => inputs.mass_per_height2 = Some(x),
                Axis::Steps => inputs.steps = x,
                Axis::Style => inputs.style = Some(x as usize),
                Axis::Attribute(n) => inputs.attributes.push((n.clone(), x)),
            }
        }
        if inputs.request == GaitRequest::default() {
            inputs.request.velocity = Some(1.4);
        }
        inputs.mass = match (inputs.mass_per_height2, mass) {
            (Some(k), _) => tidy(k * inputs.height * inputs.height),
            (None, Some(m)) => m,
            (None, None) => 80.0,
        };
        inputs
    }

    /// The input column names: `point`, the gait, the body, `steps`, the swept attributes.
    pub fn input_header(&self) -> Vec<String> {
        let mut h: Vec<String> = [
            "point",
            "velocity",
            "step_length",
            "step_frequency",
            "height",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        if self.axes.iter().any(|(a, _)| *a == Axis::MassPerHeight2) {
            h.push("mass_per_height2".into());
        }
        h.push("mass".into());
        h.push("steps".into());
        if self.axes.iter().any(|(a, _)| *a == Axis::Style) {
            h.push("style".into());
        }
        for (axis, _) in &self.axes {
            if let Axis::Attribute(n) = axis {
                h.push(n.clone());
            }
        }
        h
    }

    /// The column names: the inputs, then `OUTPUT_COLUMNS`.
    pub fn header(&self) -> Vec<String> {
        let mut h = self.input_header();
        h.extend(OUTPUT_COLUMNS.iter().map(|s| s.to_string()));
        h
    }

    /// Walk point `k` and summarize it; a failure is recorded in the row, never returned.
    pub fn walk(&self, k: usize, table: &AttributeTable) -> Row {
        let inputs = self.inputs(k);
        let outcome =
            run_walk(&inputs, table).map_err(|e| e.to_string().replace(['\n', '\r'], " "));
        Row { inputs, outcome }
    }

    /// Run the walks of `points` (any order) on the rayon pool, a chunk of
    /// `CHUNK_PER_THREAD × threads` at a time; `emit` receives every row, in the order of
    /// `points`, as soon as its chunk is done; `progress()` is called after each walk (from any
    /// thread). An `emit` error stops the sweep.
    pub fn run(
        &self,
        points: impl IntoIterator<Item = usize>,
        progress: &(dyn Fn() + Sync),
        mut emit: impl FnMut(Row) -> Result<()>,
    ) -> Result<()> {
        let table = AttributeTable::builtin();
        let chunk = (CHUNK_PER_THREAD * rayon::current_num_threads()).max(64);
        let mut points = points.into_iter();
        loop {
            let batch: Vec<usize> = points.by_ref().take(chunk).collect();
            if batch.is_empty() {
                return Ok(());
            }
            let rows: Vec<Row> = batch
                .into_par_iter()
                .map(|k| {
                    let row = self.walk(k, &table);
                    progress();
                    row
                })
                .collect();
            for row in rows {
                emit(row)?;
            }
        }
    }
}

/// Simulate one walk and summarize it.
pub fn run_walk(inputs: &Inputs, table: &AttributeTable) -> Result<Summary> {
    let steps = Error::check_range("steps", inputs.steps, 1.0, MAX_STEPS as f64, "steps")?;
    if steps.fract() != 0.0 {
        return Err(Error::Geometry {
            what: format!("steps = {steps} is not a whole number"),
        });
    }
    let body = Body::standard(inputs.height, inputs.mass)?;
    let mut overrides: BTreeMap<String, f64> = match inputs.style {
        Some(i) => crate::model::attributes::style(STYLES[i].0)?,
        None => BTreeMap::new(),
    };
    overrides.extend(inputs.attributes.iter().cloned());
    let attrs = table.resolve(&overrides, "--attr")?;
    let gait = inputs.request.complete(&body, &attrs)?;
    let timing = Timing::new(gait.step_frequency)?;
    let walk = simulate(body, attrs, &vec![gait; steps as usize])?;
    let report = walk.report();
    let iterations: Vec<usize> = report
        .steps
        .iter()
        .flat_map(|s| s.solves.iter().map(|r| r.report.iterations))
        .collect();
    let unconverged = report
        .steps
        .iter()
        .flat_map(|s| &s.solves)
        .filter(|r| !r.report.converged)
        .count();
    if unconverged > 0 {
        return Err(Error::Geometry {
            what: format!("{unconverged} shooting solves did not converge"),
        });
    }
    let n = report.steps.len().max(1) as f64;
    let mean = |f: &dyn Fn(&crate::engine::report::StepReport) -> f64| {
        report.steps.iter().map(f).sum::<f64>() / n
    };
    let distance: f64 = report.steps.iter().map(|s| s.achieved.step_length).sum();
    let work: f64 = report.steps.iter().map(|s| s.positive_work).sum();
    Ok(Summary {
        mean_iterations: if iterations.is_empty() {
            0.0
        } else {
            iterations.iter().sum::<usize>() as f64 / iterations.len() as f64
        },
        max_iterations: iterations.iter().copied().max().unwrap_or(0),
        achieved_velocity: mean(&|s| s.achieved.velocity),
        achieved_step_length: mean(&|s| s.achieved.step_length),
        achieved_step_frequency: mean(&|s| 60.0 / s.achieved.duration),
        mean_hip_excursion: mean(&|s| s.hip_excursion),
        max_peak_swing_knee_flexion_deg: report
            .steps
            .iter()
            .map(|s| s.peak_swing_knee_flexion.to_degrees())
            .fold(f64::NEG_INFINITY, f64::max),
        stance_pct: 100.0 * (timing.t_step + timing.t_ds) / timing.t_cycle,
        double_support_pct: 100.0 * 2.0 * timing.t_ds / timing.t_cycle,
        min_toe_clearance: report
            .steps
            .iter()
            .map(|s| s.min_toe_clearance)
            .fold(f64::INFINITY, f64::min),
        work_per_m: work / distance,
        work_per_kg_m: work / distance / inputs.mass,
    })
}

impl Inputs {
    /// The input cells, aligned with `Sweep::input_header`.
    pub fn cells(&self) -> Vec<Cell> {
        let opt = |v: Option<f64>| v.map_or(Cell::Empty, Cell::Num);
        let mut c = vec![
            Cell::Int(self.point),
            opt(self.request.velocity),
            opt(self.request.step_length),
            opt(self.request.step_frequency),
            Cell::Num(self.height),
        ];
        if let Some(k) = self.mass_per_height2 {
            c.push(Cell::Num(k));
        }
        c.push(Cell::Num(self.mass));
        c.push(Cell::Num(self.steps));
        if let Some(i) = self.style {
            c.push(Cell::Text(STYLES[i].0.to_string()));
        }
        c.extend(self.attributes.iter().map(|(_, v)| Cell::Num(*v)));
        c
    }
}

impl Row {
    /// The cells of the row, aligned with `Sweep::header`.
    pub fn cells(&self) -> Vec<Cell> {
        let mut c = self.inputs.cells();
        match &self.outcome {
            Ok(s) => {
                c.push(Cell::Bool(true));
                c.push(Cell::Text(String::new()));
                c.push(Cell::Num(s.mean_iterations));
                c.push(Cell::Int(s.max_iterations));
                for v in [
                    s.achieved_velocity,
                    s.achieved_step_length,
                    s.achieved_step_frequency,
                    s.mean_hip_excursion,
                    s.max_peak_swing_knee_flexion_deg,
                    s.stance_pct,
                    s.double_support_pct,
                    s.min_toe_clearance,
                    s.work_per_m,
                    s.work_per_kg_m,
                ] {
                    c.push(Cell::Num(v));
                }
            }
            Err(e) => {
                c.push(Cell::Bool(false));
                c.push(Cell::Text(e.clone()));
                c.extend(std::iter::repeat_n(Cell::Empty, OUTPUT_COLUMNS.len() - 2));
            }
        }
        c
    }
}

fn csv_text(cell: &Cell) -> String {
    match cell {
        Cell::Empty => String::new(),
        Cell::Num(v) => v.to_string(),
        Cell::Int(v) => v.to_string(),
        Cell::Bool(b) => b.to_string(),
        Cell::Text(s) => s.clone(),
    }
}

fn json_value(cell: &Cell) -> serde_json::Value {
    match cell {
        Cell::Empty => serde_json::Value::Null,
        Cell::Num(v) => {
            serde_json::Number::from_f64(*v).map_or(serde_json::Value::Null, Into::into)
        }
        Cell::Int(v) => (*v).into(),
        Cell::Bool(b) => (*b).into(),
        Cell::Text(s) => s.clone().into(),
    }
}

/// Output format of a sweep, by the file's extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Csv,
    Jsonl,
}

impl Format {
    /// `.csv` or `.jsonl` (case-insensitive); anything else is an error.
    pub fn from_path(path: &Path) -> Result<Format> {
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        match ext.as_deref() {
            Some("csv") => Ok(Format::Csv),
            Some("jsonl") => Ok(Format::Jsonl),
            _ => Err(Error::Malformed {
                what: "output path",
                path: path.to_path_buf(),
                reason: "a sweep is written as .csv or .jsonl".into(),
            }),
        }
    }

    /// The text of one row, with its final newline: a CSV record, or a JSON object with the
    /// keys of `header` in order (empty cells as null). `cells` may be a prefix of the row.
    pub fn line(&self, header: &[String], cells: &[Cell]) -> String {
        match self {
            Format::Csv => csv_line(cells.iter().map(csv_text)),
            Format::Jsonl => {
                let mut s = String::from("{");
                for (i, (name, cell)) in header.iter().zip(cells).enumerate() {
                    if i > 0 {
                        s.push(',');
                    }
                    s.push_str(&serde_json::Value::from(name.as_str()).to_string());
                    s.push(':');
                    s.push_str(&json_value(cell).to_string());
                }
                s.push_str("}\n");
                s
            }
        }
    }

    /// The header line (CSV), or nothing (JSON Lines name the columns in every row).
    pub fn header_line(&self, header: &[String]) -> String {
        match self {
            Format::Csv => csv_line(header.iter().cloned()),
            Format::Jsonl => String::new(),
        }
    }

    /// How a row's text starts, given its input cells (an exact prefix of `line`).
    pub fn input_prefix(&self, header: &[String], inputs: &[Cell]) -> String {
        let mut line = self.line(header, inputs);
        let end = match self {
            Format::Csv => "\n",
            Format::Jsonl => "}\n",
        };
        line.truncate(line.len() - end.len());
        line.push(',');
        line
    }
}

/// One CSV record as text (quoted where needed), with a final newline.
fn csv_line(fields: impl Iterator<Item = String>) -> String {
    let mut w = csv::WriterBuilder::new()
        .has_headers(false)
        .from_writer(Vec::new());
    let fields: Vec<String> = fields.collect();
    w.write_record(&fields).expect("writing to memory");
    String::from_utf8(w.into_inner().expect("writing to memory")).expect("UTF-8 fields")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn single_value_and_list() {
        assert_eq!(parse_spec("height", "1.8").unwrap(), vec![1.8]);
        assert_eq!(
            parse_spec("height", "1.5, 1.65,1.8").unwrap(),
            vec![1.5, 1.65, 1.8]
        );
        assert_eq!(parse_spec("mass", "-3").unwrap(), vec![-3.0]);
    }

    #[test]
    fn floating_range_includes_its_stop() {
        let v = parse_spec("velocity", "0.6:2.0:0.1").unwrap();
        assert_eq!(v.len(), 15, "{v:?}");
        assert_eq!(v[0], 0.6);
        assert_eq!(v[3], 0.9);
        assert_eq!(*v.last().unwrap(), 2.0);
        let v = parse_spec("velocity", "0.1:0.3:0.1").unwrap();
        assert_eq!(v, vec![0.1, 0.2, 0.3]);
        let v = parse_spec("steps", "1:10:3").unwrap();
        assert_eq!(v, vec![1.0, 4.0, 7.0, 10.0]);
        let v = parse_spec("height", "2.0:1.5:-0.25").unwrap();
        assert_eq!(v, vec![2.0, 1.75, 1.5]);
        assert_eq!(parse_spec("height", "1.8:1.8:0.1").unwrap(), vec![1.8]);
    }

    #[test]
    fn bad_specs_name_the_flag() {
        for (flag, spec) in [
            ("velocity", ""),
            ("velocity", "abc"),
            ("velocity", "1,,2"),
            ("velocity", "1:2"),
            ("velocity", "1:2:3:4"),
            ("velocity", "1:2:0"),
            ("velocity", "2:1:0.1"),
            ("velocity", "1:x:0.1"),
            ("velocity", "nan"),
            ("velocity", "0:1e300:1e-300"),
        ] {
            let e = parse_spec(flag, spec).unwrap_err();
            assert!(matches!(e, Error::BadSpec { .. }), "{spec}: {e}");
            assert!(e.to_string().starts_with("--velocity:"), "{spec}: {e}");
            assert_eq!(e.exit_code(), 2);
        }
        let table = AttributeTable::builtin();
        let e = parse_attr("nonsense=1", &table).unwrap_err().to_string();
        assert!(e.contains("--attr") && e.contains("nonsense"), "{e}");
        let e = parse_attr("bounciness", &table).unwrap_err().to_string();
        assert!(e.contains("--attr"), "{e}");
        let e = parse_attr("bounciness=x", &table).unwrap_err().to_string();
        assert!(e.contains("--attr bounciness"), "{e}");
        let (n, v) = parse_attr("bounciness=0.2,0.5", &table).unwrap();
        assert_eq!((n.as_str(), v), ("bounciness", vec![0.2, 0.5]));
    }

    #[test]
    fn product_order_is_row_major() {
        let s = Sweep {
            axes: vec![
                (Axis::Velocity, vec![1.0, 1.2]),
                (Axis::Height, vec![1.6, 1.7, 1.8]),
            ],
        };
        assert_eq!(s.len(), 6);
        assert_eq!(
            s.points(),
            vec![
                vec![1.0, 1.6],
                vec![1.0, 1.7],
                vec![1.0, 1.8],
                vec![1.2, 1.6],
                vec![1.2, 1.7],
                vec![1.2, 1.8],
            ]
        );
        let empty = Sweep::default();
        assert_eq!(empty.points(), vec![Vec::<f64>::new()]);
    }

    #[test]
    fn inputs_take_walk_defaults_and_mass_per_height2() {
        let s = Sweep {
            axes: vec![
                (Axis::Height, vec![1.5]),
                (Axis::MassPerHeight2, vec![20.0]),
            ],
        };
        let i = s.inputs(0);
        assert_eq!(i.request.velocity, Some(1.4));
        assert!((i.mass - 45.0).abs() < 1e-12);
        assert_eq!(i.steps, 10.0);
        let h = s.header();
        assert!(h.contains(&"mass_per_height2".to_string()));
        assert_eq!(h.len(), 8 + OUTPUT_COLUMNS.len());
        assert_eq!(h[0], "point");
    }

    #[test]
    fn failed_point_records_the_reason() {
        let s = Sweep {
            axes: vec![(Axis::Velocity, vec![5.0]), (Axis::Steps, vec![2.0])],
        };
        let mut rows = Vec::new();
        s.run(0..1, &|| {}, |r| {
            rows.push(r);
            Ok(())
        })
        .unwrap();
        assert_eq!(rows.len(), 1);
        let e = rows[0].outcome.as_ref().unwrap_err();
        assert!(e.contains("velocity"), "{e}");
        assert_eq!(rows[0].cells().len(), s.header().len());
    }

    fn table() -> AttributeTable {
        AttributeTable::builtin()
    }

    #[test]
    fn shard_specs_are_validated() {
        assert_eq!(Shard::parse("1/1").unwrap(), Shard::ALL);
        assert_eq!(
            Shard::parse(" 3 / 8 ").unwrap(),
            Shard { index: 3, count: 8 }
        );
        for bad in [
            "0/4",
            "5/4",
            "1/0",
            "0/0",
            "-1/4",
            "1",
            "1/2/3",
            "a/4",
            "1.5/4",
            "",
            "2/2000000",
        ] {
            let e = Shard::parse(bad).unwrap_err();
            assert!(matches!(e, Error::BadSpec { .. }), "{bad}: {e}");
            let text = e.to_string();
            assert!(
                text.starts_with("--shard:") && text.contains("1 ≤ K ≤ N"),
                "{bad}: {text}"
            );
            assert_eq!(e.exit_code(), 2);
        }
    }

    #[test]
    fn shard_points_start_where_asked() {
        let s = Shard { index: 2, count: 3 };
        assert_eq!(s.points(10, 0).collect::<Vec<_>>(), vec![1, 4, 7]);
        assert_eq!(s.points(10, 2).collect::<Vec<_>>(), vec![4, 7]);
        assert_eq!(s.points(10, 4).collect::<Vec<_>>(), vec![4, 7]);
        assert_eq!(s.points(10, 8).count(), 0);
        assert_eq!(Shard::ALL.points(3, 1).collect::<Vec<_>>(), vec![1, 2]);
    }

    proptest::proptest! {
        /// The N shards of a sweep are disjoint and together hold every point exactly once, and
        /// `points(total, from)` is `contains` filtered from `from` on.
        #[test]
        fn shards_partition_the_product(total in 0usize..500, count in 1usize..40, from in 0usize..520) {
            let mut seen = vec![0u32; total];
            for index in 1..=count {
                let shard = Shard { index, count };
                let points: Vec<usize> = shard.points(total, 0).collect();
                let filtered: Vec<usize> = (0..total).filter(|&p| shard.contains(p)).collect();
                proptest::prop_assert_eq!(&points, &filtered);
                let later: Vec<usize> = shard.points(total, from).collect();
                let want: Vec<usize> = filtered.iter().copied().filter(|&p| p >= from).collect();
                proptest::prop_assert_eq!(later, want);
                for p in points {
                    seen[p] += 1;
                }
            }
            proptest::prop_assert!(seen.iter().all(|&n| n == 1));
        }
    }

    #[test]
    fn sweep_file_values_and_keys() {
        let entries = parse_sweep_toml(
            "velocity = \"0.6:1.0:0.2\"\nstep-length = 0.7\nheight = [1.5, 1.7]\nsteps = 2\nbounciness = [0.2, 0.5]\n",
            &table(),
        )
        .unwrap();
        let get = |a: Axis| {
            entries
                .iter()
                .find(|(x, _)| *x == a)
                .map(|(_, v)| v.clone())
        };
        assert_eq!(get(Axis::Velocity), Some(vec![0.6, 0.8, 1.0]));
        assert_eq!(get(Axis::StepLength), Some(vec![0.7]));
        assert_eq!(get(Axis::Height), Some(vec![1.5, 1.7]));
        assert_eq!(get(Axis::Steps), Some(vec![2.0]));
        assert_eq!(
            get(Axis::Attribute("bounciness".into())),
            Some(vec![0.2, 0.5])
        );
    }

    #[test]
    fn malformed_sweep_files_say_what_is_wrong() {
        for (text, expect) in [
            ("velocity = ", "velocity"),
            ("speed = 1.2", "unknown key `speed`"),
            ("velocity = true", "`velocity` must be a number"),
            ("velocity = []", "empty array"),
            ("velocity = [1.0, \"x\"]", "`velocity` must be a number"),
            ("velocity = \"1:2\"", "START:STOP:STEP"),
            (
                "velocity = 1.0\nstep_length = 0.7\nstep-length = 0.8",
                "given twice",
            ),
            ("[velocity]\nx = 1", "`velocity` must be a number"),
            ("velocity = nan", "not a finite number"),
        ] {
            let e = parse_sweep_toml(text, &table()).unwrap_err();
            assert!(e.contains(expect), "{text:?}: {e}");
        }
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("bad.toml");
        std::fs::write(&path, "speed = 1").unwrap();
        let e = read_sweep_file(&path, &table()).unwrap_err();
        assert!(
            matches!(
                e,
                Error::Malformed {
                    what: "sweep file",
                    ..
                }
            ),
            "{e}"
        );
        assert_eq!(e.exit_code(), 2);
        let e = read_sweep_file(&dir.path().join("none.toml"), &table()).unwrap_err();
        assert!(matches!(e, Error::Io { .. }), "{e}");
    }

    #[test]
    fn flags_override_the_file_and_axes_take_product_order() {
        let bounce = Axis::Attribute("bounciness".into());
        let lean = Axis::Attribute("trunk_lean".into());
        let file = vec![
            (bounce.clone(), vec![0.2, 0.5]),
            (Axis::Height, vec![1.6, 1.7]),
            (Axis::Mass, vec![60.0]),
            (Axis::Velocity, vec![1.0]),
        ];
        let flags = vec![
            (lean.clone(), vec![5.0]),
            (Axis::Velocity, vec![1.2, 1.4]),
            (Axis::MassPerHeight2, vec![22.0]),
        ];
        let s = Sweep::build(file, flags).unwrap();
        let axes: Vec<(&str, &[f64])> = s
            .axes
            .iter()
            .map(|(a, v)| (a.name(), v.as_slice()))
            .collect();
        assert_eq!(
            axes,
            vec![
                ("velocity", &[1.2, 1.4][..]),
                ("height", &[1.6, 1.7][..]),
                ("mass_per_height2", &[22.0][..]),
                ("bounciness", &[0.2, 0.5][..]),
                ("trunk_lean", &[5.0][..]),
            ]
        );
        // both masses from the file, or the same flag twice, are errors
        let e = Sweep::build(
            vec![(Axis::Mass, vec![60.0]), (Axis::MassPerHeight2, vec![20.0])],
            vec![],
        )
        .unwrap_err();
        assert!(
            matches!(e, Error::BadSpec { .. }) && e.to_string().contains("exclude"),
            "{e}"
        );
        let e = Sweep::build(
            vec![],
            vec![(bounce.clone(), vec![0.1]), (bounce, vec![0.2])],
        )
        .unwrap_err();
        assert!(e.to_string().contains("given twice"), "{e}");
        let e = Sweep::build(vec![(Axis::Steps, vec![1.5])], vec![]).unwrap_err();
        assert!(e.to_string().contains("whole number"), "{e}");
        assert_eq!(
            Axis::from_name("step-frequency", &table()),
            Some(Axis::StepFrequency)
        );
        assert_eq!(Axis::from_name("nonsense", &table()), None);
    }
}
