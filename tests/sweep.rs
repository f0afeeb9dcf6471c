//! `klaw sweep` and `klaw merge` end to end: rows, failed points, independence of the thread
//! count, sweep files, shards and their merge, resuming interrupted and truncated runs.
use std::fs;
use std::path::Path;
use std::process::{Command, Output};

mod common;

fn sweep_ok(dir: &Path, args: &[&str], threads: Option<&str>) -> Output {
    let env: Vec<(&str, &str)> = threads
        .map(|t| ("RAYON_NUM_THREADS", t))
        .into_iter()
        .collect();
    let out = common::klaw_with(dir, args, &env);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "klaw {args:?} failed:\n{stderr}");
    out
}

/// Run klaw expecting an input error (status 2); returns stderr.
fn klaw_fails(dir: &Path, args: &[&str]) -> String {
    let out = common::klaw(dir, args);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?}:\n{stderr}");
    stderr
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
    sweep_ok(
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
    sweep_ok(
        dir.path(),
        &[
            "sweep",
            "--velocity",
            "1.0,2.9",
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
            "0.8,1.2,2.9",
            "--attr",
            "bounciness=0.7,0.8",
            "--steps",
            "2",
            "--out",
            out,
        ]
    };
    sweep_ok(dir.path(), &args("one.jsonl"), Some("1"));
    sweep_ok(dir.path(), &args("two.jsonl"), Some("2"));
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

/// A small sweep with a failing point (v = 2.9 m/s, above velocity_max): 3 × 2 × 2 = 12 one-step walks.
const SMALL: [&str; 8] = [
    "--velocity",
    "0.9,1.4,2.9",
    "--height",
    "1.6,1.8",
    "--attr",
    "bounciness=0.7,0.75",
    "--steps",
    "1",
];

fn sweep_args<'a>(extra: &[&'a str]) -> Vec<&'a str> {
    let mut v = vec!["sweep"];
    v.extend_from_slice(&SMALL);
    v.extend_from_slice(extra);
    v
}

#[test]
fn rows_are_numbered_in_product_order() {
    let dir = tempfile::tempdir().unwrap();
    sweep_ok(dir.path(), &sweep_args(&["--out", "s.csv"]), None);
    let (header, rows) = rows(&dir.path().join("s.csv"));
    assert_eq!(header[0], "point");
    assert_eq!(rows.len(), 12);
    let (v, h, b) = (
        col(&header, "velocity"),
        col(&header, "height"),
        col(&header, "bounciness"),
    );
    for (k, r) in rows.iter().enumerate() {
        assert_eq!(r[0], k.to_string());
        // row-major: velocity slowest, bounciness fastest
        assert_eq!(r[v], ["0.9", "1.4", "2.9"][k / 4], "{r:?}");
        assert_eq!(r[h], ["1.6", "1.8"][(k / 2) % 2], "{r:?}");
        assert_eq!(r[b], ["0.7", "0.75"][k % 2], "{r:?}");
        let converged = r[col(&header, "converged")] == "true";
        assert_eq!(converged, k < 8, "{r:?}");
        if converged {
            let w: f64 = r[col(&header, "work_per_m")].parse().unwrap();
            let wkg: f64 = r[col(&header, "work_per_kg_m")].parse().unwrap();
            assert!(w > 0.0 && (wkg * 80.0 - w).abs() < 1e-9 * w, "{r:?}");
        } else {
            assert_eq!(r[col(&header, "work_per_m")], "");
        }
    }
    // nothing left behind
    assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1);
}

#[test]
fn merged_shards_are_byte_identical_to_the_whole_sweep() {
    let dir = tempfile::tempdir().unwrap();
    for ext in ["csv", "jsonl"] {
        let whole = format!("whole.{ext}");
        sweep_ok(dir.path(), &sweep_args(&["--out", &whole]), None);
        // 5 shards of 12 points: uneven (3, 3, 2, 2, 2)
        let mut parts = Vec::new();
        let mut union = Vec::new();
        for k in 1..=5 {
            let part = format!("part-{k}.{ext}");
            let shard = format!("{k}/5");
            sweep_ok(
                dir.path(),
                &sweep_args(&["--shard", &shard, "--out", &part]),
                Some("1"),
            );
            if ext == "csv" {
                let (_, rows) = rows(&dir.path().join(&part));
                let points: Vec<usize> = rows.iter().map(|r| r[0].parse().unwrap()).collect();
                // shard k holds the points ≡ k − 1 (mod 5), in order
                let want: Vec<usize> = (0..12).filter(|p| p % 5 == k - 1).collect();
                assert_eq!(points, want);
                union.extend(points);
            }
            parts.push(part);
        }
        if ext == "csv" {
            union.sort();
            assert_eq!(union, (0..12).collect::<Vec<_>>());
        }
        // merge in a scrambled order
        let merged = format!("merged.{ext}");
        let mut args = vec!["merge", merged.as_str()];
        for i in [3, 0, 4, 1, 2] {
            args.push(&parts[i]);
        }
        sweep_ok(dir.path(), &args, None);
        let a = fs::read(dir.path().join(&whole)).unwrap();
        let b = fs::read(dir.path().join(&merged)).unwrap();
        assert!(a == b, "{ext}: merged output differs from the whole sweep");
    }
}

#[test]
fn merge_reports_missing_duplicate_and_conflicting_rows() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for k in 1..=3 {
        let shard = format!("{k}/3");
        let out = format!("p{k}.csv");
        sweep_ok(d, &sweep_args(&["--shard", &shard, "--out", &out]), None);
    }
    // a missing shard: an error, no output
    let e = klaw_fails(d, &["merge", "m.csv", "p1.csv", "p3.csv"]);
    assert!(e.contains("missing") && e.contains("first: 1"), "{e}");
    assert!(!d.join("m.csv").exists());
    // --allow-missing writes the rows and warns
    let out = sweep_ok(
        d,
        &["merge", "m.csv", "p1.csv", "p3.csv", "--allow-missing"],
        None,
    );
    assert!(String::from_utf8_lossy(&out.stderr).contains("4 points are missing"));
    assert_eq!(rows(&d.join("m.csv")).1.len(), 8);
    // the same shard twice: identical rows, written once, with a warning
    let out = sweep_ok(
        d,
        &["merge", "m.csv", "p1.csv", "p2.csv", "p3.csv", "p2.csv"],
        None,
    );
    assert!(String::from_utf8_lossy(&out.stderr).contains("4 rows were found in more than one"));
    assert_eq!(rows(&d.join("m.csv")).1.len(), 12);
    // a shard of another sweep: different rows for the same points
    sweep_ok(
        d,
        &[
            "sweep",
            "--velocity",
            "1.0",
            "--height",
            "1.6,1.8",
            "--attr",
            "bounciness=0.7,0.75",
            "--steps",
            "1",
            "--shard",
            "2/3",
            "--out",
            "other.csv",
        ],
        None,
    );
    let e = klaw_fails(d, &["merge", "m2.csv", "p1.csv", "p2.csv", "other.csv"]);
    assert!(e.contains("not the same sweep"), "{e}");
    // other columns
    sweep_ok(
        d,
        &[
            "sweep",
            "--velocity",
            "1.0",
            "--steps",
            "1",
            "--out",
            "cols.csv",
        ],
        None,
    );
    let e = klaw_fails(d, &["merge", "m2.csv", "p1.csv", "cols.csv"]);
    assert!(e.contains("columns differ"), "{e}");
    // formats must agree
    let e = klaw_fails(d, &["merge", "m2.jsonl", "p1.csv"]);
    assert!(e.contains("format"), "{e}");
    assert!(!d.join("m2.csv").exists() && !d.join("m2.jsonl").exists());
}

#[test]
fn resume_after_a_truncated_run_gives_the_uninterrupted_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for ext in ["csv", "jsonl"] {
        let whole = format!("whole.{ext}");
        sweep_ok(d, &sweep_args(&["--out", &whole]), None);
        let full = fs::read(d.join(&whole)).unwrap();
        let out = format!("r.{ext}");
        let partial = format!(".r.{ext}.partial");
        // cut anywhere: in the header, at a line end, mid-row
        let ends: Vec<usize> = full
            .iter()
            .enumerate()
            .filter(|(_, c)| **c == b'\n')
            .map(|(i, _)| i + 1)
            .collect();
        for cut in [
            0,
            10,
            ends[0],
            ends[3],
            ends[3] + 25,
            ends[7] - 1,
            full.len(),
        ] {
            // an interrupted run's partial file
            fs::write(d.join(&partial), &full[..cut]).unwrap();
            let _ = fs::remove_file(d.join(&out));
            sweep_ok(d, &sweep_args(&["--out", &out, "--resume"]), None);
            assert!(
                fs::read(d.join(&out)).unwrap() == full,
                "{ext}: partial cut at {cut}"
            );
            assert!(!d.join(&partial).exists());
            // a truncated target (whole lines only: rows in the middle may be missing too)
            if cut == ends[3] {
                let mut holes: Vec<u8> = full[..ends[1]].to_vec();
                holes.extend_from_slice(&full[ends[4]..ends[6]]);
                fs::write(d.join(&out), &holes).unwrap();
                let o = sweep_ok(d, &sweep_args(&["--out", &out, "--resume"]), None);
                assert!(fs::read(d.join(&out)).unwrap() == full, "{ext}: holes");
                let said = String::from_utf8_lossy(&o.stdout).into_owned();
                let kept = if ext == "csv" { 3 } else { 4 };
                assert!(said.contains(&format!("{kept} rows kept")), "{said}");
            }
        }
        // resuming a complete output runs nothing and changes nothing
        let o = sweep_ok(d, &sweep_args(&["--out", &out, "--resume"]), None);
        assert!(String::from_utf8_lossy(&o.stdout).contains("swept 0 walks"));
        assert!(fs::read(d.join(&out)).unwrap() == full);
    }
}

#[test]
fn resume_refuses_another_sweeps_rows() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    sweep_ok(d, &sweep_args(&["--out", "s.csv"]), None);
    // other values, same columns: the inputs of a point differ
    let e = klaw_fails(
        d,
        &[
            "sweep",
            "--velocity",
            "1.0,1.2,1.4",
            "--height",
            "1.6,1.8",
            "--attr",
            "bounciness=0.7,0.8",
            "--steps",
            "1",
            "--out",
            "s.csv",
            "--resume",
        ],
    );
    assert!(e.contains("different sweep"), "{e}");
    // other columns
    let e = klaw_fails(
        d,
        &["sweep", "--velocity", "1.0", "--out", "s.csv", "--resume"],
    );
    assert!(e.contains("different sweep"), "{e}");
    // another shard's rows
    let e = klaw_fails(
        d,
        &sweep_args(&["--shard", "1/2", "--out", "s.csv", "--resume"]),
    );
    assert!(e.contains("not in this sweep's shard 1/2"), "{e}");
    // the target is untouched by the refusals
    sweep_ok(d, &sweep_args(&["--out", "t.csv"]), None);
    assert_eq!(
        fs::read(d.join("s.csv")).unwrap(),
        fs::read(d.join("t.csv")).unwrap()
    );
}

#[test]
fn a_partial_file_needs_resume() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::write(d.join(".s.csv.partial"), "point\n").unwrap();
    let e = klaw_fails(d, &sweep_args(&["--out", "s.csv"]));
    assert!(
        e.contains("--resume") && e.contains(".s.csv.partial"),
        "{e}"
    );
    assert!(!d.join("s.csv").exists());
}

/// Kill a sweep once it has written rows, resume it: the file of an uninterrupted run.
#[test]
fn resume_after_a_killed_run() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let args = [
        "sweep",
        "--velocity",
        "0.8:1.6:0.02",
        "--height",
        "1.6:1.9:0.1",
        "--steps",
        "1",
        "--out",
        "k.csv",
    ];
    let mut child = Command::new(env!("CARGO_BIN_EXE_klaw"))
        .args(args)
        .env("RAYON_NUM_THREADS", "1")
        .current_dir(d)
        .stderr(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let partial = d.join(".k.csv.partial");
    let start = std::time::Instant::now();
    while fs::read(&partial).map_or(0, |b| b.iter().filter(|c| **c == b'\n').count()) < 30 {
        assert!(start.elapsed().as_secs() < 60, "no rows after 60 s");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(
        !d.join("k.csv").exists(),
        "the sweep finished before it was killed"
    );
    sweep_ok(d, &[&args[..], &["--resume"]].concat(), None);
    sweep_ok(d, &[&args[..7], &["--out", "u.csv"]].concat(), None);
    let (k, u) = (
        fs::read(d.join("k.csv")).unwrap(),
        fs::read(d.join("u.csv")).unwrap(),
    );
    assert_eq!(rows(&d.join("u.csv")).1.len(), 41 * 4);
    assert!(
        k == u,
        "the resumed output differs from an uninterrupted run"
    );
}

#[test]
fn sweep_file_with_flags_overriding_it() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::write(
        d.join("grid.toml"),
        "velocity = \"1.0:1.4:0.2\"\nheight = [1.6, 1.8]\nsteps = 1\nbounciness = 0.7\n",
    )
    .unwrap();
    // the flag replaces the file's velocity; the rest comes from the file
    sweep_ok(
        d,
        &[
            "sweep",
            "--file",
            "grid.toml",
            "--velocity",
            "0.9",
            "--out",
            "f.csv",
        ],
        None,
    );
    let (header, rows) = rows(&d.join("f.csv"));
    assert_eq!(rows.len(), 2);
    let got: Vec<(&str, &str, &str, &str)> = rows
        .iter()
        .map(|r| {
            (
                &*r[col(&header, "velocity")],
                &*r[col(&header, "height")],
                &*r[col(&header, "steps")],
                &*r[col(&header, "bounciness")],
            )
        })
        .collect();
    assert_eq!(
        got,
        [("0.9", "1.6", "1", "0.7"), ("0.9", "1.8", "1", "0.7")]
    );
    // the same sweep from flags alone is the same file
    sweep_ok(
        d,
        &[
            "sweep",
            "--velocity",
            "0.9",
            "--height",
            "1.6,1.8",
            "--steps",
            "1",
            "--attr",
            "bounciness=0.7",
            "--out",
            "g.csv",
        ],
        None,
    );
    assert_eq!(
        fs::read(d.join("f.csv")).unwrap(),
        fs::read(d.join("g.csv")).unwrap()
    );
}

#[test]
fn bad_shards_and_sweep_files_are_input_errors() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for bad in ["0/3", "4/3", "3", "x/3", "1/0"] {
        let e = klaw_fails(d, &["sweep", "--velocity", "1.0", "--shard", bad]);
        assert!(
            e.contains("--shard") && e.contains("1 ≤ K ≤ N"),
            "{bad}: {e}"
        );
    }
    fs::write(d.join("bad.toml"), "velocity = [1.0,\n").unwrap();
    let e = klaw_fails(d, &["sweep", "--file", "bad.toml"]);
    assert!(
        e.contains("malformed sweep file") && e.contains("bad.toml"),
        "{e}"
    );
    fs::write(d.join("unknown.toml"), "speed = 1.0\n").unwrap();
    let e = klaw_fails(d, &["sweep", "--file", "unknown.toml"]);
    assert!(e.contains("unknown key `speed`"), "{e}");
    let e = klaw_fails(d, &["sweep", "--file", "none.toml"]);
    assert!(e.contains("none.toml"), "{e}");
    assert_eq!(
        fs::read_dir(d).unwrap().count(),
        2,
        "no output is written on an input error"
    );
}

/// `--style` sweeps the presets by name: the rows name their style, a style's own speed limits
/// apply (the elderly preset stops at 1.1 m/s: recorded, not fatal), the same style from a
/// sweep file gives the same rows, and an unknown style is an input error listing the known.
#[test]
fn styles_are_a_sweep_axis() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let args = [
        "sweep",
        "--style",
        "normal,elderly",
        "--velocity",
        "0.9,1.4",
        "--steps",
        "3",
        "--out",
        "s.csv",
    ];
    let out = sweep_ok(d, &args, None);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (header, rows) = rows(&d.join("s.csv"));
    let (style, conv, v) = (
        col(&header, "style"),
        col(&header, "converged"),
        col(&header, "velocity"),
    );
    let got: Vec<(&str, &str, &str)> = rows
        .iter()
        .map(|r| (r[v].as_str(), r[style].as_str(), r[conv].as_str()))
        .collect();
    assert_eq!(
        got,
        [
            ("0.9", "normal", "true"),
            ("0.9", "elderly", "true"),
            ("1.4", "normal", "true"),
            ("1.4", "elderly", "false"),
        ]
    );
    fs::write(
        d.join("f.toml"),
        "style = [\"normal\", \"elderly\"]\nvelocity = [0.9, 1.4]\n",
    )
    .unwrap();
    let out = sweep_ok(
        d,
        &[
            "sweep", "--file", "f.toml", "--steps", "3", "--out", "f.csv",
        ],
        None,
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        fs::read_to_string(d.join("s.csv")).unwrap(),
        fs::read_to_string(d.join("f.csv")).unwrap()
    );
    let e = klaw_fails(d, &["sweep", "--style", "normal,sprint", "--out", "x.csv"]);
    assert!(e.contains("sprint") && e.contains("long-stride"), "{e}");
}

/// `--body-table` sweeps the anthropometric tables by name, and each point's leg comes from its
/// table: at H 1.5 m the walk–run transition √(0.5 g l1) is 1.9022 m/s for de Leva's men
/// (l1 = (0.242504 + 0.249282) · 1.5 m), 1.88366 m/s for Winter's and 1.84280 m/s for de Leva's
/// women (by hand; the message floors them to 1.8836 and 1.8427), so 1.89 m/s walks for the
/// first only; the sweep file's `body_table` gives the
/// same rows; an unknown table is an input error listing the tables.
#[test]
fn body_tables_are_a_sweep_axis() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let args = [
        "sweep",
        "--body-table",
        "winter,deleva-male,deleva-female",
        "--velocity",
        "1.89",
        "--height",
        "1.5",
        "--steps",
        "3",
        "--out",
        "s.csv",
    ];
    let out = sweep_ok(d, &args, None);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (header, rows) = rows(&d.join("s.csv"));
    let (table, conv) = (col(&header, "body_table"), col(&header, "converged"));
    let got: Vec<(&str, &str)> = rows
        .iter()
        .map(|r| (r[table].as_str(), r[conv].as_str()))
        .collect();
    assert_eq!(
        got,
        [
            ("winter", "false"),
            ("deleva-male", "true"),
            ("deleva-female", "false"),
        ]
    );
    let error = col(&header, "error");
    assert!(rows[0][error].contains("1.8836]"), "{}", rows[0][error]);
    assert!(rows[2][error].contains("1.8427]"), "{}", rows[2][error]);
    fs::write(
        d.join("f.toml"),
        "body_table = [\"winter\", \"deleva-male\", \"deleva-female\"]\nvelocity = 1.89\nheight = 1.5\n",
    )
    .unwrap();
    let out = sweep_ok(
        d,
        &[
            "sweep", "--file", "f.toml", "--steps", "3", "--out", "f.csv",
        ],
        None,
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        fs::read_to_string(d.join("s.csv")).unwrap(),
        fs::read_to_string(d.join("f.csv")).unwrap()
    );
    let e = klaw_fails(
        d,
        &["sweep", "--body-table", "winter,dempster", "--out", "x.csv"],
    );
    assert!(e.contains("dempster") && e.contains("deleva-female"), "{e}");
}

/// A sweep point beyond its body's walk–run transition (2.0 m/s at H 1.5 m: limit
/// √(0.5 · 9.81 · 0.723375) = 1.8836 m/s by hand) is a failed row with that reason; the sweep
/// carries on and the same speed at H 1.8 m walks.
#[test]
fn a_point_beyond_the_walk_run_transition_is_a_failed_row() {
    let dir = tempfile::tempdir().unwrap();
    sweep_ok(
        dir.path(),
        &[
            "sweep",
            "--velocity",
            "2.0",
            "--height",
            "1.5,1.8",
            "--steps",
            "1",
            "--out",
            "s.csv",
        ],
        None,
    );
    let (header, rows) = rows(&dir.path().join("s.csv"));
    let (c, e) = (col(&header, "converged"), col(&header, "error"));
    assert_eq!(rows.len(), 2);
    assert_eq!(rows[0][c], "false");
    assert!(
        rows[0][e].contains("beyond the walk–run transition") && rows[0][e].contains("1.8836"),
        "{:?}",
        rows[0]
    );
    assert_eq!(rows[1][c], "true", "{:?}", rows[1]);
}
