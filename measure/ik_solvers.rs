//! The secondary tasks' minimisers side by side on the same per-frame problems: Torczon's
//! multi-directional search (src/ik/mds.rs) and argmin's Nelder–Mead, each from the same initial
//! simplex with the same iteration cap, alternating which runs first on each problem. Prints
//! the medians (iterations, cost evaluations, z reached, time per problem) as a markdown table.
//!
//! `cargo run --release --example ik_solvers`
use std::time::Instant;

use klaw::ik::{Ik, Optimizer};
use klaw::poulaine::Trajectory;
use klaw::{Body, Simulation};

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let mut ik_mds = None;
    let mut rows: Vec<[f64; 8]> = Vec::new(); // mds it, ev, z, t; nm it, ev, z, t
    for (h, v) in [(1.6, 0.9), (1.8, 1.4), (2.0, 1.8)] {
        let body = Body::standard(h, 23.0 * h * h).unwrap();
        let walk = Simulation::new(body).velocity(v).steps(6).run().unwrap();
        let (poulaine, _) = Trajectory::from_walk(&walk, 60.0).unwrap();
        let dt = poulaine.uniform_step().unwrap();
        let targets = poulaine.targets();
        let ik = Ik::new(&body);
        let mut nm = ik;
        nm.params.optimizer = Optimizer::NelderMead;
        let sol = ik.solve(&targets, dt, true).unwrap();
        for i in 0..targets.len() {
            let prev = sol.frames[(i + targets.len() - 1) % targets.len()].theta;
            let problem = ik.problem(&prev, &targets[i], Some(dt));
            let run = |solver: &Ik| {
                let t = Instant::now();
                let m = solver.minimise(&problem).unwrap();
                [
                    m.iterations as f64,
                    m.evaluations as f64,
                    m.cost,
                    t.elapsed().as_secs_f64() * 1e6,
                ]
            };
            let (a, b) = if i % 2 == 0 {
                let a = run(&ik);
                (a, run(&nm))
            } else {
                let b = run(&nm);
                (run(&ik), b)
            };
            rows.push([a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]]);
        }
        ik_mds.get_or_insert(ik.params);
    }
    let p = ik_mds.unwrap();
    println!(
        "{} per-frame problems (3 walks: H 1.6 m v 0.9, H 1.8 m v 1.4, H 2.0 m v 1.8 m/s, 60 Hz); \
         initial simplex h = {} rad, cap {} iterations, stop: MDS simplex size {} rad, NM cost sd {}\n",
        rows.len(),
        p.simplex,
        p.max_iterations,
        p.simplex_tolerance,
        p.simplex_tolerance
    );
    println!("| minimiser | iterations | cost evaluations | time per problem (µs) |");
    println!("|---|---|---|---|");
    let col = |k: usize| median(rows.iter().map(|r| r[k]).collect());
    println!(
        "| multi-directional search (Torczon) | {} | {} | {:.1} |",
        col(0),
        col(1),
        col(3)
    );
    println!(
        "| Nelder–Mead (argmin) | {} | {} | {:.1} |",
        col(4),
        col(5),
        col(7)
    );
    let diff: Vec<f64> = rows.iter().map(|r| r[6] - r[2]).collect();
    let rel: Vec<f64> = rows
        .iter()
        .map(|r| (r[6] - r[2]) / r[2].abs().max(1e-300))
        .collect();
    let mds_lower = rows.iter().filter(|r| r[2] < r[6]).count();
    println!(
        "\nz reached: median NM − MDS {:.3e} (relative {:.3e}); MDS lower on {} of {} problems, \
         NM lower on {}; largest NM − MDS {:.3e}, smallest {:.3e}",
        median(diff.clone()),
        median(rel),
        mds_lower,
        rows.len(),
        rows.iter().filter(|r| r[6] < r[2]).count(),
        diff.iter().cloned().fold(f64::MIN, f64::max),
        diff.iter().cloned().fold(f64::MAX, f64::min),
    );
}
