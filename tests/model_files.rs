//! Model files of your own (docs/cli.md, "Model files"): a body table (`--body-table FILE.toml`,
//! a sweep's axis, a scenario's `[body] table`), the inverse kinematics' model (`--ik-model`),
//! the NRS constants (`--nrs-model`) and the generalization's constants
//! (`--generalize-model`). A bad file exits 2 naming the file, the key and the rule, and writes
//! nothing; a copy of the bundled file walks byte-identically to the bundled one; a changed value
//! changes the motion.
use std::path::Path;

mod common;

use common::{klaw, refused_in};

const WINTER: &str = include_str!("../models/body-winter.toml");

/// The bundled `text` with its first `from` replaced by `to` (which must be there).
fn edited(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "`{from}` not in the bundled file");
    text.replacen(from, to, 1)
}

/// `klaw args` in `dir`, which must succeed.
fn run(dir: &Path, args: &[&str]) {
    let out = klaw(dir, args);
    assert!(
        out.status.success(),
        "klaw {args:?}:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The bytes of `dir/name`.
fn bytes(dir: &Path, name: &str) -> Vec<u8> {
    std::fs::read(dir.join(name)).unwrap()
}

/// The column `name` of the CSV file `dir/file`, as numbers.
fn column(dir: &Path, file: &str, name: &str) -> Vec<f64> {
    let text = std::fs::read_to_string(dir.join(file)).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let i = header.iter().position(|h| *h == name).unwrap();
    lines
        .map(|l| l.split(',').nth(i).unwrap().parse().unwrap())
        .collect()
}

fn max(v: &[f64]) -> f64 {
    v.iter().copied().fold(f64::NEG_INFINITY, f64::max)
}

/// Each rule of a body table refused, before any work: exit 2, nothing written, the message
/// naming the file, the key and the rule.
#[test]
fn a_body_table_breaking_a_rule_is_refused_naming_file_key_and_rule() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (from, to, parts) in [
        (
            "length = 0.23669",
            "length = -0.2",
            &["thigh.length = -0.2", "must be a fraction in (0, 1]"][..],
        ),
        (
            "gamma = 0.416",
            "gamma = nan",
            &["shank.gamma = NaN", "must be a fraction in (0, 1]"],
        ),
        (
            "r = 0.5\n",
            "r = 0.0\n",
            &["upper_body.r = 0", "must be a fraction in (0, 1]"],
        ),
        (
            "mass = 0.1\n",
            "mass = 0.12\n",
            &[
                "upper_body.mass + 2 × (thigh.mass + shank.mass) = 0.678 + 2 × (0.12 + 0.061) = 1.04, not 1",
                "within 0.0001",
            ],
        ),
        (
            "heel_to_ankle = 0.04853",
            "heel_to_ankle = 0.06",
            &[
                "the hind foot must close: foot.heel_to_ankle = 0.06 must be √(foot.hind_foot² + foot.ankle_height²)",
            ],
        ),
        (
            "ankle_to_metatarsal = 0.08901",
            "ankle_to_metatarsal = 0.03",
            &["foot.ankle_to_metatarsal = 0.03 must exceed foot.ankle_height = 0.03846"],
        ),
        (
            "length = 0.24556",
            "length = 0.3",
            &[
                "foot.ankle_height + thigh.length + shank.length + upper_body.length = 1.04515 exceeds 1",
            ],
        ),
        (
            "height = [1.2, 2.2]",
            "height = [2.2, 1.2]",
            &["limits.height = [2.2, 1.2] must be ordered"],
        ),
        (
            "mass = [25.0, 200.0]",
            "mass = [-25.0, 200.0]",
            &["limits.mass = [-25, 200] must be ordered"],
        ),
        (
            "r = 0.553\n",
            "",
            &["line 11, column 1: missing field `r` in [leg]"],
        ),
        (
            "gamma = 0.326\n",
            "gamma = 0.326\nmass = 0.16\n",
            &["line 14, column 1: unknown field `mass`"],
        ),
        (
            "[foot]",
            "[feet]",
            &["line 33, column 2: unknown field `feet`"],
        ),
    ] {
        std::fs::write(d.join("bad.toml"), edited(WINTER, from, to)).unwrap();
        let mut expect = vec!["malformed body table bad.toml: "];
        expect.extend(parts);
        refused_in(
            d,
            &["walk", "--body-table", "bad.toml", "--out", "w.csv"],
            &expect,
        );
    }
    refused_in(
        d,
        &["walk", "--body-table", "none.toml"],
        &["reading body table none.toml: "],
    );
    refused_in(
        d,
        &["walk", "--body-table", "dempster"],
        &[
            "--body-table: unknown body table `dempster`",
            "a file of your own",
        ],
    );
}

/// Every command that takes a body table takes a file, and refuses a bad one before any work.
#[test]
fn every_command_with_a_body_table_reads_files() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("bad.toml"),
        edited(WINTER, "hind_foot = 0.02959", "hind_foot = 0.04"),
    )
    .unwrap();
    let want = ["malformed body table bad.toml: ", "foot.heel_to_ankle"];
    for args in [
        &["walk", "--mode", "kinematic"][..],
        &["plot"],
        &["animate"],
        &["step", "--forward", "0.4"],
        &["turn"],
        &["prototype", "--from-walk", "--out", "p.json"],
        &["generalize", "--step-length", "0.7", "--out", "g.json"],
        &["poulaine", "extract"],
    ] {
        let mut args = args.to_vec();
        args.extend(["--body-table", "bad.toml"]);
        refused_in(d, &args, &want);
    }
    refused_in(
        d,
        &["sweep", "--body-table", "winter,bad.toml", "--out", "s.csv"],
        &want,
    );
    std::fs::write(
        d.join("s.toml"),
        "[body]\ntable = \"bad.toml\"\n[[action]]\ntype = \"stand\"\nseconds = 0.1\n",
    )
    .unwrap();
    refused_in(
        d,
        &["scenario", "s.toml", "--out", "s.csv"],
        &["[body]", "`table`", "malformed body table bad.toml: "],
    );
}

/// A copy of `models/body-winter.toml` given as a file walks byte-identically to `--body-table
/// winter`, in a walk, a sweep (its row names the file) and a scenario (the path relative to
/// the scenario's folder).
#[test]
fn a_copy_of_the_bundled_table_walks_like_it() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::create_dir(d.join("sub")).unwrap();
    std::fs::write(d.join("sub/mine.toml"), WINTER).unwrap();
    let walk = |table: &str, out: &str| {
        run(
            d,
            &[
                "walk",
                "--steps",
                "3",
                "--body-table",
                table,
                "--no-plot",
                "--out",
                out,
            ],
        );
        bytes(d, out)
    };
    assert_eq!(walk("sub/mine.toml", "a.csv"), walk("winter", "b.csv"));

    run(
        d,
        &[
            "sweep",
            "--body-table",
            "winter,sub/mine.toml",
            "--velocity",
            "1.3",
            "--steps",
            "2",
            "--out",
            "s.csv",
        ],
    );
    let text = std::fs::read_to_string(d.join("s.csv")).unwrap();
    let rows: Vec<&str> = text.lines().collect();
    assert_eq!(rows.len(), 3, "{text}");
    let body_table = |row: &str| row.split(',').nth(7).unwrap().to_string();
    assert_eq!(body_table(rows[1]), "winter");
    assert_eq!(body_table(rows[2]), "sub/mine.toml");
    // the same walk but for the point's number and the table's name
    let rest = |row: &str| row.split(',').skip(8).collect::<Vec<_>>().join(",");
    assert_eq!(rest(rows[1]), rest(rows[2]));

    let scenario = |table: &str| {
        format!(
            "[body]\ntable = \"{table}\"\n[[action]]\ntype = \"step\"\nside = \"right\"\nforward = 0.4\n"
        )
    };
    std::fs::write(d.join("sub/file.toml"), scenario("mine.toml")).unwrap();
    std::fs::write(d.join("sub/name.toml"), scenario("winter")).unwrap();
    run(d, &["scenario", "sub/file.toml", "--out", "f.csv"]);
    run(d, &["scenario", "sub/name.toml", "--out", "n.csv"]);
    assert_eq!(bytes(d, "f.csv"), bytes(d, "n.csv"));
}

/// A table of your own with a longer thigh (0.245 H against Winter's 0.23669 H) walks
/// otherwise: the hip flexes further at the same speed; a sweep's row and a scenario's step
/// differ from Winter's too.
#[test]
fn a_longer_thigh_changes_the_walk() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("long.toml"),
        edited(WINTER, "length = 0.23669", "length = 0.245"),
    )
    .unwrap();
    let peak = |table: &str, out: &str| {
        run(
            d,
            &[
                "walk",
                "--steps",
                "3",
                "--body-table",
                table,
                "--no-plot",
                "--out",
                out,
            ],
        );
        max(&column(d, out, "hip_flexion_r_deg"))
    };
    let (winter, long) = (peak("winter", "w.csv"), peak("long.toml", "l.csv"));
    assert!(
        (long - winter).abs() > 0.1,
        "hip flexion peak {winter}° and {long}°"
    );

    run(
        d,
        &[
            "sweep",
            "--body-table",
            "winter,long.toml",
            "--velocity",
            "1.3",
            "--steps",
            "2",
            "--out",
            "s.csv",
        ],
    );
    let text = std::fs::read_to_string(d.join("s.csv")).unwrap();
    let rows: Vec<&str> = text.lines().collect();
    let outputs = |row: &str| row.split(',').skip(8).collect::<Vec<_>>().join(",");
    assert_ne!(outputs(rows[1]), outputs(rows[2]), "{text}");

    let scenario = |table: &str| {
        format!(
            "[body]\ntable = \"{table}\"\n[[action]]\ntype = \"step\"\nside = \"right\"\nforward = 0.4\n"
        )
    };
    std::fs::write(d.join("long-step.toml"), scenario("long.toml")).unwrap();
    std::fs::write(d.join("winter-step.toml"), scenario("winter")).unwrap();
    run(d, &["scenario", "long-step.toml", "--out", "ls.csv"]);
    run(d, &["scenario", "winter-step.toml", "--out", "ws.csv"]);
    assert_ne!(bytes(d, "ls.csv"), bytes(d, "ws.csv"));
}

const IK: &str = include_str!("../models/ik.toml");

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

/// `klaw ik --ik-model`: a bad model file refused before any work, naming the file, the key and
/// the rule; a copy of models/ik.toml solves byte-identically to none; a rest posture with the
/// knees flexed 20° instead of 5° bends the knees further over the cycle.
#[test]
fn an_ik_model_file_is_checked_and_moves_the_figure() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    run(
        d,
        &["poulaine", "extract", "--steps", "4", "--out", "p.csv"],
    );
    for (from, to, parts) in [
        (
            "knee_flexion = 5.0",
            "knee_flexion = -5.0",
            &[
                "rest.knee_flexion = -5° lies outside its limits models/rom.toml's knee_flexion = [0°, 135°]",
            ][..],
        ),
        (
            "list = [-35.0, 35.0]",
            "list = [35.0, -35.0]",
            &["pelvis_limits.list = [35°, -35°]: the lower limit must be below the upper"],
        ),
        (
            "xi = 20.0",
            "xi = -1.0",
            &["weights.xi = -1 must be finite and ≥ 0"],
        ),
        (
            "pelvis_mass = 0.1117",
            "pelvis_mass = 1.5",
            &["inertia.pelvis_mass = 1.5 must lie in (0, 1)"],
        ),
        ("rest = 10.0\n", "", &["missing field `rest` in [weights]"]),
        (
            "xi = 20.0",
            "xi = 20.0\nzeta = 1.0",
            &["line 55, column 1: unknown field `zeta`"],
        ),
        (
            "[rest]",
            "[leg_limits]\nhip_flexion = [-20.0, 100.0]\n\n[rest]",
            &["missing field `hip_adduction` in [leg_limits]"],
        ),
    ] {
        std::fs::write(d.join("bad.toml"), edited(IK, from, to)).unwrap();
        let mut expect = vec!["malformed inverse-kinematics model bad.toml: "];
        expect.extend(parts);
        refused_in(
            d,
            &[
                "ik",
                "--poulaine",
                "p.csv",
                "--ik-model",
                "bad.toml",
                "--out",
                "ik.csv",
            ],
            &expect,
        );
    }
    refused_in(
        d,
        &["ik", "--poulaine", "p.csv", "--ik-model", "none.toml"],
        &["reading inverse-kinematics model none.toml: "],
    );

    std::fs::write(d.join("copy.toml"), IK).unwrap();
    std::fs::write(
        d.join("knee.toml"),
        edited(IK, "knee_flexion = 5.0", "knee_flexion = 20.0"),
    )
    .unwrap();
    let ik = |model: Option<&str>, out: &str| {
        let mut args = vec!["ik", "--poulaine", "p.csv", "--cycles", "1", "--out", out];
        if let Some(m) = model {
            args.extend(["--ik-model", m]);
        }
        run(d, &args);
    };
    ik(None, "bundled.csv");
    ik(Some("copy.toml"), "copy.csv");
    ik(Some("knee.toml"), "knee.csv");
    assert_eq!(bytes(d, "copy.csv"), bytes(d, "bundled.csv"));
    let knee = |f: &str| mean(&column(d, f, "knee_flexion_r_deg"));
    let (five, twenty) = (knee("bundled.csv"), knee("knee.csv"));
    assert!(
        twenty > five + 0.5,
        "mean knee flexion {five}° and {twenty}°"
    );
}

const NRS: &str = include_str!("../models/nrs.toml");

/// The rows of the CSV file `dir/file`, the header not counted.
fn rows(dir: &Path, file: &str) -> usize {
    std::fs::read_to_string(dir.join(file))
        .unwrap()
        .lines()
        .count()
        - 1
}

/// `--nrs-model` of `klaw step`, `turn` and `scenario`: a bad model file refused before any
/// work, naming the file, the key and the rule; a scenario's values checked against the file's
/// ranges.
#[test]
fn a_bad_nrs_model_file_is_refused_naming_file_key_and_rule() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("s.toml"),
        "[[action]]\ntype = \"step\"\nside = \"right\"\nforward = 0.4\nswing_height_factor = 3\n",
    )
    .unwrap();
    for (from, to, parts) in [
        (
            "region_angle = 60.0",
            "region_angle = 200.0",
            &["region_angle = 200° must lie in (0, 172)°"][..],
        ),
        (
            "swing_height = 0.05",
            "swing_height = -0.05",
            &["swing_height = -0.05 m must lie in (0, 0.5] m"],
        ),
        (
            "turn_max = 100.0",
            "turn_max = 0.0",
            &["turn_max = 0° must lie in (0, 180]°"],
        ),
        (
            "duration_max = 3.0",
            "duration_max = 0.2",
            &["duration_max = 0.2 s must lie in (0.3, 60] s"],
        ),
        (
            "neck_share = 0.6666666666666666\n",
            "",
            &["missing field `neck_share`"],
        ),
        (
            "table_intervals = 256",
            "table_intervals = 256\nnu = 60.0",
            &["line 75, column 1: unknown field `nu`"],
        ),
    ] {
        std::fs::write(d.join("bad.toml"), edited(NRS, from, to)).unwrap();
        let mut expect = vec!["malformed NRS model bad.toml: "];
        expect.extend(parts);
        for command in [
            &["step", "--forward", "0.4"][..],
            &["turn"],
            &["scenario", "s.toml"],
        ] {
            let mut args = command.to_vec();
            args.extend(["--nrs-model", "bad.toml", "--out", "m.csv"]);
            refused_in(d, &args, &expect);
        }
    }
    refused_in(
        d,
        &["turn", "--nrs-model", "none.toml"],
        &["reading NRS model none.toml: "],
    );
    // the scenario's swhf 3 lies within the bundled range [0, 4], not within the file's [0, 2]
    std::fs::write(
        d.join("low.toml"),
        edited(
            NRS,
            "swing_height_factor_max = 4.0",
            "swing_height_factor_max = 2.0",
        ),
    )
    .unwrap();
    refused_in(
        d,
        &[
            "scenario",
            "s.toml",
            "--nrs-model",
            "low.toml",
            "--out",
            "m.csv",
        ],
        &[
            "action 0 (step, from 0), `swing_height_factor`: swing_height_factor = 3 is out of range: valid range is [0, 2]",
        ],
    );
}

/// A copy of models/nrs.toml steps byte-identically to none; a swing peak of 12 cm instead of
/// Ko & Badler's 5 cm lifts the stepping knee higher; a largest turn of 60° instead of their
/// 100° makes a 90° turn two turnarounds, twice as long, in `klaw turn` and in a scenario.
#[test]
fn an_nrs_model_file_changes_steps_and_turns() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("copy.toml"), NRS).unwrap();
    std::fs::write(
        d.join("high.toml"),
        edited(NRS, "swing_height = 0.05", "swing_height = 0.12"),
    )
    .unwrap();
    std::fs::write(
        d.join("t60.toml"),
        edited(NRS, "turn_max = 100.0", "turn_max = 60.0"),
    )
    .unwrap();
    let with = |command: &[&str], model: Option<&str>, out: &str| {
        let mut args = command.to_vec();
        args.extend(["--out", out]);
        if let Some(m) = model {
            args.extend(["--nrs-model", m]);
        }
        run(d, &args);
    };
    let step = ["step", "--side", "right", "--forward", "0.4"];
    with(&step, None, "bundled.csv");
    with(&step, Some("copy.toml"), "copy.csv");
    with(&step, Some("high.toml"), "high.csv");
    assert_eq!(bytes(d, "copy.csv"), bytes(d, "bundled.csv"));
    let knee = |f: &str| max(&column(d, f, "knee_flexion_r_deg"));
    let (low, high) = (knee("bundled.csv"), knee("high.csv"));
    assert!(
        high > low + 5.0,
        "peak right knee flexion {low}° and {high}°"
    );

    let turn = ["turn", "--angle", "90"];
    with(&turn, None, "t100.csv");
    with(&turn, Some("t60.toml"), "t60.csv");
    assert_eq!((rows(d, "t100.csv"), rows(d, "t60.csv")), (151, 301));
    std::fs::write(
        d.join("s.toml"),
        "[[action]]\ntype = \"turn\"\nangle = 90\nside = \"left\"\nkind = \"dynamic\"\n",
    )
    .unwrap();
    with(&["scenario", "s.toml"], None, "s100.csv");
    with(&["scenario", "s.toml"], Some("t60.toml"), "s60.csv");
    assert_eq!((rows(d, "s100.csv"), rows(d, "s60.csv")), (151, 301));
}

const GENERALIZE: &str = include_str!("../models/generalize.toml");

/// `--generalize-model` of `klaw prototype`, `generalize` and `walk --mode kinematic`: a bad
/// model file refused before any work, naming the file, the key and the rule; the dynamic mode
/// refuses the flag.
#[test]
fn a_bad_generalization_model_file_is_refused_naming_file_key_and_rule() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (from, to, parts) in [
        (
            "alpha2 = 22.31",
            "alpha2 = 200",
            &["alpha2 = 200 °/leg length is out of range: valid range is [-170, 170] °/leg length"]
                [..],
        ),
        (
            "contact_height = 0.001",
            "contact_height = -1",
            &["contact_height = -1 m is out of range: valid range is [0, 0.1] m"],
        ),
        (
            "check_samples = 100",
            "check_samples = 1",
            &["check_samples = 1 is out of range: valid range is [2, 1000000]"],
        ),
        ("slide_max = 1e-3\n", "", &["missing field `slide_max`"]),
        (
            "alpha1 = 0.00",
            "alpha1 = 0.00\nalpha5 = 1.0",
            &["line 18, column 1: unknown field `alpha5`"],
        ),
    ] {
        std::fs::write(d.join("bad.toml"), edited(GENERALIZE, from, to)).unwrap();
        let mut expect = vec!["malformed generalization model bad.toml: "];
        expect.extend(parts);
        for command in [
            &["prototype", "--from-walk", "--out", "p.json"][..],
            &["generalize", "--step-length", "0.7", "--out", "g.json"],
            &["walk", "--mode", "kinematic", "--out", "k.csv"],
        ] {
            let mut args = command.to_vec();
            args.extend(["--generalize-model", "bad.toml"]);
            refused_in(d, &args, &expect);
        }
    }
    refused_in(
        d,
        &[
            "generalize",
            "--step-length",
            "0.7",
            "--out",
            "g.json",
            "--generalize-model",
            "none.toml",
        ],
        &["reading generalization model none.toml: "],
    );
    std::fs::write(d.join("good.toml"), GENERALIZE).unwrap();
    refused_in(
        d,
        &["walk", "--generalize-model", "good.toml"],
        &["--generalize-model: applies to --mode kinematic only"],
    );
}

/// A copy of models/generalize.toml makes the bundled prototype byte-identically and walks it
/// byte-identically; α2 = 60 °/leg length instead of 22.31 makes a prototype whose walk at 1.0
/// m/s (a shorter step than its own) lands with the toes further up; a largest hip drop of 1 cm
/// instead of 5 cm refuses a step the bundled constants generalize to (its hip comes down 2.4
/// cm).
#[test]
fn a_generalization_model_file_changes_the_kinematic_walk() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("copy.toml"), GENERALIZE).unwrap();
    std::fs::write(
        d.join("alpha.toml"),
        edited(GENERALIZE, "alpha2 = 22.31", "alpha2 = 60.0"),
    )
    .unwrap();
    std::fs::write(
        d.join("drop.toml"),
        edited(GENERALIZE, "hip_drop_max = 0.05", "hip_drop_max = 0.01"),
    )
    .unwrap();
    run(d, &["prototype", "--from-walk", "--out", "p.json"]);
    run(
        d,
        &[
            "prototype",
            "--from-walk",
            "--out",
            "copy.json",
            "--generalize-model",
            "copy.toml",
        ],
    );
    run(
        d,
        &[
            "prototype",
            "--from-walk",
            "--out",
            "alpha.json",
            "--generalize-model",
            "alpha.toml",
        ],
    );
    assert_eq!(bytes(d, "copy.json"), bytes(d, "p.json"));
    let walk = |prototype: &str, model: Option<&str>, out: &str| {
        let mut args = vec![
            "walk",
            "--mode",
            "kinematic",
            "--velocity",
            "1.0",
            "--steps",
            "3",
            "--no-plot",
            "--prototype",
            prototype,
            "--out",
            out,
        ];
        if let Some(m) = model {
            args.extend(["--generalize-model", m]);
        }
        let o = klaw(d, &args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    walk("p.json", None, "bundled.csv");
    assert_eq!(walk("p.json", Some("copy.toml"), "copy.csv"), "");
    walk("alpha.json", None, "alpha.csv");
    assert_eq!(bytes(d, "copy.csv"), bytes(d, "bundled.csv"));
    let ankle = |f: &str| max(&column(d, f, "ankle_dorsiflexion_r_deg"));
    let (bundled, alpha) = (ankle("bundled.csv"), ankle("alpha.csv"));
    assert!(
        alpha > bundled + 1.0,
        "peak ankle dorsiflexion {bundled}° and {alpha}°"
    );
    // the α of a file given to the walk are not the prototype's: said, not used
    let said = walk("p.json", Some("alpha.toml"), "warned.csv");
    assert!(said.starts_with("warning: alpha.toml's α slopes"), "{said}");
    assert_eq!(bytes(d, "warned.csv"), bytes(d, "bundled.csv"));

    run(
        d,
        &["generalize", "--step-length", "0.6", "--out", "g.json"],
    );
    refused_in(
        d,
        &[
            "generalize",
            "--step-length",
            "0.6",
            "--out",
            "h.json",
            "--generalize-model",
            "drop.toml",
        ],
        &[
            "step length 0.6 m is too short for this body",
            "(at most 0.01 m allowed)",
        ],
    );
}

const ENGINE: &str = include_str!("../models/engine.toml");

/// The engine's model constants (`--engine-model`, models/engine.toml's layout): a bad file is
/// refused naming the file and the key, before any work; a flag the command cannot use is
/// refused; a copy of the bundled file walks byte-identically; a stiffer leg servo changes the
/// walk's pelvis height.
#[test]
fn an_engine_model_file_is_checked_and_changes_the_walk() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let write = |name: &str, text: &str| std::fs::write(d.join(name), text).unwrap();
    write(
        "neg.toml",
        &edited(ENGINE, "damping_ratio = 0.7", "damping_ratio = -0.7"),
    );
    write("missing.toml", &edited(ENGINE, "foot_samples = 100\n", ""));
    write("copy.toml", ENGINE);
    write(
        "stiff.toml",
        &edited(ENGINE, "leg_frequency = 5.0", "leg_frequency = 8.0"),
    );
    refused_in(
        d,
        &["walk", "--engine-model", "neg.toml"],
        &["neg.toml", "damping_ratio"],
    );
    refused_in(
        d,
        &["walk", "--engine-model", "missing.toml"],
        &["missing.toml", "foot_samples"],
    );
    refused_in(d, &["walk", "--engine-model", "none.toml"], &["none.toml"]);
    refused_in(
        d,
        &["walk", "--mode", "kinematic", "--engine-model", "copy.toml"],
        &["engine-model", "dynamic"],
    );
    let walk = |out: &str, model: Option<&str>| {
        let mut args = vec!["walk", "--steps", "4", "--no-plot", "--out", out];
        if let Some(m) = model {
            args.extend(["--engine-model", m]);
        }
        run(d, &args);
    };
    walk("bundled.csv", None);
    walk("copy.csv", Some("copy.toml"));
    walk("stiff.csv", Some("stiff.toml"));
    assert_eq!(bytes(d, "bundled.csv"), bytes(d, "copy.csv"));
    let (a, b) = (
        column(d, "bundled.csv", "pelvis_ty_m"),
        column(d, "stiff.csv", "pelvis_ty_m"),
    );
    let largest = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(largest > 1e-5, "{largest}");
}
