//! The `klaw` binary end to end: files written, exit statuses, error messages. Every invocation
//! runs in its own temporary directory; expected values are computed here, never copied from
//! output.
use std::fs;
use std::path::Path;
use std::process::Output;

mod common;
use common::klaw;

fn texts(out: &Output) -> (String, String) {
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Run and expect success; returns stdout.
fn ok(dir: &Path, args: &[&str]) -> String {
    let out = klaw(dir, args);
    let (stdout, stderr) = texts(&out);
    assert!(
        out.status.success(),
        "klaw {args:?} failed ({:?}):\n{stderr}",
        out.status
    );
    stdout
}

/// Run and expect exit status 2 with a one-line `error: …` naming every string of `names`.
fn bad_input(dir: &Path, args: &[&str], names: &[&str]) -> String {
    let out = klaw(dir, args);
    let (_, stderr) = texts(&out);
    assert_eq!(out.status.code(), Some(2), "klaw {args:?}:\n{stderr}");
    assert!(stderr.starts_with("error: "), "klaw {args:?}:\n{stderr}");
    for name in names {
        assert!(
            stderr.contains(name),
            "klaw {args:?}: `{name}` not in\n{stderr}"
        );
    }
    stderr
}

fn files(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&fs::read_to_string(path).unwrap()).unwrap()
}

/// The default walk writes the whole figure's motion: the issue's columns, one row per frame.
#[test]
fn default_walk_writes_every_frame() {
    let dir = tempfile::tempdir().unwrap();
    let stdout = ok(dir.path(), &["walk"]);
    assert!(
        stdout.contains("walked 10 steps") && stdout.contains("walk.csv"),
        "{stdout}"
    );

    let mut reader = csv::Reader::from_path(dir.path().join("walk.csv")).unwrap();
    let header = reader.headers().unwrap().clone();
    let mut columns = vec![
        "time_s".to_string(),
        "pelvis_tx_m".into(),
        "pelvis_ty_m".into(),
        "pelvis_tz_m".into(),
        "pelvis_tilt_deg".into(),
        "pelvis_list_deg".into(),
        "pelvis_rotation_deg".into(),
    ];
    for side in ["r", "l"] {
        for joint in [
            "hip_flexion",
            "hip_adduction",
            "hip_rotation",
            "knee_flexion",
            "ankle_dorsiflexion",
            "mtp_dorsiflexion",
            "shoulder_flexion",
            "elbow_flexion",
        ] {
            columns.push(format!("{joint}_{side}_deg"));
        }
    }
    for column in &columns {
        assert!(
            header.iter().any(|h| h == column),
            "{column} missing from {header:?}"
        );
    }
    let rows: Vec<csv::StringRecord> = reader.records().map(|r| r.unwrap()).collect();

    // v = 1.4 m/s alone, H = 1.8 m: sf = √(15000 v / H) = 108.01 steps/min, each step 60/sf s
    let sf = (15000.0_f64 * 1.4 / 1.8).sqrt();
    let duration = 10.0 * 60.0 / sf; // 5.5549 s
    let expected = (duration * 100.0).round() as usize + 1; // 556 frames at 100 frames/s
    assert_eq!(
        rows.len(),
        expected,
        "frames from t = 0 to {duration} s at 100 frames/s"
    );
    let time = header.iter().position(|h| h == "time_s").unwrap();
    let t_first: f64 = rows[0][time].parse().unwrap();
    let t_last: f64 = rows[rows.len() - 1][time].parse().unwrap();
    assert!(t_first.abs() < 1e-9, "first frame at {t_first} s");
    assert!(
        (t_last - duration).abs() <= 0.5 / 100.0 + 1e-9,
        "last frame at {t_last} s"
    );
}

#[test]
fn report_names_targets_and_shooting_iterations() {
    let dir = tempfile::tempdir().unwrap();
    let stdout = ok(dir.path(), &["walk", "--steps", "2", "--report", "r.json"]);
    assert!(stdout.contains("r.json"), "{stdout}");
    let r = json(&dir.path().join("r.json"));
    assert_eq!(r["height"], 1.8);
    assert_eq!(r["mass"], 80.0);
    let steps = r["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 2, "{r:#}");
    let v = steps[0]["target"]["velocity"].as_f64().unwrap();
    assert!((v - 1.4).abs() < 1e-9, "target velocity {v}");
    for step in steps {
        let solves = step["solves"].as_array().unwrap();
        assert!(!solves.is_empty(), "{step:#}");
        for solve in solves {
            assert!(solve["iterations"].as_u64().unwrap() >= 1, "{solve:#}");
        }
    }
    assert!(stdout.contains("iterations per solve"), "{stdout}");
}

#[test]
fn schedule_rows_are_steps_and_the_last_is_held() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(
        dir.path().join("s.toml"),
        "[[step]]\nstep_frequency = 100\n\n[[step]]\nstep_frequency = 110\n",
    )
    .unwrap();
    // 3 steps from 2 rows: 60/100 + 2 · 60/110 = 0.6 + 1.0909 = 1.691 s
    let stdout = ok(
        dir.path(),
        &["walk", "--schedule", "s.toml", "--steps", "3"],
    );
    let duration = 60.0 / 100.0 + 2.0 * 60.0 / 110.0;
    assert!(
        stdout.contains(&format!("walked 3 steps: {duration:.3} s")),
        "{stdout}"
    );

    fs::write(
        dir.path().join("s.csv"),
        "velocity,step_frequency\n1.2,\n,105\n",
    )
    .unwrap();
    // no --steps: the schedule's length; 1.2 m/s alone → sf = √(15000 · 1.2 / 1.8) = 100
    let stdout = ok(dir.path(), &["walk", "--schedule", "s.csv"]);
    let duration = 60.0 / (15000.0_f64 * 1.2 / 1.8).sqrt() + 60.0 / 105.0;
    assert!(
        stdout.contains(&format!("walked 2 steps: {duration:.3} s")),
        "{stdout}"
    );
}

#[test]
fn out_of_range_flags_name_the_value_and_the_range() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    bad_input(
        d,
        &["walk", "--velocity", "5"],
        &["velocity", "5", "[0.4, 2.0634]"],
    );
    bad_input(
        d,
        &["walk", "--velocity", "nan"],
        &["velocity", "NaN", "finite"],
    );
    bad_input(d, &["walk", "--velocity", "-1"], &["velocity", "-1"]);
    bad_input(
        d,
        &["walk", "--height", "3"],
        &["height", "3", "[1.2, 2.2]"],
    );
    bad_input(d, &["walk", "--mass", "10"], &["mass", "10", "[25, 200]"]);
    bad_input(d, &["walk", "--fps", "0"], &["fps", "0", "10000"]);
    bad_input(d, &["walk", "--fps", "20000"], &["fps", "20000", "10000"]);
    bad_input(d, &["walk", "--fps", "nan"], &["fps", "NaN", "finite"]);
    bad_input(
        d,
        &["walk", "--steps", "0"],
        &["steps", "0", "[1, 1000000]"],
    );
    bad_input(
        d,
        &["walk", "--step-frequency", "300"],
        &["step_frequency", "300"],
    );
    bad_input(d, &["bench", "--repeat", "0"], &["repeat", "0"]);
    bad_input(
        d,
        &["walk", "--out", "x.csv", "--state-out", "./x.csv"],
        &["--out", "--state-out", "same"],
    );
    bad_input(
        d,
        &[
            "walk",
            "--out",
            "x.csv",
            "--events",
            "e.csv",
            "--cycle-out",
            "e.csv",
        ],
        &["--events", "--cycle-out", "same"],
    );
    bad_input(d, &["walk", "--out", "x.txt"], &["x.txt", ".bvh"]);
    // nothing was written by a rejected invocation
    assert!(files(d).is_empty(), "{:?}", files(d));
}

#[test]
fn inconsistent_gait_is_rejected() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "walk",
        "--velocity",
        "1.4",
        "--step-length",
        "0.5",
        "--step-frequency",
        "100",
    ];
    // sl · sf / 60 = 0.5 · 100 / 60 = 0.8333 m/s ≠ 1.4 m/s
    bad_input(dir.path(), &args, &["inconsistent", "1.4", "0.8333"]);
}

#[test]
fn usage_errors_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    bad_input(d, &["walk", "--bogus"], &["--bogus"]);
    bad_input(d, &["walk", "--steps", "many"], &["many"]);
    bad_input(d, &["walk", "--velocity"], &["--velocity"]);
    bad_input(d, &["fly"], &["fly"]);
    // no subcommand: clap prints the usage to stderr and exits 2
    let out = klaw(d, &[]);
    assert_eq!(out.status.code(), Some(2));
    assert!(texts(&out).1.contains("Usage: klaw <COMMAND>"));
    fs::write(d.join("s.toml"), "[[step]]\nvelocity = 1.2\n").unwrap();
    bad_input(
        d,
        &["walk", "--schedule", "s.toml", "--velocity", "1.2"],
        &["--schedule"],
    );
}

#[test]
fn malformed_schedules_are_rejected_naming_the_row() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cases: &[(&str, &str, &[&str])] = &[
        (
            "a.toml",
            "[[step]]\nvelocity = 1.4\n[[step]]\nspeed = 1.2\n",
            &["a.toml", "line 4", "speed"],
        ),
        ("b.toml", "[[step]]\nvelocity = \n", &["b.toml", "line 2"]),
        ("c.toml", "", &["c.toml", "no steps"]),
        (
            "a.csv",
            "velocity\n1.4\nfast\n",
            &["a.csv", "row 2", "fast"],
        ),
        ("b.csv", "velocity\n1.4\n1.3,0.7\n", &["b.csv", "row 2"]),
        ("c.csv", "speed\n1.4\n", &["c.csv", "speed"]),
        // parses, but the second step is out of range: the step is named with the range
        (
            "d.csv",
            "velocity\n1.4\n9\n",
            &["d.csv", "step 2", "velocity", "[0.4, 2.0634]"],
        ),
        (
            "e.csv",
            "velocity,step_length\n1.4,\n,\n",
            &["e.csv", "step 2"],
        ),
        ("s.json", "{}", &["s.json", ".toml", ".csv"]),
    ];
    for (name, text, needles) in cases {
        fs::write(d.join(name), text).unwrap();
        bad_input(d, &["walk", "--schedule", name], needles);
    }
    bad_input(
        d,
        &["walk", "--schedule", "missing.toml"],
        &["reading", "missing.toml"],
    );
    assert!(!d.join("walk.csv").exists());
}

#[test]
fn malformed_attribute_files_are_rejected() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cases: &[(&str, &str, &[&str])] = &[
        (
            "a.toml",
            "bounciness = \"high\"\n",
            &["a.toml", "bounciness", "number"],
        ),
        ("b.toml", "bounciness = \n", &["b.toml"]),
        (
            "c.toml",
            "bouncyness = 0.5\n",
            &["c.toml", "bouncyness", "bounciness"],
        ),
        (
            "d.toml",
            "bounciness = 5\n",
            &["bounciness", "5", "[0.7, 0.88]"],
        ),
        ("e.toml", "bounciness = nan\n", &["bounciness", "finite"]),
    ];
    for (name, text, needles) in cases {
        fs::write(d.join(name), text).unwrap();
        bad_input(d, &["walk", "--steps", "2", "--attributes", name], needles);
    }
    bad_input(
        d,
        &["walk", "--attributes", "missing.toml"],
        &["reading", "missing.toml"],
    );
    assert!(!d.join("walk.csv").exists());
}

#[test]
fn attribute_file_is_applied() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(
        dir.path().join("a.toml"),
        "description = \"calm\"\nbounciness = 0.7\n",
    )
    .unwrap();
    let stdout = ok(
        dir.path(),
        &["walk", "--steps", "2", "--attributes", "a.toml"],
    );
    assert!(stdout.contains("walked 2 steps"), "{stdout}");
}

#[test]
fn unwritable_output_fails_without_partial_files() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for args in [
        &["walk", "--steps", "2", "--out", "no/such/dir/w.csv"][..],
        &["walk", "--steps", "2", "--report", "no/such/dir/r.json"][..],
    ] {
        let out = klaw(d, args);
        let (_, stderr) = texts(&out);
        assert!(!out.status.success(), "klaw {args:?} succeeded");
        assert!(
            stderr.starts_with("error: ") && stderr.contains("no/such/dir"),
            "{stderr}"
        );
        assert!(files(d).is_empty(), "klaw {args:?} left {:?}", files(d));
    }
    // an output path that is a directory: the rename fails, nothing is left behind
    fs::create_dir(d.join("taken.csv")).unwrap();
    let out = klaw(d, &["walk", "--steps", "2", "--out", "taken.csv"]);
    assert!(!out.status.success());
    assert_eq!(files(d), ["taken.csv"]);
    assert!(fs::read_dir(d.join("taken.csv")).unwrap().next().is_none());
}

#[test]
fn help_explains_every_flag_with_units_and_defaults() {
    let dir = tempfile::tempdir().unwrap();
    let help = ok(dir.path(), &["walk", "--help"]);
    for needle in [
        "--velocity",
        "--step-length",
        "--step-frequency",
        "--height",
        "--mass",
        "--steps",
        "--schedule",
        "--attributes",
        "--fps",
        "--out",
        "--report",
        "m/s",
        "steps/min",
        "kg",
        "frames per second",
        "normalizing formula",
        "sl = 0.004 · sf · H",
        "v = sl · sf / 60",
        "[default: 1.8]",
        "[default: 80]",
        "[default: 100]",
        "[default: walk.csv]",
        "[default when none of --velocity",
        "preferred_velocity, 1.4 m/s",
    ] {
        assert!(
            help.contains(needle),
            "`{needle}` missing from walk --help:\n{help}"
        );
    }
    let help = ok(dir.path(), &["bench", "--help"]);
    assert!(
        help.contains("--steps") && help.contains("--repeat") && help.contains("[default: 20]")
    );
}

#[test]
fn bench_reports_rates() {
    let dir = tempfile::tempdir().unwrap();
    let stdout = ok(dir.path(), &["bench", "--steps", "1", "--repeat", "2"]);
    for needle in [
        "real-time factor",
        "steps per second",
        "iterations per solve",
    ] {
        assert!(stdout.contains(needle), "{stdout}");
    }
    assert!(files(dir.path()).is_empty());
}

/// `--cycle-out` needs a steady cycle after the start-up one: with 4 steps it is refused before
/// anything is simulated or written; with 5 it writes 101 rows (0…100 %) and the events file
/// lists every event of the walk's feet.
#[test]
fn cycle_and_events_outputs() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let args = |n: &'static str| {
        vec![
            "walk",
            "--steps",
            n,
            "--no-plot",
            "--out",
            "m.csv",
            "--cycle-out",
            "c.csv",
            "--events",
            "e.csv",
        ]
    };
    bad_input(d, &args("4"), &["--cycle-out", "5 steps", "4"]);
    assert!(files(d).is_empty(), "{:?}", files(d));
    ok(d, &args("5"));
    let mut r = csv::Reader::from_path(d.join("c.csv")).unwrap();
    assert_eq!(&r.headers().unwrap()[0], "cycle_pct");
    let pct: Vec<String> = r.records().map(|x| x.unwrap()[0].to_string()).collect();
    assert_eq!(pct.len(), 101);
    assert_eq!((pct[0].as_str(), pct[100].as_str()), ("0", "100"));
    let mut e = csv::Reader::from_path(d.join("e.csv")).unwrap();
    assert_eq!(
        e.headers().unwrap(),
        vec!["time_s", "side", "event", "step"]
    );
    let rows: Vec<csv::StringRecord> = e.records().map(|x| x.unwrap()).collect();
    // 5 heel strikes; every stance but the last reaches toe-off
    let count = |name: &str| rows.iter().filter(|r| &r[2] == name).count();
    assert_eq!((count("HS"), count("TO")), (5, 4));
}
