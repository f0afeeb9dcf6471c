//! File input and output at the edge of the crate: atomic writes of the frame CSV and the JSON
//! report, and reading of step schedules and attribute files. No physics here.
use std::collections::BTreeMap;
use std::fs::{self, File, OpenOptions};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use serde::Deserialize;

use crate::engine::report::{Report, StateFrame};
use crate::error::{Error, Result};
use crate::model::attributes;
use crate::plan::gait::GaitRequest;

/// The columns (CSV) and keys (TOML) a schedule row may name.
pub const SCHEDULE_FIELDS: [&str; 3] = ["velocity", "step_length", "step_frequency"];

fn io_error(action: &'static str, path: &Path, source: std::io::Error) -> Error {
    Error::Io {
        action,
        path: path.to_path_buf(),
        source,
    }
}

/// Removes the temporary file unless the write was committed by the rename.
struct TempGuard {
    path: PathBuf,
    armed: bool,
}

impl Drop for TempGuard {
    fn drop(&mut self) {
        if self.armed {
            let _ = fs::remove_file(&self.path);
        }
    }
}

/// Create a fresh temporary file next to `path` (same directory, so the rename stays on one
/// file system and is atomic).
fn create_temp(path: &Path) -> std::io::Result<(File, PathBuf)> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .ok_or_else(|| {
            std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "the path does not name a file",
            )
        })?;
    let pid = std::process::id();
    loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let tmp = dir.join(format!(".{name}.{pid}.{n}.tmp"));
        match OpenOptions::new().write(true).create_new(true).open(&tmp) {
            Ok(f) => return Ok((f, tmp)),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
}

/// A file written whole or not at all: rows go to a temporary file in the target's directory
/// (so the rename stays on one file system and is atomic), which `commit` flushes, syncs and
/// renames over the target. Dropped uncommitted, the temporary file is removed and an existing
/// target is left untouched. Errors are `Error::Io { action: "writing", .. }`.
pub struct AtomicFile {
    path: PathBuf,
    guard: TempGuard,
    out: BufWriter<File>,
}

impl AtomicFile {
    /// Start writing `path`.
    pub fn create(path: &Path) -> Result<AtomicFile> {
        let (file, tmp) = create_temp(path).map_err(|e| io_error("writing", path, e))?;
        Ok(AtomicFile {
            path: path.to_path_buf(),
            guard: TempGuard {
                path: tmp,
                armed: true,
            },
            out: BufWriter::new(file),
        })
    }

    /// The temporary file, for writers that open the file by name (its content is what
    /// `commit` renames over the target; write nothing through [`AtomicFile::writer`] then).
    pub fn temp_path(&self) -> &Path {
        &self.guard.path
    }

    /// Where to write.
    pub fn writer(&mut self) -> &mut BufWriter<File> {
        &mut self.out
    }

    /// The error of a failed write to this file.
    pub fn error(&self, e: std::io::Error) -> Error {
        io_error("writing", &self.path, e)
    }

    /// Flush, sync and rename over the target.
    pub fn commit(mut self) -> Result<()> {
        let path = self.path.clone();
        let err = |e| io_error("writing", &path, e);
        self.out.flush().map_err(err)?;
        self.out.get_ref().sync_all().map_err(err)?;
        fs::rename(&self.guard.path, &path).map_err(err)?;
        self.guard.armed = false;
        Ok(())
    }
}

/// Write `path` whole or not at all: `write` fills an [`AtomicFile`]. On any error the temporary
/// file is removed and an existing `path` is left untouched. Errors are
/// `Error::Io { action: "writing", .. }`.
pub fn write_atomic(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<()> {
    let mut file = AtomicFile::create(path)?;
    write(file.writer()).map_err(|e| file.error(e))?;
    file.commit()
}

/// The CSV header: the serde field names of `StateFrame`, in declaration order.
pub fn frame_header() -> Vec<String> {
    let mut w = csv::WriterBuilder::new()
        .has_headers(true)
        .from_writer(Vec::new());
    w.serialize(StateFrame::default())
        .expect("a default frame serializes");
    let bytes = w.into_inner().expect("writing to memory does not fail");
    let mut r = csv::ReaderBuilder::new()
        .has_headers(false)
        .from_reader(bytes.as_slice());
    let mut header = csv::StringRecord::new();
    r.read_record(&mut header)
        .expect("the header written above reads back");
    header.iter().map(str::to_string).collect()
}

/// Write the frames as CSV: a header of the `StateFrame` field names (written even when there are no
/// frames), then one row per frame; floats in their shortest exact (round-trip) form.
pub fn write_frames_csv(path: &Path, frames: &[StateFrame]) -> Result<()> {
    write_atomic(path, |out| {
        let mut w = csv::WriterBuilder::new()
            .has_headers(false)
            .from_writer(out);
        w.write_record(frame_header())?;
        for f in frames {
            w.serialize(f)?;
        }
        w.flush()
    })
}

/// Write gait events as CSV: `time_s, side, event, step`, one row per event.
pub fn write_events_csv(path: &Path, events: &[crate::analysis::events::Event]) -> Result<()> {
    write_atomic(path, |out| {
        let mut w = csv::Writer::from_writer(out);
        if events.is_empty() {
            w.write_record(["time_s", "side", "event", "step"])?;
        }
        for e in events {
            w.serialize(e)?;
        }
        w.flush()
    })
}

/// Write the report as pretty-printed JSON (with a final newline).
pub fn write_report_json(path: &Path, report: &Report) -> Result<()> {
    write_atomic(path, |out| {
        serde_json::to_writer_pretty(&mut *out, report)?;
        out.write_all(b"\n")
    })
}

fn read_text(path: &Path) -> Result<String> {
    fs::read_to_string(path).map_err(|e| io_error("reading", path, e))
}

/// Read a user attribute file (flat TOML `name = number`, user units) into overrides, to be
/// resolved by `AttributeTable::resolve`.
pub fn read_attributes(path: &Path) -> Result<BTreeMap<String, f64>> {
    let text = read_text(path)?;
    attributes::parse_overrides(&text, path)
}

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

/// Read a step schedule: one gait request per step, from
/// - a TOML file (`.toml`): `[[step]]` tables with any of `velocity` (m/s), `step_length` (m),
///   `step_frequency` (steps/min), no other keys;
/// - a CSV file (`.csv`): a header naming any subset of those three columns, then one row per
///   step; empty cells are absent values; lines starting with `#` are comments.
///
/// Values are not range-checked here: that is `GaitRequest::complete`'s job.
pub fn read_schedule(path: &Path) -> Result<Vec<GaitRequest>> {
    let malformed = |reason: String| Error::Malformed {
        what: "schedule",
        path: path.to_path_buf(),
        reason,
    };
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let steps = match ext.as_deref() {
        Some("toml") => parse_schedule_toml(&read_text(path)?).map_err(malformed)?,
        Some("csv") => parse_schedule_csv(&read_text(path)?).map_err(malformed)?,
        _ => {
            return Err(malformed(
                "unrecognised file extension: a schedule is a .toml file ([[step]] tables) or \
                 a .csv file (columns velocity, step_length, step_frequency)"
                    .to_string(),
            ));
        }
    };
    if steps.is_empty() {
        return Err(malformed("the schedule has no steps".to_string()));
    }
    Ok(steps)
}

/// Line and column (1-based) of byte `offset` in `text`.
fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = text.get(..offset).unwrap_or(text);
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

fn parse_schedule_toml(text: &str) -> std::result::Result<Vec<GaitRequest>, String> {
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
            let message = e.message().trim_end().to_string();
            let Some(span) = e.span() else {
                return Err(message);
            };
            let (line, col) = line_col(text, span.start);
            // the step whose table holds the error: count the `[[step]]` headers above it
            let step = text
                .get(..span.start)
                .unwrap_or(text)
                .lines()
                .filter(|l| l.trim_start().starts_with("[[step]]"))
                .count();
            let within = if step > 0 {
                format!(" (step {step})")
            } else {
                String::new()
            };
            Err(format!("line {line}, column {col}{within}: {message}"))
        }
    }
}

fn parse_schedule_csv(text: &str) -> std::result::Result<Vec<GaitRequest>, String> {
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
        } => {
            let line = pos
                .as_ref()
                .map_or(String::new(), |p| format!(" (line {})", p.line()));
            format!("{len} cells where the header has {expected_len}{line}")
        }
        _ => e.to_string(),
    };
    let header = reader
        .headers()
        .map_err(|e| format!("header: {}", csv_err(e)))?
        .clone();
    let mut columns = Vec::with_capacity(header.len());
    for (i, name) in header.iter().enumerate() {
        let Some(field) = SCHEDULE_FIELDS.iter().position(|f| *f == name) else {
            return Err(format!(
                "line 1: unknown column `{name}` (column {}); the columns are {}",
                i + 1,
                SCHEDULE_FIELDS.join(", ")
            ));
        };
        if columns.contains(&field) {
            return Err(format!("line 1: column `{name}` appears twice"));
        }
        columns.push(field);
    }
    if columns.is_empty() {
        return Err(format!(
            "line 1: the header names no column; the columns are {}",
            SCHEDULE_FIELDS.join(", ")
        ));
    }
    let mut steps = Vec::new();
    for (row, record) in reader.records().enumerate() {
        let record = record.map_err(|e| format!("row {}: {}", row + 1, csv_err(e)))?;
        let line = record.position().map_or(row + 2, |p| p.line() as usize);
        let mut values = [None; 3];
        for (cell, &field) in record.iter().zip(&columns) {
            if cell.is_empty() {
                continue;
            }
            let value = cell.parse::<f64>().map_err(|_| {
                format!(
                    "row {} (line {line}): {} `{cell}` is not a number",
                    row + 1,
                    SCHEDULE_FIELDS[field]
                )
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
    use std::io::ErrorKind;

    fn files_in(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

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
    fn atomic_write_commits_whole_file() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("out.txt");
        write_atomic(&p, |w| w.write_all(b"hello\n")).unwrap();
        assert_eq!(fs::read_to_string(&p).unwrap(), "hello\n");
        write_atomic(&p, |w| w.write_all(b"again\n")).unwrap();
        assert_eq!(fs::read_to_string(&p).unwrap(), "again\n");
        assert_eq!(files_in(dir.path()), ["out.txt"]);
    }

    #[test]
    fn failed_atomic_write_leaves_no_file() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("out.csv");
        let e = write_atomic(&p, |w| {
            // more than the BufWriter holds, so part of it reached the temporary file
            w.write_all(&vec![b'x'; 100_000])?;
            Err(std::io::Error::other("disk on fire"))
        })
        .unwrap_err();
        assert!(
            matches!(
                e,
                Error::Io {
                    action: "writing",
                    ..
                }
            ),
            "{e}"
        );
        assert!(
            e.to_string().contains("out.csv") && e.to_string().contains("disk on fire"),
            "{e}"
        );
        assert_eq!(e.exit_code(), 1);
        assert!(
            files_in(dir.path()).is_empty(),
            "{:?}",
            files_in(dir.path())
        );
    }

    #[test]
    fn failed_atomic_write_keeps_existing_target() {
        let dir = tempfile::tempdir().unwrap();
        let p = write_file(dir.path(), "out.csv", "old contents\n");
        let e = write_atomic(&p, |w| {
            w.write_all(b"new, partial")?;
            Err(std::io::Error::other("interrupted"))
        });
        assert!(e.is_err());
        assert_eq!(fs::read_to_string(&p).unwrap(), "old contents\n");
        assert_eq!(files_in(dir.path()), ["out.csv"]);
    }

    #[test]
    fn atomic_write_into_missing_directory_is_an_io_error() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("no/such/dir/out.csv");
        let e = write_atomic(&p, |w| w.write_all(b"x")).unwrap_err();
        match &e {
            Error::Io {
                action,
                path,
                source,
            } => {
                assert_eq!(*action, "writing");
                assert_eq!(path, &p);
                assert_eq!(source.kind(), ErrorKind::NotFound);
            }
            other => panic!("{other:?}"),
        }
        assert!(files_in(dir.path()).is_empty());
    }

    #[test]
    fn frames_csv_has_header_and_exact_floats() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("f.csv");
        write_frames_csv(&p, &[]).unwrap();
        let text = fs::read_to_string(&p).unwrap();
        assert_eq!(text.lines().count(), 1);
        let header: Vec<&str> = text.trim_end().split(',').collect();
        assert_eq!(header.len(), 22);
        assert_eq!(header[..3], ["time_s", "step", "phase"]);
        assert_eq!(header[21], "swing_toe_y_m");

        let f = StateFrame {
            time_s: 0.1 + 0.2,
            step: 3,
            phase: "swing2",
            stance_side: "left",
            stance_mode: "locked",
            hip_x_m: 1.0 / 3.0,
            swing_toe_y_m: -1e-12,
            ..StateFrame::default()
        };
        write_frames_csv(&p, &[f.clone(), f]).unwrap();
        let mut r = csv::Reader::from_path(&p).unwrap();
        let hdr = r.headers().unwrap().clone();
        let rows: Vec<csv::StringRecord> = r.records().map(|r| r.unwrap()).collect();
        assert_eq!(rows.len(), 2);
        let col = |name: &str| hdr.iter().position(|h| h == name).unwrap();
        let row = &rows[0];
        assert_eq!(row[col("time_s")].parse::<f64>().unwrap(), 0.1 + 0.2);
        assert_eq!(row[col("hip_x_m")].parse::<f64>().unwrap(), 1.0 / 3.0);
        assert_eq!(row[col("swing_toe_y_m")].parse::<f64>().unwrap(), -1e-12);
        assert_eq!(&row[col("phase")], "swing2");
        assert_eq!(&row[col("step")], "3");
    }

    #[test]
    fn report_json_is_written() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("r.json");
        let report = Report {
            height: 1.8,
            mass: 80.0,
            steps: Vec::new(),
        };
        write_report_json(&p, &report).unwrap();
        let v: serde_json::Value = serde_json::from_str(&fs::read_to_string(&p).unwrap()).unwrap();
        assert_eq!(v["height"], 1.8);
        assert_eq!(v["mass"], 80.0);
        assert!(v["steps"].as_array().unwrap().is_empty());
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
                Error::Malformed {
                    what: "schedule",
                    ..
                }
            ),
            "{e:?}"
        );
        assert_eq!(e.exit_code(), 2);
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
    fn missing_files_are_io_errors() {
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
        assert_eq!(e.exit_code(), 2);
        let e = read_attributes(&dir.path().join("none.toml")).unwrap_err();
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

    #[test]
    fn attribute_files_are_read() {
        let dir = tempfile::tempdir().unwrap();
        let p = write_file(
            dir.path(),
            "a.toml",
            "description = \"x\"\nbounciness = 0.5\ntrunk_lean = 3\n",
        );
        let o = read_attributes(&p).unwrap();
        assert_eq!(o.len(), 2);
        assert_eq!(o["bounciness"], 0.5);
        assert_eq!(o["trunk_lean"], 3.0);
        let p = write_file(dir.path(), "b.toml", "bounciness = [1]\n");
        let e = read_attributes(&p).unwrap_err();
        assert!(
            matches!(e, Error::Malformed { .. }) && e.to_string().contains("b.toml"),
            "{e}"
        );
    }
}
