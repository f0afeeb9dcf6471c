//! The α slopes of Ko & Badler 1992 (eqs. 5, 6, 21, 24) fitted over klaw's own walks: for each
//! walk of a grid of speeds and heights, the prototype of its step 8 (`klaw prototype
//! --from-walk`), and μ1…μ4 (its knee at heel strike, the foot's toes-up angle at heel strike,
//! heel-up angle and toes' angle at toe-off) regressed by least squares on its step length in
//! leg lengths. Prints each slope (deg per leg length, the `models/generalize.toml` values),
//! its intercept, R² and the RMS residual. `cargo run --release --example regenerate -- models`
//! writes the slopes into `models/generalize.toml`; tests/generated.rs fails when they are stale.
//!
//! Run: cargo run --release --example generalize_fit
use klaw::generalize::GeneralizeParameters;
use klaw::generalize::extract::from_walk;
use klaw::{Body, Simulation};

/// The names of μ1…μ4.
pub const NAMES: [&str; 4] = [
    "μ1 knee at heel strike",
    "μ2 foot at heel strike",
    "μ3 foot at toe-off",
    "μ4 toes at toe-off",
];

/// One μ's least-squares line against sl / ll (degrees).
#[derive(Clone, Copy, Debug)]
pub struct Line {
    /// α, deg per leg length of step length.
    pub slope: f64,
    /// The line at sl / ll = 0 (deg).
    pub intercept: f64,
    /// The share of μ's variance the line explains.
    pub r2: f64,
    /// The RMS residual (deg).
    pub rms: f64,
}

/// The lines of μ1…μ4 over the grid (H 1.5, 1.65, 1.8, 1.95 m × v 0.6 m/s by 0.1 up to the
/// body's walk–run transition, M = 23 H², default attributes), and the number of walks.
pub fn fit() -> klaw::Result<(usize, [Line; 4])> {
    let params = GeneralizeParameters::default();
    let mut rows: Vec<[f64; 5]> = Vec::new();
    for h in [1.5, 1.65, 1.8, 1.95] {
        let body = Body::standard(h, 23.0 * h * h)?;
        let vmax = (0.5 * klaw::model::GRAVITY * body.l1).sqrt();
        for i in 0..=16 {
            let v = 0.6 + 0.1 * i as f64;
            if v > vmax - 0.02 {
                break;
            }
            let walk = Simulation::new(body).velocity(v).steps(10).run()?;
            let w = from_walk(walk.engine(), 8, &params)?;
            let c = w.character;
            rows.push([
                c.step_length,
                c.knee_at_strike,
                c.foot_at_strike,
                c.foot_at_toe_off,
                c.meta_at_toe_off,
            ]);
        }
    }
    let x: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    let n = x.len() as f64;
    let mx = x.iter().sum::<f64>() / n;
    let sxx: f64 = x.iter().map(|a| (a - mx).powi(2)).sum();
    let lines = std::array::from_fn(|j| {
        let y: Vec<f64> = rows.iter().map(|r| r[j + 1].to_degrees()).collect();
        let my = y.iter().sum::<f64>() / n;
        let sxy: f64 = x.iter().zip(&y).map(|(a, b)| (a - mx) * (b - my)).sum();
        let slope = sxy / sxx;
        let intercept = my - slope * mx;
        let res: f64 = x
            .iter()
            .zip(&y)
            .map(|(a, b)| (b - intercept - slope * a).powi(2))
            .sum();
        let tot: f64 = y.iter().map(|b| (b - my).powi(2)).sum();
        Line {
            slope,
            intercept,
            r2: if tot > 0.0 { 1.0 - res / tot } else { 1.0 },
            rms: (res / n).sqrt(),
        }
    });
    Ok((rows.len(), lines))
}

#[allow(dead_code)] // a module of `regenerate` and of tests/generated.rs too
fn main() -> klaw::Result<()> {
    let (walks, lines) = fit()?;
    println!("{walks} walks (H 1.5–1.95 m, v 0.6 m/s up to the walk–run transition)");
    println!(
        "| μ | α (deg / leg length) | intercept at sl/ll = 0 (deg) | R² | RMS residual (deg) |"
    );
    println!("|---|---|---|---|---|");
    for (name, l) in NAMES.iter().zip(lines) {
        println!(
            "| {name} | {:.3} | {:.3} | {:.4} | {:.3} |",
            l.slope, l.intercept, l.r2, l.rms
        );
    }
    Ok(())
}
