use klaw::engine::walker as walk;
use klaw::*;
fn main() {
    let attrs = Attributes::default();
    let mut fails = 0;
    let mut refused = 0;
    let mut maxit = 0;
    let mut late = vec![];
    let mut worst_mid = f64::INFINITY;
    let mut exc_dev: f64 = 0.0;
    for hi in 0..4 {
        let h = 1.5 + 0.15 * hi as f64;
        for vi in 0..15 {
            let v = 0.6 + 0.1 * vi as f64;
            let body = Body::standard(h, 23.0 * h * h).unwrap();
            let request = GaitRequest {
                velocity: Some(v),
                ..Default::default()
            };
            // beyond the body's walk–run transition: refused before any work, not a walk
            let Ok(gait) = request.complete(&body, &attrs) else {
                refused += 1;
                continue;
            };
            match walk::simulate(body, attrs.clone(), &vec![gait; 10]) {
                Ok(w) => {
                    for s in &w.steps {
                        for so in &s.solves {
                            maxit = maxit.max(so.report.iterations);
                            if s.index >= 3 {
                                late.push(so.report.iterations);
                            }
                        }
                        worst_mid = worst_mid.min(s.report.min_toe_clearance);
                        exc_dev =
                            exc_dev.max((s.report.hip_excursion - s.report.bounce_reference).abs());
                    }
                }
                Err(e) => {
                    fails += 1;
                    println!("v {v:.1} h {h:.2}: {e}");
                }
            }
        }
    }
    late.sort();
    let mean = late.iter().sum::<usize>() as f64 / late.len() as f64;
    println!(
        "fails {fails} refused {refused} (past the walk–run transition) maxit {maxit} late mean {mean:.2} p95 {} worst_mid {worst_mid:.3e} exc_dev {exc_dev:.4}",
        late.get(late.len() * 95 / 100).copied().unwrap_or(0)
    );
}
