//! Using klaw as a library: simulate the default walk (H = 1.8 m, M = 80 kg, v = 1.4 m/s,
//! 10 steps), print the right knee's peak flexion from the clinical angles, and write the
//! motion as an OpenSim `.mot` file.
//!
//! `cargo run --release --example library [OUT.mot]` (default: `klaw-library.mot` in the
//! system's temporary directory).
use std::path::PathBuf;

use klaw::{Options, Simulation};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let fps = 100.0;
    let walk = Simulation::default().run()?;

    // the clinical angles (rad) of every frame; the knee's largest flexion is in mid swing
    let angles = walk.clinical_angles(fps)?;
    let peak = angles
        .iter()
        .max_by(|a, b| a.right.knee.flexion.total_cmp(&b.right.knee.flexion))
        .expect("a walk has frames");
    println!(
        "right knee flexion peak: {:.1}° at t = {:.2} s (step {})",
        peak.right.knee.flexion.to_degrees(),
        peak.time,
        peak.step
    );

    let path = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| std::env::temp_dir().join("klaw-library.mot"));
    walk.write(&path, fps, &Options::default())?;
    let bytes = std::fs::metadata(&path)?.len();
    println!(
        "wrote {}: {} frames at {fps} frames/s ({:.3} s of walking, {bytes} bytes), the \
         coordinates of OpenSim's {:?} model",
        path.display(),
        angles.len(),
        walk.duration(),
        Options::default().opensim_model
    );
    Ok(())
}

/// The example runs (`cargo test` builds it as a test: `test = true` in Cargo.toml).
#[test]
fn runs() {
    main().unwrap();
}
