//! Fixtures shared by the integration tests: the default body and attributes, walks built
//! through the library's `Simulation` builder, and the (v, H) grid the whole-walk bounds are
//! checked over. Each test file uses some of them.
#![allow(dead_code)]

use klaw::engine::walker::Walk;
use klaw::{AttributeTable, Attributes, Body, Gait, GaitRequest, Simulation};

/// The paper's example body: H = 1.8 m, M = 80 kg.
pub fn default_body() -> Body {
    Body::standard(1.8, 80.0).unwrap()
}

/// A body of height `h` (m) and mass 23 h² kg (BMI 23), as the grid scales it.
pub fn body_of_height(h: f64) -> Body {
    Body::standard(h, 23.0 * h * h).unwrap()
}

/// The bundled default attributes.
pub fn default_attributes() -> Attributes {
    AttributeTable::builtin().defaults()
}

/// The gait at `v` m/s for `body`, sl and sf by the normalizing formula (default attributes).
pub fn gait(body: &Body, v: f64) -> Gait {
    GaitRequest {
        velocity: Some(v),
        ..GaitRequest::default()
    }
    .complete(body, &default_attributes())
    .unwrap()
}

/// `steps` steps of `body` at `v` m/s with the default attributes: the engine's walk, built by
/// the builder (the same as `simulate(body, defaults, &[gait(body, v); steps])`).
pub fn walk(body: Body, v: f64, steps: usize) -> klaw::Result<Walk> {
    Ok(Simulation::new(body)
        .velocity(v)
        .steps(steps)
        .run()?
        .into_engine())
}

/// The default walk (H 1.8 m, M 80 kg, v 1.4 m/s, default attributes) of `steps` steps.
pub fn default_walk(steps: usize) -> Walk {
    walk(default_body(), 1.4, steps).unwrap()
}

/// The grid of the whole-walk bounds, as (v, H): H = 1.5, 1.65, 1.8, 1.95 m (outer) ×
/// v = 0.6, 0.7, …, 2.0 m/s (inner), each computed as 1.5 + 0.15 i and 0.6 + 0.1 j.
pub fn grid() -> Vec<(f64, f64)> {
    (0..4)
        .flat_map(|hi| {
            let h = 1.5 + 0.15 * hi as f64;
            (0..15).map(move |vi| (0.6 + 0.1 * vi as f64, h))
        })
        .collect()
}

/// Run the `klaw` binary in `dir`.
pub fn klaw(dir: &std::path::Path, args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_klaw"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the klaw binary runs")
}

/// Run `klaw` in an empty directory and expect exit 2, nothing written, and one `error:` line
/// holding every one of `parts`; the message.
pub fn refused(args: &[&str], parts: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    refused_in(dir.path(), args, parts)
}

/// [`refused`] in `dir`, whose files must be left as they were.
pub fn refused_in(dir: &std::path::Path, args: &[&str], parts: &[&str]) -> String {
    let before = files(dir);
    let out = klaw(dir, args);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "klaw {args:?}:\n{stderr}");
    assert_eq!(stderr.lines().count(), 1, "klaw {args:?}:\n{stderr}");
    for part in parts {
        assert!(
            stderr.contains(part),
            "klaw {args:?}: `{part}` not in\n{stderr}"
        );
    }
    assert_eq!(files(dir), before, "klaw {args:?} wrote files");
    stderr
}

/// The names in `dir` with their sizes, sorted (hidden files too).
pub fn files(dir: &std::path::Path) -> Vec<(String, u64)> {
    let mut v: Vec<(String, u64)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            let name = e.file_name().to_string_lossy().into_owned();
            (name, e.metadata().unwrap().len())
        })
        .collect();
    v.sort();
    v
}

/// Run the `klaw` binary with `args`: its exit status and its stderr.
pub fn klaw_status(args: &[&str]) -> (i32, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_klaw"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// A new scratch directory for the test `name` of the file `file`.
pub fn scratch(file: &str, name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("klaw-{file}-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}
