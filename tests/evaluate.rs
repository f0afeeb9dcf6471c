//! `klaw evaluate` and the motion files it reads (`export::read`): klaw's own CSV and `.mot`
//! read back give the walk's frames; every kind of malformed file or bad flag exits 2 naming
//! the file, the line and what was expected, with nothing written.
use std::fs;
use std::path::Path;

use klaw::analysis::criteria::segments::{POSE, pose};
use klaw::analysis::criteria::{CriteriaFrames, CriteriaParameters, evaluate};
use klaw::export::read::read_motion;
use klaw::{OpenSimModel, Options};

mod common;
use common::{default_body, klaw, refused_in};

/// A 6-step default walk written by the binary as CSV, `.mot` and its report, in `dir`.
fn walk_files(dir: &Path) {
    let out = klaw(
        dir,
        &[
            "walk",
            "--steps",
            "6",
            "--out",
            "w.csv",
            "--report",
            "w.json",
            "--no-plot",
        ],
    );
    assert_eq!(out.status.code(), Some(0));
    let out = klaw(
        dir,
        &["walk", "--steps", "6", "--out", "w.mot", "--no-plot"],
    );
    assert_eq!(out.status.code(), Some(0));
}

fn largest_difference(a: &CriteriaFrames, b: &CriteriaFrames) -> f64 {
    assert_eq!(a.frames.len(), b.frames.len());
    a.frames
        .iter()
        .zip(&b.frames)
        .map(|(x, y)| {
            let (p, q) = (pose(x), pose(y));
            (0..POSE)
                .map(|i| (p[i] - q[i]).abs())
                .chain([(x.time - y.time).abs()])
                .chain([
                    (x.right.ankle.flexion - y.right.ankle.flexion).abs(),
                    (x.left.ankle.flexion - y.left.ankle.flexion).abs(),
                ])
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

/// The CSV and the `.mot` (gait2392 and Rajagopal 2015) of a walk read back to its own frames
/// (pelvis centre, pelvis, lumbar, hip, knee and ankle angles) to 1e-9; the CSV's heel strikes
/// are the step starts to the frame, the `.mot`'s the ankle's foremost positions.
#[test]
fn klaw_files_read_back_to_the_walk() {
    let dir = tempfile::tempdir().unwrap();
    let body = default_body();
    let walk = klaw::Simulation::new(body).steps(6).run().unwrap();
    let fps = 100.0;
    let exact = CriteriaFrames::from_walk(walk.engine(), fps).unwrap();
    let params = CriteriaParameters::default();
    let csv = dir.path().join("w.csv");
    walk.write(&csv, fps, &Options::default()).unwrap();
    let from_csv = read_motion(&csv, &body, &params).unwrap();
    assert!(largest_difference(&exact, &from_csv.motion) < 1e-9);
    assert_eq!(from_csv.steps, Some(6));
    assert!(from_csv.absent.is_empty(), "{:?}", from_csv.absent);
    for model in [OpenSimModel::Gait2392, OpenSimModel::Rajagopal2015] {
        let mot = dir.path().join("w.mot");
        let options = Options {
            opensim_model: model,
            ..Default::default()
        };
        walk.write(&mot, fps, &options).unwrap();
        let from_mot = read_motion(&mot, &body, &params).unwrap();
        let d = largest_difference(&exact, &from_mot.motion);
        assert!(d < 1e-9, "{model:?}: {d}");
        assert!(from_mot.format.contains(&format!("{model:?}")));
        assert_eq!(from_mot.steps, None);
        assert_eq!(from_mot.motion.heel_strikes.right.len(), 3);
    }
    // the step column's heel strikes: the steps' first frames
    let h = &from_csv.motion.heel_strikes;
    assert_eq!((h.right.len(), h.left.len()), (3, 3));
    for (a, b) in h.left.iter().zip(&exact.heel_strikes.left) {
        assert!(a - b >= 0.0 && a - b < 1.0 / fps, "{a} {b}");
    }
}

/// The printed and JSON criteria are the library's; a file with only the needed columns is
/// evaluated without C3 and says what it lacks.
#[test]
fn evaluate_prints_and_writes_the_criteria() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    walk_files(d);
    let out = klaw(
        d,
        &[
            "evaluate", "w.csv", "--report", "w.json", "--json", "c.json",
        ],
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{stdout}");
    assert!(
        stdout.contains("actuator work:") && stdout.contains(" J/m"),
        "{stdout}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(d.join("c.json")).unwrap()).unwrap();
    let body = default_body();
    let params = CriteriaParameters::default();
    let m = read_motion(&d.join("w.csv"), &body, &params).unwrap();
    let c = evaluate(&m.motion, &body, &params).unwrap();
    let mean = &json["criteria"]["mean"];
    assert_eq!(mean["total_jerk"].as_f64().unwrap(), c.mean.total_jerk);
    assert_eq!(mean["cyclicity"].as_f64().unwrap(), c.mean.cyclicity);
    let literal = mean["power"]["literal"].as_f64().unwrap();
    assert_eq!(literal, c.mean.power.unwrap().literal);
    assert!(json["actuator_work"]["per_metre"].as_f64().unwrap() > 0.0);
    assert!(!json["norms"].as_array().unwrap().is_empty());
    // the speed-dependent norms are read at the file's own speed: the pelvis advances at the
    // walk's 1.4 m/s (to the start-up's transient), v / √(g l1) = 1.4 / √(9.81 · 0.868) = 0.480
    // (Orendurff's excursion row in m/s: 1.4)
    let speeds = |scale: &str| -> Vec<f64> {
        json["norms"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|n| n["speed_scale"] == scale)
            .filter_map(|n| n["speed"].as_f64())
            .collect()
    };
    let (hof, ms) = (speeds("v/sqrt(g l1)"), speeds("m/s"));
    assert!(!hof.is_empty() && ms.len() == 1, "{hof:?} {ms:?}");
    let want = 1.4 / (9.81 * body.l1).sqrt();
    assert!(hof.iter().all(|v| (v - want).abs() < 0.01), "{hof:?}");
    assert!((ms[0] - 1.4).abs() < 0.01, "{ms:?}");
    // the same walk in two formats compares to zero
    let out = klaw(d, &["evaluate", "w.mot", "--against", "w.csv"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{stdout}");
    let knee = stdout
        .lines()
        .find(|l| l.trim_start().starts_with("knee_flexion_l"))
        .unwrap();
    assert!(knee.ends_with(" 0.0000 rad (0.00°)"), "{stdout}");
    assert!(stdout.contains("actuator work: not available"), "{stdout}");
    // only the needed columns
    let text = fs::read_to_string(d.join("w.csv")).unwrap();
    let keep = [
        "time_s",
        "pelvis_tilt_deg",
        "pelvis_list_deg",
        "pelvis_rotation_deg",
        "hip_flexion_r_deg",
        "hip_adduction_r_deg",
        "hip_rotation_r_deg",
        "knee_flexion_r_deg",
        "hip_flexion_l_deg",
        "hip_adduction_l_deg",
        "hip_rotation_l_deg",
        "knee_flexion_l_deg",
    ];
    fs::write(d.join("few.csv"), select(&text, &keep)).unwrap();
    let out = klaw(d, &["evaluate", "few.csv"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{stdout}");
    assert!(
        stdout.contains("heel strikes from the kinematics")
            && stdout.contains("without the pelvis position")
            && stdout.contains("without the lumbar angles"),
        "{stdout}"
    );
}

/// A reader that stops early (`klaw evaluate … | head -1`) is not an error of klaw's: with its
/// standard output closed before it prints, the command still writes the JSON and exits 0,
/// not 101 with a panic ("failed printing to stdout", before the lines were written with
/// `writeln!`).
#[test]
fn a_closed_standard_output_is_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    walk_files(dir.path());
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_klaw"))
        .current_dir(dir.path())
        .args([
            "evaluate", "w.csv", "--report", "w.json", "--json", "c.json",
        ])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(dir.path().join("c.json").exists());
}

/// The columns `keep` of a CSV text.
fn select(text: &str, keep: &[&str]) -> String {
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let at: Vec<usize> = keep
        .iter()
        .map(|k| header.iter().position(|h| h == k).unwrap())
        .collect();
    text.lines()
        .map(|l| {
            let cells: Vec<&str> = l.split(',').collect();
            at.iter().map(|&i| cells[i]).collect::<Vec<_>>().join(",") + "\n"
        })
        .collect()
}

/// Every kind of bad input exits 2 with one line naming the file, the line and what was
/// expected, and writes nothing (not even --json).
#[test]
fn bad_files_and_flags_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    walk_files(d);
    let csv = fs::read_to_string(d.join("w.csv")).unwrap();
    let mot = fs::read_to_string(d.join("w.mot")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    let replace_cell = |line: usize, column: usize, with: &str| {
        let mut l: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
        let mut cells: Vec<&str> = lines[line - 1].split(',').collect();
        cells[column] = with;
        l[line - 1] = cells.join(",");
        l.join("\n") + "\n"
    };
    let cases: Vec<(&str, String, Vec<&str>)> = vec![
        (
            "missing.csv",
            csv.replace("knee_flexion_l_deg", "knee_l"),
            vec!["missing.csv", "line 1: no column `knee_flexion_l_deg`"],
        ),
        (
            "nan.csv",
            replace_cell(3, 12, "abc"),
            vec!["line 3: hip_flexion_r_deg `abc` is not a finite number"],
        ),
        (
            "inf.csv",
            replace_cell(4, 15, "inf"),
            vec!["line 4: knee_flexion_r_deg `inf`"],
        ),
        (
            "short.csv",
            format!("{}\n{}\n0.02,0\n", lines[0], lines[1]),
            vec!["line 3: 2 values where the header names 30 columns"],
        ),
        (
            "time.csv",
            replace_cell(5, 0, "0.01"),
            vec!["line 5: time 0.01 s does not follow the previous row's 0.02 s"],
        ),
        (
            "step.csv",
            replace_cell(6, 1, "0.5"),
            vec!["line 6: step `0.5` is not a whole number"],
        ),
        (
            "header.csv",
            format!("{}\n", lines[0]),
            vec!["header.csv", "no rows after the header"],
        ),
        (
            "twice.csv",
            csv.replace("mtp_dorsiflexion_r_deg", "hip_flexion_r_deg"),
            vec!["line 1: column `hip_flexion_r_deg` appears twice"],
        ),
        (
            "x.txt",
            csv.clone(),
            vec![
                "x.txt",
                "a motion file is klaw's frame CSV (.csv) or OpenSim storage",
            ],
        ),
        (
            "deg.mot",
            mot.replace("inDegrees=yes\n", ""),
            vec!["deg.mot", "no inDegrees=yes or no"],
        ),
        (
            "degword.mot",
            mot.replace("inDegrees=yes", "inDegrees=maybe"),
            vec!["line 5: inDegrees `maybe`: expected yes or no"],
        ),
        (
            "rows.mot",
            mot.replace("nRows=334", "nRows=600"),
            vec!["line 3: nRows=600 but the file has 334 rows"],
        ),
        (
            "cols.mot",
            mot.replace("nColumns=24", "nColumns=23"),
            vec!["line 11: 24 column names where nColumns=23 (line 4)"],
        ),
        (
            "end.mot",
            mot.replace("endheader", "end"),
            vec!["no `endheader` line"],
        ),
        (
            "count.mot",
            mot.replace("nRows=334", "nRows=many"),
            vec!["line 3: nRows `many` is not a whole number"],
        ),
        (
            "knee.mot",
            mot.replace("knee_angle_r", "knee_r"),
            vec!["line 11: no column `knee_angle_r`"],
        ),
        (
            "tiny.csv",
            lines[..60].join("\n") + "\n",
            vec!["tiny.csv", "no complete gait cycle"],
        ),
    ];
    assert!(
        mot.contains("nRows=334") && mot.contains("nColumns=24"),
        "{}",
        &mot[..200]
    );
    for (name, text, needles) in &cases {
        fs::write(d.join(name), text).unwrap();
        refused_in(d, &["evaluate", name, "--json", "out.json"], needles);
    }
    fs::write(d.join("bad.json"), "{\"height\": 1.8}").unwrap();
    fs::write(d.join("binary.csv"), [0u8, 159, 146, 150]).unwrap();
    let flags: Vec<(Vec<&str>, Vec<&str>)> = vec![
        (vec!["none.csv"], vec!["reading none.csv"]),
        (vec!["binary.csv"], vec!["binary.csv", "UTF-8"]),
        (
            vec!["w.csv", "--json", "c.txt"],
            vec!["--json: c.txt: the extension must be .json"],
        ),
        (
            vec!["w.csv", "--json", "no-such-dir/c.json"],
            vec!["directory no-such-dir does not exist"],
        ),
        (
            vec!["w.csv", "--height", "3"],
            vec!["height = 3 m", "[1.2, 2.2]"],
        ),
        (vec!["w.csv", "--mass", "-1"], vec!["mass = -1 kg"]),
        (
            vec!["w.csv", "--skip-cycles", "-1"],
            vec!["skip-cycles = -1"],
        ),
        (
            vec!["w.csv", "--report", "bad.json"],
            vec!["malformed walk report bad.json"],
        ),
        (
            vec!["w.mot", "--report", "w.json"],
            vec!["--report: w.json: w.mot has no step column"],
        ),
        (
            vec!["w.csv", "--report", "w.json", "--height", "1.7"],
            vec!["the walk's body is H 1.8 m, M 80 kg"],
        ),
        (
            vec!["w.csv", "--against", "rows.mot"],
            vec!["rows.mot", "nRows=600"],
        ),
    ];
    for (args, needles) in flags {
        let mut a = vec!["evaluate"];
        a.extend(args);
        refused_in(d, &a, &needles);
    }
    // a report of another walk
    let out = klaw(
        d,
        &[
            "walk",
            "--steps",
            "8",
            "--report",
            "eight.json",
            "--no-plot",
        ],
    );
    assert_eq!(out.status.code(), Some(0));
    refused_in(
        d,
        &["evaluate", "w.csv", "--report", "eight.json"],
        &[
            "a walk of 8 steps",
            "w.csv holds 6 steps",
            "not the same walk",
        ],
    );
}
