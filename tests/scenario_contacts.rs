//! A scenario's foot contacts (`klaw scenario --events`), found on the continuous motion by the
//! height of each foot's lowest point, checked against what they must agree with: the walking
//! engine's heel strikes (its dynamics, not the feet's geometry), the frames sampled
//! independently, and the steps each action takes.
use klaw::figure::Landmarks;
use klaw::nrs::NrsParameters;
use klaw::scenario::contacts::lowest;
use klaw::scenario::{Contact, Motion, read_scenario, run};

const FPS: f64 = 200.0;

fn example(name: &str) -> Motion {
    let path = format!(
        "{}/examples/scenarios/{name}.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    run(&read_scenario(std::path::Path::new(&path)).unwrap(), FPS).unwrap()
}

fn foot<'a>(lm: &'a Landmarks, side: &str) -> &'a klaw::figure::LegPoints {
    if side == "right" { &lm.right } else { &lm.left }
}

fn of<'a>(m: &'a Motion, side: &'a str) -> impl Iterator<Item = &'a Contact> + 'a {
    m.contacts.iter().filter(move |c| c.side == side)
}

#[test]
fn every_walking_heel_strike_is_a_foot_strike_just_before_it() {
    let m = example("table");
    let mut walk_strikes = 0;
    for f in m.footprints.iter().filter(|f| {
        m.spans.iter().any(|s| {
            s.kind == "walk"
                && s.action == f.action
                && f.time > s.t_start + 1e-9
                && f.time <= s.t_end + 1e-9
        })
    }) {
        let side = if f.side == klaw::nrs::Side::Right {
            "right"
        } else {
            "left"
        };
        // the heel falls the last millimetre at ≥ 0.05 m/s: within 20 ms of the engine's strike
        let near = of(&m, side)
            .filter(|c| c.event == "foot_strike")
            .any(|c| c.time_s <= f.time + 1e-6 && c.time_s > f.time - 0.02);
        assert!(
            near,
            "no foot strike of the {side} foot just before {:.3} s",
            f.time
        );
        walk_strikes += 1;
    }
    assert!(
        walk_strikes >= 5,
        "{walk_strikes} walking heel strikes checked"
    );
}

#[test]
fn contacts_alternate_and_agree_with_the_frames() {
    let h = NrsParameters::default().contact_height;
    for name in ["table", "doorway", "spin"] {
        let m = example(name);
        for side in ["right", "left"] {
            let list: Vec<&Contact> = of(&m, side).collect();
            assert!(!list.is_empty(), "{name}: the {side} foot never moves");
            // from standing the first event lifts the foot, then strike and off alternate
            for (k, c) in list.iter().enumerate() {
                let want = if k % 2 == 0 {
                    "foot_off"
                } else {
                    "foot_strike"
                };
                assert_eq!(
                    c.event, want,
                    "{name}, {side} event {k} at {:.4} s",
                    c.time_s
                );
            }
            assert_eq!(
                list.last().unwrap().event,
                "foot_strike",
                "{name}: ends standing"
            );
            // every frame away from an event (by more than a frame) is on or off the floor as
            // the events say
            for lm in &m.frames {
                let t = lm.time;
                if list.iter().any(|c| (c.time_s - t).abs() < 1.0 / FPS) {
                    continue;
                }
                let off = list.iter().filter(|c| c.time_s < t).count() % 2 == 1;
                let y = lowest(foot(lm, side));
                assert_eq!(
                    y > h,
                    off,
                    "{name}, {side} foot at {t:.3} s: lowest point {y:.5} m"
                );
            }
        }
    }
}

#[test]
fn a_step_lifts_and_sets_down_its_foot_once_and_a_turnaround_each_foot_once() {
    steps_lift_once(&example("table"));
}

/// The same with the hip's lead at heel strike (docs/realism.md): its walking steps'
/// plantarflexed push-off put the stop step's toe back on the floor just after it left,
/// until the airborne foot kept its toe above the engine's rising floor (docs/nrs.md).
#[test]
fn with_the_hip_lead_a_step_still_lifts_its_foot_once() {
    let path = format!(
        "{}/examples/scenarios/table.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(path).unwrap()
        + "\n[attributes]\nhip_lead_slope = 0.595\nheel_off_dorsiflexion = 8.0\n";
    let dir = std::env::temp_dir().join(format!("klaw-lead-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("table-lead.toml");
    std::fs::write(&file, text).unwrap();
    let m = run(&read_scenario(&file).unwrap(), FPS);
    std::fs::remove_dir_all(&dir).unwrap();
    steps_lift_once(&m.unwrap());
}

fn steps_lift_once(m: &Motion) {
    for s in &m.spans {
        let inside: Vec<&Contact> = m
            .contacts
            .iter()
            .filter(|c| c.time_s > s.t_start - 1e-9 && c.time_s <= s.t_end + 1e-9)
            .collect();
        match s.kind {
            "step" | "start" | "stop" => assert_eq!(inside.len(), 2, "{s:?}: {inside:?}"),
            // the table's 180° turn is two turnarounds of 90°, two steps each
            "turn" => assert_eq!(inside.len(), 8, "{s:?}: {inside:?}"),
            "stand" | "pause" => assert!(inside.is_empty(), "{s:?}: {inside:?}"),
            _ => {}
        }
    }
}
