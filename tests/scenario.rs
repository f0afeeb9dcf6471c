//! Scenarios (issue 15): starts, walks, stops, steps and turns run one after the other, with
//! the pelvis continuous and its velocity jumping by at most 0.05 m/s at every hand-over, and
//! no clinical angle changing between frames at 100 fps by more than 0.5° beyond what the same
//! frames show inside a walk; deterministic.
use klaw::figure::clinical::{angle_columns, clinical};
use klaw::model::attributes::AttributeTable;
use klaw::model::body::Body;
use klaw::nrs::{Side, TurnKind};
use klaw::plan::GaitRequest;
use klaw::scenario::{Action, Goal, Motion, Scenario, run};

const FPS: f64 = 100.0;

fn scenario(actions: Vec<Action>) -> Scenario {
    Scenario {
        body: Body::standard(1.8, 80.0).unwrap(),
        attrs: AttributeTable::builtin().defaults(),
        nrs: klaw::nrs::NrsParameters::default(),
        actions,
    }
}

fn walk(steps: usize, velocity: f64) -> Action {
    Action::Walk {
        gaits: vec![
            GaitRequest {
                velocity: Some(velocity),
                ..Default::default()
            };
            steps
        ],
    }
}

/// A step of the `side` foot `left` metres to the figure's left.
fn side_step(side: Side, left: f64) -> Action {
    Action::Step {
        side,
        goal: Goal::Relative {
            forward: 0.0,
            left,
            turn: 0.0,
        },
        duration: None,
        swing_height_factor: None,
        gaze: None,
        foot_angles: None,
    }
}

fn table() -> Scenario {
    scenario(vec![
        Action::Stand {
            seconds: 0.5,
            at: Some([1.0, 2.0]),
            facing: Some(0.4),
        },
        walk(4, 1.2),
        side_step(Side::Left, 0.35),
        side_step(Side::Right, 0.35),
        Action::Turn {
            angle: 180f64.to_radians(),
            side: Side::Left,
            kind: TurnKind::Stationary,
            step_duration: None,
        },
        walk(3, 1.0),
        Action::Pause { seconds: 0.3 },
    ])
}

/// The largest per-frame change of each clinical angle (deg) within `frames[a..b]`.
fn jumps(m: &Motion, body: &Body, a: usize, b: usize) -> Vec<(String, f64, usize)> {
    let cols = angle_columns();
    let c: Vec<_> = m.frames[a..b]
        .iter()
        .map(|lm| clinical(lm, body).unwrap())
        .collect();
    cols.iter()
        .map(|col| {
            let mut worst = (0.0, 0);
            for k in 1..c.len() {
                let d = ((col.get)(&c[k]) - (col.get)(&c[k - 1])).abs();
                if d > worst.0 {
                    worst = (d, a + k);
                }
            }
            (col.name.clone(), worst.0.to_degrees(), worst.1)
        })
        .collect()
}

/// The frame rate of the velocity checks: the engine's hip velocity left by the heel-strike
/// impulse decays in ≈ 15 ms after each heel strike (the stance servo absorbing the leg's
/// shortening), which one-sided differences over 10 ms frames cannot follow (they read it as a
/// jump of 0.17 m/s at a start's hand-over; 2e-4 m/s at 1 ms).
const FINE_FPS: f64 = 1000.0;

/// The change of the pelvis velocity at frame k of a motion sampled at `fps` (m/s):
/// second-order one-sided differences on either side, which agree to O(Δt²) where the path is
/// C¹.
fn kink(m: &Motion, k: usize, fps: f64) -> f64 {
    let p = |i: usize, c: usize| m.frames[i].pelvis[c];
    (0..3)
        .map(|c| {
            let before = (3.0 * p(k, c) - 4.0 * p(k - 1, c) + p(k - 2, c)) * fps / 2.0;
            let after = (-3.0 * p(k, c) + 4.0 * p(k + 1, c) - p(k + 2, c)) * fps / 2.0;
            (after - before).powi(2)
        })
        .sum::<f64>()
        .sqrt()
}

/// Every hand-over: the pelvis velocity jumps by at most 0.05 m/s (a stop included: it takes
/// over `stop_handover` after the walk's last heel strike, where the engine's hip velocity,
/// which jumps at every heel strike, runs smooth again), and no clinical angle changes between
/// frames by more than 0.5° beyond the largest change inside the walks.
#[test]
fn hand_overs_are_continuous() {
    let s = table();
    let m = run(&s, FPS).unwrap();
    let kinds: Vec<&str> = m.spans.iter().map(|s| s.kind).collect();
    assert_eq!(
        kinds,
        [
            "stand", "start", "walk", "stop", "step", "step", "turn", "start", "walk", "stop",
            "pause"
        ]
    );
    let body = s.body;
    let fine = run(&s, FINE_FPS).unwrap();
    // the walks' own frame-to-frame changes
    let index = |t: f64| (t * FPS).round() as usize;
    let fine_index = |t: f64| (t * FINE_FPS).round() as usize;
    let mut inside = std::collections::HashMap::<String, f64>::new();
    let mut heel_strike: f64 = 0.0;
    for sp in m.spans.iter().filter(|s| s.kind == "walk") {
        for k in fine_index(sp.t_start) + 3..fine_index(sp.t_end) - 3 {
            heel_strike = heel_strike.max(kink(&fine, k, FINE_FPS));
        }
        for (name, d, _) in jumps(&m, &body, index(sp.t_start) + 1, index(sp.t_end) - 1) {
            let e = inside.entry(name).or_insert(0.0);
            *e = e.max(d);
        }
    }
    eprintln!("inside the walks: the pelvis velocity jumps up to {heel_strike:.3} m/s");
    for sp in &m.spans[1..] {
        let k = index(sp.t_start);
        // pelvis velocity on either side of the hand-over
        let jump = kink(&fine, fine_index(sp.t_start), FINE_FPS);
        let allowed = 0.05;
        eprintln!(
            "{} at {:.2}: velocity jump {jump:.3} m/s",
            sp.kind, sp.t_start
        );
        assert!(
            jump <= allowed,
            "{} at {:.2}: velocity jumps {jump:.3} m/s, {allowed:.3} allowed",
            sp.kind,
            sp.t_start
        );
        for (name, d, at) in jumps(&m, &body, k.saturating_sub(3), (k + 4).min(m.frames.len())) {
            let allowed = inside.get(&name).copied().unwrap_or(0.0) + 0.5;
            assert!(
                d <= allowed,
                "{name} jumps {d:.2}° at frame {at} ({} at {:.2} s), {allowed:.2}° allowed",
                sp.kind,
                sp.t_start
            );
        }
    }
}

/// The same scenario twice gives the same frames, bit for bit.
#[test]
fn scenarios_are_deterministic() {
    let a = run(&table(), FPS).unwrap();
    let b = run(&table(), FPS).unwrap();
    assert_eq!(a.frames, b.frames);
    assert_eq!(a.footprints, b.footprints);
}

/// Every example scenario runs, within the hand-over bounds of `hand_overs_are_continuous`'s
/// kind checked coarsely here: the pelvis moves less than 5 cm between frames at 100 fps.
#[test]
fn the_example_scenarios_run() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenarios");
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    names.sort();
    assert!(names.len() >= 3);
    for path in names {
        let s = klaw::scenario::read_scenario(&path).unwrap();
        let m = run(&s, FPS).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        for w in m.frames.windows(2) {
            let d = (0..3)
                .map(|c| (w[1].pelvis[c] - w[0].pelvis[c]).powi(2))
                .sum::<f64>();
            assert!(
                d.sqrt() < 0.05,
                "{}: the pelvis jumps at {}",
                path.display(),
                w[1].time
            );
        }
        eprintln!(
            "{}: {:.2} s, {} frames, {} footprints",
            path.display(),
            m.frames.last().unwrap().time,
            m.frames.len(),
            m.footprints.len()
        );
    }
}

/// A turn past ±180°: the exported pelvis rotation stays continuous and ends at the turn the
/// scenario asks for (the spin example: 270° to the right from facing 0, −270°), in the clinical
/// angles, the CSV, the .mot and the BVH root's Yrotation.
#[test]
fn a_turn_past_180_degrees_exports_a_continuous_rotation() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenarios/spin.toml");
    let s = klaw::scenario::read_scenario(&path).unwrap();
    let m = run(&s, FPS).unwrap();
    let clin: Vec<f64> = m
        .frames
        .iter()
        .map(|lm| clinical(lm, &s.body).unwrap().pelvis_rotation.to_degrees())
        .collect();
    let dir = std::env::temp_dir().join(format!("klaw-spin-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let column = |ext: &str| -> Vec<f64> {
        let out = dir.join(format!("spin.{ext}"));
        let format = klaw::export::Format::from_path(&out).unwrap();
        let options = klaw::export::Options::default();
        klaw::export::write(
            &out,
            format,
            &s.body,
            FPS,
            m.frames.iter().copied(),
            &options,
        )
        .unwrap();
        let text = std::fs::read_to_string(&out).unwrap();
        match ext {
            "csv" => {
                let mut lines = text.lines();
                let head: Vec<&str> = lines.next().unwrap().split(',').collect();
                let i = head
                    .iter()
                    .position(|h| *h == "pelvis_rotation_deg")
                    .unwrap();
                lines
                    .map(|l| l.split(',').nth(i).unwrap().parse().unwrap())
                    .collect()
            }
            "mot" => {
                let mut lines = text.split("endheader").nth(1).unwrap().trim().lines();
                let head: Vec<&str> = lines.next().unwrap().split('\t').collect();
                let i = head.iter().position(|h| *h == "pelvis_rotation").unwrap();
                lines
                    .map(|l| l.split('\t').nth(i).unwrap().parse().unwrap())
                    .collect()
            }
            _ => {
                // the root's channels: 3 positions, then Yrotation
                let motion = text.split("Frame Time:").nth(1).unwrap();
                motion
                    .lines()
                    .skip(1)
                    .map(|l| l.split(' ').nth(3).unwrap().parse().unwrap())
                    .collect()
            }
        }
    };
    for (what, v) in [
        ("clinical", clin),
        ("csv", column("csv")),
        ("mot", column("mot")),
        ("bvh", column("bvh")),
    ] {
        let step = v
            .windows(2)
            .map(|w| (w[1] - w[0]).abs())
            .fold(0.0, f64::max);
        assert!(
            step < 5.0,
            "{what}: the pelvis rotation jumps {step:.1}° in a frame"
        );
        let last = *v.last().unwrap();
        assert!(
            (last + 270.0).abs() < 1.0,
            "{what}: ends at {last:.2}°, not −270°"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
