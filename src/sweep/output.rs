//! Sweep output files: rows streamed, in point order, to a partial file next to the target and
//! renamed over it when the sweep is done; resuming from what an interrupted or truncated run
//! left; merging the outputs of shards.
//!
//! - While `klaw sweep --out DIR/NAME` runs, rows go to `DIR/.NAME.partial` as their chunk
//!   completes, so memory does not grow with the sweep; the target appears whole, by a rename,
//!   only when every point is written. An interrupted run leaves the partial file.
//! - `--resume` keeps the complete rows of the partial file (a cut-off last line is dropped) and
//!   of an existing target, checks that each was written by this sweep (same columns, same
//!   inputs for its point, point in this shard, points increasing), and walks only the other
//!   points. The result is the union, in point order, byte-identical to an uninterrupted run.
//! - `merge` joins shard outputs in point order (a k-way merge of the sorted files).
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::fs::{self, File, OpenOptions};
use std::io::{BufRead, BufReader, BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use crate::error::{Error, Result};
use crate::export::file::AtomicFile;
use crate::sweep::{Format, Shard, Sweep};

/// The partial output of a sweep writing `target`: `.NAME.partial` in the same directory.
pub fn partial_path(target: &Path) -> PathBuf {
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

fn malformed(path: &Path, reason: String) -> Error {
    Error::Malformed {
        what: "sweep output",
        path: path.to_path_buf(),
        reason,
    }
}

/// The column names of a file as they are compared: the CSV header in order, or the sorted keys
/// of a JSON Lines row.
fn comparable(format: Format, header: &[String]) -> Vec<String> {
    let mut h = header.to_vec();
    if format == Format::Jsonl {
        h.sort();
    }
    h
}

/// Reads the rows of a sweep output in order, checking that every row is complete, has the
/// file's columns and a `point` larger than the one before. A last line without its newline
/// (cut off by an interruption) is not returned: `cut_off` says so.
pub struct RowReader {
    path: PathBuf,
    format: Format,
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
    pub fn open(path: &Path, format: Format) -> Result<RowReader> {
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
        if format == Format::Csv
            && let Some(text) = r.read_line()?
        {
            r.columns = Some(parse_csv(&text).map_err(|e| r.error(e))?);
        }
        Ok(r)
    }

    /// The columns, once known (see the field).
    pub fn columns(&self) -> Option<&[String]> {
        self.columns.as_deref()
    }

    fn error(&self, reason: String) -> Error {
        malformed(&self.path, format!("line {}: {reason}", self.line))
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
            Format::Csv => {
                let fields = parse_csv(&text).map_err(|e| self.error(e))?;
                let want = self.columns.as_ref().map_or(0, Vec::len);
                if fields.len() != want {
                    return Err(
                        self.error(format!("{} fields, the header has {want}", fields.len()))
                    );
                }
                fields[0].parse::<usize>().ok()
            }
            Format::Jsonl => {
                let map: serde_json::Map<String, serde_json::Value> =
                    serde_json::from_str(&text)
                        .map_err(|e| self.error(format!("not a JSON object: {e}")))?;
                let mut keys: Vec<String> = map.keys().cloned().collect();
                keys.sort();
                match &self.columns {
                    None => self.columns = Some(keys),
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
        if self.last.is_some_and(|l| point <= l) {
            return Err(self.error(format!(
                "point {point} after point {}: rows must be in increasing point order",
                self.last.unwrap_or(0)
            )));
        }
        self.last = Some(point);
        Ok(Some((point, text)))
    }
}

fn parse_csv(text: &str) -> std::result::Result<Vec<String>, String> {
    let mut r = csv::ReaderBuilder::new()
        .has_headers(false)
        .from_reader(text.as_bytes());
    let mut record = csv::StringRecord::new();
    match r.read_record(&mut record) {
        Ok(true) => Ok(record.iter().map(str::to_string).collect()),
        Ok(false) => Err("empty line".into()),
        Err(e) => Err(format!("not a CSV record: {e}")),
    }
}

/// What a sweep run did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RunStats {
    /// Points of the shard (of the whole sweep for 1/1).
    pub points: usize,
    /// Walks run now, and how many of them failed.
    pub computed: usize,
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
    format: Format,
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
            return Err(reader.error(format!(
                "point {p} is not in this sweep's shard {}/{} of {} points",
                shard.index,
                shard.count,
                sweep.len()
            )));
        }
        let prefix = format.input_prefix(&input_header, &sweep.inputs(p).cells());
        if !line.starts_with(&prefix) {
            return Err(reader.error(format!(
                "point {p} has other inputs than this sweep's (`{}`): it was written by a \
                 different sweep",
                prefix.trim_end_matches(',')
            )));
        }
        each(p);
    }
    Ok(reader)
}

/// Run a sweep (or one shard of it) into `target`, streaming rows in point order to the
/// partial file (module docs) and renaming it over `target` at the end. Without `resume` an
/// existing partial file is an error (it holds an interrupted run: resume it or delete it).
/// `progress(done, total)` counts the walks of this run, from any thread.
pub fn run_to_file(
    sweep: &Sweep,
    target: &Path,
    shard: Shard,
    resume: bool,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<RunStats> {
    let format = Format::from_path(target)?;
    let header = sweep.header();
    let total = sweep.len();
    let partial = partial_path(target);
    let mut done = PointSet::new(total);
    let mut stats = RunStats {
        points: shard.points(total, 0).count(),
        ..RunStats::default()
    };

    // the partial file: continued after its last complete row, or started
    let mut next = 0;
    let file = if partial.exists() {
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
        let reader = scan(sweep, shard, &partial, format, |p| {
            done.insert(p);
            next = p + 1;
            stats.kept += 1;
        })?;
        let restart = reader.columns().is_none() && format == Format::Csv;
        let mut file = OpenOptions::new()
            .write(true)
            .open(&partial)
            .map_err(io_err("writing", &partial))?;
        let keep = if restart { 0 } else { reader.valid_len };
        file.set_len(keep).map_err(io_err("writing", &partial))?;
        file.seek(SeekFrom::End(0))
            .map_err(io_err("writing", &partial))?;
        if restart {
            file.write_all(format.header_line(&header).as_bytes())
                .map_err(io_err("writing", &partial))?;
        }
        file
    } else {
        let mut file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&partial)
            .map_err(io_err("writing", &partial))?;
        file.write_all(format.header_line(&header).as_bytes())
            .map_err(io_err("writing", &partial))?;
        file
    };
    let mut out = BufWriter::new(file);

    // the existing target's rows after the partial file's last one are kept too
    let mut existing = None;
    if resume && target.exists() {
        scan(sweep, shard, target, format, |p| {
            if p >= next {
                done.insert(p);
                stats.kept += 1;
            }
        })?;
        existing = Some(RowReader::open(target, format)?);
    }
    let mut pending = None;
    let mut copy_before = |limit: usize, out: &mut BufWriter<File>| -> Result<()> {
        let Some(reader) = existing.as_mut() else {
            return Ok(());
        };
        loop {
            if pending.is_none() {
                pending = reader.next_row()?;
            }
            match &pending {
                Some((p, line)) if *p < limit => {
                    if *p >= next {
                        out.write_all(line.as_bytes())
                            .map_err(io_err("writing", &partial))?;
                    }
                    pending = None;
                }
                _ => return Ok(()),
            }
        }
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

/// What a merge did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MergeStats {
    pub rows: usize,
    /// Rows found in more than one input (identical; written once).
    pub duplicates: usize,
    /// Points missing between 0 and the largest point found, and the first few of them.
    pub missing: usize,
    pub first_missing: Vec<usize>,
    /// Inputs whose last line was cut off (not merged).
    pub cut_off: Vec<PathBuf>,
}

/// Join sweep outputs (typically the shards of one sweep) into `out`, rows in point order,
/// written whole or not at all. All files must have the format of `out` (by extension) and the
/// same columns. A point found in several inputs must have the same row in each (a duplicate is
/// written once and counted); different rows for one point are an error. Points missing below
/// the largest point found are an error unless `allow_missing` (then counted). Points after the
/// largest one cannot be detected: the files do not record the sweep's size.
pub fn merge(out: &Path, inputs: &[PathBuf], allow_missing: bool) -> Result<MergeStats> {
    let format = Format::from_path(out)?;
    if inputs.is_empty() {
        return Err(Error::BadSpec {
            flag: "merge".into(),
            reason: "no input files".into(),
        });
    }
    let mut readers = Vec::with_capacity(inputs.len());
    for path in inputs {
        if Format::from_path(path)? != format {
            return Err(malformed(
                path,
                format!("its format differs from the output's ({})", out.display()),
            ));
        }
        readers.push(RowReader::open(path, format)?);
    }
    let mut heap = BinaryHeap::new();
    let mut heads: Vec<Option<String>> = vec![None; readers.len()];
    let mut columns: Option<(Vec<String>, usize)> = None;
    let mut pull = |i: usize,
                    readers: &mut Vec<RowReader>,
                    heap: &mut BinaryHeap<Reverse<(usize, usize)>>,
                    heads: &mut Vec<Option<String>>|
     -> Result<()> {
        if let Some((p, line)) = readers[i].next_row()? {
            heap.push(Reverse((p, i)));
            heads[i] = Some(line);
        }
        if let Some(c) = readers[i].columns() {
            match &columns {
                None => columns = Some((c.to_vec(), i)),
                Some((first, j)) if first.as_slice() != c => {
                    return Err(malformed(
                        &inputs[i],
                        format!(
                            "its columns differ from those of {}: not the same sweep",
                            inputs[*j].display()
                        ),
                    ));
                }
                _ => {}
            }
        }
        Ok(())
    };
    for i in 0..readers.len() {
        pull(i, &mut readers, &mut heap, &mut heads)?;
    }
    let mut file = AtomicFile::create(out)?;
    let mut stats = MergeStats::default();
    if format == Format::Csv
        && let Some(c) = readers.iter().find_map(RowReader::columns)
    {
        let line = format.header_line(c);
        file.writer()
            .write_all(line.as_bytes())
            .map_err(|e| file.error(e))?;
    }
    let mut previous: Option<(usize, String, usize)> = None;
    while let Some(Reverse((p, i))) = heap.pop() {
        let line = heads[i].take().unwrap_or_default();
        match &previous {
            Some((q, text, j)) if *q == p => {
                if *text != line {
                    return Err(malformed(
                        &inputs[i],
                        format!(
                            "point {p} differs from its row in {}: not the same sweep",
                            inputs[*j].display()
                        ),
                    ));
                }
                stats.duplicates += 1;
            }
            _ => {
                let from = previous.as_ref().map_or(0, |(q, _, _)| q + 1);
                for m in from..p {
                    stats.missing += 1;
                    if stats.first_missing.len() < 10 {
                        stats.first_missing.push(m);
                    }
                }
                file.writer()
                    .write_all(line.as_bytes())
                    .map_err(|e| file.error(e))?;
                stats.rows += 1;
                previous = Some((p, line, i));
            }
        }
        pull(i, &mut readers, &mut heap, &mut heads)?;
    }
    stats.cut_off = readers
        .iter()
        .filter(|r| r.cut_off)
        .map(|r| r.path.clone())
        .collect();
    if stats.missing > 0 && !allow_missing {
        let list: Vec<String> = stats.first_missing.iter().map(|p| p.to_string()).collect();
        return Err(Error::Malformed {
            what: "merge of sweep outputs",
            path: out.to_path_buf(),
            reason: format!(
                "{} points are missing (first: {}): is a shard missing or unfinished? \
                 (--allow-missing writes the rows anyway)",
                stats.missing,
                list.join(", ")
            ),
        });
    }
    file.commit()?;
    Ok(stats)
}
