//! The kinematic walk mode (Ko & Badler 1992, the bundled prototype) side by side with the
//! dynamic mode (issue 17): over step lengths 0.6–1.4 × the prototype's (in leg lengths),
//! heights 1.5–2.0 m and the body tables (Winter's, de Leva's male and female), the RMS difference of the hip, knee and ankle flexion
//! between the two modes (steps 2–9 of 10, 100 frames/s, both legs), how many of
//! `models/gait-norms.toml`'s ranges each mode's averaged gait cycle meets, and the most the
//! kinematic hip comes down; then the speed, alternating the two modes in one run, medians: the
//! whole process with the same outputs (`klaw walk [--mode kinematic] --out walk.csv --no-plot`)
//! and in process without output (the walk's motion plus every frame's figure and clinical
//! angles), with the share of generalizing the step.
//!
//! Run: cargo build --release && cargo run --release --example compare_modes [OVERLAY.png]
//! With a path it also draws the right leg's hip, knee and ankle cycles of both modes at one
//! point of the table (de Leva female, H 1.65 m, 1.2 × the prototype's step) over each other.
//! The cadence of every walk is the prototype's scaled for dynamic similarity,
//! sf = 108.0 · √(ll* / ll) steps/min (the same Froude number at the same step length in leg
//! lengths).
use std::process::Command;
use std::time::Instant;

use klaw::analysis::cycle::GaitCycle;
use klaw::analysis::norms::{NormTable, WalkSpeed, check};
use klaw::figure::clinical::{Clinical, clinical};
use klaw::generalize::{GeneralizeParameters, KinematicWalk, default_prototype};
use klaw::plot::overlay::write_overlay;
use klaw::{Attributes, Body, Gait, GaitRequest, Simulation};

const STEPS: usize = 10;
const FPS: f64 = 100.0;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn strikes(times: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let r = times.iter().step_by(2).copied().collect();
    let l = times.iter().skip(1).step_by(2).copied().collect();
    (r, l)
}

/// How many norms the averaged cycle of `frames` meets, and of how many.
fn norms_met(
    frames: &[Clinical],
    heel_strikes: &[f64],
    norms: &NormTable,
    speed: WalkSpeed,
) -> (usize, usize) {
    let (r, l) = strikes(heel_strikes);
    match GaitCycle::from_clinical(frames, &r, &l, 1) {
        Ok(cycle) => {
            let c = check(&cycle, norms, speed);
            (c.iter().filter(|x| x.inside()).count(), c.len())
        }
        Err(_) => (0, 0),
    }
}

fn kinematic(
    body: Body,
    attrs: &Attributes,
    gait: Gait,
) -> klaw::Result<(Vec<Clinical>, KinematicWalk)> {
    let walk = KinematicWalk::new(
        &default_prototype(),
        body,
        attrs.clone(),
        gait,
        STEPS,
        &GeneralizeParameters::default(),
    )?;
    let frames = walk
        .frames(FPS)
        .map(|lm| Ok(clinical(&lm?, &body)?))
        .collect::<klaw::Result<Vec<_>>>()?;
    Ok((frames, walk))
}

fn dynamic(body: Body, gait: Gait) -> klaw::Result<(Vec<Clinical>, Vec<f64>)> {
    let request = GaitRequest {
        step_length: Some(gait.step_length),
        step_frequency: Some(gait.step_frequency),
        velocity: None,
    };
    let walk = Simulation::new(body).gait(request).steps(STEPS).run()?;
    let strikes = walk.engine().steps.iter().map(|s| s.t_start).collect();
    Ok((walk.clinical_angles(FPS)?, strikes))
}

fn rms(a: &[Clinical], b: &[Clinical]) -> [f64; 3] {
    let mut sq = [0.0; 3];
    let mut n = 0.0;
    for (x, y) in a.iter().zip(b).filter(|(x, _)| x.step >= 2) {
        for (p, q) in [(x.right, y.right), (x.left, y.left)] {
            let d = [
                p.hip.flexion - q.hip.flexion,
                p.knee.flexion - q.knee.flexion,
                p.ankle.flexion - q.ankle.flexion,
            ];
            for j in 0..3 {
                sq[j] += d[j] * d[j];
            }
            n += 1.0;
        }
    }
    sq.map(|s| (s / n).sqrt().to_degrees())
}

fn gait_for(body: &Body, k: f64) -> Gait {
    let proto = default_prototype();
    let sl = k * proto.character.step_length * body.l1;
    let sf = 108.0 * (proto.body.leg_length() / body.l1).sqrt();
    Gait {
        velocity: sl * sf / 60.0,
        step_length: sl,
        step_frequency: sf,
    }
}

fn main() -> klaw::Result<()> {
    let attrs = klaw::AttributeTable::builtin().defaults();
    let norms = NormTable::builtin();
    println!(
        "| table | H (m) | sl / sl* | sl (m) | v (m/s) | RMS hip / knee / ankle (°) | norms met, dynamic | norms met, kinematic | hip lowered (mm) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for table in ["winter", "deleva-male", "deleva-female"] {
        for h in [1.5, 1.65, 1.8, 2.0] {
            let body = Body::from_table(table, h, 23.0 * h * h)?;
            for k in [0.6, 0.8, 1.0, 1.2, 1.4] {
                let gait = gait_for(&body, k);
                let cells = row(body, &attrs, gait, &norms);
                println!(
                    "| {table} | {h} | {k} | {:.3} | {:.2} | {cells} |",
                    gait.step_length, gait.velocity
                );
            }
        }
    }
    if let Some(path) = std::env::args().nth(1) {
        overlay(&attrs, std::path::Path::new(&path))?;
    }
    speed(&attrs)
}

/// The cells of one point of the table: both modes walked, compared and checked.
fn row(body: Body, attrs: &Attributes, gait: Gait, norms: &NormTable) -> String {
    let speed = WalkSpeed {
        velocity: gait.velocity,
        leg_length: body.l1,
    };
    let kin_norms = |b: &[Clinical], w: &KinematicWalk| {
        let kt: Vec<f64> = (0..STEPS).map(|i| i as f64 * w.step.duration).collect();
        norms_met(b, &kt, norms, speed)
    };
    match (dynamic(body, gait), kinematic(body, attrs, gait)) {
        (Ok((a, s)), Ok((b, w))) => {
            let [x, y, z] = rms(&a, &b);
            let (dm, dn) = norms_met(&a, &s, norms, speed);
            let (km, kn) = kin_norms(&b, &w);
            format!(
                "{x:.2} / {y:.2} / {z:.2} | {dm}/{dn} | {km}/{kn} | {:.1}",
                1e3 * w.hip_drop
            )
        }
        (Err(e), Ok((b, w))) => {
            let (km, kn) = kin_norms(&b, &w);
            format!(
                "— | dynamic fails: {} | {km}/{kn} | {:.1}",
                short(&e.to_string()),
                1e3 * w.hip_drop
            )
        }
        (Ok((a, s)), Err(e)) => {
            let (dm, dn) = norms_met(&a, &s, norms, speed);
            format!(
                "— | {dm}/{dn} | kinematic refuses: {} | —",
                short(&e.to_string())
            )
        }
        (Err(e), Err(f)) => format!(
            "— | {} | {} | —",
            short(&e.to_string()),
            short(&f.to_string())
        ),
    }
}

/// The right leg's averaged cycles of both modes at one point (de Leva female, H 1.65 m,
/// 1.2 × the prototype's step) drawn over each other to `path`.
fn overlay(attrs: &Attributes, path: &std::path::Path) -> klaw::Result<()> {
    let (h, k) = (1.65, 1.2);
    let body = Body::from_table("deleva-female", h, 23.0 * h * h)?;
    let gait = gait_for(&body, k);
    let (a, s) = dynamic(body, gait)?;
    let (b, w) = kinematic(body, attrs, gait)?;
    let kt: Vec<f64> = (0..STEPS).map(|i| i as f64 * w.step.duration).collect();
    let cycle = |frames: &[Clinical], strikes_at: &[f64]| {
        let (r, l) = strikes(strikes_at);
        GaitCycle::from_clinical(frames, &r, &l, 1).map_err(klaw::Error::from)
    };
    let title = format!(
        "de Leva female, H {h} m, sl {:.3} m ({k} × the prototype's), sf {:.1} steps/min: right leg, the steady cycles averaged",
        gait.step_length, gait.step_frequency
    );
    write_overlay(
        ("dynamic mode", &cycle(&a, &s)?),
        ("kinematic mode", &cycle(&b, &kt)?),
        &title,
        path,
    )?;
    println!("overlay: {}", path.display());
    Ok(())
}

fn short(s: &str) -> String {
    s.chars().take(70).collect::<String>().replace('|', "/")
}

/// The speed of both modes on the default walk, alternated, medians.
fn speed(attrs: &Attributes) -> klaw::Result<()> {
    let body = Body::standard(1.8, 80.0)?;
    let gait = GaitRequest {
        velocity: Some(1.4),
        ..Default::default()
    }
    .complete(&body, attrs)?;
    let (mut d, mut ds, mut k, mut g, mut t0) = (vec![], vec![], vec![], vec![], vec![]);
    let proto = default_prototype();
    let condition = klaw::generalize::BodyCondition::of(&body);
    let pelvis = klaw::generalize::Pelvis {
        rotation: attrs.pelvic_rotation,
        step_width: attrs.step_width,
    };
    for _ in 0..21 {
        let t = Instant::now();
        let request = GaitRequest {
            velocity: Some(1.4),
            ..Default::default()
        };
        let walk = Simulation::new(body).gait(request).steps(STEPS).run()?;
        ds.push(t.elapsed().as_secs_f64());
        let frames = walk.clinical_angles(FPS)?;
        d.push(t.elapsed().as_secs_f64());
        assert_eq!(frames.len(), 556);
        let t = Instant::now();
        let step = klaw::generalize::steady(&proto, &condition, &pelvis, gait.step_length)?;
        t0.push(t.elapsed().as_secs_f64());
        assert!(step.step_length > 0.0);
        let t = Instant::now();
        let walk = KinematicWalk::new(
            &proto,
            body,
            attrs.clone(),
            gait,
            STEPS,
            &GeneralizeParameters::default(),
        )?;
        g.push(t.elapsed().as_secs_f64());
        let frames = walk
            .frames(FPS)
            .map(|lm| Ok(clinical(&lm?, &body)?))
            .collect::<klaw::Result<Vec<_>>>()?;
        k.push(t.elapsed().as_secs_f64());
        assert_eq!(frames.len(), 556);
    }
    let (md, mds, mk, mg, m0) = (median(d), median(ds), median(k), median(g), median(t0));
    println!();
    println!(
        "In process, the default walk (10 steps, 556 frames at 100 frames/s: the motion, every frame's figure and clinical angles), 21 runs alternated, medians:"
    );
    println!(
        "- dynamic {:.2} ms: the simulation {:.2} ms ({:.0} µs a step), the frames {:.1} µs each",
        1e3 * md,
        1e3 * mds,
        1e6 * mds / STEPS as f64,
        1e6 * (md - mds) / 556.0
    );
    println!(
        "- kinematic {:.2} ms ({:.1}× faster): generalizing the step (φ, ψ) {:.1} µs ({:.2} % of the walk), posing it at the check's instants {:.2} ms, the frames {:.1} µs each",
        1e3 * mk,
        md / mk,
        1e6 * m0,
        100.0 * m0 / mk,
        1e3 * mg,
        1e6 * (mk - mg) / 556.0
    );
    let exe = std::env::current_exe()
        .ok()
        .and_then(|p| Some(p.parent()?.parent()?.join("klaw")));
    let Some(exe) = exe.filter(|p| p.exists()) else {
        println!("(the klaw binary is not built next to this example: cargo build --release)");
        return Ok(());
    };
    let dir = tempfile::tempdir().map_err(|e| klaw::Error::Io {
        action: "writing",
        path: "tmp".into(),
        source: e,
    })?;
    let run = |mode: &str| {
        let t = Instant::now();
        let ok = Command::new(&exe)
            .args(["walk", "--mode", mode, "--out", "walk.csv", "--no-plot"])
            .current_dir(dir.path())
            .output()
            .is_ok_and(|o| o.status.success());
        assert!(ok, "klaw walk --mode {mode} failed");
        t.elapsed().as_secs_f64()
    };
    let (mut pd, mut pk) = (Vec::new(), Vec::new());
    for _ in 0..21 {
        pd.push(run("dynamic"));
        pk.push(run("kinematic"));
    }
    let (a, b) = (median(pd), median(pk));
    println!(
        "Whole process, `klaw walk [--mode kinematic] --out walk.csv --no-plot`, 21 runs alternated, medians: dynamic {:.1} ms, kinematic {:.1} ms ({:.1}× faster)",
        1e3 * a,
        1e3 * b,
        a / b
    );
    Ok(())
}
