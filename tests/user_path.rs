//! The user's path (issue 14): one test per class of defect, each over every subcommand and
//! input file kind it concerns. Bad input exits 2 before any work with nothing written; a sweep
//! whose every walk failed exits 1; an interrupted command removes its temporary files and
//! exits 128 + the signal; long jobs draw bounded figures.
use std::fs;
use std::process::{Command, Stdio};
use std::time::Duration;

mod common;
use common::{files, klaw, refused, refused_in};

/// Class 1: every output path of every command is checked before any work: its extension, a
/// directory that exists and takes a file, not a directory, not another output's file.
#[test]
fn output_paths_are_checked_before_any_work() {
    let gone = "no-such-dir/x";
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            args("walk --plot /proc/x.png"),
            "--plot: /proc/x.png: cannot create a file",
        ),
        (args("walk --report /proc/r.json"), "--report"),
        (
            args(&format!("walk --state-out {gone}.csv")),
            "directory no-such-dir does not exist",
        ),
        (
            args("walk --cycle-out . --steps 6"),
            "--cycle-out: .: the extension must be .csv",
        ),
        (
            args("walk --out walk.csv --events walk.csv"),
            "--out and --events name the same file",
        ),
        (
            args("walk --out a.csv --plot ./a.png --report a.png"),
            "--report: a.png: the extension must be .json",
        ),
        (
            args("walk --out walk.txt"),
            "--out: walk.txt: the extension must be .csv, .mot, .sto or .bvh",
        ),
        (args("plot --out /proc/c.png"), "--out: /proc/c.png"),
        (
            args("plot --out c.gif"),
            "the extension must be .png or .svg",
        ),
        (args("animate --out a.png"), "the extension must be .gif"),
        (
            args("sweep --velocity 1 --out /proc/s.csv"),
            "--out: /proc/s.csv",
        ),
        (
            args("sweep --velocity 1 --out s.txt"),
            "the extension must be .csv or .jsonl",
        ),
        (args(&format!("merge {gone}.csv in.csv")), "does not exist"),
        (
            args("plot-sweep in.csv --x velocity --y height --column converged --out h.jpg"),
            "the extension must be .png or .svg",
        ),
    ];
    for (a, needle) in cases {
        let a: Vec<&str> = a.iter().map(String::as_str).collect();
        refused(&a, &[needle]);
    }
    // a directory named like a file
    let dir = tempfile::tempdir().unwrap();
    fs::create_dir(dir.path().join("d.png")).unwrap();
    refused_in(
        dir.path(),
        &["walk", "--plot", "d.png"],
        &["d.png: is a directory"],
    );
}

/// Class 2: an option or extension either does what it says or is refused.
#[test]
fn options_that_would_be_ignored_are_refused() {
    refused(
        &["walk", "--events", "ev.json"],
        &["--events: ev.json: the extension must be .csv"],
    );
    refused(
        &["walk", "--in-place"],
        &["--in-place: applies to a .bvh --out only"],
    );
    refused(
        &["walk", "--out", "w.bvh", "--opensim-model", "rajagopal2015"],
        &["--opensim-model: applies to a .mot or .sto --out only"],
    );
    // a blank line among a CSV schedule's steps
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("s.csv"), "velocity\n1.2\n\n1.3\n").unwrap();
    refused_in(
        dir.path(),
        &["walk", "--schedule", "s.csv", "--steps", "3", "--no-plot"],
        &["line 3 is blank"],
    );
}

/// Class 3: a sweep value outside its range, fixed or in a list or range, is refused before
/// any walk; a sweep whose every walk failed exits 1 with its rows written.
#[test]
fn sweep_values_are_checked_and_an_all_failed_sweep_fails() {
    for (a, needle) in [
        ("sweep --steps 0", "steps = 0 steps"),
        ("sweep --mass -80", "mass = -80 kg"),
        ("sweep --height 1.0,1.8", "height = 1 m"),
        ("sweep --velocity -1,1", "velocity = -1 m/s"),
        ("sweep --velocity 0:1:0.5", "velocity = 0 m/s"),
        ("sweep --attr bounciness=5", "bounciness = 5 "),
    ] {
        let a = args(a);
        let a: Vec<&str> = a.iter().map(String::as_str).collect();
        refused(&a, &[needle, "out of range: valid range is"]);
    }
    // each value in range, the point not walkable: a failed row, and exit 1 when all fail
    let dir = tempfile::tempdir().unwrap();
    let out = klaw(
        dir.path(),
        &args("sweep --velocity 2.9 --height 1.5 --steps 2")
            .iter()
            .map(String::as_str)
            .collect::<Vec<_>>(),
    );
    assert_eq!(
        out.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let rows = fs::read_to_string(dir.path().join("sweep.csv")).unwrap();
    assert!(rows.lines().nth(1).unwrap().contains("false"), "{rows}");
    assert!(String::from_utf8_lossy(&out.stderr).contains("every walk of the sweep failed"));
}

/// Class 4: merge and plot-sweep refuse files that are not sweep outputs, and a text column;
/// a heat map's title counts the failed walks its cells average.
#[test]
fn merge_and_plot_sweep_refuse_what_is_not_a_sweep_output() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let ok = run(d, "sweep --velocity 1.0,1.2 --height 1.7,1.8 --steps 2");
    assert_eq!(ok.status.code(), Some(0));
    let header = fs::read_to_string(d.join("sweep.csv")).unwrap();
    let header = header.lines().next().unwrap().to_string();
    fs::write(d.join("empty.csv"), "").unwrap();
    fs::write(d.join("header.csv"), format!("{header}\n")).unwrap();
    fs::write(d.join("binary.csv"), [0u8, 159, 146, 150, 10, 1, 2]).unwrap();
    fs::write(d.join("other.csv"), "a,b\n1,2\n").unwrap();
    refused_in(d, &["merge", "m.csv", "empty.csv"], &["no header line"]);
    refused_in(
        d,
        &["merge", "m.csv", "header.csv"],
        &["no rows in any input"],
    );
    refused_in(
        d,
        &["merge", "m.csv", "binary.csv"],
        &["binary.csv", "UTF-8"],
    );
    refused_in(
        d,
        &["merge", "m.csv", "other.csv"],
        &["not a sweep output", "no column point"],
    );
    let map = |input: &str, column: &str| {
        vec![
            "plot-sweep",
            input,
            "--x",
            "velocity",
            "--y",
            "height",
            "--column",
            column,
            "--out",
            "h.png",
        ]
        .into_iter()
        .map(String::from)
        .collect::<Vec<String>>()
    };
    for (input, column, needle) in [
        ("header.csv", "converged", "no rows after the header"),
        ("other.csv", "converged", "not a sweep output"),
        ("sweep.csv", "error", "`error` is not numeric"),
    ] {
        let a = map(input, column);
        let a: Vec<&str> = a.iter().map(String::as_str).collect();
        refused_in(d, &a, &[needle]);
    }
    // a map averaging over a third parameter counts the failed walks its cells hide
    let out = run(
        d,
        "sweep --velocity 1.0,1.2 --height 1.7,1.8 --steps 2 --attr velocity_max=1.1,2.5 \
         --out three.csv",
    );
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let a = map("three.csv", "converged");
    let out = klaw(d, &a.iter().map(String::as_str).collect::<Vec<_>>());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{stdout}");
    assert!(
        stdout.contains("0 failed cells, 2 of 8 walks failed"),
        "{stdout}"
    );
}

/// Class 5: SIGINT and SIGTERM remove the temporary files and exit 130 and 143; a sweep's
/// partial file stays for --resume, and a refused --resume leaves none.
#[test]
fn interruptions_leave_no_temporary_file() {
    for (signal, code) in [("INT", 130), ("TERM", 143)] {
        let dir = tempfile::tempdir().unwrap();
        let child = Command::new(env!("CARGO_BIN_EXE_klaw"))
            .args([
                "walk",
                "--steps",
                "50000",
                "--out",
                "long.csv",
                "--state-out",
                "s.csv",
                "--no-plot",
            ])
            .current_dir(dir.path())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(1500));
        let kill = Command::new("kill")
            .args([format!("-{signal}"), child.id().to_string()])
            .status()
            .unwrap();
        assert!(kill.success());
        let out = child.wait_with_output().unwrap();
        assert_eq!(
            out.status.code(),
            Some(code),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(String::from_utf8_lossy(&out.stderr).contains("interrupted"));
        assert_eq!(files(dir.path()), vec![], "SIG{signal} left files");
    }
    // a refused --resume (the target is another sweep's) leaves no partial file
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    assert_eq!(
        klaw(d, &["sweep", "--velocity", "1.2", "--steps", "2"])
            .status
            .code(),
        Some(0)
    );
    let before = files(d);
    let out = klaw(
        d,
        &["sweep", "--velocity", "1.0,1.1", "--steps", "2", "--resume"],
    );
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(files(d), before);
}

/// Class 6: the default figure is named after --out, holds only the first steps' frames (so a
/// long walk's memory stays bounded), and the summary names it; klaw plot writes into the
/// current directory.
#[test]
fn the_default_figure_follows_the_motion_file_and_is_bounded() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = klaw(d, &["walk", "--steps", "30", "--out", "slow.csv"]);
    assert_eq!(out.status.code(), Some(0));
    assert!(d.join("slow.png").exists() && !d.join("walk.png").exists());
    assert!(String::from_utf8_lossy(&out.stdout).contains("plot: slow.png"));
    let out = klaw(d, &["plot", "--steps", "6"]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(d.join("gait-cycle.png").exists());
    refused(&["plot", "--steps", "5000"], &["at most 1000 steps"]);
    // an animation's frame cap is checked from the gait, before the walk is simulated
    refused(
        &["animate", "--steps", "1500", "--fps", "30"],
        &["frame count", "[1, 20000]"],
    );
}

/// Class 7: a job's progress goes to stderr as at most a line every 10 s when it is not a
/// terminal: a short sweep prints no progress line.
#[test]
fn short_jobs_print_no_progress_lines_to_a_pipe() {
    let dir = tempfile::tempdir().unwrap();
    let out = klaw(
        dir.path(),
        &["sweep", "--velocity", "1.0:1.4:0.1", "--steps", "2"],
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
}

/// `klaw` in `dir` with the words of `line` as its arguments.
fn run(dir: &std::path::Path, line: &str) -> std::process::Output {
    let a = args(line);
    klaw(dir, &a.iter().map(String::as_str).collect::<Vec<_>>())
}

/// The words of `line`.
fn args(line: &str) -> Vec<String> {
    line.split_whitespace().map(String::from).collect()
}
