//! The larger validation grids of tests/ik_validation.rs: IK on the own poulaines of klaw walks
//! over heights × speeds, with f3 towards a database's angles and towards the rest posture, and
//! leave-one-out over a synthetic database; eq. 7 per Table 2 angle (mean of both legs), as
//! markdown tables.
//!
//! `cargo run --release --example ik_validation`
use klaw::ik::Ik;
use klaw::poulaine::Trajectory;
use klaw::poulaine::build::{Grid, synthetic};
use klaw::poulaine::database::clamp_to_reach;
use klaw::poulaine::trajectory::cycle_frames;
use klaw::poulaine::validate::{Recovery, TABLE2, frames_angles, recover, recover_referenced};
use klaw::{AttributeTable, Body, GaitRequest, Simulation};

fn header(first: &str) {
    print!("| {first} | ");
    for (n, _) in TABLE2 {
        print!("{n} | ");
    }
    println!("within limits |");
    println!("|---|{}---|", "---|".repeat(TABLE2.len()));
    print!("| Table 2 (paper) | ");
    for (_, b) in TABLE2 {
        print!("{b:.2} | ");
    }
    println!(" |");
}

fn row(name: &str, r: &Recovery) {
    print!("| {name} | ");
    for (n, _) in TABLE2 {
        print!("{:.3} | ", r.table2(n));
    }
    println!("{} |", r.within_limits);
}

/// A walk of the 16-point grid: its label "H, v", body, own poulaine (60 Hz) and angles.
struct Own {
    label: String,
    body: Body,
    poulaine: Trajectory,
    truth: Vec<klaw::ik::chain::Angles>,
}

/// The walks of H 1.5–2.1 m × v 0.8–1.7 m/s that run, each simulated once for both tables.
fn own_walks() -> Vec<Own> {
    let mut walks = Vec::new();
    for h in [1.5, 1.7, 1.9, 2.1] {
        for v in [0.8, 1.1, 1.4, 1.7] {
            let body = Body::standard(h, 23.0 * h * h).unwrap();
            let Ok(walk) = Simulation::new(body).velocity(v).steps(6).run() else {
                continue;
            };
            let (poulaine, frames) = Trajectory::from_walk(&walk, 60.0).unwrap();
            let truth = frames_angles(&frames, &body).unwrap();
            walks.push(Own {
                label: format!("{h}, {v}"),
                body,
                poulaine,
                truth,
            });
        }
    }
    walks
}

fn main() {
    let walks = own_walks();
    own_with_database(&walks);
    println!("IK on each walk's own poulaine (60 Hz):\n");
    header("H (m), v (m/s)");
    for w in &walks {
        match recover(&Ik::new(&w.body), &w.poulaine, &w.truth) {
            Ok(r) => row(&w.label, &r),
            Err(e) => println!("| {} | failed: {e} |", w.label),
        }
    }
    let grid = Grid {
        heights: vec![1.6, 1.8, 2.0],
        step_lengths: vec![0.6, 0.7, 0.8],
        attributes: vec![("step_width".into(), vec![0.05, 0.1])],
    };
    let (db, skipped) = synthetic(&grid).unwrap();
    println!(
        "\nLeave-one-out over a database of {} klaw walks ({} skipped): H {:?} m × step length {:?} m × step width {:?} m\n",
        db.entries.len(),
        skipped.len(),
        grid.heights,
        grid.step_lengths,
        grid.attributes[0].1
    );
    header("left out");
    for e in &db.entries {
        let h = e.height.unwrap();
        let body = Body::standard(h, 23.0 * h * h).unwrap();
        let attrs = AttributeTable::builtin()
            .resolve(&e.attributes, "grid")
            .unwrap();
        let walk = Simulation::new(body)
            .attributes(attrs)
            .gait(GaitRequest {
                step_length: Some(e.step_length),
                ..Default::default()
            })
            .steps(6)
            .run()
            .unwrap();
        let (frames, _, period) = cycle_frames(&walk, 60.0).unwrap();
        let truth = frames_angles(&frames, &body).unwrap();
        let rest = db.without(&e.label);
        let (model, _) = rest.poulaine(&e.axes, body.l1, period);
        let mut poulaine = model.sample(frames.len());
        let mut ik = Ik::new(&body);
        clamp_to_reach(&mut poulaine, body.l0 / 2.0, ik.params.reach * body.l1);
        match recover(&ik, &poulaine, &truth) {
            Ok(r) => row(&format!("{}, rest posture", e.label), &r),
            Err(err) => println!("| {}, rest posture | failed: {err} |", e.label),
        }
        let reference = rest.reference(&poulaine, body.l1, false).map(|r| r.angles);
        ik.model.weights.energy = ik.model.weights.energy_with_reference;
        match recover_referenced(&ik, &poulaine, &truth, reference.as_deref()) {
            Ok(r) => row(&format!("{}, the database's angles", e.label), &r),
            Err(err) => println!("| {}, the database's angles | failed: {err} |", e.label),
        }
    }
}

/// IK on each walk's own poulaine with f3 towards a database's angles (`klaw ik --poulaine P
/// --db DB`): a database of walks at other heights, so no walk is in it.
fn own_with_database(walks: &[Own]) {
    let grid = Grid {
        heights: vec![1.6, 1.8, 2.0],
        step_lengths: vec![0.5, 0.6, 0.7, 0.8, 0.9],
        attributes: vec![],
    };
    let (db, skipped) = synthetic(&grid).unwrap();
    println!(
        "IK on each walk's own poulaine, f3 towards the angles of a database of {} walks ({} skipped; H {:?} m × step length {:?} m):\n",
        db.entries.len(),
        skipped.len(),
        grid.heights,
        grid.step_lengths
    );
    header("H (m), v (m/s)");
    for w in walks {
        let reference = db.reference(&w.poulaine, w.body.l1, false).unwrap();
        let mut ik = Ik::new(&w.body);
        ik.model.weights.energy = ik.model.weights.energy_with_reference;
        match recover_referenced(&ik, &w.poulaine, &w.truth, Some(&reference.angles)) {
            Ok(r) => row(&w.label, &r),
            Err(e) => println!("| {} | failed: {e} |", w.label),
        }
    }
    println!();
}
