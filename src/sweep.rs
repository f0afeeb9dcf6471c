//! Parameter sweeps: the Cartesian product of value lists for the gait, the body and any
//! locomotion attribute, one independent walk per point, run in parallel (rayon) and summarized
//! one row per walk. Rows come out in product order whatever the thread count, and each walk is
//! deterministic, so the output is byte-identical for any `RAYON_NUM_THREADS`.
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;

use crate::attributes::AttributeTable;
use crate::body::Body;
use crate::error::{Error, Result};
use crate::io;
use crate::params::GaitRequest;
use crate::plan::Timing;
use crate::walk::simulate;

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
    Attribute(String),
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
            Axis::Attribute(n) => n,
        }
    }
}

/// A sweep: axes in product order (the first varies slowest, the last fastest).
#[derive(Clone, Debug, Default)]
pub struct Sweep {
    pub axes: Vec<(Axis, Vec<f64>)>,
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
}

/// The output columns after the inputs.
pub const OUTPUT_COLUMNS: [&str; 12] = [
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
];

/// The inputs of one walk, decoded from a point of the product.
#[derive(Clone, Debug, PartialEq)]
pub struct Inputs {
    pub request: GaitRequest,
    pub height: f64,
    pub mass_per_height2: Option<f64>,
    pub mass: f64,
    pub steps: f64,
    pub attributes: Vec<(String, f64)>,
}

/// The row of one walk: its inputs and its outcome (a summary, or the reason it failed).
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    pub inputs: Inputs,
    pub outcome: std::result::Result<Summary, String>,
}

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

    /// Decode a point into the inputs of a walk; unswept quantities take the `klaw walk`
    /// defaults (H 1.8 m, M 80 kg, 10 steps, v 1.4 m/s when no gait quantity is swept).
    pub fn inputs(&self, point: &[f64]) -> Inputs {
        let mut inputs = Inputs {
            request: GaitRequest::default(),
            height: 1.8,
            mass_per_height2: None,
            mass: 80.0,
            steps: 10.0,
            attributes: Vec::new(),
        };
        let mut mass = None;
        for ((axis, _), &x) in self.axes.iter().zip(point) {
            match axis {
                Axis::Velocity => inputs.request.velocity = Some(x),
                Axis::StepLength => inputs.request.step_length = Some(x),
                Axis::StepFrequency => inputs.request.step_frequency = Some(x),
                Axis::Height => inputs.height = x,
                Axis::Mass => mass = Some(x),
                Axis::MassPerHeight2 => inputs.mass_per_height2 = Some(x),
                Axis::Steps => inputs.steps = x,
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

    /// The column names: the inputs, then `OUTPUT_COLUMNS`.
    pub fn header(&self) -> Vec<String> {
        let mut h: Vec<String> = ["velocity", "step_length", "step_frequency", "height"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        if self.axes.iter().any(|(a, _)| *a == Axis::MassPerHeight2) {
            h.push("mass_per_height2".into());
        }
        h.push("mass".into());
        h.push("steps".into());
        for (axis, _) in &self.axes {
            if let Axis::Attribute(n) = axis {
                h.push(n.clone());
            }
        }
        h.extend(OUTPUT_COLUMNS.iter().map(|s| s.to_string()));
        h
    }

    /// Run every walk on the rayon pool; `progress(done, total)` is called after each walk
    /// (from any thread). Rows are returned in product order.
    pub fn run(&self, progress: impl Fn(usize, usize) + Sync) -> Result<Vec<Row>> {
        let total = self.len();
        if total > MAX_POINTS {
            return Err(Error::OutOfRange {
                name: "sweep size (product of the value counts)".into(),
                value: total as f64,
                min: 1.0,
                max: MAX_POINTS as f64,
                unit: "walks".into(),
            });
        }
        let table = AttributeTable::builtin();
        let done = AtomicUsize::new(0);
        Ok((0..total)
            .into_par_iter()
            .map(|k| {
                let inputs = self.inputs(&self.point(k));
                let outcome = run_walk(&inputs, &table).map_err(|e| e.to_string());
                let n = done.fetch_add(1, Ordering::Relaxed) + 1;
                progress(n, total);
                Row { inputs, outcome }
            })
            .collect())
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
    let overrides: BTreeMap<String, f64> = inputs.attributes.iter().cloned().collect();
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
    let mean =
        |f: &dyn Fn(&crate::report::StepReport) -> f64| report.steps.iter().map(f).sum::<f64>() / n;
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
    })
}

impl Row {
    /// The cells of the row, aligned with `Sweep::header`.
    pub fn cells(&self) -> Vec<Cell> {
        let i = &self.inputs;
        let opt = |v: Option<f64>| v.map_or(Cell::Empty, Cell::Num);
        let mut c = vec![
            opt(i.request.velocity),
            opt(i.request.step_length),
            opt(i.request.step_frequency),
            Cell::Num(i.height),
        ];
        if let Some(k) = i.mass_per_height2 {
            c.push(Cell::Num(k));
        }
        c.push(Cell::Num(i.mass));
        c.push(Cell::Num(i.steps));
        c.extend(i.attributes.iter().map(|(_, v)| Cell::Num(*v)));
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
}

/// Write the rows atomically: CSV with a header, or JSON Lines (one object per row, keys in
/// column order, empty cells as null).
pub fn write_rows(path: &Path, header: &[String], rows: &[Row]) -> Result<()> {
    let format = Format::from_path(path)?;
    io::write_atomic(path, |out| match format {
        Format::Csv => {
            let mut w = csv::WriterBuilder::new()
                .has_headers(false)
                .from_writer(out);
            w.write_record(header)?;
            for row in rows {
                w.write_record(row.cells().iter().map(csv_text))?;
            }
            w.flush()
        }
        Format::Jsonl => {
            for row in rows {
                out.write_all(b"{")?;
                for (i, (name, cell)) in header.iter().zip(row.cells()).enumerate() {
                    if i > 0 {
                        out.write_all(b",")?;
                    }
                    serde_json::to_writer(&mut *out, name)?;
                    out.write_all(b":")?;
                    serde_json::to_writer(&mut *out, &json_value(&cell))?;
                }
                out.write_all(b"}\n")?;
            }
            Ok(())
        }
    })
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
        let i = s.inputs(&s.point(0));
        assert_eq!(i.request.velocity, Some(1.4));
        assert!((i.mass - 45.0).abs() < 1e-12);
        assert_eq!(i.steps, 10.0);
        let h = s.header();
        assert!(h.contains(&"mass_per_height2".to_string()));
        assert_eq!(h.len(), 7 + OUTPUT_COLUMNS.len());
    }

    #[test]
    fn failed_point_records_the_reason() {
        let s = Sweep {
            axes: vec![(Axis::Velocity, vec![5.0]), (Axis::Steps, vec![2.0])],
        };
        let rows = s.run(|_, _| {}).unwrap();
        assert_eq!(rows.len(), 1);
        let e = rows[0].outcome.as_ref().unwrap_err();
        assert!(e.contains("velocity"), "{e}");
        assert_eq!(rows[0].cells().len(), s.header().len());
    }
}
