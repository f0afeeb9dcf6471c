//! `klaw sweep` end to end: rows, failed points, and independence of the thread count.
use std::fs;
use std::path::Path;
use std::process::{Command, Output};

fn klaw(dir: &Path, args: &[&str], threads: Option<&str>) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_klaw"));
    cmd.args(args).current_dir(dir);
    if let Some(t) = threads {
        cmd.env("RAYON_NUM_THREADS", t);
    }
    let out = cmd.output().expect("the klaw binary runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !stderr.contains("panicked"),
        "klaw {args:?} panicked:\n{stderr}"
    );
    assert!(out.status.success(), "klaw {args:?} failed:\n{stderr}");
    out
}

fn rows(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let mut r = csv::Reader::from_path(path).unwrap();
    let header = r.headers().unwrap().iter().map(str::to_string).collect();
    let rows = r
        .records()
        .map(|rec| rec.unwrap().iter().map(str::to_string).collect())
        .collect();
    (header, rows)
}

fn col(header: &[String], name: &str) -> usize {
    header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name} in {header:?}"))
}

#[test]
fn two_by_two_sweep_writes_four_rows() {
    let dir = tempfile::tempdir().unwrap();
    klaw(
        dir.path(),
        &[
            "sweep",
            "--velocity",
            "1.0,1.4",
            "--height",
            "1.6:1.8:0.2",
            "--steps",
            "3",
            "--out",
            "s.csv",
        ],
        None,
    );
    let (header, rows) = rows(&dir.path().join("s.csv"));
    assert_eq!(rows.len(), 4);
    let (v, h, c, e) = (
        col(&header, "velocity"),
        col(&header, "height"),
        col(&header, "converged"),
        col(&header, "error"),
    );
    let inputs: Vec<(&str, &str)> = rows.iter().map(|r| (&*r[v], &*r[h])).collect();
    assert_eq!(
        inputs,
        [("1", "1.6"), ("1", "1.8"), ("1.4", "1.6"), ("1.4", "1.8")]
    );
    for r in &rows {
        assert_eq!(r[c], "true", "{r:?}");
        assert_eq!(r[e], "", "{r:?}");
        let av: f64 = r[col(&header, "achieved_velocity")].parse().unwrap();
        let want: f64 = r[v].parse().unwrap();
        assert!((av - want).abs() < 0.1 * want, "{r:?}");
        let ds: f64 = r[col(&header, "double_support_pct")].parse().unwrap();
        assert!(ds > 0.0 && ds < 50.0, "{r:?}");
    }
}

#[test]
fn out_of_range_point_is_recorded_and_the_sweep_carries_on() {
    let dir = tempfile::tempdir().unwrap();
    klaw(
        dir.path(),
        &[
            "sweep",
            "--velocity",
            "1.0,5.0",
            "--steps",
            "3",
            "--out",
            "s.csv",
        ],
        None,
    );
    let (header, rows) = rows(&dir.path().join("s.csv"));
    assert_eq!(rows.len(), 2);
    let (c, e) = (col(&header, "converged"), col(&header, "error"));
    assert_eq!(rows[0][c], "true");
    assert_eq!(rows[1][c], "false");
    assert!(rows[1][e].contains("velocity"), "{:?}", rows[1]);
}

#[test]
fn bad_spec_is_an_input_error_naming_the_flag() {
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_klaw"))
        .args(["sweep", "--height", "1.5:2.0"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--height"));
    assert!(!dir.path().join("sweep.csv").exists());
}

#[test]
fn thread_count_does_not_change_the_output() {
    let dir = tempfile::tempdir().unwrap();
    let args = |out: &'static str| {
        [
            "sweep",
            "--velocity",
            "0.8,1.2,5.0",
            "--attr",
            "bounciness=0.2,0.8",
            "--steps",
            "2",
            "--out",
            out,
        ]
    };
    klaw(dir.path(), &args("one.jsonl"), Some("1"));
    klaw(dir.path(), &args("two.jsonl"), Some("2"));
    let one = fs::read(dir.path().join("one.jsonl")).unwrap();
    let two = fs::read(dir.path().join("two.jsonl")).unwrap();
    assert_eq!(one, two);
    let text = String::from_utf8(one).unwrap();
    assert_eq!(text.lines().count(), 6);
    for line in text.lines() {
        let v: serde_json::Value = serde_json::from_str(line).unwrap();
        assert!(v.get("bounciness").is_some() && v.get("converged").is_some());
    }
}
