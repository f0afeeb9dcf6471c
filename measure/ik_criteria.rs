//! The quality criteria C1–C3 (Pronost et al. §6.2, eqs. 8–11, `src/analysis/criteria`) of the
//! inverse kinematics' results next to the paper's Table 1, at the validation points of
//! `measure/ik_validation.rs`: for each klaw walk (H × v) the criteria of the walk itself and of
//! the IK on its own poulaine (60 Hz, the figure posed at the walk's speed, three cycles, the
//! first left out as `klaw evaluate` does), and two cyclicities of the IK's sequence itself
//! (eq. 9: the posture one frame after the last, at the first frame's target, against the first):
//! of the kept pass (after the warm-up) and of a single pass from the rest posture; and the
//! same with f3 towards the angles of a database of walks at other heights (`klaw ik
//! --poulaine P --db DB`).
//!
//! `cargo run --release --example ik_criteria`
use klaw::analysis::criteria::heel_strikes::from_steps;
use klaw::analysis::criteria::{CriteriaFrames, CriteriaParameters, Means, evaluate};
use klaw::figure::clinical::clinical;
use klaw::ik::{Angles, Ik, Solution};
use klaw::poulaine::Trajectory;
use klaw::poulaine::build::{Grid, synthetic};
use klaw::{AttributeTable, Body, Simulation};

/// Eq. 9 of a solved cycle: ‖θ(after the last frame, at the first target) − θ(first frame)‖.
fn closure(ik: &Ik, sol: &Solution, poulaine: &Trajectory) -> f64 {
    let targets = poulaine.targets();
    let n = sol.frames.len();
    let next = ik
        .step(
            &sol.frames[n - 1].theta,
            &targets[0],
            Some(sol.dt),
            n,
            sol.dt,
        )
        .expect("the first frame again");
    (next.theta - sol.frames[0].theta).norm()
}

fn cells(m: &Means) -> String {
    let p = m.power.expect("positioned frames");
    format!(
        "{:.2} | {:.4} | {:.2} | {:.2}",
        m.total_jerk / 1e7,
        m.cyclicity,
        p.literal,
        p.internal
    )
}

/// C1–C3 of the IK on `poulaine` (the figure posed at speed `v`, three cycles) with f3
/// towards `reference` (or the rest posture), and eq. 9 of the kept pass.
fn solved(
    ik: &Ik,
    body: &Body,
    poulaine: &Trajectory,
    v: f64,
    reference: Option<&[Angles]>,
) -> Option<(Means, f64)> {
    let dt = poulaine.uniform_step().unwrap();
    let kept = ik
        .solve_referenced(&poulaine.targets(), dt, true, reference)
        .ok()?;
    let attrs = AttributeTable::builtin().defaults();
    let angles: Vec<Angles> = kept.frames.iter().map(|f| f.theta).collect();
    let frames = klaw::ik::figure::frames((body, &attrs), &angles, dt, v, 3);
    let clin: Vec<_> = frames.iter().map(|f| clinical(f, body).unwrap()).collect();
    let motion = CriteriaFrames {
        heel_strikes: from_steps(&clin),
        frames: clin,
    };
    let means = evaluate(&motion, body, &CriteriaParameters::default())
        .unwrap()
        .mean;
    let mut first = *ik;
    if let Some(r) = reference {
        first.model.rest = r[0];
    }
    Some((means, closure(&first, &kept, poulaine)))
}

fn main() {
    let params = CriteriaParameters::default();
    let grid = Grid {
        heights: vec![1.6, 1.8, 2.0],
        step_lengths: vec![0.5, 0.6, 0.7, 0.8, 0.9],
        attributes: vec![],
    };
    let (db, _) = synthetic(&grid).unwrap();
    println!(
        "| H (m), v (m/s) | walk: C1 (1e7 rad² s⁻⁶) | C2 (rad) | C3 literal (W/kg) | internal (W/kg) \
         | IK: C1 | C2 repeated | C3 literal | internal | IK C2 kept pass | IK C2 one pass from rest \
         | IK, database's angles: C1 | C2 repeated | C3 literal | internal | C2 kept pass |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    println!("| Table 1 mean (paper) | 7.2 | 0.02 | 6.1 | — | | | | | | | | | | | |");
    for h in [1.5, 1.7, 1.9, 2.1] {
        for v in [0.8, 1.1, 1.4, 1.7] {
            let body = Body::standard(h, 23.0 * h * h).unwrap();
            let Ok(walk) = Simulation::new(body).velocity(v).steps(6).run() else {
                continue;
            };
            let own = evaluate(
                &CriteriaFrames::from_walk(walk.engine(), 60.0).unwrap(),
                &body,
                &params,
            )
            .unwrap();
            let (poulaine, _) = Trajectory::from_walk(&walk, 60.0).unwrap();
            let dt = poulaine.uniform_step().unwrap();
            let ik = Ik::new(&body);
            let reference = db.reference(&poulaine, body.l1, false).unwrap().angles;
            let mut referenced = ik;
            referenced.model.weights.energy = ik.model.weights.energy_with_reference;
            let (Some((rest, kept)), Ok(single), Some((with, kept_with))) = (
                solved(&ik, &body, &poulaine, v, None),
                ik.solve(&poulaine.targets(), dt, false),
                solved(&referenced, &body, &poulaine, v, Some(&reference)),
            ) else {
                println!("| {h}, {v} | IK failed |");
                continue;
            };
            println!(
                "| {h}, {v} | {} | {} | {kept:.4} | {:.4} | {} | {kept_with:.4} |",
                cells(&own.mean),
                cells(&rest),
                closure(&ik, &single, &poulaine),
                cells(&with),
            );
        }
    }
}
