//! One row per walk: the columns (the inputs, then the summary), the cells of a row and their
//! text as CSV or JSON Lines.
use std::path::Path;

use super::product::{Axis, Inputs, Sweep};
use crate::error::Result;
use crate::model::InputError;
use crate::model::attributes::STYLES;

/// One cell of an output row.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Cell {
    Empty,
    Num(f64),
    Int(usize),
    Bool(bool),
    Text(String),
}

/// What one walk of the sweep produced.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Summary {
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
    /// Steps that walked with a fallback's change of their plan (the step report's `repairs`).
    pub repaired_steps: usize,
}

/// The output columns after the inputs.
pub(crate) const OUTPUT_COLUMNS: [&str; 15] = [
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
    "repaired_steps",
];

/// Whether `columns` (a CSV header, a JSON Lines row's keys) are those of a sweep output: a
/// `point` and a `converged` column, which every sweep writes and merging and heat maps read
/// (the other output columns may grow with versions); else which are missing, in words.
pub(crate) fn check_sweep_columns(columns: &[String]) -> Result<(), String> {
    let missing: Vec<&str> = ["point", "converged"]
        .into_iter()
        .filter(|c| !columns.iter().any(|h| h == c))
        .collect();
    if missing.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "not a sweep output (written by klaw sweep): no column {}",
            missing.join(", ")
        ))
    }
}

/// The row of one walk: its inputs and its outcome (a summary, or the reason it failed).
#[derive(Debug)]
pub(crate) struct Row {
    pub inputs: Inputs,
    pub outcome: Result<Summary>,
}

impl Sweep {
    /// The input column names: `point`, the gait, the body, `steps`, the swept attributes.
    pub(crate) fn input_header(&self) -> Vec<String> {
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
        if self.axes.iter().any(|(a, _)| *a == Axis::BodyTable) {
            h.push("body_table".into());
        }
        for (axis, _) in &self.axes {
            if let Axis::Attribute(n) = axis {
                h.push(n.clone());
            }
        }
        h
    }

    /// The column names: the inputs, then `OUTPUT_COLUMNS`.
    pub(crate) fn header(&self) -> Vec<String> {
        let mut h = self.input_header();
        h.extend(OUTPUT_COLUMNS.iter().map(|s| s.to_string()));
        h
    }
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
        if let Some(i) = self.body_table {
            c.push(Cell::Text(super::tables::name(i).to_string()));
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
                c.push(Cell::Int(s.repaired_steps));
            }
            Err(e) => {
                c.push(Cell::Bool(false));
                c.push(Cell::Text(e.to_string().replace(['\n', '\r'], " ")));
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
pub enum RowFormat {
    /// `.csv`: a header line, then one line per walk.
    Csv,
    /// `.jsonl`: JSON Lines, one object per walk.
    Jsonl,
}

impl RowFormat {
    /// `.csv` or `.jsonl` (case-insensitive); anything else is an error.
    pub fn from_path(path: &Path) -> Result<RowFormat, InputError> {
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        match ext.as_deref() {
            Some("csv") => Ok(RowFormat::Csv),
            Some("jsonl") => Ok(RowFormat::Jsonl),
            _ => Err(InputError::malformed(
                "output path",
                path,
                "a sweep is written as .csv or .jsonl",
            )),
        }
    }

    /// The text of one row, with its final newline: a CSV record, or a JSON object with the
    /// keys of `header` in order (empty cells as null). `cells` may be a prefix of the row.
    pub(crate) fn line(&self, header: &[String], cells: &[Cell]) -> String {
        match self {
            RowFormat::Csv => csv_line(cells.iter().map(csv_text)),
            RowFormat::Jsonl => {
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
    pub(crate) fn header_line(&self, header: &[String]) -> String {
        match self {
            RowFormat::Csv => csv_line(header.iter().cloned()),
            RowFormat::Jsonl => String::new(),
        }
    }

    /// How a row's text starts, given its input cells (an exact prefix of `line`).
    pub(crate) fn input_prefix(&self, header: &[String], inputs: &[Cell]) -> String {
        let mut line = self.line(header, inputs);
        let end = match self {
            RowFormat::Csv => "\n",
            RowFormat::Jsonl => "}\n",
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
