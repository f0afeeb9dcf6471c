//! Messages a user can act on (issue 14, class 8): a style's own default speed, derived values
//! said to be derived and shown without float noise, negative numbers taken as values and given
//! their range, the minimum walk of a gait cycle, degrees in the report, every step walked at a
//! low frame rate.
use std::fs;
use std::path::Path;

mod common;
use common::{klaw, refused};

/// The `preferred_velocity` of a bundled style, read from its file.
fn style_speed(style: &str) -> f64 {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("models/styles/{style}.toml"));
    let table: toml::Table = toml::from_str(&fs::read_to_string(path).unwrap()).unwrap();
    table["preferred_velocity"].as_float().unwrap()
}

fn walk_report(args: &[&str]) -> serde_json::Value {
    let dir = tempfile::tempdir().unwrap();
    let mut all = vec!["walk", "--no-plot", "--out", "w.csv", "--report", "r.json"];
    all.extend_from_slice(args);
    let out = klaw(dir.path(), &all);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_str(&fs::read_to_string(dir.path().join("r.json")).unwrap()).unwrap()
}

#[test]
fn a_style_walks_at_its_own_speed_and_a_default_out_of_range_says_so() {
    let speed = style_speed("elderly");
    // the style's range excludes the adults' 1.4 m/s, which used to be the only default
    assert!(speed < 1.1);
    let report = walk_report(&["--style", "elderly", "--steps", "2"]);
    let target = report["steps"][0]["target"]["velocity"].as_f64().unwrap();
    assert_eq!(target, speed);

    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("slow.toml"), "velocity_max = 1.2\n").unwrap();
    let args = ["walk", "--attributes", "slow.toml"];
    let out = klaw(dir.path(), &args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    for part in ["velocity = 1.4 m/s (the default speed", "[0.4, 1.2] m/s"] {
        assert!(stderr.contains(part), "`{part}` not in {stderr}");
    }
}

/// sf = 181.9 steps/min alone for H = 1.8 m: v = 0.004 · 181.9² · 1.8 / 60 = 3.9705132 m/s by
/// hand (238.230792 / 60), over v_max.
#[test]
fn a_derived_value_is_said_to_be_derived_and_shown_without_noise() {
    refused(
        &["walk", "--step-frequency", "181.9"],
        &["velocity = 3.9705132 m/s (derived from step_frequency = 181.9 steps/min"],
    );
    let message = refused(
        &["walk", "--velocity", "1e308"],
        &["1e308 m/s", "[0.4, 2.0634]"],
    );
    assert!(message.len() < 120, "{message}");
}

#[test]
fn negative_numbers_are_values_with_a_range() {
    refused(&["walk", "--steps", "-5"], &["steps = -5", "[1, 1000000]"]);
    refused(&["bench", "--repeat", "-1"], &["repeat = -1", "[1, "]);
    refused(&["sweep", "--shard", "-1/3"], &["-1/3", "1 ≤ K ≤ N"]);
    refused(
        &["animate", "--size", "-600x300"],
        &["width = -600 px", "[200, 4000]"],
    );
}

#[test]
fn a_gait_cycle_of_too_short_a_walk_names_the_minimum() {
    refused(
        &["plot", "--steps", "5", "--out", "c.png"],
        &["--steps", "at least 6 steps are needed, not 5"],
    );
    refused(
        &["walk", "--steps", "4", "--cycle-out", "c.csv"],
        &["at least 5 steps are needed, not 4"],
    );
}

/// The report's knee peak is in degrees, like every angle the user sees: the swing knee of a
/// normal walk peaks near 60–70° (gait-norms.md; 1.1 would be radians).
#[test]
fn the_report_names_its_units_and_gives_angles_in_degrees() {
    let report = walk_report(&["--steps", "4"]);
    let step = &report["steps"][2];
    assert!(step.get("peak_swing_knee_flexion").is_none());
    let knee = step["peak_swing_knee_flexion_deg"].as_f64().unwrap();
    assert!((45.0..80.0).contains(&knee), "{knee}");
}

/// At 0.05 frames/s a 10-step walk (≈ 5.6 s) has one frame, at t = 0; every step is walked all
/// the same, and the summary says so.
#[test]
fn a_low_frame_rate_walks_and_reports_every_step() {
    let report = walk_report(&["--fps", "0.05"]);
    assert_eq!(report["steps"].as_array().unwrap().len(), 10);
    let dir = tempfile::tempdir().unwrap();
    let out = klaw(dir.path(), &["walk", "--no-plot", "--fps", "0.05"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.starts_with("walked 10 steps"), "{stdout}");
    assert!(stdout.contains(" 1 frame at"), "{stdout}");
}

/// A speed beyond the body's walk–run transition is refused before any step, with the body's
/// limit: H = 1.75 m, l1 = 0.48225 · 1.75 = 0.84394 m, √(0.5 · 9.81 · l1) = 2.034558 m/s (by
/// hand), shown rounded down; a taller body walks at the same speed.
#[test]
fn a_speed_beyond_the_walk_run_transition_names_the_bodys_limit() {
    refused(
        &[
            "walk",
            "--velocity",
            "2.1",
            "--height",
            "1.75",
            "--mass",
            "70",
        ],
        &[
            "velocity = 2.1 m/s is beyond the walk–run transition for this body",
            "[0.4, 2.0345] m/s",
            "v²/(g·l) ≤ 0.5",
            "l = 0.8439 m",
        ],
    );
    let dir = tempfile::tempdir().unwrap();
    let out = klaw(
        dir.path(),
        &[
            "walk",
            "--velocity",
            "2.1",
            "--height",
            "2.0",
            "--mass",
            "92",
            "--steps",
            "2",
            "--no-plot",
        ],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}
