//! The commands of the kinematic walk mode (issue 17): `klaw prototype`, `klaw generalize`,
//! `klaw walk --mode kinematic`: their files, their refusals (exit 2, nothing written), and the
//! bundled prototype, which must be what its documented command makes today.
use std::path::Path;

mod common;

use klaw::generalize::extract::from_walk;
use klaw::generalize::{GeneralizeParameters, default_prototype};

fn run(args: &[&str], dir: &Path) -> (i32, String) {
    let out = common::klaw(dir, args);
    let text =
        String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    (out.status.code().unwrap(), text)
}

/// A prototype made, generalized and walked, every output of `klaw walk` but the report.
#[test]
fn prototype_generalize_and_walk_write_their_files() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (code, text) = run(
        &[
            "prototype",
            "--from-walk",
            "--velocity",
            "1.2",
            "--out",
            "p.json",
        ],
        d,
    );
    assert_eq!(code, 0, "{text}");
    let (code, text) = run(
        &[
            "generalize",
            "--prototype",
            "p.json",
            "--step-length",
            "0.6",
            "--height",
            "1.6",
            "--out",
            "g.csv",
        ],
        d,
    );
    assert_eq!(code, 0, "{text}");
    assert!(d.join("g.csv").exists());
    let (code, text) = run(
        &[
            "walk",
            "--mode",
            "kinematic",
            "--prototype",
            "p.json",
            "--steps",
            "6",
            "--out",
            "k.mot",
            "--events",
            "e.csv",
            "--cycle-out",
            "c.csv",
            "--state-out",
            "s.csv",
            "--plot",
            "k.png",
        ],
        d,
    );
    assert_eq!(code, 0, "{text}");
    for f in ["k.mot", "e.csv", "c.csv", "s.csv", "k.png"] {
        assert!(d.join(f).exists(), "{f}: {text}");
    }
    let events = std::fs::read_to_string(d.join("e.csv")).unwrap();
    assert_eq!(events.lines().filter(|l| l.contains(",HS,")).count(), 6);
}

/// The kinematic mode's refusals, before anything is written: a report (no shooting), a
/// prototype for the dynamic mode, a step too long for the body (the longest named), an
/// unknown body table.
#[test]
fn refusals_exit_2_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (args, says) in [
        (
            vec![
                "walk",
                "--mode",
                "kinematic",
                "--out",
                "a.csv",
                "--report",
                "r.json",
            ],
            "report",
        ),
        (
            vec!["walk", "--prototype", "x.json", "--out", "a.csv"],
            "kinematic",
        ),
        (
            vec![
                "walk",
                "--mode",
                "kinematic",
                "--prototype",
                "missing.json",
                "--out",
                "a.csv",
            ],
            "missing.json",
        ),
        (
            vec![
                "generalize",
                "--step-length",
                "1.05",
                "--height",
                "1.5",
                "--out",
                "g.json",
            ],
            "longest",
        ),
        (
            vec![
                "generalize",
                "--step-length",
                "0.6",
                "--body-table",
                "nobody",
                "--out",
                "g.json",
            ],
            "winter",
        ),
        (
            vec![
                "prototype",
                "--from-walk",
                "--steps",
                "2",
                "--out",
                "p.json",
            ],
            "at least 3",
        ),
    ] {
        let (code, text) = run(&args, d);
        assert_eq!(code, 2, "{args:?}: {text}");
        assert!(text.contains(says), "{args:?}: {text}");
    }
    let left: Vec<_> = std::fs::read_dir(d).unwrap().collect();
    assert!(left.is_empty(), "{left:?}");
}

/// The bundled prototype is what `klaw prototype --from-walk` makes from today's engine
/// (regenerate it with the other generated tables: `cargo run --release --example regenerate --
/// models`).
#[test]
fn the_bundled_prototype_is_the_default_walks() {
    let walk = klaw::Simulation::default().steps(10).run().unwrap();
    let fresh = from_walk(walk.engine(), 8, &GeneralizeParameters::default()).unwrap();
    let bundled = default_prototype();
    let (a, b) = (fresh.character, bundled.character);
    for (x, y) in [
        (a.knee_at_strike, b.knee_at_strike),
        (a.foot_at_strike, b.foot_at_strike),
        (a.foot_at_toe_off, b.foot_at_toe_off),
        (a.meta_at_toe_off, b.meta_at_toe_off),
        (fresh.step_length, bundled.step_length),
        (fresh.phases.tom, bundled.phases.tom),
    ] {
        assert!(
            (x - y).abs() < 1e-9,
            "{x} vs {y}: regenerate with `cargo run --release --example regenerate -- models`"
        );
    }
    assert!(klaw::generalize::DEFAULT_PROTOTYPE.len() < 30_000);
    // and the whole of it: every sample of every sequence, as the command writes them
    let data = |text: &str| -> Vec<String> {
        text.lines()
            .filter(|l| !l.starts_with('#'))
            .map(str::to_owned)
            .collect()
    };
    assert!(
        data(&klaw::generalize::text::to_csv(&fresh).unwrap())
            == data(klaw::generalize::DEFAULT_PROTOTYPE),
        "the bundled prototype's samples differ from today's engine's: regenerate it with \
         `cargo run --release --example regenerate -- models`"
    );
}
