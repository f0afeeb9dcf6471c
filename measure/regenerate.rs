//! Regenerates every table klaw derives from its own engine, into a folder you name:
//! - `startup-guesses.toml`: the shooting solves' start-up guesses (`startup_fit`);
//! - `generalize.toml`: `models/generalize.toml` with its α slopes refitted (`generalize_fit`);
//! - `prototype-default.csv`: step 8 of the default walk as walk data (`klaw prototype
//!   --from-walk`), the kinematic mode's bundled prototype.
//!
//! `cargo run --release --example regenerate -- models` rewrites the committed tables;
//! tests/generated.rs fails whenever one of them differs from what this writes. The prototype
//! is walked with the start-up guesses compiled into this binary: when the guesses change, the
//! program says so, and a second run (after the rebuild `cargo run` does) settles the prototype.
#[path = "generalize_fit.rs"]
mod generalize_fit;
#[path = "startup_fit.rs"]
mod startup_fit;

use std::path::{Path, PathBuf};

use klaw::generalize::GeneralizeParameters;
use klaw::generalize::extract::from_walk;

/// `models/generalize.toml` with the four α lines set to `alphas` (deg per leg length, two
/// decimals) and the fit's quality in the comment above them.
fn generalize_toml(alphas: [f64; 4], walks: usize, lines: &[generalize_fit::Line; 4]) -> String {
    let committed = include_str!("../models/generalize.toml");
    let mut out = String::new();
    for line in committed.lines() {
        let key = line.split('=').next().unwrap_or("").trim();
        match ["alpha1", "alpha2", "alpha3", "alpha4"]
            .iter()
            .position(|k| *k == key)
        {
            Some(i) => {
                out += &format!("{key} = {:.2}\n", (alphas[i] * 100.0).round() / 100.0 + 0.0)
            }
            None if line.starts_with("# over klaw's own walks") => {
                out += &format!(
                    "# over klaw's own walks (`cargo run --release --example generalize_fit`: {walks} walks, H 1.5–1.95 m,\n"
                );
            }
            None if line.starts_with("# flexion at heel strike is an attribute") => {
                out += &format!(
                    "# flexion at heel strike is an attribute, the same at every step length. α2: R² {:.4}, RMS\n# residual {:.2}°; α3: R² {:.3}, RMS {:.2}°; α4 = α3 (klaw's toes turn about their tip from\n",
                    lines[1].r2, lines[1].rms, lines[2].r2, lines[2].rms
                );
            }
            None if line.starts_with("# residual ") && line.contains("α3: R²") => {}
            None => {
                out += line;
                out.push('\n');
            }
        }
    }
    out
}

fn main() -> klaw::Result<()> {
    let Some(dir) = std::env::args_os().nth(1).map(PathBuf::from) else {
        eprintln!("usage: cargo run --release --example regenerate -- DIR (e.g. models)");
        std::process::exit(2);
    };
    std::fs::create_dir_all(&dir).expect("the folder can be made");
    let write = |name: &str, text: &str| {
        let path: PathBuf = dir.join(name);
        std::fs::write(&path, text).expect("the folder is writable");
        println!("wrote {}", path.display());
    };

    let guesses = startup_fit::generate();
    let stale = guesses != include_str!("../models/startup-guesses.toml");
    write("startup-guesses.toml", &guesses);

    let (walks, lines) = generalize_fit::fit()?;
    let alphas = lines.map(|l| l.slope);
    write("generalize.toml", &generalize_toml(alphas, walks, &lines));

    let walk = klaw::Simulation::default().steps(10).run()?;
    let prototype = from_walk(walk.engine(), 8, &GeneralizeParameters::default())?;
    write(
        "prototype-default.csv",
        &klaw::generalize::text::to_csv(&prototype)?,
    );
    if stale && Path::new(&dir) == Path::new("models") {
        println!(
            "the start-up guesses changed: run this again (after cargo's rebuild) so that the \
             prototype is walked with them"
        );
    }
    Ok(())
}
