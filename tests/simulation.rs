//! The library API (`klaw::Simulation` and the `Walk` it returns) against independent paths
//! through the crate: its default walk is `engine::walker::simulate` of the same inputs frame
//! for frame; a schedule's per-step targets are met; bad input is an error before anything is
//! simulated; every export re-parses with the expected number of rows.
use std::fs;

use klaw::engine::walker::{simulate, walk_attributes};
use klaw::export::bvh;
use klaw::figure::frames;
use klaw::model::InputError;
use klaw::{
    AttributeTable, Body, Error, GaitRequest, Gather, Landmarks, OpenSimModel, Options, Simulation,
};

fn request(v: Option<f64>, sl: Option<f64>, sf: Option<f64>) -> GaitRequest {
    GaitRequest {
        velocity: v,
        step_length: sl,
        step_frequency: sf,
    }
}

/// The builder's default walk is H 1.8 m, M 80 kg, the default attributes, v 1.4 m/s for
/// 10 steps: the same figure frames, report and events as the engine's walk of those inputs,
/// built here by hand; the streamed walk gives the same frames again.
#[test]
fn default_walk_is_the_engines_walk_of_the_same_inputs() {
    let body = Body::standard(1.8, 80.0).unwrap();
    let attrs = AttributeTable::builtin().defaults();
    let gait = request(Some(1.4), None, None)
        .complete(&body, &attrs)
        .unwrap();
    let engine = simulate(body, attrs.clone(), &[gait; 10]).unwrap();

    let walk = Simulation::default().run().unwrap();
    assert_eq!(walk.body(), &body);
    assert_eq!(
        walk.attributes(),
        &walk_attributes(&body, &attrs, &[gait; 10])
    );
    assert_eq!(walk.attributes(), &engine.attrs);
    assert_eq!(walk.gaits(), &[gait; 10]);
    assert_eq!(walk.duration(), engine.duration());
    let fps = 100.0;
    let want: Vec<Landmarks> = frames(&engine, fps).collect::<Result<_, _>>().unwrap();
    let got = walk.frames(fps).unwrap();
    assert_eq!(got.len(), (engine.duration() * fps).floor() as usize + 1);
    assert_eq!(got, want);
    let json = |r: &klaw::Report| serde_json::to_string(r).unwrap();
    assert_eq!(json(&walk.report()), json(&engine.report()));
    assert_eq!(walk.events(), klaw::analysis::events::events(&engine));
    // the figure at a frame's time is that frame
    assert_eq!(walk.figure_at(want[123].time).unwrap(), want[123]);

    let prepared = Simulation::default().prepare().unwrap();
    assert_eq!(prepared.gaits(), &[gait; 10]);
    assert!((prepared.duration() - engine.duration()).abs() < 1e-12);
    let gather = Gather {
        events: true,
        ..Gather::default()
    };
    let mut stream = prepared.stream(fps, gather).unwrap();
    let streamed: Vec<Landmarks> = (&mut stream).collect::<klaw::Result<_>>().unwrap();
    stream.finish();
    assert_eq!(streamed, want);
    assert_eq!(stream.events, walk.events());
}

/// At a frame rate whose last frame comes before the last steps start (0.05 frames/s: frames
/// at 0 s and 20 s would need 20 s, so only t = 0 is sampled for a 5.5 s walk), the stream
/// still walks every step: the same reports and events as the full-rate stream.
#[test]
fn a_low_frame_rate_still_walks_every_step() {
    let gather = Gather {
        events: true,
        reports: true,
        ..Gather::default()
    };
    let run = |fps: f64| {
        let prepared = Simulation::default().prepare().unwrap();
        let mut stream = prepared.stream(fps, gather).unwrap();
        let frames = (&mut stream).collect::<klaw::Result<Vec<_>>>().unwrap();
        stream.finish();
        (
            frames.len(),
            stream.steps,
            stream.reports.len(),
            stream.events.len(),
        )
    };
    let (frames, steps, reports, events) = run(0.05);
    assert_eq!(frames, 1);
    let (full_frames, full_steps, full_reports, full_events) = run(100.0);
    assert!(full_frames > 500);
    assert_eq!((steps, reports, events), (10, 10, full_events));
    assert_eq!((full_steps, full_reports), (10, 10));
}

/// A schedule of requests of each kind, held for two more steps: every step's target is its
/// completed request, achieved to 0.5 % in step length (tests/walk.rs's bound).
#[test]
fn a_schedule_meets_its_per_step_targets() {
    let schedule = vec![
        request(Some(1.0), None, None),
        request(None, Some(0.7), None),
        request(None, None, Some(110.0)),
        request(Some(1.5), None, Some(112.0)),
    ];
    let walk = Simulation::default()
        .schedule(schedule.clone())
        .steps(6)
        .run()
        .unwrap();
    let body = Body::standard(1.8, 80.0).unwrap();
    let attrs = AttributeTable::builtin().defaults();
    let mut want: Vec<_> = schedule
        .iter()
        .map(|r| r.complete(&body, &attrs).unwrap())
        .collect();
    want.extend([want[3]; 2]);
    assert_eq!(walk.gaits(), &want[..]);
    let report = walk.report();
    assert_eq!(report.steps.len(), 6);
    for (s, g) in report.steps.iter().zip(&want) {
        assert_eq!(s.target.step_length, g.step_length);
        assert_eq!(s.target.step_frequency, g.step_frequency);
        let err = (s.achieved.step_length - g.step_length).abs() / g.step_length;
        assert!(err <= 0.005, "step {}: {:.3} %", s.index, 100.0 * err);
    }
    // a shorter walk cuts the schedule
    let cut = Simulation::default().schedule(schedule).steps(2);
    assert_eq!(cut.prepare().unwrap().gaits(), &want[..2]);
}

/// Bad input is found by `prepare`, which simulates nothing, and `run` returns the same error.
#[test]
fn bad_input_is_an_error_before_any_simulation() {
    let too_fast = Simulation::default().velocity(3.5);
    let e = too_fast.prepare().unwrap_err();
    assert!(
        matches!(&e, Error::Input(InputError::OutOfRange { name, .. }) if name == "velocity"),
        "{e}"
    );
    assert_eq!(
        too_fast.run().unwrap_err().to_string(),
        e.to_string(),
        "run checks as prepare does"
    );
    let cases = [
        (Simulation::default().steps(0), "steps"),
        (Simulation::default().steps(1_000_001), "steps"),
        (
            Simulation::default().gait(request(Some(1.4), Some(0.6), Some(100.0))),
            "inconsistent",
        ),
        (
            Simulation::default().gait(GaitRequest::default()),
            "no gait",
        ),
        (Simulation::default().schedule(Vec::new()), "no gait"),
        (
            Simulation::default().schedule(vec![
                request(Some(1.0), None, None),
                request(None, None, Some(190.0)),
            ]),
            "step_frequency = 190",
        ),
        (Simulation::default().style("sneaky"), "unknown style"),
    ];
    for (sim, what) in cases {
        let e = sim.prepare().unwrap_err();
        assert!(matches!(e, Error::Input(_)), "{e}");
        assert!(e.to_string().contains(what), "{what}: {e}");
    }
    let walk = Simulation::default().steps(1).run().unwrap();
    for fps in [0.0, -1.0, f64::NAN, 1e5] {
        assert!(walk.frames(fps).is_err(), "{fps}");
        assert!(walk.clinical_angles(fps).is_err(), "{fps}");
    }
    assert!(walk.figure_at(f64::NAN).is_err());
}

/// `write` by extension: the CSV has ⌊T · fps⌋ + 1 rows (frames at k / fps up to the last heel
/// strike; round(T · fps) + 1 at 100 frames/s, where T · fps = 333.3), the `.mot` / `.sto` as
/// many (and say so in `nRows`), the BVH parses back with as many frames; the events, report,
/// state and cycle files parse too. An unknown extension writes nothing.
#[test]
fn every_export_re_parses() {
    let walk = Simulation::default().steps(6).run().unwrap();
    let dir = tempfile::tempdir().unwrap();
    for fps in [100.0, 30.0] {
        let rows = (walk.duration() * fps).floor() as usize + 1;
        if fps == 100.0 {
            assert_eq!(rows, (walk.duration() * fps).round() as usize + 1);
        }
        let csv = dir.path().join("walk.csv");
        walk.write(&csv, fps, &Options::default()).unwrap();
        let mut reader = csv::Reader::from_path(&csv).unwrap();
        assert!(
            reader
                .headers()
                .unwrap()
                .iter()
                .any(|h| h == "knee_flexion_r_deg")
        );
        let records: Vec<_> = reader.records().collect::<Result<_, _>>().unwrap();
        assert_eq!(records.len(), rows);
        assert!(records.iter().flatten().all(|c| c.parse::<f64>().is_ok()));
        for (name, model) in [
            ("walk.mot", OpenSimModel::Gait2392),
            ("walk.sto", OpenSimModel::Rajagopal2015),
        ] {
            let path = dir.path().join(name);
            let options = Options {
                opensim_model: model,
                ..Options::default()
            };
            walk.write(&path, fps, &options).unwrap();
            let text = fs::read_to_string(&path).unwrap();
            let (head, table) = text.split_once("endheader\n").unwrap();
            assert!(head.contains(&format!("nRows={rows}\n")), "{head}");
            let mut lines = table.lines();
            let columns = lines.next().unwrap().split('\t').count();
            assert!(head.contains(&format!("nColumns={columns}\n")), "{head}");
            let body: Vec<&str> = lines.collect();
            assert_eq!(body.len(), rows);
            for line in body {
                let cells: Vec<f64> = line.split('\t').map(|c| c.parse().unwrap()).collect();
                assert_eq!(cells.len(), columns);
            }
        }
        let path = dir.path().join("walk.bvh");
        walk.write(&path, fps, &Options::default()).unwrap();
        let parsed = bvh::parse(&fs::read_to_string(&path).unwrap(), &path).unwrap();
        assert_eq!(parsed.frames.len(), rows);
    }

    let events = dir.path().join("events.csv");
    walk.write_events(&events).unwrap();
    let mut reader = csv::Reader::from_path(&events).unwrap();
    assert_eq!(reader.records().count(), walk.events().len());
    let report = dir.path().join("report.json");
    walk.write_report(&report).unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(&report).unwrap()).unwrap();
    assert_eq!(json["steps"].as_array().unwrap().len(), 6);
    let state = dir.path().join("state.csv");
    walk.write_state(&state, 100.0).unwrap();
    let mut reader = csv::Reader::from_path(&state).unwrap();
    assert_eq!(
        reader.records().count(),
        (walk.duration() * 100.0).round() as usize + 1
    );
    let cycle = dir.path().join("cycle.csv");
    walk.write_cycle(&cycle, 100.0).unwrap();
    let mut reader = csv::Reader::from_path(&cycle).unwrap();
    assert_eq!(reader.records().count(), 101);

    let bad = dir.path().join("walk.txt");
    let e = walk.write(&bad, 100.0, &Options::default()).unwrap_err();
    assert!(matches!(e, Error::Export(_)), "{e}");
    assert!(!bad.exists());
}
