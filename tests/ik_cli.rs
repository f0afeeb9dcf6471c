//! `klaw poulaine extract|fit`, `klaw poulaine-db build` and `klaw ik` end to end: the files they
//! write, and every bad input refused with exit status 2 before anything is written.
use std::fs;
use std::path::Path;

mod common;
use common::klaw;

fn ok(dir: &Path, args: &[&str]) -> String {
    let out = klaw(dir, args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "klaw {args:?} failed:\n{stderr}");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Exit 2, the message naming `what`, and no file `out` written.
fn refused(dir: &Path, args: &[&str], what: &str, out: &str) {
    let o = klaw(dir, args);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "klaw {args:?}:\n{stderr}");
    assert!(stderr.contains(what), "klaw {args:?}: {stderr}");
    assert!(!dir.join(out).exists(), "klaw {args:?} wrote {out}");
}

/// A walk's poulaine, its model, a database of two walks and a measured entry, and the IK from
/// the poulaine and from the database, to CSV, .mot and BVH.
#[test]
fn the_commands_chain_from_a_walk_to_a_figure() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let said = ok(
        d,
        &[
            "poulaine",
            "extract",
            "--velocity",
            "1.2",
            "--steps",
            "4",
            "--out",
            "p.csv",
        ],
    );
    assert!(said.contains("(v 1.200 m/s)"), "{said}");
    let text = fs::read_to_string(d.join("p.csv")).unwrap();
    assert!(text.starts_with(
        "time_s,right_x_m,right_y_m,right_z_m,left_x_m,left_y_m,left_z_m,pelvis_speed_m_s\n"
    ));
    let said = ok(
        d,
        &[
            "poulaine", "fit", "p.csv", "--out", "m.json", "--plot", "p.png",
        ],
    );
    let png = fs::read(d.join("p.png")).unwrap();
    assert!(
        png.starts_with(b"\x89PNG") && png.len() > 10_000,
        "{}",
        png.len()
    );
    refused(
        d,
        &[
            "poulaine", "fit", "p.csv", "--out", "m2.json", "--plot", "p.jpg",
        ],
        "plot",
        "m2.json",
    );
    assert!(said.contains("fit error"), "{said}");
    let m: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(d.join("m.json")).unwrap()).unwrap();
    assert!(m["fit_error"]["rms"].as_f64().unwrap() < 0.03);
    ok(
        d,
        &[
            "poulaine",
            "fit",
            "p.csv",
            "--out",
            "e.json",
            "--leg-length",
            "0.868",
            "--step-length",
            "0.7",
        ],
    );
    ok(
        d,
        &[
            "poulaine-db",
            "build",
            "--height",
            "1.7,1.9",
            "--step-length",
            "0.7",
            "--entry",
            "e.json",
            "--out",
            "db.json",
        ],
    );
    let db: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(d.join("db.json")).unwrap()).unwrap();
    let sources: Vec<&str> = db["entries"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["source"].as_str().unwrap())
        .collect();
    assert_eq!(sources, ["synthetic", "synthetic", "measured"]);
    ok(
        d,
        &[
            "ik",
            "--poulaine",
            "p.csv",
            "--cycles",
            "2",
            "--out",
            "a.csv",
        ],
    );
    // 72 frames a cycle (1.2 s at 60 Hz), two cycles, and the header
    assert_eq!(
        fs::read_to_string(d.join("a.csv")).unwrap().lines().count(),
        2 * 72 + 1
    );
    ok(
        d,
        &[
            "ik",
            "--db",
            "db.json",
            "--height",
            "1.75",
            "--step-length",
            "0.7",
            "--out",
            "b.mot",
            "--report",
            "r.json",
        ],
    );
    let r: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(d.join("r.json")).unwrap()).unwrap();
    assert!(r["max_residual_m"].as_f64().unwrap() <= 1e-3 && r["within_limits"].as_bool().unwrap());
    // the walk's own poulaine with f3 towards the angles of the database's synthetic walks
    // nearest in trace (the measured entry carries none)
    let said = ok(
        d,
        &[
            "ik",
            "--poulaine",
            "p.csv",
            "--db",
            "db.json",
            "--cycles",
            "1",
            "--out",
            "own.csv",
            "--report",
            "own.json",
        ],
    );
    assert!(said.contains("f3 towards the angles of H1."), "{said}");
    let r: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(d.join("own.json")).unwrap()).unwrap();
    assert!(r["max_residual_m"].as_f64().unwrap() <= 1e-3 && r["within_limits"].as_bool().unwrap());
    assert!(r["selected"].is_null(), "the poulaine is the file's: {r}");
    // the same poulaine started 40 % into its cycle: a warning naming the offset, and with
    // --align-phase the database's angles read 0.4 of a cycle on
    let text = fs::read_to_string(d.join("p.csv")).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap();
    let rows: Vec<&str> = lines.collect();
    let (n, k) = (rows.len(), rows.len() * 2 / 5);
    let dt = 1.2 / n as f64;
    let mut rotated = format!("{header}\n");
    for (i, row) in rows[k..].iter().chain(&rows[..k]).enumerate() {
        let rest = row.split_once(',').unwrap().1;
        rotated += &format!("{:.9},{rest}\n", i as f64 * dt);
    }
    fs::write(d.join("p40.csv"), rotated).unwrap();
    let args = [
        "ik",
        "--poulaine",
        "p40.csv",
        "--db",
        "db.json",
        "--cycles",
        "1",
        "--out",
        "late.csv",
    ];
    let o = klaw(d, &args);
    assert!(o.status.success());
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stderr.contains("of a cycle out of phase"), "{stderr}");
    let said = ok(d, &[&args[..], &["--align-phase"]].concat());
    let shifts: Vec<f64> = said
        .split("phase ")
        .skip(1)
        .map(|t| t[..6].parse().unwrap())
        .collect();
    let start = k as f64 / n as f64;
    assert!(
        !shifts.is_empty() && shifts.iter().all(|s| (s - start).abs() < 0.02),
        "{start} {said}"
    );
    refused(
        d,
        &[
            "ik",
            "--poulaine",
            "p.csv",
            "--db",
            "db.json",
            "--step-length",
            "0.7",
            "--out",
            "o.csv",
        ],
        "--step-length",
        "o.csv",
    );
    ok(
        d,
        &[
            "ik",
            "--db",
            "db.json",
            "--step-width",
            "0.1",
            "--minimiser",
            "nelder-mead",
            "--out",
            "c.bvh",
        ],
    );
    assert!(
        fs::read_to_string(d.join("c.bvh"))
            .unwrap()
            .starts_with("HIERARCHY")
    );
}

/// Every bad input: exit 2, a message naming it, nothing written.
#[test]
fn bad_inputs_are_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::write(d.join("bad.csv"), "time,x\n0,1\n").unwrap();
    fs::write(d.join("bad.json"), "{\"entries\": []}").unwrap();
    let header = "time_s,right_x_m,right_y_m,right_z_m,left_x_m,left_y_m,left_z_m\n";
    fs::write(
        d.join("short.csv"),
        format!("{header}0,0,-0.8,0.1,0,-0.8,-0.1\n0.1,0,-0.8,0.1,0,-0.8,-0.1\n"),
    )
    .unwrap();
    refused(
        d,
        &["ik", "--poulaine", "missing.csv", "--out", "o.csv"],
        "missing.csv",
        "o.csv",
    );
    refused(
        d,
        &["ik", "--poulaine", "bad.csv", "--out", "o.csv"],
        "header",
        "o.csv",
    );
    refused(
        d,
        &["ik", "--poulaine", "short.csv", "--out", "o.csv"],
        "at least 8",
        "o.csv",
    );
    refused(
        d,
        &["ik", "--db", "bad.json", "--out", "o.csv"],
        "bad.json",
        "o.csv",
    );
    refused(
        d,
        &["ik", "--poulaine", "bad.csv", "--out", "o.txt"],
        "--out",
        "o.txt",
    );
    refused(
        d,
        &[
            "ik",
            "--poulaine",
            "bad.csv",
            "--cycles",
            "0",
            "--out",
            "o.csv",
        ],
        "cycles",
        "o.csv",
    );
    refused(
        d,
        &[
            "ik",
            "--poulaine",
            "bad.csv",
            "--height",
            "3",
            "--out",
            "o.csv",
        ],
        "height",
        "o.csv",
    );
    refused(
        d,
        &["ik", "--db", "bad.json", "--stance", "2", "--out", "o.csv"],
        "stance",
        "o.csv",
    );
    refused(
        d,
        &["ik", "--db", "bad.json", "--fps", "5", "--out", "o.csv"],
        "fps",
        "o.csv",
    );
    refused(
        d,
        &["poulaine-db", "build", "--out", "db.json"],
        "grid",
        "db.json",
    );
    refused(
        d,
        &[
            "poulaine-db",
            "build",
            "--height",
            "1.8",
            "--step-length",
            "0.7",
            "--attr",
            "bogus=1",
            "--out",
            "db.json",
        ],
        "bogus",
        "db.json",
    );
    refused(
        d,
        &[
            "poulaine-db",
            "build",
            "--height",
            "9",
            "--step-length",
            "0.7",
            "--out",
            "db.json",
        ],
        "height",
        "db.json",
    );
    refused(
        d,
        &["poulaine", "fit", "bad.csv", "--out", "m.json"],
        "header",
        "m.json",
    );
    refused(
        d,
        &[
            "poulaine",
            "fit",
            "bad.csv",
            "--leg-length",
            "5",
            "--step-length",
            "0.7",
            "--out",
            "m.json",
        ],
        "leg-length",
        "m.json",
    );
    refused(
        d,
        &["poulaine", "extract", "--velocity", "9", "--out", "p.csv"],
        "velocity",
        "p.csv",
    );
    refused(
        d,
        &["poulaine", "extract", "--steps", "1", "--out", "p.csv"],
        "steps",
        "p.csv",
    );
    refused(
        d,
        &["poulaine", "extract", "--rate", "1", "--out", "p.csv"],
        "rate",
        "p.csv",
    );
}
