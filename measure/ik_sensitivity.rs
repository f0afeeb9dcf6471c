//! The secondary tasks' weights and ξ against the recovery of klaw's angles (Pronost et al.
//! Table 2's columns, eq. 7, mean of both legs) on two walks, one weight varied at a time from
//! models/ik.toml's; prints a markdown table.
//!
//! `cargo run --release --example ik_sensitivity`
use klaw::ik::{Ik, Weights};
use klaw::poulaine::Trajectory;
use klaw::poulaine::validate::{TABLE2, frames_angles, recover};
use klaw::{Body, Simulation};

fn main() {
    let walks: Vec<_> = [(1.8, 1.4), (1.6, 1.0)]
        .iter()
        .map(|&(h, v)| {
            let body = Body::standard(h, 23.0 * h * h).unwrap();
            let walk = Simulation::new(body).velocity(v).steps(6).run().unwrap();
            let (poulaine, frames) = Trajectory::from_walk(&walk, 60.0).unwrap();
            let truth = frames_angles(&frames, &body).unwrap();
            (body, poulaine, truth)
        })
        .collect();
    let base = Ik::new(&walks[0].0).model.weights;
    let mut settings = vec![("models/ik.toml".to_string(), base)];
    for k in [0.0, 0.1, 10.0] {
        settings.push((
            format!("limits × {k}"),
            Weights {
                limits: base.limits * k,
                ..base
            },
        ));
        settings.push((
            format!("energy × {k}"),
            Weights {
                energy: base.energy * k,
                ..base
            },
        ));
        settings.push((
            format!("rest × {k}"),
            Weights {
                rest: base.rest * k,
                ..base
            },
        ));
    }
    for xi in [10.0, 50.0] {
        settings.push((format!("ξ = {xi}"), Weights { xi, ..base }));
    }
    print!("| weights | ");
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
    for (name, w) in settings {
        let mut sums = [0.0; 7];
        let mut within = true;
        let mut failed = false;
        for (body, poulaine, truth) in &walks {
            let mut ik = Ik::new(body);
            ik.model.weights = w;
            match recover(&ik, poulaine, truth) {
                Ok(r) => {
                    for (k, (n, _)) in TABLE2.iter().enumerate() {
                        sums[k] += r.table2(n) / walks.len() as f64;
                    }
                    within &= r.within_limits;
                }
                Err(e) => {
                    println!(
                        "| {name} (limits {}, energy {}, rest {}, ξ {}) | failed: {e} |",
                        w.limits, w.energy, w.rest, w.xi
                    );
                    failed = true;
                    break;
                }
            }
        }
        if failed {
            continue;
        }
        print!(
            "| {name} (limits {}, energy {}, rest {}, ξ {}) | ",
            w.limits, w.energy, w.rest, w.xi
        );
        for s in sums {
            print!("{s:.3} | ");
        }
        println!("{within} |");
    }
}
