//! Validation of the inverse kinematics as Pronost et al. §6 do it, on klaw's own walks: the
//! hip and knee angles recovered from a walk's poulaine against the walk's own (eq. 7, Table 2),
//! over speeds and heights; and leave-one-out: a walk's poulaine removed from the database, the
//! poulaine the database gives for its parameters drives the IK. docs/ik.md has the numbers and
//! why klaw's knee and hip rotation stay above Table 2; the larger grids are in
//! `measure/ik_validation.rs`.
use klaw::ik::Ik;
use klaw::poulaine::Trajectory;
use klaw::poulaine::build::{Grid, synthetic};
use klaw::poulaine::database::clamp_to_reach;
use klaw::poulaine::trajectory::cycle_frames;
use klaw::poulaine::validate::{Recovery, TABLE2, frames_angles, recover, recover_referenced};
use klaw::{Body, Simulation};

const RATE: f64 = 60.0;

fn body(h: f64) -> Body {
    Body::standard(h, 23.0 * h * h).unwrap()
}

/// The six speeds and heights (H m, v m/s) the own-poulaine tests run.
const SIX: [(f64, f64); 6] = [
    (1.6, 0.9),
    (1.6, 1.4),
    (1.8, 1.0),
    (1.8, 1.6),
    (2.0, 1.2),
    (2.0, 1.8),
];

/// The walk of H `h` at `v`: its body, own poulaine (samples at 60 Hz) and angles.
fn walk_of(h: f64, v: f64) -> (Body, Trajectory, Vec<klaw::ik::chain::Angles>) {
    let b = body(h);
    let walk = Simulation::new(b).velocity(v).steps(6).run().unwrap();
    let (poulaine, frames) = Trajectory::from_walk(&walk, RATE).unwrap();
    let truth = frames_angles(&frames, &b).unwrap();
    (b, poulaine, truth)
}

/// IK on the walk's own poulaine (samples at 60 Hz).
fn own(h: f64, v: f64) -> Recovery {
    let (b, poulaine, truth) = walk_of(h, v);
    recover(&Ik::new(&b), &poulaine, &truth).unwrap()
}

/// Nothing is lost to the task: with f3 pulling towards the walk's own angles at each frame
/// (`Ik::solve_referenced`) and no kinetic term, the IK gives them back (≤ 0.01 rad on every
/// angle of the chain; docs/ik.md measures 0.008 at worst over 16 walks), so the errors of
/// the default solve are the secondary tasks' choice in the null space. With the rest posture
/// instead, the same solve is far off (pelvis rotation > 0.1 rad).
#[test]
fn the_walks_own_angles_as_reference_come_back() {
    let (b, poulaine, truth) = walk_of(1.8, 1.2);
    let mut ik = Ik::new(&b);
    ik.model.weights.energy = 0.0;
    let r = recover_referenced(&ik, &poulaine, &truth, Some(&truth)).unwrap();
    show("own angles as reference", &r);
    assert!(r.rms.iter().all(|&e| e < 0.01), "{:?}", r.rms);
    let rest = recover(&ik, &poulaine, &truth).unwrap();
    assert!(rest.table2("pelvis_rotation") > 0.1, "{:?}", rest.rms);
    let short = recover_referenced(&ik, &poulaine, &truth, Some(&truth[1..]));
    assert!(short.unwrap_err().to_string().contains("one per target"));
}

fn show(what: &str, r: &Recovery) {
    let cols: Vec<String> = TABLE2
        .iter()
        .map(|(n, _)| format!("{n} {:.3}", r.table2(n)))
        .collect();
    eprintln!("{what}: {}", cols.join(", "));
}

/// Six speeds and heights: the closed loop within 1 mm and every angle within its limits (the
/// method's own guarantees), and the recovered angles' RMS errors against the walk's (eq. 7,
/// rad) as a snapshot, reviewed when it changes. They are above Table 2's (hip flexion 0.05,
/// abduction 0.04, rotation 0.03, knee 0.02 rad), and no published value holds klaw's: klaw's
/// imposed determinants of gait (pelvic rotation and list ±4°) lie in the null space, where
/// the secondary tasks choose other pelvis motions, and klaw's straight stance knee turns each
/// millimetre of hip height into ≈ 0.1 rad of knee (docs/ik.md).
#[test]
fn the_hip_and_knee_angles_of_klaws_walks_are_recovered() {
    let mut table =
        String::from("H (m), v (m/s): RMS hip flexion, adduction, rotation, knee (rad)\n");
    for (h, v) in SIX {
        let r = own(h, v);
        show(&format!("H {h} v {v}"), &r);
        assert!(r.residual <= 1e-3 && r.within_limits);
        table += &format!(
            "H {h}, v {v}: {:.3}, {:.3}, {:.3}, {:.3}\n",
            r.table2("hip_flexion"),
            r.table2("hip_adduction"),
            r.table2("hip_rotation"),
            r.table2("knee_flexion")
        );
    }
    insta::assert_snapshot!(table);
}

/// IK on the walk's own poulaine with f3 towards the angles of a database of other walks
/// (heights 1.6 and 2.0 m at other step lengths: none of the six; `klaw ik --poulaine P --db
/// DB`): over six speeds
/// and heights the mean errors of the hip and knee angles meet Table 2 (hip flexion 0.05,
/// abduction 0.04, rotation 0.03, knee 0.02 rad), every walk's within twice them, the ankles
/// within 1 mm and every angle within its limits.
#[test]
fn the_hip_and_knee_angles_meet_table_2_with_the_databases_angles() {
    let grid = Grid {
        heights: vec![1.6, 2.0],
        step_lengths: vec![0.5, 0.65, 0.8, 0.95],
        attributes: vec![],
    };
    let (db, _) = synthetic(&grid).unwrap();
    let mut all = Vec::new();
    for (h, v) in SIX {
        let (b, poulaine, truth) = walk_of(h, v);
        let same = |e: &klaw::poulaine::Entry| {
            e.height == Some(h) && (e.velocity.unwrap() - v).abs() < 0.01
        };
        assert!(
            !db.entries.iter().any(same),
            "H {h} v {v} is in the database"
        );
        let reference = db.reference(&poulaine, b.l1, false).unwrap();
        let mut ik = Ik::new(&b);
        ik.model.weights.energy = ik.model.weights.energy_with_reference;
        let r = recover_referenced(&ik, &poulaine, &truth, Some(&reference.angles)).unwrap();
        show(&format!("H {h} v {v}, the database's angles"), &r);
        assert!(r.residual <= 1e-3 && r.within_limits);
        all.push(r);
    }
    for (n, bound) in TABLE2.iter().skip(3) {
        let each: Vec<f64> = all.iter().map(|r| r.table2(n)).collect();
        let mean = each.iter().sum::<f64>() / each.len() as f64;
        assert!(mean <= *bound, "{n}: mean {mean}");
        assert!(each.iter().all(|e| *e <= 2.0 * bound), "{n}: {each:?}");
    }
}

/// Leave-one-out: for each walk of a small database, the database without it gives the
/// poulaine for the walk's parameters (its leg, trace, spacing and stance, its period), clamped
/// to the leg's reach; the IK on it recovers the walk's hip and knee angles within 0.1 rad
/// (hip flexion), 0.25 rad (knee and the other hip angles). With f3 pulling towards the
/// selected entry's angles at each phase (`Database::reference`, the kinetic weight
/// `energy_with_reference`) every walk's pelvis rotation, hip flexion and hip rotation come
/// closer than with the rest posture, and over the walks the mean errors of pelvis tilt, hip
/// flexion and hip rotation meet Table 2 (0.03, 0.05, 0.03 rad).
#[test]
fn leave_one_out_recovers_the_left_out_walk() {
    let grid = Grid {
        heights: vec![1.7, 1.9],
        step_lengths: vec![0.65, 0.8],
        attributes: vec![("step_width".into(), vec![0.06, 0.1])],
    };
    let (db, skipped) = synthetic(&grid).unwrap();
    assert!(skipped.is_empty());
    let mut referenced = Vec::new();
    for e in db.entries.iter().take(4) {
        let b = body(e.height.unwrap());
        let walk = Simulation::new(b)
            .attributes(
                klaw::AttributeTable::builtin()
                    .resolve(&e.attributes, "test")
                    .unwrap(),
            )
            .gait(klaw::GaitRequest {
                step_length: Some(e.step_length),
                ..Default::default()
            })
            .steps(6)
            .run()
            .unwrap();
        let (frames, _, period) = cycle_frames(&walk, RATE).unwrap();
        let truth = frames_angles(&frames, &b).unwrap();
        let rest = db.without(&e.label);
        let (model, _) = rest.poulaine(&e.axes, b.l1, period);
        let mut poulaine = model.sample(frames.len());
        clamp_to_reach(&mut poulaine, b.l0 / 2.0, Ik::new(&b).params.reach * b.l1);
        let r = recover(&Ik::new(&b), &poulaine, &truth).unwrap();
        show(&format!("leave-one-out {}", e.label), &r);
        assert!(r.within_limits);
        assert!(r.table2("hip_flexion") <= 0.1);
        for n in ["hip_adduction", "hip_rotation", "knee_flexion"] {
            assert!(r.table2(n) <= 0.25, "{n}: {}", r.table2(n));
        }
        let reference = rest.reference(&poulaine, b.l1, false).unwrap().angles;
        let mut ik = Ik::new(&b);
        ik.model.weights.energy = ik.model.weights.energy_with_reference;
        let with = recover_referenced(&ik, &poulaine, &truth, Some(&reference)).unwrap();
        show(&format!("with the database's angles {}", e.label), &with);
        assert!(with.within_limits && with.residual <= 1e-3);
        for n in ["pelvis_rotation", "hip_flexion", "hip_rotation"] {
            assert!(with.table2(n) < r.table2(n), "{n}: {}", with.table2(n));
        }
        referenced.push(with);
    }
    for (n, bound) in [
        ("pelvis_tilt", 0.03),
        ("hip_flexion", 0.05),
        ("hip_rotation", 0.03),
    ] {
        let mean = referenced.iter().map(|r| r.table2(n)).sum::<f64>() / referenced.len() as f64;
        assert!(mean <= bound, "{n}: mean {mean}");
    }
}
