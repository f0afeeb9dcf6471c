//! Every output file of a command checked before any work: the extension its flag allows, a
//! directory that exists and takes a new file (a creation probe, which also catches read-only
//! and pseudo file systems), not a directory itself, and no two outputs naming one file. A
//! failure is bad input (exit 2) naming the flag, and nothing is written.
use std::path::{Path, PathBuf};

use klaw::Result;
use klaw::export::file::parent_dir;
use klaw::model::InputError;

/// One output file of a command: the flag that names it (without its dashes), its path and the
/// extensions it may have (lower case, without the dot).
pub(crate) struct Output<'a> {
    pub flag: &'static str,
    pub path: &'a Path,
    pub extensions: &'static [&'static str],
}

impl<'a> Output<'a> {
    /// The output `path` of `--flag`, which must end in one of `extensions`.
    pub(crate) fn new(flag: &'static str, path: &'a Path, extensions: &'static [&str]) -> Self {
        Output {
            flag,
            path,
            extensions,
        }
    }
}

/// The extensions of a motion file, a figure, a CSV table and a report.
pub(crate) const MOTION: &[&str] = &["csv", "mot", "sto", "bvh"];
pub(crate) const FIGURE: &[&str] = &["png", "svg"];
pub(crate) const CSV: &[&str] = &["csv"];
pub(crate) const JSON: &[&str] = &["json"];
/// The extensions of a sweep's rows: CSV or JSON Lines.
pub(crate) const SWEEP: &[&str] = &["csv", "jsonl"];

/// Check every output of a command (module doc); the first that fails is the error.
pub(crate) fn check(outputs: &[Output]) -> Result<()> {
    let mut seen: Vec<(PathBuf, &'static str)> = Vec::with_capacity(outputs.len());
    for out in outputs {
        check_one(out)?;
        let key = identity(out.path);
        if let Some((_, other)) = seen.iter().find(|(k, _)| *k == key) {
            let reason = format!(
                "{}: --{other} and --{} name the same file",
                out.path.display(),
                out.flag
            );
            return Err(InputError::bad_value(out.flag, reason).into());
        }
        seen.push((key, out.flag));
    }
    Ok(())
}

/// The extension, the directory and the creation probe of one output.
fn check_one(out: &Output) -> Result<()> {
    let bad = |reason: String| -> Result<()> {
        let reason = format!("{}: {reason}", out.path.display());
        Err(InputError::bad_value(out.flag, reason).into())
    };
    let ext = out
        .path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    if !ext.as_deref().is_some_and(|e| out.extensions.contains(&e)) {
        let list: Vec<String> = out.extensions.iter().map(|e| format!(".{e}")).collect();
        let list = match list.split_last() {
            Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
            _ => list.concat(),
        };
        return bad(format!("the extension must be {list}"));
    }
    if out.path.is_dir() {
        return bad("is a directory".to_string());
    }
    let dir = parent_dir(out.path);
    if !dir.is_dir() {
        return bad(format!("directory {} does not exist", dir.display()));
    }
    // the probe: the atomic write creates its temporary file in the same directory
    let probe = dir.join(format!(".klaw-probe-{}", std::process::id()));
    match std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&probe)
    {
        Ok(_) => {
            let _ = std::fs::remove_file(&probe);
        }
        Err(e) => return bad(format!("cannot create a file in {}: {e}", dir.display())),
    }
    Ok(())
}

/// The file a path names, for comparing outputs: its directory resolved (links, `..`) and its
/// name.
fn identity(path: &Path) -> PathBuf {
    let dir = parent_dir(path);
    let dir = dir.canonicalize().unwrap_or_else(|_| dir.to_path_buf());
    match path.file_name() {
        Some(name) => dir.join(name),
        None => dir,
    }
}
