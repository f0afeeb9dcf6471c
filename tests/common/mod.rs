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
    body_of_height_in("winter", h)
}

/// [`body_of_height`] scaled from the body table `table` (`klaw::model::body::BODY_TABLES`).
pub fn body_of_height_in(table: &str, h: f64) -> Body {
    Body::from_table(table, h, 23.0 * h * h).unwrap()
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

/// The grid of the whole-walk bounds, as (v, H), over the whole valid range of the default
/// attributes: H = 1.2, 1.45, 1.7, 1.95, 2.2 m (outer, 1.2 + 0.25 i) × v = 0.4, 0.6, … m/s
/// (inner, 0.4 + 0.2 j) up to the body's walk–run transition (`velocity_limit`, Froude number
/// 0.5), and that limit itself: 48 walks. [`fine_grid`] is the 0.1 × 0.1 box.
pub fn grid() -> Vec<(f64, f64)> {
    grid_of(
        "winter",
        0.2,
        &(0..5).map(|i| 1.2 + 0.25 * i as f64).collect::<Vec<_>>(),
    )
}

/// The valid box in steps of 0.1 m/s and 0.1 m (H 1.2–2.2 m), each height's walk–run limit
/// included: 192 walks.
pub fn fine_grid() -> Vec<(f64, f64)> {
    grid_of(
        "winter",
        0.1,
        &(0..11).map(|i| 1.2 + 0.1 * i as f64).collect::<Vec<_>>(),
    )
}

/// v = 0.4 + dv j up to each height's limit (by 1e-9), then the limit, for each of `heights`,
/// for the bodies of the body table `table`.
pub fn grid_of(table: &str, dv: f64, heights: &[f64]) -> Vec<(f64, f64)> {
    let attrs = default_attributes();
    heights
        .iter()
        .flat_map(|&h| {
            let limit = klaw::plan::gait::velocity_limit(&body_of_height_in(table, h), &attrs);
            let n = ((limit - attrs.velocity_min) / dv + 1e-9).floor() as usize;
            let mut vs: Vec<f64> = (0..=n)
                .map(|j| attrs.velocity_min + dv * j as f64)
                .collect();
            if limit - vs[n] > 1e-9 {
                vs.push(limit);
            }
            vs.into_iter().map(move |v| (v, h))
        })
        .collect()
}

/// Run the `klaw` binary in `dir`; it may not panic, whatever the arguments.
pub fn klaw(dir: &std::path::Path, args: &[&str]) -> std::process::Output {
    klaw_with(dir, args, &[])
}

/// [`klaw`] with the environment variables `env` set.
pub fn klaw_with(
    dir: &std::path::Path,
    args: &[&str],
    env: &[(&str, &str)],
) -> std::process::Output {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_klaw"))
        .args(args)
        .envs(env.iter().copied())
        .current_dir(dir)
        .output()
        .expect("the klaw binary runs");
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert!(
        !stdout.contains("panicked") && !stderr.contains("panicked"),
        "klaw {args:?} panicked:\n{stderr}"
    );
    out
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

/// The distance between two points.
pub fn d(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// a − b.
pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Knee flexion from the points: the angle between thigh and shank directions.
pub fn knee_angle(l: &klaw::figure::LegPoints) -> f64 {
    let (u, v) = (sub(l.knee, l.hip), sub(l.ankle, l.knee));
    let dot = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    (dot / (d(l.knee, l.hip) * d(l.ankle, l.knee)))
        .clamp(-1.0, 1.0)
        .acos()
}

/// Foot pitch (heel up +) from heel and metatarsal joint.
pub fn foot_pitch(l: &klaw::figure::LegPoints) -> f64 {
    let (a, b) = (l.heel, l.mtp);
    -(b[1] - a[1]).atan2(b[0] - a[0])
}

/// The farthest any foot point on the floor (heel, metatarsal joint, toe within 1e-9 m of it at
/// both instants) moves between consecutive frames 1 ms apart over `n` ms of `figure(t)`.
pub fn worst_contact_slide(n: usize, figure: impl Fn(f64) -> klaw::figure::Landmarks) -> f64 {
    let mut prev = figure(0.0);
    let mut worst: f64 = 0.0;
    for k in 1..=n {
        let f = figure(k as f64 / 1000.0);
        for (a, b) in [(&prev.right, &f.right), (&prev.left, &f.left)] {
            for (p, q) in [(a.heel, b.heel), (a.mtp, b.mtp), (a.toe, b.toe)] {
                if p[1].abs() < 1e-9 && q[1].abs() < 1e-9 {
                    worst = worst.max(d(p, q));
                }
            }
        }
        prev = f;
    }
    worst
}
