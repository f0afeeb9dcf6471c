//! Sweep output files: rows streamed, in point order, to a partial file next to the target and
//! renamed over it when the sweep is done; resuming from what an interrupted or truncated run
//! left; reading them back row by row (also for [`super::merge`]).
//!
//! - While `klaw sweep --out DIR/NAME` runs, rows go to `DIR/.NAME.partial` as their chunk
//!   completes, so memory does not grow with the sweep; the target appears whole, by a rename,
//!   only when every point is written. An interrupted run leaves the partial file.
//! - `--resume` keeps the complete rows of the partial file (a cut-off last line is dropped) and
//!   of an existing target, checks that each was written by this sweep (same columns, same
//!   inputs for its point, point in this shard, points increasing), and walks only the other
//!   points. The result is the union, in point order, byte-identical to an uninterrupted run.
use std::fs::{self, File, OpenOptions};
use std::io::{BufRead, BufReader, BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use crate::error::{Error, Result};
use crate::model::InputError;
use crate::model::error::Reason;
use crate::sweep::rows::check_sweep_columns;
use crate::sweep::{RowFormat, Shard, Sweep};

/// The partial output of a sweep writing `target`: `.NAME.partial` in the same directory.
pub(crate) fn partial_path(target: &Path) -> PathBuf {
    let name = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    target.with_file_name(format!(".{name}.partial"))
}

fn io_err<'a>(action: &'static str, path: &'a Path) -> impl Fn(std::io::Error) -> Error + 'a {
    move |source| Error::Io {
        action,
        path: path.to_path_buf(),
        source,
    }
}

pub(super) fn malformed(path: &Path, reason: impl Into<Reason>) -> Error {
    InputError::malformed("sweep output", path, reason).into()
}

/// A line of a sweep output that is not a row, `line` counted from 1.
#[derive(Debug, thiserror::Error)]
#[error("line {line}: {reason}")]
pub struct LineError {
    /// The line's number, from 1.
    pub line: usize,
    /// Why it is not a row.
    #[source]
    pub reason: Reason,
}

/// A line that is not one CSV record.
#[derive(Debug, thiserror::Error)]
enum CsvLineError {
    #[error("empty line")]
    Empty,
    #[error("not a CSV record: {0}")]
    NotCsv(#[source] csv::Error),
}

/// The column names of a file as they are compared: the CSV header in order, or the sorted keys
/// of a JSON Lines row.
fn comparable(format: RowFormat, header: &[String]) -> Vec<String> {
    let mut h = header.to_vec();
    if format == RowFormat::Jsonl {
        h.sort();
    }
    h
}

/// Reads the rows of a sweep output in order, checking that every row is complete, has the
/// file's columns and a `point` larger than the one before. A last line without its newline
/// (cut off by an interruption) is not returned: `cut_off` says so.
pub(crate) struct RowReader {
    pub(super) path: PathBuf,
    format: RowFormat,
    reader: BufReader<File>,
    /// CSV: the header; JSON Lines: the sorted keys of the first row (`None` before it).
    columns: Option<Vec<String>>,
    line: usize,
    last: Option<usize>,
    /// Bytes of the complete lines read so far.
    pub valid_len: u64,
    pub cut_off: bool,
}

impl RowReader {
    /// Open a sweep output; a CSV file's header is read here (a file without a complete first
    /// line has no columns).
    pub fn open(path: &Path, format: RowFormat) -> Result<RowReader> {
        let file = File::open(path).map_err(io_err("reading", path))?;
        let mut r = RowReader {
            path: path.to_path_buf(),
            format,
            reader: BufReader::new(file),
            columns: None,
            line: 0,
            last: None,
            valid_len: 0,
            cut_off: false,
        };
        if format == RowFormat::Csv
            && let Some(text) = r.read_line()?
        {
            let columns = parse_csv(&text).map_err(|e| r.error(Box::new(e)))?;
            check_sweep_columns(&columns).map_err(|e| r.error(e.into()))?;
            r.columns = Some(columns);
        }
        Ok(r)
    }

    /// The columns, once known (see the field).
    pub fn columns(&self) -> Option<&[String]> {
        self.columns.as_deref()
    }

    fn error(&self, reason: Reason) -> Error {
        let line = self.line;
        malformed(&self.path, LineError { line, reason })
    }

    /// The next complete line, with its newline.
    fn read_line(&mut self) -> Result<Option<String>> {
        let mut text = String::new();
        let n = self
            .reader
            .read_line(&mut text)
            .map_err(io_err("reading", &self.path))?;
        if n == 0 {
            return Ok(None);
        }
        self.line += 1;
        if !text.ends_with('\n') {
            self.cut_off = true;
            return Ok(None);
        }
        self.valid_len += n as u64;
        Ok(Some(text))
    }

    /// The next row: its point and its text (with the newline).
    pub fn next_row(&mut self) -> Result<Option<(usize, String)>> {
        let Some(text) = self.read_line()? else {
            return Ok(None);
        };
        let point = match self.format {
            RowFormat::Csv => {
                let fields = parse_csv(&text).map_err(|e| self.error(Box::new(e)))?;
                let want = self.columns.as_ref().map_or(0, Vec::len);
                if fields.len() != want {
                    let n = fields.len();
                    return Err(self.error(format!("{n} fields, the header has {want}").into()));
                }
                fields[0].parse::<usize>().ok()
            }
            RowFormat::Jsonl => {
                let map: serde_json::Map<String, serde_json::Value> =
                    serde_json::from_str(&text).map_err(|e| self.error(Box::new(NotJson(e))))?;
                let mut keys: Vec<String> = map.keys().cloned().collect();
                keys.sort();
                match &self.columns {
                    None => {
                        check_sweep_columns(&keys).map_err(|e| self.error(e.into()))?;
                        self.columns = Some(keys);
                    }
                    Some(c) if *c == keys => {}
                    Some(_) => {
                        return Err(self.error("its keys differ from the first row's".into()));
                    }
                }
                map.get("point")
                    .and_then(|v| v.as_u64())
                    .and_then(|p| usize::try_from(p).ok())
            }
        };
        let point = point.ok_or_else(|| self.error("no whole-number `point`".into()))?;
        if let Some(last) = self.last.filter(|&l| point <= l) {
            return Err(self.error(
                format!("point {point} after point {last}: rows must be in increasing point order")
                    .into(),
            ));
        }
        self.last = Some(point);
        Ok(Some((point, text)))
    }
}

/// A line that is not one JSON object.
#[derive(Debug, thiserror::Error)]
#[error("not a JSON object: {0}")]
struct NotJson(#[source] serde_json::Error);

fn parse_csv(text: &str) -> Result<Vec<String>, CsvLineError> {
    let mut r = csv::ReaderBuilder::new()
        .has_headers(false)
        .from_reader(text.as_bytes());
    let mut record = csv::StringRecord::new();
    match r.read_record(&mut record) {
        Ok(true) => Ok(record.iter().map(str::to_string).collect()),
        Ok(false) => Err(CsvLineError::Empty),
        Err(e) => Err(CsvLineError::NotCsv(e)),
    }
}

/// What a sweep run did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RunStats {
    /// Points of the shard (of the whole sweep for 1/1).
    pub points: usize,
    /// Walks run now.
    pub computed: usize,
    /// Walks run now that failed (their rows carry the error).
    pub failed: usize,
    /// Rows kept from the partial file or the existing target (with `resume`).
    pub kept: usize,
}

/// Set of point indices (one bit each: ≤ 1.25 MB for the largest sweep).
struct PointSet(Vec<u64>);

impl PointSet {
    fn new(total: usize) -> Self {
        PointSet(vec![0; total.div_ceil(64)])
    }
    fn insert(&mut self, p: usize) {
        self.0[p / 64] |= 1 << (p % 64);
    }
    fn contains(&self, p: usize) -> bool {
        self.0[p / 64] & (1 << (p % 64)) != 0
    }
}

/// Check the rows of an earlier output of this sweep and shard, calling `each(point)` for every
/// complete row; returns the reader's final state (valid length, cut-off).
fn scan(
    sweep: &Sweep,
    shard: Shard,
    path: &Path,
    format: RowFormat,
    mut each: impl FnMut(usize),
) -> Result<RowReader> {
    let header = sweep.header();
    let input_header = sweep.input_header();
    let expected = comparable(format, &header);
    let mut reader = RowReader::open(path, format)?;
    let check_columns = |r: &RowReader| match r.columns() {
        Some(c) if c != expected.as_slice() => Err(malformed(
            path,
            format!(
                "its columns ({}) are not this sweep's ({}): it was written by a different sweep",
                c.join(","),
                expected.join(",")
            ),
        )),
        _ => Ok(()),
    };
    check_columns(&reader)?;
    while let Some((p, line)) = reader.next_row()? {
        check_columns(&reader)?;
        if p >= sweep.len() || !shard.contains(p) {
            return Err(reader.error(
                format!(
                    "point {p} is not in this sweep's shard {}/{} of {} points",
                    shard.index,
                    shard.count,
                    sweep.len()
                )
                .into(),
            ));
        }
        let prefix = format.input_prefix(&input_header, &sweep.inputs(p).cells());
        if !line.starts_with(&prefix) {
            return Err(reader.error(
                format!(
                    "point {p} has other inputs than this sweep's (`{}`): it was written by a \
                     different sweep",
                    prefix.trim_end_matches(',')
                )
                .into(),
            ));
        }
        each(p);
    }
    Ok(reader)
}

/// Run a sweep (or one shard of it) into `target`, streaming rows in point order to the
/// partial file (module docs) and renaming it over `target` at the end. Without `resume` an
/// existing partial file is an error (it holds an interrupted run: resume it or delete it).
/// `progress(done, total)` counts the walks of this run, from any thread. A partial file this
/// run created is removed when the run fails (a refused `resume`, a write error); one an
/// earlier run left holds its rows and stays, and so does every partial file when the process
/// is interrupted (that is what `resume` continues).
pub fn run_to_file(
    sweep: &Sweep,
    target: &Path,
    shard: Shard,
    resume: bool,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<RunStats> {
    let partial = partial_path(target);
    let created = !partial.exists();
    let result = run_into(sweep, target, shard, resume, progress);
    if result.is_err() && created {
        let _ = fs::remove_file(&partial);
    }
    result
}

/// [`run_to_file`] but for the removal of a partial file it created.
fn run_into(
    sweep: &Sweep,
    target: &Path,
    shard: Shard,
    resume: bool,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<RunStats> {
    let format = RowFormat::from_path(target)?;
    let header = sweep.header();
    let total = sweep.len();
    let partial = partial_path(target);
    let mut done = PointSet::new(total);
    let mut stats = RunStats {
        points: shard.points(total, 0).count(),
        ..RunStats::default()
    };
    let (file, next) = open_partial(sweep, shard, target, resume, &mut done, &mut stats)?;
    let mut out = BufWriter::new(file);
    // the existing target's rows after the partial file's last one are kept too
    let mut existing = None;
    if resume && target.exists() {
        existing = Some(Existing::open(
            sweep, shard, target, next, &mut done, &mut stats,
        )?);
    }
    let mut copy_before = |limit: usize, out: &mut BufWriter<File>| match existing.as_mut() {
        Some(e) => e.copy_before(limit, out, &partial),
        None => Ok(()),
    };

    let to_run = shard
        .points(total, next)
        .filter(|&p| !done.contains(p))
        .count();
    let counter = AtomicUsize::new(0);
    let tick = || {
        let n = counter.fetch_add(1, Ordering::Relaxed) + 1;
        progress(n, to_run);
    };
    let input_header = sweep.input_header();
    let mut last_flush = Instant::now();
    sweep.run(
        shard.points(total, next).filter(|&p| !done.contains(p)),
        &tick,
        |row| {
            copy_before(row.inputs.point, &mut out)?;
            stats.computed += 1;
            if row.outcome.is_err() {
                stats.failed += 1;
            }
            debug_assert!(
                format
                    .line(&header, &row.cells())
                    .starts_with(&format.input_prefix(&input_header, &row.inputs.cells()))
            );
            out.write_all(format.line(&header, &row.cells()).as_bytes())
                .map_err(io_err("writing", &partial))?;
            // an interruption loses at most a second of rows
            if last_flush.elapsed().as_secs_f64() > 1.0 {
                out.flush().map_err(io_err("writing", &partial))?;
                last_flush = Instant::now();
            }
            Ok(())
        },
    )?;
    copy_before(usize::MAX, &mut out)?;
    let file = out
        .into_inner()
        .map_err(|e| io_err("writing", &partial)(e.into_error()))?;
    file.sync_all().map_err(io_err("writing", &partial))?;
    drop(file);
    fs::rename(&partial, target).map_err(io_err("writing", target))?;
    Ok(stats)
}

/// The partial file of `target`, open at its end for the next rows, and the point after its
/// last complete row: continued (with `resume`: its points are marked in `done` and counted as
/// kept; a CSV file cut off inside its header starts over), or started with the header.
fn open_partial(
    sweep: &Sweep,
    shard: Shard,
    target: &Path,
    resume: bool,
    done: &mut PointSet,
    stats: &mut RunStats,
) -> Result<(File, usize)> {
    let format = RowFormat::from_path(target)?;
    let header = sweep.header();
    let partial = partial_path(target);
    let write_err = io_err("writing", &partial);
    if !partial.exists() {
        let mut file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&partial)
            .map_err(&write_err)?;
        file.write_all(format.header_line(&header).as_bytes())
            .map_err(&write_err)?;
        return Ok((file, 0));
    }
    if !resume {
        return Err(malformed(
            &partial,
            format!(
                "an interrupted sweep left this partial output of {}: rerun with --resume to \
                 continue it, or delete it to start over",
                target.display()
            ),
        ));
    }
    let mut next = 0;
    let reader = scan(sweep, shard, &partial, format, |p| {
        done.insert(p);
        next = p + 1;
        stats.kept += 1;
    })?;
    let restart = reader.columns().is_none() && format == RowFormat::Csv;
    let mut file = OpenOptions::new()
        .write(true)
        .open(&partial)
        .map_err(&write_err)?;
    let keep = if restart { 0 } else { reader.valid_len };
    file.set_len(keep).map_err(&write_err)?;
    file.seek(SeekFrom::End(0)).map_err(&write_err)?;
    if restart {
        file.write_all(format.header_line(&header).as_bytes())
            .map_err(&write_err)?;
    }
    Ok((file, next))
}

/// The rows of the existing target of a resumed run, copied into the new output in point order
/// between the rows walked now.
struct Existing {
    reader: RowReader,
    /// A row read but not yet copied: its point is after the last limit.
    pending: Option<(usize, String)>,
    /// Rows of points below this one are in the partial file already: not copied.
    from: usize,
}

impl Existing {
    /// The rows of `target` from point `from` on, checked to be this sweep's, their points
    /// marked in `done` and counted as kept.
    fn open(
        sweep: &Sweep,
        shard: Shard,
        target: &Path,
        from: usize,
        done: &mut PointSet,
        stats: &mut RunStats,
    ) -> Result<Existing> {
        let format = RowFormat::from_path(target)?;
        scan(sweep, shard, target, format, |p| {
            if p >= from {
                done.insert(p);
                stats.kept += 1;
            }
        })?;
        Ok(Existing {
            reader: RowReader::open(target, format)?,
            pending: None,
            from,
        })
    }

    /// Copy the rows of the points below `limit` to `out`, the writer of `partial`.
    fn copy_before(&mut self, limit: usize, out: &mut impl Write, partial: &Path) -> Result<()> {
        loop {
            if self.pending.is_none() {
                self.pending = self.reader.next_row()?;
            }
            match &self.pending {
                Some((p, line)) if *p < limit => {
                    if *p >= self.from {
                        out.write_all(line.as_bytes())
                            .map_err(io_err("writing", partial))?;
                    }
                    self.pending = None;
                }
                _ => return Ok(()),
            }
        }
    }
}
