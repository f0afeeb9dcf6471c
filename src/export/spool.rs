//! The file a motion file's rows stream into: unnamed, in the target's directory, so that a
//! failed or killed export leaves nothing behind.
//!
//! When the header could be written before the rows (a format without a row count, or the count
//! known beforehand and met), the spool is the finished file: it is synced and given a name
//! next to the target, then renamed over it ([`Spool::into_target`]); where an unnamed file
//! cannot be named (not Linux, no `O_TMPFILE`, no `/proc`), it is copied into an
//! [`AtomicFile`](super::file::AtomicFile) instead. Otherwise the header is written to the target
//! and the rows copied behind it ([`Spool::copy_behind`]). While the rows stream into a spool
//! that will be the target, the kernel is asked every few MiB to start writing them to the disk,
//! so that the final `fsync` waits for little more than the last of them (what this saves:
//! `docs/engine.md`, "Output speed").
use std::fs::File;
use std::io::{self, BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use super::file::{parent_dir, write_atomic, write_error};
use crate::error::Result;

/// The writer's buffer: rows reach the file in pieces this large.
const BUFFER: usize = 256 << 10;

/// Writeback of a spool that will be the target is started for every this many bytes.
const WRITEBACK: u64 = 4 << 20;

/// Rows on their way to the file at `path`.
pub(crate) struct Spool {
    path: PathBuf,
    out: BufWriter<File>,
    /// Bytes written to `out`.
    written: u64,
    /// Writeback has been started for the bytes before this offset.
    written_back: u64,
    /// The spool may become the target: start its writeback as it fills.
    target: bool,
}

impl Spool {
    /// An empty spool for `path`, in its directory; `target`: it is meant to become the file.
    pub fn create(path: &Path, target: bool) -> Result<Spool> {
        let file = unnamed_in(parent_dir(path)).map_err(|e| write_error(path, e))?;
        Ok(Spool {
            path: path.to_path_buf(),
            out: BufWriter::with_capacity(BUFFER, file),
            written: 0,
            written_back: 0,
            target,
        })
    }

    /// Append `bytes`.
    pub fn write(&mut self, bytes: &[u8]) -> Result<()> {
        self.out
            .write_all(bytes)
            .map_err(|e| write_error(&self.path, e))?;
        self.written += bytes.len() as u64;
        if self.target {
            // what the buffer holds has not reached the file yet
            let in_file = self.written - self.out.buffer().len() as u64;
            if in_file - self.written_back >= WRITEBACK {
                start_writeback(self.out.get_ref(), self.written_back, in_file);
                self.written_back = in_file;
            }
        }
        Ok(())
    }

    /// The spool, written whole, becomes the file at `path` (replacing it).
    pub fn into_target(self) -> Result<()> {
        let path = self.path.clone();
        let err = |e| write_error(&path, e);
        let mut file = self.out.into_inner().map_err(|e| err(e.into_error()))?;
        file.sync_all().map_err(err)?;
        if let Ok(named) = name_in_directory(&file, &path) {
            return named.persist(&path).map_err(|e| err(e.error));
        }
        file.rewind().map_err(err)?;
        write_atomic(&path, |out| {
            io::copy(&mut file, out)?;
            Ok(())
        })
    }

    /// Write `header`, then the spool from byte `skip` on, to the file at `path` (replacing it).
    pub fn copy_behind(self, header: &[u8], skip: u64) -> Result<()> {
        let path = self.path.clone();
        let mut file = self
            .out
            .into_inner()
            .map_err(|e| write_error(&path, e.into_error()))?;
        file.seek(SeekFrom::Start(skip))
            .map_err(|e| write_error(&path, e))?;
        write_atomic(&path, |out| {
            out.write_all(header)?;
            io::copy(&mut file, out)?;
            Ok(())
        })
    }
}

/// Give the unnamed `file` a fresh name `.NAME.XXXXXX.tmp` next to `path` (removed on drop unless
/// persisted).
fn name_in_directory(file: &File, path: &Path) -> io::Result<tempfile::TempPath> {
    let name = path.file_name().ok_or(io::ErrorKind::InvalidInput)?;
    let mut prefix = std::ffi::OsString::from(".");
    prefix.push(name);
    prefix.push(".");
    let (_, temp) = tempfile::Builder::new()
        .prefix(&prefix)
        .suffix(".tmp")
        .make_in(parent_dir(path), |p| link(file, p))?
        .into_parts();
    Ok(temp)
}

#[cfg(all(target_os = "linux", target_env = "gnu"))]
mod os {
    use std::ffi::CString;
    use std::fs::{File, OpenOptions};
    use std::io;
    use std::os::unix::ffi::OsStrExt;
    use std::os::unix::fs::OpenOptionsExt;
    use std::os::unix::io::AsRawFd;
    use std::path::Path;

    /// An unnamed file in `dir` that can be linked in later (`O_TMPFILE` without `O_EXCL`), with
    /// the usual mode of a new file (0666 less the umask); else an unnamed scratch file.
    pub fn unnamed_in(dir: &Path) -> io::Result<File> {
        OpenOptions::new()
            .read(true)
            .write(true)
            .custom_flags(libc::O_TMPFILE)
            .open(dir)
            .or_else(|_| tempfile::tempfile_in(dir))
    }

    /// Link the unnamed `file` in as `to` (fails for a file that cannot be linked).
    pub fn link(file: &File, to: &Path) -> io::Result<()> {
        let from = CString::new(format!("/proc/self/fd/{}", file.as_raw_fd()))?;
        let to = CString::new(to.as_os_str().as_bytes())?;
        // SAFETY: both paths are NUL-terminated strings that live across the call; linkat only
        // reads them.
        let r = unsafe {
            libc::linkat(
                libc::AT_FDCWD,
                from.as_ptr(),
                libc::AT_FDCWD,
                to.as_ptr(),
                libc::AT_SYMLINK_FOLLOW,
            )
        };
        if r == 0 {
            Ok(())
        } else {
            Err(io::Error::last_os_error())
        }
    }

    /// Ask the kernel to start writing `file`'s bytes `from..to` to the disk, without waiting.
    pub fn start_writeback(file: &File, from: u64, to: u64) {
        // SAFETY: sync_file_range takes no pointers; a failure only means no early writeback
        // (the final fsync writes everything), so its result is not needed.
        unsafe {
            libc::sync_file_range(
                file.as_raw_fd(),
                from as libc::off64_t,
                (to - from) as libc::off64_t,
                libc::SYNC_FILE_RANGE_WRITE,
            );
        }
    }
}

#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
mod os {
    use std::fs::File;
    use std::io;
    use std::path::Path;

    /// An unnamed scratch file in `dir`.
    pub fn unnamed_in(dir: &Path) -> io::Result<File> {
        tempfile::tempfile_in(dir)
    }

    /// Unnamed files cannot be linked in here.
    pub fn link(_file: &File, _to: &Path) -> io::Result<()> {
        Err(io::ErrorKind::Unsupported.into())
    }

    /// Nothing: the final `fsync` writes everything.
    pub fn start_writeback(_file: &File, _from: u64, _to: u64) {}
}

use os::{link, start_writeback, unnamed_in};
