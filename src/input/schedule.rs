//! Step schedules (`klaw walk --schedule`): one gait request per step, from TOML or CSV.
use std::path::Path;

use serde::Deserialize;

use super::read_text;
use crate::error::Result;
use crate::model::InputError;
use crate::model::attributes::Attributes;
use crate::model::body::Body;
use crate::plan::gait::{Gait, GaitRequest};

/// The columns (CSV) and keys (TOML) a schedule row may name.
const SCHEDULE_FIELDS: [&str; 3] = ["velocity", "step_length", "step_frequency"];

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TomlStep {
    velocity: Option<f64>,
    step_length: Option<f64>,
    step_frequency: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TomlSchedule {
    #[serde(default)]
    step: Vec<TomlStep>,
}

/// Why a step schedule cannot be read (an [`InputError::Malformed`] of the file).
#[derive(Debug, thiserror::Error)]
pub enum ScheduleError {
    /// TOML that does not parse or is not `[[step]]` tables, at `line`, `column` (1-based),
    /// inside the `step`-th table (0: before the first).
    #[error(
        "line {line}, column {column}{}: {}",
        within_step(*step),
        source.message().trim_end()
    )]
    TomlAt {
        /// The line of the error, from 1.
        line: usize,
        /// Its column, from 1.
        column: usize,
        /// The `[[step]]` table it is in, from 1; 0 before the first.
        step: usize,
        /// The TOML parser's error.
        source: toml::de::Error,
    },
    /// The same where TOML gives no position.
    #[error("{}", .0.message().trim_end())]
    Toml(#[source] toml::de::Error),
    /// A CSV header that cannot be read.
    #[error("header: {0}")]
    CsvHeader(#[source] CsvError),
    /// A blank line before the last row of a CSV schedule: a CSV reader would skip it, and
    /// with it the step the user may have meant (a step needs at least one value).
    #[error(
        "line {line} is blank: every line after the header is a step and needs at least one \
         value (remove the line, or start it with # to make it a comment)"
    )]
    BlankLine {
        /// The blank line (1-based).
        line: usize,
    },
    /// CSV row `row` (1-based, the header not counted).
    #[error("row {row}: {source}")]
    CsvRow {
        /// The row, from 1.
        row: usize,
        /// Why it cannot be read.
        source: CsvError,
    },
    /// A header column (1-based) that is not `velocity`, `step_length` or `step_frequency`.
    #[error(
        "line 1: unknown column `{name}` (column {column}); the columns are {}",
        SCHEDULE_FIELDS.join(", ")
    )]
    UnknownColumn {
        /// The column's name.
        name: String,
        /// Its place in the header, from 1.
        column: usize,
    },
    /// A header column named twice.
    #[error("line 1: column `{name}` appears twice")]
    RepeatedColumn {
        /// The column's name.
        name: String,
    },
    /// A header with no column.
    #[error(
        "line 1: the header names no column; the columns are {}",
        SCHEDULE_FIELDS.join(", ")
    )]
    NoColumn,
    /// A cell of `field` in row `row` (at `line` of the file) that is not a number.
    #[error("row {row} (line {line}): {field} `{cell}` is not a number")]
    NotANumber {
        /// The row, from 1.
        row: usize,
        /// The line of the file, from 1.
        line: usize,
        /// The cell's column.
        field: &'static str,
        /// The cell's text, trimmed.
        cell: String,
    },
    /// A path whose extension is neither `.toml` nor `.csv`.
    #[error(
        "unrecognised file extension: a schedule is a .toml file ([[step]] tables) or a .csv \
         file (columns velocity, step_length, step_frequency)"
    )]
    Extension,
    /// A schedule without a row.
    #[error("the schedule has no steps")]
    NoSteps,
    /// Row `step` (1-based) cannot be completed to a gait.
    #[error("step {step}: {source}")]
    Step {
        /// The row, from 1.
        step: usize,
        /// Why it cannot be completed.
        source: InputError,
    },
}

/// A CSV record of a schedule that cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum CsvError {
    /// A record with `len` cells under a header of `expected`.
    #[error(
        "{len} cells where the header has {expected}{}",
        line.map_or(String::new(), |l| format!(" (line {l})"))
    )]
    UnequalLengths {
        /// The record's cells.
        len: u64,
        /// The header's cells.
        expected: u64,
        /// The record's line, from 1, where the CSV reader knows it.
        line: Option<u64>,
    },
    /// Any other error of the CSV reader.
    #[error(transparent)]
    Csv(csv::Error),
}

/// ` (step N)` for a position inside the N-th `[[step]]` table, nothing before the first.
fn within_step(step: usize) -> String {
    if step > 0 {
        format!(" (step {step})")
    } else {
        String::new()
    }
}

/// Read a step schedule: one gait request per step, from
/// - a TOML file (`.toml`): `[[step]]` tables with any of `velocity` (m/s), `step_length` (m),
///   `step_frequency` (steps/min), no other keys;
/// - a CSV file (`.csv`): a header naming any subset of those three columns, then one row per
///   step; empty cells are absent values; lines starting with `#` are comments; a blank line
///   before the last step is an error ([`ScheduleError::BlankLine`]).
///
/// Values are not range-checked here: that is `GaitRequest::complete`'s job.
pub fn read_schedule(path: &Path) -> Result<Vec<GaitRequest>> {
    let malformed = |e| InputError::malformed("schedule", path, e);
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let steps = match ext.as_deref() {
        Some("toml") => parse_schedule_toml(&read_text(path)?).map_err(malformed)?,
        Some("csv") => parse_schedule_csv(&read_text(path)?).map_err(malformed)?,
        _ => return Err(malformed(ScheduleError::Extension).into()),
    };
    if steps.is_empty() {
        return Err(malformed(ScheduleError::NoSteps).into());
    }
    Ok(steps)
}

/// The gait of each of `steps` steps from the rows of the schedule `path`: row i completed
/// (`GaitRequest::complete`) for step i, the last row held for the steps after the schedule's
/// end. A row that cannot be completed is [`InputError::Malformed`], naming the schedule and the
/// step.
pub fn schedule_gaits(
    path: &Path,
    rows: &[GaitRequest],
    steps: usize,
    body: &Body,
    attrs: &Attributes,
) -> Result<Vec<Gait>, InputError> {
    let mut gaits = rows
        .iter()
        .take(steps)
        .enumerate()
        .map(|(i, r)| {
            r.complete(body, attrs).map_err(|source| {
                let e = ScheduleError::Step {
                    step: i + 1,
                    source,
                };
                InputError::malformed("schedule", path, e)
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    if let Some(&last) = gaits.last() {
        gaits.resize(steps, last);
    }
    Ok(gaits)
}

fn parse_schedule_toml(text: &str) -> Result<Vec<GaitRequest>, ScheduleError> {
    match toml::from_str::<TomlSchedule>(text) {
        Ok(s) => Ok(s
            .step
            .into_iter()
            .map(|s| GaitRequest {
                velocity: s.velocity,
                step_length: s.step_length,
                step_frequency: s.step_frequency,
            })
            .collect()),
        Err(e) => {
            let Some(span) = e.span() else {
                return Err(ScheduleError::Toml(e));
            };
            let (line, column) = crate::model::file::line_col(text, span.start);
            // the step whose table holds the error: count the `[[step]]` headers above it
            let step = text
                .get(..span.start)
                .unwrap_or(text)
                .lines()
                .filter(|l| l.trim_start().starts_with("[[step]]"))
                .count();
            Err(ScheduleError::TomlAt {
                line,
                column,
                step,
                source: e,
            })
        }
    }
}

fn parse_schedule_csv(text: &str) -> Result<Vec<GaitRequest>, ScheduleError> {
    let lines: Vec<&str> = text.lines().collect();
    let last = lines.iter().rposition(|l| !l.trim().is_empty());
    if let Some(last) = last
        && let Some(blank) = lines[..last].iter().position(|l| l.trim().is_empty())
    {
        return Err(ScheduleError::BlankLine { line: blank + 1 });
    }
    // (the blank lines after the last step are the file's end, not empty steps)
    let text = lines[..last.map_or(0, |l| l + 1)].join("\n");
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(true)
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    let csv_err = |e: csv::Error| match e.kind() {
        csv::ErrorKind::UnequalLengths {
            pos,
            expected_len,
            len,
        } => CsvError::UnequalLengths {
            len: *len,
            expected: *expected_len,
            line: pos.as_ref().map(|p| p.line()),
        },
        _ => CsvError::Csv(e),
    };
    let header = reader
        .headers()
        .map_err(|e| ScheduleError::CsvHeader(csv_err(e)))?
        .clone();
    let mut columns = Vec::with_capacity(header.len());
    for (i, name) in header.iter().enumerate() {
        let Some(field) = SCHEDULE_FIELDS.iter().position(|f| *f == name) else {
            return Err(ScheduleError::UnknownColumn {
                name: name.to_string(),
                column: i + 1,
            });
        };
        if columns.contains(&field) {
            return Err(ScheduleError::RepeatedColumn {
                name: name.to_string(),
            });
        }
        columns.push(field);
    }
    if columns.is_empty() {
        return Err(ScheduleError::NoColumn);
    }
    let mut steps = Vec::new();
    for (row, record) in reader.records().enumerate() {
        let record = record.map_err(|e| ScheduleError::CsvRow {
            row: row + 1,
            source: csv_err(e),
        })?;
        let line = record.position().map_or(row + 2, |p| p.line() as usize);
        let mut values = [None; 3];
        for (cell, &field) in record.iter().zip(&columns) {
            if cell.is_empty() {
                continue;
            }
            let value = cell.parse::<f64>().map_err(|_| ScheduleError::NotANumber {
                row: row + 1,
                line,
                field: SCHEDULE_FIELDS[field],
                cell: cell.to_string(),
            })?;
            values[field] = Some(value);
        }
        steps.push(GaitRequest {
            velocity: values[0],
            step_length: values[1],
            step_frequency: values[2],
        });
    }
    Ok(steps)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;
    use std::fs;
    use std::path::PathBuf;

    fn write_file(dir: &Path, name: &str, text: &str) -> PathBuf {
        let p = dir.join(name);
        fs::write(&p, text).unwrap();
        p
    }

    fn req(v: Option<f64>, sl: Option<f64>, sf: Option<f64>) -> GaitRequest {
        GaitRequest {
            velocity: v,
            step_length: sl,
            step_frequency: sf,
        }
    }

    #[test]
    fn schedule_toml_round_trip() {
        let dir = tempfile::tempdir().unwrap();
        let p = write_file(
            dir.path(),
            "s.toml",
            "# a schedule\n\
             [[step]]\nvelocity = 1.4\n\n\
             [[step]]\nstep_length = 0.72\nstep_frequency = 100\n\n\
             [[step]]\n\n\
             [[step]]\nvelocity = 1.2\nstep_length = 0.72\nstep_frequency = 100.0\n",
        );
        let s = read_schedule(&p).unwrap();
        assert_eq!(
            s,
            [
                req(Some(1.4), None, None),
                req(None, Some(0.72), Some(100.0)),
                req(None, None, None),
                req(Some(1.2), Some(0.72), Some(100.0)),
            ]
        );
    }

    #[test]
    fn schedule_csv_round_trip() {
        let dir = tempfile::tempdir().unwrap();
        let p = write_file(
            dir.path(),
            "s.CSV",
            "step_frequency, velocity\n\
             100,\n\
             # a comment line\n\
             , 1.4\n\
             110 ,1.5\n",
        );
        let s = read_schedule(&p).unwrap();
        assert_eq!(
            s,
            [
                req(None, None, Some(100.0)),
                req(Some(1.4), None, None),
                req(Some(1.5), None, Some(110.0)),
            ]
        );
        let p = write_file(dir.path(), "one.csv", "step_length\n0.7\n0.75\n");
        assert_eq!(
            read_schedule(&p).unwrap(),
            [req(None, Some(0.7), None), req(None, Some(0.75), None)]
        );
    }

    fn schedule_error(dir: &Path, name: &str, text: &str) -> String {
        let p = write_file(dir, name, text);
        let e = read_schedule(&p).unwrap_err();
        assert!(
            matches!(
                e,
                Error::Input(InputError::Malformed {
                    what: "schedule",
                    ..
                })
            ),
            "{e:?}"
        );
        let msg = e.to_string();
        assert!(msg.contains(name), "{msg}");
        msg
    }

    #[test]
    fn malformed_schedules_name_the_row() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        let m = schedule_error(d, "a.csv", "velocity,step_length\n1.4,\n1.3,abc\n");
        assert!(
            m.contains("row 2") && m.contains("line 3") && m.contains("abc"),
            "{m}"
        );
        assert!(m.contains("step_length"), "{m}");
        let m = schedule_error(d, "b.csv", "velocity\n1.4\n1.3,0.7\n");
        assert!(m.contains("row 2") && m.contains("line 3"), "{m}");
        let m = schedule_error(d, "c.csv", "velocity,speed\n1.4,1\n");
        assert!(m.contains("line 1") && m.contains("`speed`"), "{m}");
        let m = schedule_error(d, "d.csv", "velocity,velocity\n1.4,1.4\n");
        assert!(m.contains("twice"), "{m}");
        let m = schedule_error(d, "e.csv", "velocity\n");
        assert!(m.contains("no steps"), "{m}");
        let m = schedule_error(d, "f.csv", "");
        assert!(m.contains("line 1") || m.contains("no steps"), "{m}");
        // a blank line among the steps is refused, not skipped with its step; blank lines
        // after the last step are the file's end
        let m = schedule_error(d, "g.csv", "velocity\n1.4\n\n1.3\n");
        assert!(m.contains("line 3 is blank"), "{m}");
        let p = write_file(d, "h.csv", "velocity\n1.4\n1.3\n\n  \n");
        assert_eq!(read_schedule(&p).unwrap().len(), 2);

        let m = schedule_error(
            d,
            "a.toml",
            "[[step]]\nvelocity = 1.4\n[[step]]\nspeed = 1.2\n",
        );
        assert!(
            m.contains("line 4") && m.contains("step 2") && m.contains("speed"),
            "{m}"
        );
        let m = schedule_error(
            d,
            "b.toml",
            "[[step]]\nvelocity = 1.4\n\n[[step]]\nvelocity = \"fast\"\n",
        );
        assert!(m.contains("line 5") && m.contains("step 2"), "{m}");
        let m = schedule_error(d, "c.toml", "[[step]]\nvelocity = \n");
        assert!(m.contains("line 2"), "{m}");
        let m = schedule_error(d, "d.toml", "# nothing\n");
        assert!(m.contains("no steps"), "{m}");
        let m = schedule_error(d, "e.toml", "velocity = 1.4\n");
        assert!(m.contains("line 1") && m.contains("velocity"), "{m}");
        let m = schedule_error(d, "s.json", "[]");
        assert!(m.contains(".toml") && m.contains(".csv"), "{m}");
    }

    #[test]
    fn schedule_gaits_hold_the_last_row_and_name_a_failing_step() {
        let body = Body::standard(1.8, 80.0).unwrap();
        let attrs = crate::model::attributes::AttributeTable::builtin().defaults();
        let p = Path::new("s.toml");
        let rows = [req(Some(1.2), None, None), req(Some(1.4), None, None)];
        let g = schedule_gaits(p, &rows, 4, &body, &attrs).unwrap();
        assert_eq!(g.len(), 4);
        assert_eq!(g[0].velocity, 1.2);
        assert_eq!((g[2], g[3]), (g[1], g[1]));
        assert_eq!(g[1].velocity, 1.4);
        assert_eq!(schedule_gaits(p, &rows, 1, &body, &attrs).unwrap(), g[..1]);
        let rows = [req(Some(1.4), None, None), req(Some(9.0), None, None)];
        let e = schedule_gaits(p, &rows, 3, &body, &attrs).unwrap_err();
        assert!(
            matches!(
                e,
                InputError::Malformed {
                    what: "schedule",
                    ..
                }
            ) && e.to_string().contains("s.toml: step 2: "),
            "{e}"
        );
    }

    #[test]
    fn a_missing_schedule_is_an_io_error() {
        let dir = tempfile::tempdir().unwrap();
        let e = read_schedule(&dir.path().join("none.toml")).unwrap_err();
        assert!(
            matches!(
                e,
                Error::Io {
                    action: "reading",
                    ..
                }
            ),
            "{e:?}"
        );
    }
}
