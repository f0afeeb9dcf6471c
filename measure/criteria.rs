//! The quality criteria of klaw's walks next to Pronost et al. 2006's Table 1 (the numbers of
//! `docs/criteria.md`): for each speed, a 10-step walk (H 1.8 m, M 80 kg, default attributes),
//! its exact heel strikes, frames at `fps` resampled to 60 frames/s; C1, the share of C1 within
//! two frames (33 ms) of a heel strike, C2 at the heel strikes and at the ankle's foremost
//! position, C3 as printed and Willems et al. 1995's internal and external power, and the
//! actuators' work per metre.
//!
//! `cargo run --release --example criteria [FPS]` (default 100 frames/s).
use klaw::analysis::criteria::heel_strikes::from_kinematics;
use klaw::analysis::criteria::segments::{DOFS, POSE, pose};
use klaw::analysis::criteria::{CriteriaFrames, CriteriaParameters, evaluate};
use klaw::numerics::sampled::{lagrange, third_derivative};
use klaw::{Body, Simulation};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let fps: f64 = std::env::args().nth(1).map_or(Ok(100.0), |a| a.parse())?;
    let body = Body::standard(1.8, 80.0)?;
    let params = CriteriaParameters::default();
    println!(
        "v m/s | C1 rad²/s⁶ | C1 near HS | msj rad²/s⁶ | C2 HS rad | C2 ankle rad | C3 literal | \
         mechanical | internal | external W/kg | work J/m"
    );
    for v in [1.0, 1.2, 1.4, 1.6, 1.8] {
        let walk = Simulation::new(body).velocity(v).steps(10).run()?;
        let motion = CriteriaFrames::from_walk(walk.engine(), fps)?;
        let c = evaluate(&motion, &body, &params)?;
        let at_ankle = CriteriaFrames {
            heel_strikes: from_kinematics(&motion.frames, &body, params.heel_strike_window),
            ..motion.clone()
        };
        let k = evaluate(&at_ankle, &body, &params)?;
        let p = c.mean.power.expect("a walk has its pelvis position");
        let report = walk.report();
        let work: f64 = report.steps.iter().map(|s| s.positive_work).sum();
        let distance: f64 = report.steps.iter().map(|s| s.achieved.step_length).sum();
        println!(
            "{v:.1} | {:.3e} | {:.0} % | {:.3e} | {:.4} | {:.5} | {:.2} | {:.2} | {:.2} | {:.2} | {:.1}",
            c.mean.total_jerk,
            100.0 * near_heel_strikes(&motion, &c, &params),
            c.mean.mean_squared_jerk,
            c.mean.cyclicity,
            k.mean.cyclicity,
            p.literal,
            p.mechanical,
            p.internal,
            p.external,
            work / distance
        );
    }
    Ok(())
}

/// The share of C1 (summed over the cycles) from the 60 frames/s frames within two frames of
/// any heel strike, with the criteria's own resampling and differences.
fn near_heel_strikes(
    motion: &CriteriaFrames,
    c: &klaw::analysis::criteria::Criteria,
    params: &CriteriaParameters,
) -> f64 {
    let times = motion.times();
    let poses: Vec<[f64; POSE]> = motion.frames.iter().map(pose).collect();
    let h = 1.0 / params.rate;
    let strikes: Vec<f64> = motion
        .heel_strikes
        .right
        .iter()
        .chain(&motion.heel_strikes.left)
        .copied()
        .collect();
    let (mut near, mut all) = (0.0, 0.0);
    for cc in &c.cycles {
        let n = ((cc.cycle.end - cc.cycle.start) * params.rate + 1e-9).floor() as i64;
        let grid: Vec<f64> = (-2..=n + 2)
            .map(|k| cc.cycle.start + k as f64 * h)
            .filter(|&t| t >= times[0] - 1e-12 && t <= times[times.len() - 1] + 1e-12)
            .collect();
        let first = grid
            .iter()
            .position(|&t| (t - cc.cycle.start).abs() < 1e-12)
            .unwrap();
        for &i in &DOFS {
            let column: Vec<f64> = poses.iter().map(|p| p[i]).collect();
            let angle: Vec<f64> = grid.iter().map(|&t| lagrange(&times, &column, t)).collect();
            let jerk = third_derivative(&angle, h);
            for k in first..=first + n as usize {
                let j2 = jerk[k] * jerk[k];
                all += j2;
                if strikes
                    .iter()
                    .any(|s| (grid[k] - s).abs() <= 2.0 * h + 1e-9)
                {
                    near += j2;
                }
            }
        }
    }
    near / all
}
