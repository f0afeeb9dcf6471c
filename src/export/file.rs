//! The atomic output file: every file klaw writes appears whole, by a rename over the target, or
//! not at all.
use std::ffi::OsString;
use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use tempfile::TempPath;

use crate::error::{Error, Result};

/// The error of a failed write to `path`.
pub(crate) fn write_error(path: &Path, source: std::io::Error) -> Error {
    Error::Io {
        action: "writing",
        path: path.to_path_buf(),
        source,
    }
}

/// The directory `path` is in: its parent, `.` for a bare file name.
pub fn parent_dir(path: &Path) -> &Path {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    }
}

/// A file written whole or not at all: rows go to a temporary file `.NAME.XXXXXX.tmp` in the
/// target's directory (so the rename stays on one file system and is atomic), which `commit`
/// flushes, syncs and renames over the target. Dropped uncommitted, the temporary file is removed
/// and an existing target is left untouched. Errors are `Error::Io { action: "writing", .. }`.
pub(crate) struct AtomicFile {
    path: PathBuf,
    out: BufWriter<File>,
    temp: TempPath,
    /// The temporary file's entry in [`LIVE`], removed when the file is committed or dropped.
    _live: Live,
}

/// The temporary files of the atomic writes under way in this process, for
/// [`remove_temporary_files`].
static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// A temporary file's entry in [`LIVE`], while it lives.
struct Live(PathBuf);

impl Live {
    fn new(path: &Path) -> Live {
        LIVE.lock()
            .unwrap_or_else(|e| e.into_inner())
            .push(path.to_path_buf());
        Live(path.to_path_buf())
    }
}

impl Drop for Live {
    fn drop(&mut self) {
        let mut live = LIVE.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(i) = live.iter().position(|p| *p == self.0) {
            live.swap_remove(i);
        }
    }
}

/// Remove the temporary file of every atomic write under way (the process is about to end
/// without finishing them: an interrupting signal); returns how many were removed. Targets
/// are left as they were.
pub fn remove_temporary_files() -> usize {
    remove_temporary_files_where(|_| true)
}

/// [`remove_temporary_files`] for the temporary files whose path satisfies `which`.
fn remove_temporary_files_where(which: impl Fn(&Path) -> bool) -> usize {
    let live = LIVE.lock().unwrap_or_else(|e| e.into_inner());
    live.iter()
        .filter(|p| which(p) && std::fs::remove_file(p).is_ok())
        .count()
}

impl AtomicFile {
    /// Start writing `path`.
    pub fn create(path: &Path) -> Result<AtomicFile> {
        let err = |e| write_error(path, e);
        let name = path.file_name().ok_or_else(|| {
            err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "the path does not name a file",
            ))
        })?;
        let mut prefix = OsString::from(".");
        prefix.push(name);
        prefix.push(".");
        // opened with our OpenOptions rather than tempfile's: the target gets the usual mode
        // (0666 less the umask, not 0600), and an error keeps the system's wording (tempfile's
        // own opening appends the temporary path to it)
        let (file, temp) = tempfile::Builder::new()
            .prefix(&prefix)
            .suffix(".tmp")
            .make_in(parent_dir(path), |p| {
                OpenOptions::new().write(true).create_new(true).open(p)
            })
            .map_err(err)?
            .into_parts();
        Ok(AtomicFile {
            path: path.to_path_buf(),
            out: BufWriter::new(file),
            _live: Live::new(&temp),
            temp,
        })
    }

    /// The temporary file, for writers that open the file by name (its content is what
    /// `commit` renames over the target; write nothing through [`AtomicFile::writer`] then).
    pub fn temp_path(&self) -> &Path {
        &self.temp
    }

    /// Where to write.
    pub fn writer(&mut self) -> &mut BufWriter<File> {
        &mut self.out
    }

    /// The error of a failed write to this file.
    pub fn error(&self, e: std::io::Error) -> Error {
        write_error(&self.path, e)
    }

    /// Flush, sync and rename over the target.
    pub fn commit(mut self) -> Result<()> {
        let err = |e| write_error(&self.path, e);
        self.out.flush().map_err(err)?;
        self.out.get_ref().sync_all().map_err(err)?;
        self.temp.persist(&self.path).map_err(|e| err(e.error))
    }
}

/// Write `path` whole or not at all: `write` fills an [`AtomicFile`]. On any error the temporary
/// file is removed and an existing `path` is left untouched. Errors are
/// `Error::Io { action: "writing", .. }`.
pub(crate) fn write_atomic(
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
    use std::fs;
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

    /// The temporary files of the writes under way are removed on demand (what the binary does
    /// on SIGINT and SIGTERM), and only theirs: a committed file is not listed any more.
    #[test]
    fn temporary_files_of_unfinished_writes_are_removed() {
        let dir = tempfile::tempdir().unwrap();
        let done = dir.path().join("done.txt");
        write_atomic(&done, |w| w.write_all(b"whole\n")).unwrap();
        let mut open = AtomicFile::create(&dir.path().join("open.txt")).unwrap();
        open.writer().write_all(b"half").unwrap();
        open.writer().flush().unwrap();
        let temp = open.temp_path().to_path_buf();
        assert!(temp.exists());
        // (only this test's directory: the other tests write in parallel)
        assert_eq!(
            remove_temporary_files_where(|p| p.starts_with(dir.path())),
            1
        );
        assert!(!temp.exists());
        assert_eq!(files_in(dir.path()), ["done.txt"]);
        assert!(open.commit().is_err(), "its temporary file is gone");
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
    fn the_temporary_file_sits_next_to_the_target() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("out.csv");
        let file = AtomicFile::create(&p).unwrap();
        let temp = file.temp_path().to_path_buf();
        assert_eq!(temp.parent(), Some(dir.path()));
        let name = temp.file_name().unwrap().to_str().unwrap();
        assert!(
            name.starts_with(".out.csv.") && name.ends_with(".tmp"),
            "{name}"
        );
        file.commit().unwrap();
        assert!(!temp.exists());
        assert_eq!(files_in(dir.path()), ["out.csv"]);
    }

    #[cfg(unix)]
    #[test]
    fn the_target_gets_the_usual_mode() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let ours = dir.path().join("ours.txt");
        let plain = dir.path().join("plain.txt");
        write_atomic(&ours, |w| w.write_all(b"x")).unwrap();
        fs::write(&plain, b"x").unwrap();
        let mode = |p: &Path| fs::metadata(p).unwrap().permissions().mode();
        assert_eq!(mode(&ours), mode(&plain));
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
        // the system's message, as for creating the target itself: no temporary path added
        let direct = File::create(&p).unwrap_err();
        assert_eq!(e.to_string(), format!("writing {}: {direct}", p.display()));
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
