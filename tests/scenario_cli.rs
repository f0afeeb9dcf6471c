//! `klaw scenario`: a good file writes its frames; a bad one exits 2 naming the action and the
//! field, and writes nothing.
use std::path::PathBuf;
mod common;

use common::klaw_status as klaw;

fn dir(name: &str) -> PathBuf {
    common::scratch("scenario-cli", name)
}

#[test]
fn an_example_writes_its_frames() {
    let d = dir("good");
    let out = d.join("spin.csv");
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/scenarios/spin.toml");
    let (code, err) = klaw(&[
        "scenario",
        file,
        "--out",
        out.to_str().unwrap(),
        "--fps",
        "50",
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&out).unwrap();
    // a header and one row per frame: 5.5 s at 50 frames/s
    assert_eq!(text.lines().count(), 1 + 276);
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn bad_files_exit_2_and_write_nothing() {
    let d = dir("bad");
    for (text, want) in [
        (
            "[[action]]\ntype = \"jump\"\n",
            "action 0 (jump, from 0), `type`",
        ),
        (
            "[[action]]\ntype = \"stand\"\n[[action]]\ntype = \"step\"\nside = \"right\"\nleft = 0.5\n",
            "action 1 (step)",
        ),
        (
            "[[action]]\ntype = \"turn\"\nside = \"left\"\nkind = \"dynamic\"\n",
            "angle",
        ),
    ] {
        let file = d.join("s.toml");
        std::fs::write(&file, text).unwrap();
        let out = d.join("s.csv");
        let (code, err) = klaw(&[
            "scenario",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(code, 2, "{text}: {err}");
        assert!(err.contains(want), "{err} should name {want}");
        assert!(!out.exists(), "nothing written");
    }
    std::fs::remove_dir_all(&d).unwrap();
}

/// The files in `d`.
fn listing(d: &std::path::Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn step_and_turn_write_frames_events_and_report() {
    let d = dir("one");
    let p = |n: &str| d.join(n).to_str().unwrap().to_string();
    let (code, err) = klaw(&[
        "step",
        "--side",
        "left",
        "--forward",
        "0.6",
        "--out",
        &p("s.csv"),
        "--events",
        &p("s-events.csv"),
        "--report",
        &p("s.json"),
    ]);
    assert_eq!(code, 0, "{err}");
    // one step: the left foot lifts and lands, nothing else moves
    let events = std::fs::read_to_string(d.join("s-events.csv")).unwrap();
    let rows: Vec<&str> = events.lines().collect();
    assert_eq!(rows[0], "time_s,side,event,action,kind");
    assert_eq!(rows.len(), 3, "{events}");
    assert!(rows[1].contains(",left,foot_off,1,step"), "{events}");
    assert!(rows[2].contains(",left,foot_strike,1,step"), "{events}");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("s.json")).unwrap()).unwrap();
    // the standing feet and the step's
    assert_eq!(report["footprints"].as_array().unwrap().len(), 3);
    let (code, err) = klaw(&[
        "turn",
        "--angle",
        "250",
        "--side",
        "right",
        "--kind",
        "stationary",
        "--out",
        &p("t.bvh"),
        "--events",
        &p("t-events.csv"),
    ]);
    assert_eq!(code, 0, "{err}");
    // 250° is three turnarounds of two steps: each foot lifts and lands three times
    let events = std::fs::read_to_string(d.join("t-events.csv")).unwrap();
    assert_eq!(events.lines().count(), 1 + 3 * 2 * 2, "{events}");
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn bad_steps_and_turns_exit_2_and_write_nothing() {
    let d = dir("one-bad");
    let out = d.join("x.csv");
    let events = d.join("x-events.csv");
    let o = out.to_str().unwrap();
    let e = events.to_str().unwrap();
    for (args, want) in [
        (vec!["step"], "a step needs a goal"),
        (vec!["step", "--forward", "5"], "valid range is [-2, 2] m"),
        // the left foot across in front of the right: the illegal region
        (
            vec!["step", "--side", "left", "--left", "-0.3"],
            "illegal region",
        ),
        (
            vec!["step", "--forward", "0.6", "--duration", "9"],
            "duration",
        ),
        (vec!["turn", "--angle", "0"], "angle"),
        (vec!["turn", "--step-duration", "0.01"], "step_duration"),
        (
            vec!["step", "--forward", "0.6", "--events", "x.txt"],
            "--events",
        ),
    ] {
        let mut all = args.clone();
        all.extend(["--out", o]);
        if !args.contains(&"--events") {
            all.extend(["--events", e]);
        }
        let (code, err) = klaw(&all);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(want), "{args:?}: {err} should say {want}");
        assert!(listing(&d).is_empty(), "{args:?} wrote {:?}", listing(&d));
    }
    std::fs::remove_dir_all(&d).unwrap();
}
