//! Interruption: on SIGINT (Ctrl-C) or SIGTERM the temporary files of the writes under way are
//! removed and the process exits with 128 + the signal's number (130, 143), as a shell reports
//! a process killed by it. A sweep's partial file is not a temporary file: it stays, for
//! `klaw sweep --resume`.
use signal_hook::consts::{SIGINT, SIGTERM};
use signal_hook::iterator::Signals;

/// Start the thread that waits for SIGINT and SIGTERM. Without it (the signals could not be
/// registered) the process keeps the default action, and an interruption may leave temporary
/// files behind: a warning says so.
pub(crate) fn clean_up_on_interruption() {
    let mut signals = match Signals::new([SIGINT, SIGTERM]) {
        Ok(s) => s,
        Err(e) => {
            eprintln!(
                "warning: cannot handle SIGINT/SIGTERM ({e}): an interruption may leave temporary files"
            );
            return;
        }
    };
    std::thread::spawn(move || {
        if let Some(signal) = signals.forever().next() {
            klaw::export::file::remove_temporary_files();
            let name = if signal == SIGINT {
                "SIGINT"
            } else {
                "SIGTERM"
            };
            eprintln!(
                "interrupted ({name}): unfinished outputs removed (a sweep's partial file stays for --resume)"
            );
            std::process::exit(128 + signal);
        }
    });
}
