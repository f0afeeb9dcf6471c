//! The footprint figure of a scenario (`klaw scenario --footprints`): the table example drawn as
//! PNG and SVG; one scale on both axes; an unknown extension a typed error that writes nothing,
//! and on the command line exit 2 with nothing written.
use std::path::{Path, PathBuf};
mod common;

use common::klaw_status as klaw;

use klaw::Error;
use klaw::model::InputError;
use klaw::plot::equal_scale;
use klaw::plot::floor::{foot_outline, heading_vector, top};
use klaw::plot::footprints::{self, HEIGHT_RANGE_PX, WIDTH_PX};
use klaw::scenario::{Motion, read_scenario, run};

fn dir(name: &str) -> PathBuf {
    common::scratch("footprints", name)
}

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/scenarios")
        .join(name)
}

fn table() -> (klaw::scenario::Scenario, Motion) {
    let s = read_scenario(&example("table.toml")).unwrap();
    let m = run(&s, 25.0).unwrap();
    (s, m)
}

#[test]
fn the_table_example_draws_as_png_and_svg() {
    let d = dir("table");
    let (s, m) = table();
    let png = d.join("table.png");
    let map = footprints::write(&png, &m, &s.body, "table").unwrap().map;
    let bytes = std::fs::read(&png).unwrap();
    assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n"), "a PNG");
    let img = image::load_from_memory(&bytes).unwrap();
    assert_eq!(img.width(), WIDTH_PX);
    assert!((HEIGHT_RANGE_PX.0..=HEIGHT_RANGE_PX.1).contains(&img.height()));
    // every footprint's ankle and the whole pelvis path fall inside the image
    let inside = |(x, y): (i32, i32)| {
        (0..img.width() as i32).contains(&x) && (0..img.height() as i32).contains(&y)
    };
    for f in &m.footprints {
        let (u, v) = top(f.ankle[0], f.ankle[1]);
        assert!(inside(map.pixel(u, v)), "footprint {}", f.index);
    }
    for lm in &m.frames {
        let (u, v) = top(lm.pelvis[0], lm.pelvis[2]);
        assert!(inside(map.pixel(u, v)), "pelvis at {}", lm.time);
    }
    let svg = d.join("table.svg");
    footprints::write(&svg, &m, &s.body, "table").unwrap();
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg") && text.trim_end().ends_with("</svg>"));
    // one outline per footprint, at least (a polygon each)
    assert!(text.matches("<polygon").count() >= m.footprints.len());
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn a_one_metre_square_maps_to_a_square() {
    // the ranges of equal_scale over any extent and area: a metre spans as many pixels across as
    // up, and the extent is shown whole
    for (x, y, px) in [
        ((0.0, 5.0), (-0.2, 0.9), (1310, 400)),
        ((-1.0, 1.0), (-3.0, 3.0), (500, 700)),
        ((2.0, 2.5), (0.0, 0.1), (333, 91)),
    ] {
        let fit = equal_scale(x, y, px);
        let across = f64::from(px.0) / (fit.x.1 - fit.x.0);
        let up = f64::from(px.1) / (fit.y.1 - fit.y.0);
        assert!((across - up).abs() < 1e-9 * across, "{across} vs {up}");
        assert!(fit.x.0 <= x.0 && fit.x.1 >= x.1 && fit.y.0 <= y.0 && fit.y.1 >= y.1);
        // the binding axis is filled exactly
        let bind = ((x.1 - x.0) * across - f64::from(px.0))
            .abs()
            .min(((y.1 - y.0) * up - f64::from(px.1)).abs());
        assert!(bind < 1e-6, "{bind}");
    }
}

#[test]
fn left_feet_lie_on_the_left_of_the_walk() {
    // in the first walk (action 1, heading 0) of the table example, each left print's outline
    // lies to the left of the pelvis path (up in the top view: v greater than the pelvis's), each
    // right print's to the right; on the walk back (the last walk, heading π) the other way round
    let (s, m) = table();
    let walks: Vec<usize> = s
        .actions
        .iter()
        .enumerate()
        .filter(|(_, a)| a.name() == "walk")
        .map(|(i, _)| i)
        .collect();
    let mut checked = 0;
    for f in m.footprints.iter().filter(|f| walks.contains(&f.action)) {
        let outline = foot_outline(&s.body, f.side, f.ankle, f.direction);
        let (cu, cv) = outline
            .iter()
            .fold((0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1));
        let n = outline.len() as f64;
        let (cu, cv) = (cu / n, cv / n);
        // the pelvis when the foot landed
        let lm = m
            .frames
            .iter()
            .min_by(|a, b| (a.time - f.time).abs().total_cmp(&(b.time - f.time).abs()))
            .unwrap();
        let (pu, pv) = top(lm.pelvis[0], lm.pelvis[2]);
        // the print's offset from the pelvis along the foot's own left
        let (du, dv) = heading_vector(f.direction);
        let left = -(cu - pu) * dv + (cv - pv) * du;
        let want = match f.side {
            klaw::nrs::specs::Side::Left => 1.0,
            klaw::nrs::specs::Side::Right => -1.0,
        };
        assert!(left * want > 0.02, "footprint {}: {left} m", f.index);
        checked += 1;
    }
    assert!(checked >= 10, "{checked} footprints of walks");
}

#[test]
fn an_unknown_extension_is_a_typed_error_and_writes_nothing() {
    let d = dir("ext");
    let (s, m) = table();
    for name in ["f.txt", "f", "f.gif"] {
        let path = d.join(name);
        let e = footprints::write(&path, &m, &s.body, "table").unwrap_err();
        assert!(
            matches!(e, Error::Input(InputError::Malformed { .. })),
            "{e:?}"
        );
        assert!(e.to_string().contains(".png or .svg"), "{e}");
        assert!(!path.exists());
    }
    assert_eq!(std::fs::read_dir(&d).unwrap().count(), 0, "nothing written");
    std::fs::remove_dir_all(&d).unwrap();
}

#[test]
fn cli_checks_the_footprints_path_before_any_work() {
    let d = dir("cli");
    let spin = example("spin.toml");
    let out = d.join("spin.csv");
    let bad = d.join("x.txt");
    let (code, err) = klaw(&[
        "scenario",
        spin.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--footprints",
        bad.to_str().unwrap(),
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--footprints") || err.contains("footprints"),
        "{err}"
    );
    assert!(err.contains(".png or .svg"), "{err}");
    assert_eq!(std::fs::read_dir(&d).unwrap().count(), 0, "nothing written");
    // a good path writes the figure beside the frames
    let good = d.join("spin.svg");
    let (code, err) = klaw(&[
        "scenario",
        spin.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--fps",
        "25",
        "--footprints",
        good.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(std::fs::metadata(&good).unwrap().len() > 1000);
    assert!(out.exists());
    std::fs::remove_dir_all(&d).unwrap();
}

/// The step numbers of the table example pile up nowhere: one label per place (the right foot
/// pivots in the turn: 12, 15 and 17 are one place, one label), every footprint named exactly
/// once, the labels inside the plotting area's image, apart from each other and from every
/// footprint's outline (its pixel box), and from every gaze arrow's shaft.
#[test]
fn step_numbers_are_apart_from_each_other_and_from_the_feet() {
    let d = dir("labels");
    let (s, m) = table();
    let png = d.join("table.png");
    let layout = footprints::write(&png, &m, &s.body, "table").unwrap();
    let img = image::open(&png).unwrap();
    let (w, h) = (img.width() as i32, img.height() as i32);
    let mut named: Vec<usize> = layout
        .labels
        .iter()
        .flat_map(|l| l.indices.clone())
        .collect();
    named.sort_unstable();
    assert_eq!(named, (0..m.footprints.len()).collect::<Vec<_>>());
    let pivot = layout
        .labels
        .iter()
        .find(|l| l.indices.contains(&15))
        .unwrap();
    assert_eq!(pivot.indices, [12, 15, 17]);
    assert_eq!(pivot.text, "12, 15, 17");
    assert_eq!(layout.labels.len(), m.footprints.len() - 2);
    let overlap = |a: (i32, i32, i32, i32), b: (i32, i32, i32, i32)| {
        a.0 <= b.2 && b.0 <= a.2 && a.1 <= b.3 && b.1 <= a.3
    };
    let pixel_box = |points: Vec<(f64, f64)>| {
        points.iter().fold(
            (i32::MAX, i32::MAX, i32::MIN, i32::MIN),
            |(l, t, r, b), &(u, v)| {
                let (x, y) = layout.map.pixel(u, v);
                (l.min(x), t.min(y), r.max(x), b.max(y))
            },
        )
    };
    let feet: Vec<_> = m
        .footprints
        .iter()
        .map(|f| pixel_box(foot_outline(&s.body, f.side, f.ankle, f.direction)))
        .collect();
    for (i, a) in layout.labels.iter().enumerate() {
        let (l, t, r, b) = a.bbox;
        assert!(0 <= l && r < w && 0 <= t && b < h, "{a:?}");
        for other in &layout.labels[i + 1..] {
            assert!(!overlap(a.bbox, other.bbox), "{a:?} over {other:?}");
        }
        for (f, foot) in m.footprints.iter().zip(&feet) {
            assert!(!overlap(a.bbox, *foot), "{a:?} over footprint {}", f.index);
        }
        // the arrows' shafts, every 5 mm
        for &(at, dir) in &layout.gaze {
            for k in 0..=60 {
                let d = 0.005 * f64::from(k);
                let (x, y) = layout.map.pixel(at.0 + d * dir.cos(), at.1 + d * dir.sin());
                assert!(
                    !(l <= x && x <= r && t <= y && y <= b),
                    "{a:?} over the gaze arrow at {at:?}"
                );
            }
        }
    }
    std::fs::remove_dir_all(&d).unwrap();
}

/// The gaze arrows pile up nowhere: any two arrows start a metre apart or differ by 60° of
/// heading (standing, stepping aside and turning on the spot gave one arrow every 0.5 s at one
/// place), and every turn shows: the arrows' headings cover the walk out (0°), the turn's middle
/// and the walk back (180°).
#[test]
fn gaze_arrows_are_a_metre_or_a_turn_apart() {
    let d = dir("gaze");
    let (s, m) = table();
    let layout = footprints::write(&d.join("table.png"), &m, &s.body, "table").unwrap();
    let g = &layout.gaze;
    assert!((10..=25).contains(&g.len()), "{} arrows", g.len());
    for (i, &(p, a)) in g.iter().enumerate() {
        for &(q, b) in &g[i + 1..] {
            let apart = (p.0 - q.0).hypot(p.1 - q.1);
            let turned = (a - b).sin().atan2((a - b).cos()).abs().to_degrees();
            assert!(
                apart >= 1.0 - 1e-9 || turned >= 60.0 - 1e-9,
                "arrows at {p:?} ({:.0}°) and {q:?} ({:.0}°): {apart:.2} m, {turned:.0}°",
                a.to_degrees(),
                b.to_degrees()
            );
        }
    }
    let degrees: Vec<f64> = g
        .iter()
        .map(|&(_, a)| a.to_degrees().rem_euclid(360.0))
        .collect();
    assert!(
        degrees.iter().any(|&a| !(5.0..=355.0).contains(&a)),
        "{degrees:?}"
    );
    assert!(
        degrees.iter().any(|&a| (45.0..=135.0).contains(&a)),
        "{degrees:?}"
    );
    assert!(
        degrees.iter().any(|&a| (175.0..=185.0).contains(&a)),
        "{degrees:?}"
    );
    std::fs::remove_dir_all(&d).unwrap();
}
