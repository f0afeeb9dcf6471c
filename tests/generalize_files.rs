//! Walk data in and out: JSON and CSV round trips and their errors, and the measured-walk CSV of
//! docs/generalize.md, here written from klaw's own walk (its sagittal landmarks), read back as
//! the same prototype as the one extracted from the walk directly; a rigid foot (ball = toe)
//! accepted; every malformed clip a named error.
use klaw::generalize::extract::from_walk;
use klaw::generalize::measured::{self, columns};
use klaw::generalize::text::{from_csv, from_json, to_csv, to_json};
use klaw::generalize::{GeneralizeError, GeneralizeParameters, KinematicWalk, WalkData};

fn params() -> GeneralizeParameters {
    GeneralizeParameters::default()
}

fn walk() -> klaw::Walk {
    klaw::Simulation::default().steps(8).run().unwrap()
}

/// The walk's sagittal landmarks from `from` to `to` s at `fps` as the measured-walk CSV.
fn measured_csv(walk: &klaw::Walk, fps: f64, from: f64, to: f64) -> String {
    let mut out = format!("# klaw's default walk\n{}\n", columns().join(","));
    for lm in walk.frames(fps).unwrap() {
        if lm.time < from || lm.time > to {
            continue;
        }
        let mut row = vec![lm.time];
        for leg in [lm.right, lm.left] {
            for p in [leg.hip, leg.knee, leg.ankle, leg.heel, leg.mtp, leg.toe] {
                row.extend([p[0], p[1]]);
            }
        }
        let cells: Vec<String> = row.iter().map(|x| x.to_string()).collect();
        out += &(cells.join(",") + "\n");
    }
    out
}

/// Replace column `name`'s cells by `f(row, cell)`.
fn edit(csv: &str, name: &str, f: impl Fn(usize, &str) -> String) -> String {
    let mut lines = csv.lines();
    let mut out = String::new();
    out += lines.next().unwrap();
    out.push('\n');
    let header = lines.next().unwrap();
    let j = header.split(',').position(|c| c == name).unwrap();
    out += header;
    out.push('\n');
    for (i, l) in lines.enumerate() {
        let mut c: Vec<String> = l.split(',').map(str::to_string).collect();
        c[j] = f(i, &c[j]);
        out += &(c.join(",") + "\n");
    }
    out
}

fn same(a: &WalkData, b: &WalkData) {
    let (x, y) = (to_json(a).unwrap(), to_json(b).unwrap());
    if let Some(i) = x.lines().zip(y.lines()).position(|(p, q)| p != q) {
        panic!(
            "line {i}: {} vs {}",
            x.lines().nth(i).unwrap(),
            y.lines().nth(i).unwrap()
        );
    }
    assert!(a == b, "equal JSON, unequal data");
}

/// JSON and CSV give the walk data back exactly; a broken file names what is wrong.
#[test]
fn walk_data_round_trips_through_json_and_csv() {
    let w = from_walk(walk().engine(), 3, &params()).unwrap();
    same(&from_json(&to_json(&w).unwrap()).unwrap(), &w);
    let csv = to_csv(&w).unwrap();
    same(&from_csv(&csv).unwrap(), &w);
    let e = from_csv(&csv.replace("step_length_before,", "step_length_befor,")).unwrap_err();
    assert!(e.to_string().contains("step_length_befor"), "{e}");
    let e = from_csv(&csv.replace("phases.tom,,", "phases.tomm,,")).unwrap_err();
    assert!(e.to_string().contains("phases.tom"), "{e}");
    let e = from_json(&to_json(&w).unwrap().replace("\"tom\": 0.", "\"tom\": 1.")).unwrap_err();
    assert!(e.to_string().contains("phases"), "{e}");
    let mut bad = w.clone();
    bad.hip.t[3] = bad.hip.t[2];
    let e = to_json(&bad).unwrap_err().to_string();
    assert!(e.contains("hip") && e.contains("increasing"), "{e}");
}

/// The measured layout written from klaw's walk (steps 2…5 at 100 frames/s) reads back as the
/// prototype extracted from the walk itself: the step lengths to 0.1 mm, heel-off to a frame,
/// foot flat and toe-off to three, the attributes at heel strike to 0.5° and at toe-off to 2°, the hip at heel strike to
/// 2 mm (the heel strike dated where the heel comes within 1 mm of the floor, which it nears
/// slowly: the hip is then 1–1.5 mm higher; 1.50 mm since the metatarsal limit is 40°);
/// and it walks on klaw's body.
#[test]
fn a_measured_walk_reads_as_the_walks_own_prototype() {
    let walk = walk();
    let t = walk.engine().steps[2].t_start;
    let csv = measured_csv(&walk, 100.0, t - 0.05, t + 3.0 * 0.5555);
    let m = measured::from_csv(&csv, &params()).unwrap();
    let k = from_walk(walk.engine(), 2, &params()).unwrap();
    assert!(
        (m.step_length - k.step_length).abs() < 1e-4,
        "{} {}",
        m.step_length,
        k.step_length
    );
    assert!((m.step_length_before - k.step_length_before).abs() < 1e-4);
    let frame = 0.01 / 0.5555;
    // foot flat and toe-off to three frames: the foot comes down flat and leaves the floor
    // tangentially (with the hip's lead it lands with its pitch slowing to 0), so the reader's
    // 1e-6 rad crossing between 100 Hz samples comes 1.3–2.1 frames after the walk's events
    for (a, b, frames) in [
        (m.phases.fgm, k.phases.fgm, 3.0),
        (m.phases.tom, k.phases.tom, 3.0),
        (m.phases.heel_off, k.phases.heel_off, 1.0),
    ] {
        assert!((a - b).abs() <= frames * frame + 1e-9, "{a} vs {b}");
    }
    let (cm, ck) = (m.character, k.character);
    for (a, b, tol) in [
        (cm.foot_at_strike, ck.foot_at_strike, 0.5),
        (cm.knee_at_strike, ck.knee_at_strike, 0.5),
        // the foot turns ≈ 0.5° a millisecond at toe-off, which the toe's 1 mm rise dates
        (cm.foot_at_toe_off, ck.foot_at_toe_off, 2.0),
        (cm.meta_at_toe_off, ck.meta_at_toe_off, 2.0),
    ] {
        assert!((a - b).abs() < f64::to_radians(tol), "{a} vs {b}");
    }
    let dy = m.hip.last()[1] - k.hip.last()[1];
    assert!(dy.abs() < 2e-3, "{dy}");
    let body = *walk.body();
    let kin = KinematicWalk::new(
        &m,
        body,
        klaw::model::attributes::AttributeTable::builtin().defaults(),
        walk.gaits()[0],
        4,
        &params(),
    );
    assert!(kin.is_ok(), "{}", kin.unwrap_err());
    // a foot without toes: ball = toe
    let mut rigid = csv.clone();
    for side in ["r", "l"] {
        for axis in ["x", "y"] {
            let ball: Vec<String> = {
                let header: Vec<&str> = csv.lines().nth(1).unwrap().split(',').collect();
                let j = header
                    .iter()
                    .position(|c| *c == format!("ball_{side}_{axis}_m"))
                    .unwrap();
                csv.lines()
                    .skip(2)
                    .map(|l| l.split(',').nth(j).unwrap().to_string())
                    .collect()
            };
            rigid = edit(&rigid, &format!("toe_{side}_{axis}_m"), |i, _| {
                ball[i].clone()
            });
        }
    }
    let r = measured::from_csv(&rigid, &params()).unwrap();
    assert_eq!(r.body.ball_to_toe, 0.0);
    assert_eq!(r.character.meta_at_toe_off, 0.0);
    assert_eq!(r.character.alpha[3], 0.0);
    assert_eq!(r.phases.mom, 1.0 + r.phases.tom);
}

/// Each malformed clip is refused with an error naming what is wrong.
#[test]
fn malformed_measured_walks_are_named_errors() {
    let walk = walk();
    let t = walk.engine().steps[2].t_start;
    let csv = measured_csv(&walk, 100.0, t - 0.05, t + 1.7);
    let p = params();
    let err = |text: &str| measured::from_csv(text, &p).unwrap_err().to_string();
    let e = err(&csv.replace("knee_l_y_m", "knee_l_z_m"));
    assert!(e.contains("knee_l_z_m"), "{e}");
    let e = err(&edit(&csv, "ankle_r_x_m", |i, c| {
        if i == 5 { "NaN".into() } else { c.into() }
    }));
    assert!(e.contains("frame 5") && e.contains("ankle_r_x_m"), "{e}");
    let e = err(&edit(&csv, "heel_l_y_m", |i, c| {
        if i == 7 { String::new() } else { c.into() }
    }));
    assert!(e.contains("heel_l_y_m"), "{e}");
    let e = err(&edit(&csv, "time_s", |i, c| {
        if i == 9 { "0".into() } else { c.into() }
    }));
    assert!(e.contains("frame 9") && e.contains("time_s"), "{e}");
    let e = err(&edit(&csv, "knee_r_y_m", |i, c| {
        if i == 12 {
            (c.parse::<f64>().unwrap() + 0.1).to_string()
        } else {
            c.into()
        }
    }));
    assert!(e.contains("thigh") && e.contains("frame 12"), "{e}");
    let e = err(&edit(&csv, "toe_l_y_m", |i, c| {
        if i == 3 { "-0.05".into() } else { c.into() }
    }));
    assert!(e.contains("below the floor"), "{e}");
    // half a stride
    let short = measured_csv(&walk, 100.0, t - 0.05, t + 0.6);
    assert!(err(&short).contains("not closed"), "{}", err(&short));
    // 5 frames/s: too few frames over the step
    let sparse = measured_csv(&walk, 7.0, t - 0.3, t + 2.5);
    match measured::from_csv(&sparse, &p) {
        Err(GeneralizeError::TooFewFrames { frames, min, .. }) => assert!(frames < min),
        other => panic!("{other:?}"),
    }
}
