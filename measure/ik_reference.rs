//! Table 2's errors against the reference posture of f3 (eq. 6): IK on the own poulaines of klaw
//! walks (H 1.5–2.1 m × v 0.8–1.7 m/s, 60 Hz) with, as θ_r,
//! - `rest`: the rest posture of `models/ik.toml` (klaw's quiet standing; the default);
//! - `mean`: the walk's own mean posture over its cycle (a database poulaine's mean posture);
//! - `neighbour`: per frame, the angles at the same phase of the nearest other walk of the grid
//!   (same height, the next speed: a database walk's angles, as the paper's distance to the
//!   rest posture would use them if the database carried angles);
//! - `between`: per frame, the mean of the two neighbours' angles at the same phase (same
//!   height, the speeds on either side; interior speeds only): a reference interpolated in the
//!   walk's parameter, as `Database::reference` blends the entries on either side in trace;
//! - `own`: per frame, the walk's own angles (a bound: what the secondary tasks reach when f3
//!   pulls towards the truth, which satisfies the task exactly).
//!
//! Eq. 7 per Table 2 angle (mean of both legs), mean and largest over the walks. The
//! environment variable `ENERGY_SCALE` multiplies the kinetic-energy weight of `models/ik.toml`.
//!
//! `cargo run --release --example ik_reference` (`ENERGY_SCALE=0 cargo run …`)
use klaw::ik::{Angles, Ik};
use klaw::poulaine::Trajectory;
use klaw::poulaine::database::resample;
use klaw::poulaine::validate::{TABLE2, frames_angles, recover_referenced};
use klaw::{Body, Simulation};

struct Case {
    body: Body,
    poulaine: Trajectory,
    truth: Vec<Angles>,
}

fn main() {
    let speeds = [0.8, 1.1, 1.4, 1.7];
    let mut grid: Vec<Vec<Case>> = Vec::new();
    for h in [1.5, 1.7, 1.9, 2.1] {
        let mut row = Vec::new();
        for v in speeds {
            let body = Body::standard(h, 23.0 * h * h).unwrap();
            let walk = Simulation::new(body).velocity(v).steps(6).run().unwrap();
            let (poulaine, frames) = Trajectory::from_walk(&walk, 60.0).unwrap();
            let truth = frames_angles(&frames, &body).unwrap();
            row.push(Case {
                body,
                poulaine,
                truth,
            });
        }
        grid.push(row);
    }
    print!("| θ_r | ");
    for (n, _) in TABLE2 {
        print!("{n} | ");
    }
    println!("walks within limits |");
    println!("|---|{}---|", "---|".repeat(TABLE2.len()));
    print!("| Table 2 (paper) | ");
    for (_, b) in TABLE2 {
        print!("{b:.2} | ");
    }
    println!(" |");
    for option in ["rest", "mean", "neighbour", "between", "own"] {
        let mut all: Vec<[f64; 7]> = Vec::new();
        let mut within = 0;
        for row in &grid {
            for (j, c) in row.iter().enumerate() {
                let n = c.truth.len();
                let reference: Option<Vec<Angles>> = match option {
                    "rest" => None,
                    "mean" => {
                        let mean = c.truth.iter().fold(Angles::zeros(), |a, b| a + b) / n as f64;
                        Some(vec![mean; n])
                    }
                    "neighbour" => {
                        let k = if j + 1 < row.len() { j + 1 } else { j - 1 };
                        Some(resample(&row[k].truth, n))
                    }
                    "between" => {
                        if j == 0 || j + 1 == row.len() {
                            continue;
                        }
                        let a = resample(&row[j - 1].truth, n);
                        let b = resample(&row[j + 1].truth, n);
                        Some(a.iter().zip(&b).map(|(x, y)| (x + y) * 0.5).collect())
                    }
                    _ => Some(c.truth.clone()),
                };
                let mut ik = Ik::new(&c.body);
                if let Ok(e) = std::env::var("ENERGY_SCALE") {
                    ik.model.weights.energy *= e.parse::<f64>().unwrap();
                }
                match recover_referenced(&ik, &c.poulaine, &c.truth, reference.as_deref()) {
                    Ok(r) => {
                        all.push(std::array::from_fn(|i| r.table2(TABLE2[i].0)));
                        within += usize::from(r.within_limits);
                    }
                    Err(e) => eprintln!("{option}: {e}"),
                }
            }
        }
        let cell = |i: usize| {
            let mean = all.iter().map(|r| r[i]).sum::<f64>() / all.len() as f64;
            let max = all.iter().map(|r| r[i]).fold(0.0, f64::max);
            format!("{mean:.3} ({max:.3})")
        };
        print!("| {option} | ");
        for i in 0..TABLE2.len() {
            print!("{} | ", cell(i));
        }
        println!("{within} of {} |", all.len());
    }
}
