//! Progress of a long job on stderr: a bar (indicatif) when stderr is a terminal; otherwise a
//! plain line at most every 10 s, so that a short job prints none and a long one a few.
use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};

/// Plain lines are at least this far apart.
const LINE_INTERVAL: Duration = Duration::from_secs(10);

/// The progress of `total` units of `what` (`frames`, `walks`), shown as the module doc says.
pub(crate) enum Progress {
    /// On a terminal.
    Bar(ProgressBar),
    /// Elsewhere: the job's name, its start and when a line was last printed.
    Lines {
        job: &'static str,
        what: &'static str,
        start: Instant,
        last: Mutex<Instant>,
    },
}

impl Progress {
    /// The progress of `job` (`walk`, `sweep`) over `total` units of `what`.
    pub(crate) fn new(job: &'static str, total: u64, what: &'static str) -> Progress {
        if std::io::stderr().is_terminal() {
            let template = format!(
                "{job} {{elapsed_precise}} [{{wide_bar}}] {{pos}}/{{len}} {what}, {{per_sec}}, ETA {{eta}}"
            );
            let style = ProgressStyle::with_template(&template).expect("a valid template");
            Progress::Bar(ProgressBar::new(total).with_style(style))
        } else {
            let now = Instant::now();
            Progress::Lines {
                job,
                what,
                start: now,
                last: Mutex::new(now),
            }
        }
    }

    /// `done` of `total` units are done (from any thread).
    pub(crate) fn set(&self, done: u64, total: u64) {
        match self {
            Progress::Bar(bar) => {
                bar.set_length(total);
                bar.set_position(done);
            }
            Progress::Lines {
                job,
                what,
                start,
                last,
            } => {
                let mut last = last.lock().unwrap_or_else(|e| e.into_inner());
                if last.elapsed() >= LINE_INTERVAL && done < total {
                    *last = Instant::now();
                    eprintln!(
                        "{job}: {done}/{total} {what} ({}%), {:.0} s",
                        done * 100 / total.max(1),
                        start.elapsed().as_secs_f64()
                    );
                }
            }
        }
    }

    /// The job is over: the bar is cleared.
    pub(crate) fn finish(&self) {
        if let Progress::Bar(bar) = self {
            bar.finish_and_clear();
        }
    }
}

/// A spinner with `message` and the elapsed time while a job without a known total runs, on a
/// terminal only; cleared when dropped.
pub(crate) struct Spinner(Option<ProgressBar>);

impl Spinner {
    /// Start the spinner.
    pub(crate) fn new(message: String) -> Spinner {
        if !std::io::stderr().is_terminal() {
            return Spinner(None);
        }
        let style =
            ProgressStyle::with_template("{spinner} {msg} {elapsed}").expect("a valid template");
        let bar = ProgressBar::new_spinner()
            .with_style(style)
            .with_message(message);
        bar.enable_steady_tick(Duration::from_millis(100));
        Spinner(Some(bar))
    }
}

impl Drop for Spinner {
    fn drop(&mut self) {
        if let Some(bar) = &self.0 {
            bar.finish_and_clear();
        }
    }
}
