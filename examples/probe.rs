use klaw::*;
fn main() {
    let body = Body::standard(
        std::env::args()
            .nth(2)
            .map(|s| s.parse().unwrap())
            .unwrap_or(1.8),
        80.0,
    )
    .unwrap();
    let attrs = Attributes::default();
    let v: f64 = std::env::args()
        .nth(1)
        .map(|s| s.parse().unwrap())
        .unwrap_or(1.4);
    let gait = GaitRequest {
        velocity: Some(v),
        ..Default::default()
    }
    .complete(&body, &attrs)
    .unwrap();
    let mut w = walk::Walker::new(body, attrs);
    for _ in 0..10 {
        match w.step(gait) {
            Ok(s) => {
                let r = &s.report;
                for so in &s.solves {
                    print!(
                        "{}:{}{} ",
                        so.phase,
                        so.report.iterations,
                        if so.report.converged { "" } else { "X" }
                    );
                }
                println!(
                    "| end {:.1e} heel {:.1e} sl {:.5}/{:.5} exc {:.4}/{:.4} margin {:.1e} low {:.2e} mid {:.4} hv {:.3}",
                    r.end_condition_error,
                    r.heel_height_at_strike,
                    r.achieved.step_length,
                    r.target.step_length,
                    r.hip_excursion,
                    r.bounce_reference,
                    r.hip_min_margin,
                    r.min_foot_height,
                    r.min_toe_clearance,
                    r.heel_contact_velocity
                );
            }
            Err(e) => {
                println!("error {e}");
                break;
            }
        }
    }
}
