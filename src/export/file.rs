//! The atomic output file: every file klaw writes appears whole, by a rename over the target, or
//! not at all.
use std::fs::{self, File, OpenOptions};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use crate::error::{Error, Result};

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
}
