//! `klaw plot`: the gait-cycle figure. The norm table against the published table (values typed
//! from gait-norms.md), the cycle phases and norm checks on synthetic curves with known answers,
//! the bands' pixels where their windows say, the file formats and the errors.
use std::f64::consts::PI;
use std::fs;
use std::path::Path;

mod common;

use common::default_walk;
use klaw::Error;
use klaw::analysis::cycle::{CycleError, GaitCycle, Panel, PanelCurve, min_steps};
use klaw::analysis::norms::{Measure, NormRange, NormTable, WalkSpeed, check};
use klaw::figure::clinical::Clinical;
use klaw::figure::skeleton::Side;
use klaw::model::InputError;
use klaw::plot::cycle::{
    BAND_COLOR, CYCLE_FIGURE_SIZE, EXCURSION_BAND_COLOR, SPEED_BAND_COLOR, SPEED_EDGE_COLOR,
    write_cycle_figure,
};

/// A cycle whose curves are given functions of the cycle % (101 samples).
fn synthetic(f: impl Fn(Panel, Option<Side>, f64) -> f64) -> GaitCycle {
    let mut curves = Vec::new();
    for panel in Panel::ALL {
        let sides = if panel.per_leg() {
            vec![Some(Side::Right), Some(Side::Left)]
        } else {
            vec![None]
        };
        for side in sides {
            curves.push(PanelCurve {
                panel,
                side,
                values: (0..=100).map(|p| f(panel, side, p as f64)).collect(),
            });
        }
    }
    GaitCycle {
        curves,
        cycles: (3, 3),
        toe_off_pct: [None, None],
    }
}

/// Flat curves far from every band: 0° (pelvis height 80 cm).
fn flat() -> GaitCycle {
    synthetic(|panel, _, _| {
        if panel == Panel::PelvisHeight {
            80.0
        } else {
            0.0
        }
    })
}

/// The speed the synthetic figures' speed-dependent norms are taken at: 1.4 m/s, l1 0.9 m.
const SPEED: WalkSpeed = WalkSpeed {
    velocity: 1.4,
    leg_length: 0.9,
};

/// The bundled table's fixed rows only (gait-norms.md's).
fn fixed_norms() -> NormTable {
    let mut t = NormTable::builtin();
    t.norms
        .retain(|n| matches!(n.range, NormRange::Fixed { .. }));
    t
}

fn norm<'a>(t: &'a NormTable, name: &str) -> &'a klaw::analysis::norms::Norm {
    t.norms
        .iter()
        .find(|n| n.name == name)
        .unwrap_or_else(|| panic!("no norm {name}"))
}

/// The bundled table's fixed rows hold the published ranges (typed here from gait-norms.md) with
/// windows covering the timing the table gives (its rows by speed: tests/speed_norms.rs).
#[test]
fn bundled_norms_are_the_published_ranges() {
    let t = fixed_norms();
    let expect = [
        ("hip flexion at heel strike", 25.0, 35.0, Some(0.0)),
        ("hip peak extension", -15.0, -5.0, Some(52.5)),
        ("hip sagittal range", 40.0, 50.0, None),
        ("knee at heel strike", 0.0, 8.0, Some(0.0)),
        ("knee stance flexion peak", 10.0, 25.0, Some(15.0)),
        ("knee peak swing flexion", 55.0, 65.0, Some(72.5)),
        ("ankle at heel strike", -5.0, 3.0, Some(0.0)),
        ("ankle peak dorsiflexion in stance", 8.0, 15.0, None),
        ("ankle peak plantarflexion", -25.0, -15.0, Some(62.5)),
        ("pelvic list, right side up (right stance)", 4.0, 5.0, None),
        ("pelvic list, left side up (left stance)", -5.0, -4.0, None),
        ("pelvic rotation, right side forward", 3.0, 5.0, None),
        ("pelvic rotation, left side forward", -5.0, -3.0, None),
        (
            "vertical excursion of the hip, peak to peak",
            4.0,
            5.0,
            None,
        ),
    ];
    assert_eq!(t.norms.len(), expect.len());
    for (name, low, high, timing) in expect {
        let n = norm(&t, name);
        assert_eq!(n.range, NormRange::Fixed { low, high }, "{name}");
        if let Some(p) = timing {
            assert!(
                n.windows.iter().any(|w| w[0] <= p && p <= w[1]),
                "{name}: windows {:?} miss {p} %",
                n.windows
            );
        }
    }
    // heel strike is 0 % and 100 %: both ends are shaded
    let hs = norm(&t, "knee at heel strike");
    assert_eq!(hs.measure, Measure::At);
    assert!(hs.windows.iter().any(|w| w[1] == 100.0));
    assert_eq!(
        norm(&t, "vertical excursion of the hip, peak to peak").unit,
        "cm"
    );
}

/// The checks on curves with known extremes.
#[test]
fn checks_measure_the_curves() {
    let cycle = synthetic(|panel, side, p| match panel {
        // a swing peak of 70° at 72 %, a stance bump of 15° at 15 %
        Panel::KneeFlexion => {
            let bump = |c: f64, w: f64, a: f64| a * (-((p - c) / w).powi(2)).exp();
            bump(72.0, 6.0, 70.0) + bump(15.0, 4.0, 15.0) + 2.0
        }
        Panel::HipFlexion => {
            // the left leg 2° more flexed at heel strike
            let extra = if side == Some(Side::Left) { 2.0 } else { 0.0 };
            10.0 + 20.0 * (2.0 * PI * p / 100.0).cos() + extra
        }
        Panel::PelvisList => 4.5 * (2.0 * PI * p / 100.0).sin(),
        Panel::PelvisHeight => 90.0 + 3.0 * (4.0 * PI * p / 100.0).cos(),
        _ => 0.0,
    });
    let checks = check(&cycle, &fixed_norms(), SPEED);
    let get = |name: &str, side: Option<Side>| {
        checks
            .iter()
            .find(|c| c.name == name && c.side == side)
            .unwrap_or_else(|| panic!("no check {name} {side:?}"))
    };
    let swing = get("knee peak swing flexion", Some(Side::Right));
    assert!((swing.value - 72.0).abs() < 0.01 && swing.at_pct == Some(72.0));
    assert!(!swing.inside());
    let stance = get("knee stance flexion peak", Some(Side::Left));
    assert!((stance.value - 17.0).abs() < 0.01 && stance.at_pct == Some(15.0));
    assert!(stance.inside());
    let hs = get("knee at heel strike", Some(Side::Right));
    assert!((hs.value - 2.0).abs() < 0.01 && hs.inside());
    let hip = get("hip flexion at heel strike", Some(Side::Right));
    assert!((hip.value - 30.0).abs() < 1e-9 && hip.inside());
    let hip_l = get("hip flexion at heel strike", Some(Side::Left));
    assert!((hip_l.value - 32.0).abs() < 1e-9);
    // peak extension: the minimum inside 45–60 %, at 50 %: −10°
    let ext = get("hip peak extension", Some(Side::Right));
    assert!((ext.value + 10.0).abs() < 1e-9 && ext.at_pct == Some(50.0));
    let range = get("hip sagittal range", Some(Side::Right));
    assert!((range.value - 40.0).abs() < 1e-9 && range.inside());
    let up = get("pelvic list, right side up (right stance)", None);
    assert!((up.value - 4.5).abs() < 1e-9 && up.at_pct == Some(25.0) && up.inside());
    let down = get("pelvic list, left side up (left stance)", None);
    assert!((down.value + 4.5).abs() < 1e-9 && down.at_pct == Some(75.0));
    let excursion = get("vertical excursion of the hip, peak to peak", None);
    assert!((excursion.value - 6.0).abs() < 1e-9 && !excursion.inside());
    // rotation is flat 0: outside ±3–5
    assert!(!get("pelvic rotation, right side forward", None).inside());
}

/// Frames whose right-leg angles are a function of the right cycle's phase and whose left-leg
/// angles the same function of the left cycle's phase (half a cycle later): averaged, the two
/// legs' curves coincide, each from its own heel strike; the pelvis height has two peaks.
#[test]
fn each_leg_is_averaged_from_its_own_heel_strike() {
    let period = 1.1;
    let right: Vec<f64> = (0..5).map(|k| 0.05 + k as f64 * period).collect();
    let left: Vec<f64> = right.iter().map(|t| t + period / 2.0).collect();
    let shape = |phase: f64| 30.0 * (2.0 * PI * phase).cos() + 5.0 * (4.0 * PI * phase).sin();
    let frames: Vec<Clinical> = (0..=1100)
        .map(|k| {
            let t = k as f64 * 0.005;
            let mut c = Clinical {
                time: t,
                ..Clinical::default()
            };
            let phase_r = (t - right[0]) / period;
            let phase_l = (t - left[0]) / period;
            c.right.hip.flexion = shape(phase_r).to_radians();
            c.left.hip.flexion = shape(phase_l).to_radians();
            c.right.knee.flexion = 1.0;
            c.left.knee.flexion = 0.5;
            c.pelvis_list = (4.0 * (2.0 * PI * phase_r).sin()).to_radians();
            c.pelvis = [t, 0.9 + 0.02 * (4.0 * PI * phase_r).cos(), 0.0];
            c
        })
        .collect();
    let cycle = GaitCycle::from_clinical(&frames, &right, &left, 1).unwrap();
    assert_eq!(cycle.cycles, (3, 3));
    let curve = |panel: Panel, side: Option<Side>| {
        &cycle
            .curves
            .iter()
            .find(|c| c.panel == panel && c.side == side)
            .unwrap()
            .values
    };
    for p in 0..=100 {
        let want = shape(p as f64 / 100.0);
        for side in [Side::Right, Side::Left] {
            let got = curve(Panel::HipFlexion, Some(side))[p];
            // linear interpolation between frames 5 ms apart: error ≲ 0.02°
            assert!((got - want).abs() < 0.05, "{side:?} {p} %: {got} vs {want}");
        }
        let h = curve(Panel::PelvisHeight, None)[p];
        let want_h = 90.0 + 2.0 * (4.0 * PI * p as f64 / 100.0).cos();
        assert!((h - want_h).abs() < 0.01, "height {p} %: {h} vs {want_h}");
        let list = curve(Panel::PelvisList, None)[p];
        let want_list = 4.0 * (2.0 * PI * p as f64 / 100.0).sin();
        assert!((list - want_list).abs() < 0.01, "list {p} %: {list}");
    }
    // each leg's own column, in degrees
    assert!((curve(Panel::KneeFlexion, Some(Side::Right))[40] - 1f64.to_degrees()).abs() < 1e-9);
    assert!((curve(Panel::KneeFlexion, Some(Side::Left))[40] - 0.5f64.to_degrees()).abs() < 1e-9);
    // too few heel strikes: a typed error
    let e = GaitCycle::from_clinical(&frames, &right[..2], &left, 1).unwrap_err();
    assert!(matches!(e, CycleError::NoSteadyCycle { .. }), "{e}");
}

fn rgb(c: plotters::style::RGBColor) -> [u8; 3] {
    [c.0, c.1, c.2]
}

/// The run of `color` along row `y` of `img` that contains column `x`: (first, last) column.
fn run(img: &image::RgbImage, x: i32, y: i32, color: [u8; 3]) -> (i32, i32) {
    let at = |x: i32| img.get_pixel(x as u32, y as u32).0;
    assert_eq!(at(x), color, "no band at ({x}, {y})");
    let (mut a, mut b) = (x, x);
    while a > 0 && at(a - 1) == color {
        a -= 1;
    }
    while (b + 1) < img.width() as i32 && at(b + 1) == color {
        b += 1;
    }
    (a, b)
}

/// The knee's swing band (55–65° over 65–80 %, from the table's 70–75 %) is drawn exactly over
/// its window: found by pixel colour where the panel's axes put it, and nowhere else along its
/// row; a band of a hand-written table likewise; the excursion band sits 4–5 cm above the
/// curve's minimum.
#[test]
fn norm_bands_are_drawn_over_their_windows_only() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("cycle.png");
    let fig = write_cycle_figure(&flat(), &fixed_norms(), SPEED, "synthetic", &path).unwrap();
    let img = image::open(&path).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), CYCLE_FIGURE_SIZE);
    let panel = |p: Panel| *fig.panels.iter().find(|x| x.panel == p).unwrap();
    // the pixel of (cycle %, value) from the panel's corners, linear on both axes
    let px = |p: Panel, pct: f64, v: f64| {
        let m = panel(p);
        let (l, t) = m.left_top;
        let (r, b) = m.right_bottom;
        let (lo, hi) = m.y_range;
        (
            (l as f64 + (r - l) as f64 * pct / 100.0).round() as i32,
            (b as f64 - (b - t) as f64 * (v - lo) / (hi - lo)).round() as i32,
        )
    };
    let band = rgb(BAND_COLOR);
    let (x, y) = px(Panel::KneeFlexion, 72.5, 60.0);
    let (a, b) = run(&img, x, y, band);
    let (x65, _) = px(Panel::KneeFlexion, 65.0, 60.0);
    let (x80, _) = px(Panel::KneeFlexion, 80.0, 60.0);
    assert!(
        (a - x65).abs() <= 2 && (b - x80).abs() <= 2,
        "run {a}..{b}, window {x65}..{x80}"
    );
    // the rest of the row inside the panel has no band colour (the band is 55–65° only at
    // 65–80 %; the heel-strike band 0–8° is far below)
    let (l, _) = panel(Panel::KneeFlexion).left_top;
    let (r, _) = panel(Panel::KneeFlexion).right_bottom;
    for col in (l + 3..a - 1).chain(b + 2..r - 2) {
        assert_ne!(
            img.get_pixel(col as u32, y as u32).0,
            band,
            "band at column {col}"
        );
    }
    // above and below the value band, inside the window: no band
    for v in [50.0, 70.0] {
        let (x, y) = px(Panel::KneeFlexion, 72.5, v);
        assert_ne!(img.get_pixel(x as u32, y as u32).0, band, "{v}°");
    }
    // heel strike: both ends of the cycle, 0–8°
    let (x, y) = px(Panel::KneeFlexion, 2.0, 4.0);
    assert_eq!(img.get_pixel(x as u32, y as u32).0, band);
    let (x, y) = px(Panel::KneeFlexion, 98.0, 4.0);
    assert_eq!(img.get_pixel(x as u32, y as u32).0, band);
    let (x, y) = px(Panel::KneeFlexion, 50.0, 4.0);
    assert_ne!(img.get_pixel(x as u32, y as u32).0, band);

    // a hand-written table: one band of 40–50° over 20–30 % on the hip panel
    let table = NormTable::parse(
        "[[norm]]\npanel = \"hip_flexion\"\nname = \"test\"\nlabel = \"test\"\n\
         measure = \"max\"\nlow = 40.0\nhigh = 50.0\nunit = \"deg\"\nwindows = [[20.0, 30.0]]\n\
         window_source = \"test\"\nsource = \"test\"\n\
         [[norm]]\npanel = \"pelvis_height\"\nname = \"exc\"\nlabel = \"exc\"\n\
         measure = \"peak_to_peak\"\nlow = 4.0\nhigh = 5.0\nunit = \"cm\"\n\
         windows = [[0.0, 100.0]]\nwindow_source = \"test\"\nsource = \"test\"\n",
        Path::new("test.toml"),
    )
    .unwrap();
    let path = dir.path().join("custom.svg");
    let cycle = synthetic(|panel, _, p| match panel {
        Panel::PelvisHeight => 90.0 + 3.0 * (4.0 * PI * p / 100.0).cos(),
        _ => 0.0,
    });
    write_cycle_figure(&cycle, &table, SPEED, "synthetic", &path).unwrap();
    let svg = fs::read_to_string(&path).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("width=\"1500\""));
    let path = dir.path().join("custom.png");
    let fig = write_cycle_figure(&cycle, &table, SPEED, "synthetic", &path).unwrap();
    let img = image::open(&path).unwrap().to_rgb8();
    let panel = |p: Panel| *fig.panels.iter().find(|x| x.panel == p).unwrap();
    let px = |p: Panel, pct: f64, v: f64| {
        let m = panel(p);
        let (l, t) = m.left_top;
        let (r, b) = m.right_bottom;
        let (lo, hi) = m.y_range;
        (
            (l as f64 + (r - l) as f64 * pct / 100.0).round() as i32,
            (b as f64 - (b - t) as f64 * (v - lo) / (hi - lo)).round() as i32,
        )
    };
    let (x, y) = px(Panel::HipFlexion, 25.0, 45.0);
    let (a, b) = run(&img, x, y, band);
    let (x20, _) = px(Panel::HipFlexion, 20.0, 45.0);
    let (x30, _) = px(Panel::HipFlexion, 30.0, 45.0);
    assert!(
        (a - x20).abs() <= 2 && (b - x30).abs() <= 2,
        "run {a}..{b}, window {x20}..{x30}"
    );
    // none of the bundled bands: nothing at the knee's swing window
    let (x, y) = px(
        Panel::KneeFlexion,
        72.5,
        0.5 * (panel(Panel::KneeFlexion).y_range.1),
    );
    assert_ne!(img.get_pixel(x as u32, y as u32).0, band);
    // the excursion norm is not drawn over the cycle (where the curve's values are not what it
    // bounds): no excursion colour anywhere in the pelvis panel's plotting area
    let exc = rgb(EXCURSION_BAND_COLOR);
    let m = panel(Panel::PelvisHeight);
    for y in m.left_top.1..=m.right_bottom.1 {
        for x in m.left_top.0..=m.right_bottom.0 {
            assert_ne!(img.get_pixel(x as u32, y as u32).0, exc, "at ({x}, {y})");
        }
    }
    // but beside it (tests `range_norms_are_drawn_beside_their_panels`)
    assert_eq!(fig.ranges.len(), 1);
}

/// A range norm (peak to peak) is drawn beside its panel, right of the plotting area: a bracket
/// from the curve's minimum to its maximum, and a bar from min + low to min + high, each where
/// the panel's axis puts those values; a by-speed one light blue. The pelvis height 90 ± 3 cm
/// (min 87, max 93, a range of 6 cm, outside 4–5 cm): the bar 91–92 cm lies under the bracket's
/// top, so the reader sees the range too large. The speed bands of pelvic rotation and pelvis
/// height are nowhere over their cycles.
#[test]
fn range_norms_are_drawn_beside_their_panels() {
    let cycle = synthetic(|panel, side, p| match (panel, side) {
        (Panel::PelvisHeight, _) => 90.0 + 3.0 * (4.0 * PI * p / 100.0).cos(),
        (Panel::PelvisRotation, _) => 5.0 * (2.0 * PI * p / 100.0).cos(),
        (Panel::HipFlexion, Some(Side::Right)) => 10.0 + 20.0 * (2.0 * PI * p / 100.0).cos(),
        (Panel::HipFlexion, _) => 12.0 + 24.0 * (2.0 * PI * p / 100.0).cos(),
        _ => 0.0,
    });
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ranges.png");
    let table = NormTable::builtin();
    let fig = write_cycle_figure(&cycle, &table, SPEED, "synthetic", &path).unwrap();
    let img = image::open(&path).unwrap().to_rgb8();
    let (w, _) = img.dimensions();
    // every range norm of the table, on each curve of its panel (the speed ones are in their
    // span at 1.4 m/s, l1 0.9 m)
    let expected: Vec<(Panel, &str, Option<Side>)> = table
        .norms
        .iter()
        .filter(|n| n.measure == Measure::PeakToPeak)
        .flat_map(|n| {
            let sides = if n.panel.per_leg() {
                vec![Some(Side::Right), Some(Side::Left)]
            } else {
                vec![None]
            };
            sides.into_iter().map(|s| (n.panel, n.name.as_str(), s))
        })
        .collect();
    assert_eq!(expected.len(), 5, "{expected:?}");
    let drawn: Vec<(Panel, &str, Option<Side>)> = fig
        .ranges
        .iter()
        .map(|r| (r.panel, r.name.as_str(), r.side))
        .collect();
    let key = |&(p, n, s): &(Panel, &str, Option<Side>)| {
        (
            Panel::ALL.iter().position(|&q| q == p),
            n.to_string(),
            s.is_some_and(|s| s == Side::Left),
        )
    };
    let (mut drawn, mut expected) = (drawn, expected);
    drawn.sort_by_key(key);
    expected.sort_by_key(key);
    assert_eq!(drawn, expected);
    for r in &fig.ranges {
        let m = fig.panels.iter().find(|p| p.panel == r.panel).unwrap();
        let row = |v: f64| pixel(&fig, r.panel, 0.0, v).1 as i32;
        let ((lo, hi), (low, high)) = r.values;
        let n = table.norms.iter().find(|n| n.name == r.name).unwrap();
        let (nl, nh) = n.range.at(SPEED).unwrap();
        assert_eq!((low, high), (nl, nh), "{}", r.name);
        // the curve's own extent
        let c = cycle
            .curves
            .iter()
            .find(|c| c.panel == r.panel && c.side == r.side)
            .unwrap();
        let cmin = c.values.iter().copied().fold(f64::INFINITY, f64::min);
        let cmax = c.values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        assert_eq!((lo, hi), (cmin, cmax), "{}", r.name);
        // where the axis puts them, to a pixel
        let (bx, (bt, bb)) = r.bracket;
        assert!(
            (bt - row(hi)).abs() <= 1 && (bb - row(lo)).abs() <= 1,
            "{r:?}"
        );
        let ((l, rr), (t, b)) = r.bar;
        assert!((t - row(lo + high)).abs() <= 1, "{r:?}");
        assert!((b - row(lo + low)).abs() <= 1, "{r:?}");
        // right of the plotting area, inside the image
        let right = m.right_bottom.0;
        assert!(
            right < bx && bx < l && l < rr && rr < w as i32,
            "{r:?}, plot ends at {right}"
        );
        // the bar's colour: light blue by speed, orange fixed
        let fill = if n.range.by_speed().is_some() {
            rgb(SPEED_BAND_COLOR)
        } else {
            rgb(EXCURSION_BAND_COLOR)
        };
        let mid = img.get_pixel(((l + rr) / 2) as u32, ((t + b) / 2) as u32).0;
        assert_eq!(mid, fill, "{r:?}");
    }
    // the pelvis: a range of 6 cm against 4–5: the bracket's top is above the fixed bar
    let exc = fig
        .ranges
        .iter()
        .find(|r| r.name == "vertical excursion of the hip, peak to peak")
        .unwrap();
    assert!(exc.bracket.1.0 < exc.bar.1.0);
    // no range norm's colour over the cycle in the pelvis panels (which have no other norm of
    // that colour: the by-speed list and rotation peaks are drawn, so check height only)
    let m = fig
        .panels
        .iter()
        .find(|p| p.panel == Panel::PelvisHeight)
        .unwrap();
    for y in m.left_top.1..=m.right_bottom.1 {
        for x in m.left_top.0..=m.right_bottom.0 {
            let c = img.get_pixel(x as u32, y as u32).0;
            assert!(
                c != rgb(SPEED_BAND_COLOR) && c != rgb(EXCURSION_BAND_COLOR),
                "a range norm's fill at ({x}, {y}) over the cycle"
            );
        }
    }
    // the rotation panel: its range norm is not over the cycle either; the only speed fill
    // inside it lies in the windows of the + and − peaks (0–10 %, 40–60 %, 90–100 %)
    let m = fig
        .panels
        .iter()
        .find(|p| p.panel == Panel::PelvisRotation)
        .unwrap();
    let (x15, _) = pixel(&fig, Panel::PelvisRotation, 15.0, 0.0);
    let (x35, _) = pixel(&fig, Panel::PelvisRotation, 35.0, 0.0);
    for y in m.left_top.1..=m.right_bottom.1 {
        for x in x15..=x35 {
            assert_ne!(
                img.get_pixel(x, y as u32).0,
                rgb(SPEED_BAND_COLOR),
                "({x}, {y})"
            );
        }
    }
    // the legend's texts lie inside the image, above the panels, on rows of their own
    let top = fig.panels.iter().map(|p| p.left_top.1).min().unwrap();
    assert!(fig.legend.len() >= 7, "{:?}", fig.legend);
    for (i, &(l, t, r, b)) in fig.legend.iter().enumerate() {
        assert!(
            0 <= l && l < r && r < w as i32 && 0 <= t && b < top,
            "{:?}",
            fig.legend
        );
        for &(l2, t2, r2, b2) in &fig.legend[i + 1..] {
            assert!(r2 <= l || r <= l2 || b2 <= t || b <= t2, "{:?}", fig.legend);
        }
    }
}

/// The pixel of (cycle %, value) on `panel` of a written figure, from the panel's corners,
/// linear on both axes.
fn pixel(fig: &klaw::plot::cycle::CycleFigure, panel: Panel, pct: f64, v: f64) -> (u32, u32) {
    let m = fig.panels.iter().find(|x| x.panel == panel).unwrap();
    let ((l, t), (r, b)) = (m.left_top, m.right_bottom);
    let (lo, hi) = m.y_range;
    (
        (l as f64 + (r - l) as f64 * pct / 100.0).round() as u32,
        (b as f64 - (b - t) as f64 * (v - lo) / (hi - lo)).round() as u32,
    )
}

/// A speed-dependent band is drawn at the walk's speed: a hand-written row of mean 40…60° ± 5°
/// over v̂ 0.25…0.75 on the hip panel (20–30 %) and a fixed row of 45–55° over 25–35 %. At
/// v̂ 0.5 the speed band is 45–55°, light blue where it is alone, under the fixed band's green
/// where they overlap, its edge over both; at v̂ 0.25 it is 35–45°; outside its span it is not
/// drawn.
#[test]
fn speed_bands_are_drawn_at_the_walks_speed() {
    let table = NormTable::parse(
        "[[norm]]\npanel = \"hip_flexion\"\nname = \"speed\"\nlabel = \"speed\"\n\
         measure = \"max\"\nunit = \"deg\"\nwindows = [[20.0, 30.0]]\n\
         window_source = \"test\"\nsource = \"test\"\n[norm.by_speed]\ncite = \"test\"\n\
         speed = [0.25, 0.75]\nspan = [0.25, 0.75]\nmean = [40.0, 60.0]\nsd = [5.0, 5.0]\n\
         sd_multiple = 1.0\n\
         [[norm]]\npanel = \"hip_flexion\"\nname = \"fixed\"\nlabel = \"fixed\"\n\
         measure = \"max\"\nlow = 45.0\nhigh = 55.0\nunit = \"deg\"\nwindows = [[25.0, 35.0]]\n\
         window_source = \"test\"\nsource = \"test\"\n",
        Path::new("test.toml"),
    )
    .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("speed.png");
    // v̂ = v / √(g l) with g l = 4
    let at = |v_hat: f64| WalkSpeed {
        velocity: 2.0 * v_hat,
        leg_length: 4.0 / klaw::model::GRAVITY,
    };
    let draw = |v_hat: f64| {
        let fig = write_cycle_figure(&flat(), &table, at(v_hat), "synthetic", &path).unwrap();
        (fig, image::open(&path).unwrap().to_rgb8())
    };
    let (speed, fixed, edge) = (
        rgb(SPEED_BAND_COLOR),
        rgb(BAND_COLOR),
        rgb(SPEED_EDGE_COLOR),
    );
    let color = |fig, img: &image::RgbImage, pct, v| {
        let (x, y) = pixel(fig, Panel::HipFlexion, pct, v);
        img.get_pixel(x, y).0
    };
    let (fig, img) = draw(0.5);
    assert_eq!(color(&fig, &img, 22.0, 50.0), speed);
    assert_eq!(color(&fig, &img, 28.0, 50.0), fixed);
    assert_eq!(color(&fig, &img, 32.0, 50.0), fixed);
    assert_ne!(color(&fig, &img, 22.0, 58.0), speed);
    assert_ne!(color(&fig, &img, 22.0, 42.0), speed);
    // the edge at 55°, over the fixed band at 28 %: within a pixel of where the axes put it
    for pct in [22.0, 28.0] {
        let (x, y) = pixel(&fig, Panel::HipFlexion, pct, 55.0);
        assert!(
            (y - 1..=y + 1).any(|y| img.get_pixel(x, y).0 == edge),
            "no edge at {pct} %"
        );
    }
    let (fig, img) = draw(0.25);
    assert_eq!(color(&fig, &img, 22.0, 40.0), speed);
    assert_ne!(color(&fig, &img, 22.0, 50.0), speed);
    let (fig, img) = draw(0.8);
    assert_ne!(color(&fig, &img, 22.0, 50.0), speed);
    assert_eq!(color(&fig, &img, 28.0, 50.0), fixed);
}

/// The default walk's figure as PNG (1500 × 1000) and SVG; a bad extension is a typed error and
/// writes nothing; a walk too short for a steady cycle of each leg is a typed error.
#[test]
fn default_walk_figure_and_errors() {
    let walk = default_walk(6);
    let cycle = GaitCycle::from_walk(&walk).unwrap();
    assert_eq!(cycle.cycles, (1, 1));
    assert!(cycle.curves.iter().all(|c| c.values.len() == 101));
    // toe-off between 50 and 75 % of the cycle (stance is longer than a step, shorter than 3/4)
    for p in cycle.toe_off_pct {
        let p = p.unwrap();
        assert!(p > 50.0 && p < 75.0, "{p}");
    }
    let dir = tempfile::tempdir().unwrap();
    let norms = NormTable::builtin();
    let png = dir.path().join("gait-cycle.png");
    let speed = WalkSpeed::of_walk(&walk);
    assert!((speed.velocity - 1.4).abs() < 1e-12 && speed.leg_length == walk.body.l1);
    let fig = write_cycle_figure(&cycle, &norms, speed, "default walk", &png).unwrap();
    assert_eq!(
        image::open(&png).unwrap().to_rgb8().dimensions(),
        CYCLE_FIGURE_SIZE
    );
    assert_eq!(fig.panels.len(), 6);
    let svg = dir.path().join("gait-cycle.svg");
    write_cycle_figure(&cycle, &norms, speed, "default walk", &svg).unwrap();
    let svg = fs::read_to_string(&svg).unwrap();
    assert!(svg.starts_with("<svg"));
    if klaw::plot::text_available() {
        assert!(svg.contains("Knee flexion"));
    }

    for bad in ["cycle.jpg", "cycle", "cycle.gif"] {
        let p = dir.path().join(bad);
        let e = write_cycle_figure(&cycle, &norms, speed, "x", &p).unwrap_err();
        assert!(
            matches!(e, Error::Input(InputError::Malformed { .. })),
            "{e}"
        );
        assert!(!p.exists());
    }
    let e = GaitCycle::from_walk(&default_walk(5)).unwrap_err();
    assert!(matches!(e, CycleError::NoSteadyCycle { .. }), "{e}");
}

/// `klaw plot`: writes the figure and prints one line per check (45 for the bundled table at
/// 1.4 m/s: 9 + 9 by speed on both legs, 5 + 4 by speed on the pelvis); a bad extension exits 2
/// before simulating.
#[test]
fn cli_writes_the_figure_and_prints_the_checks() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("cycle.png");
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_klaw"))
            .args(args)
            .output()
            .unwrap()
    };
    let o = run(&["plot", "--steps", "6", "--out", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    let checks = stdout
        .lines()
        .filter(|l| l.ends_with(": inside") || l.ends_with(": OUTSIDE"))
        .count();
    assert_eq!(checks, 45, "{stdout}");
    assert_eq!(
        image::open(&out).unwrap().to_rgb8().dimensions(),
        CYCLE_FIGURE_SIZE
    );
    let bad = dir.path().join("cycle.jpg");
    let o = run(&["plot", "--out", bad.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!bad.exists());
}

/// `min_steps` is the least walk `GaitCycle::from_walk` averages: one step fewer has no steady
/// cycle of the left leg (both legs) or of the right (the right leg alone, by its own count).
#[test]
fn the_least_walk_of_a_gait_cycle_is_min_steps() {
    let walk = |n: usize| common::walk(common::default_body(), 1.4, n).unwrap();
    assert!(GaitCycle::from_walk(&walk(min_steps(true))).is_ok());
    assert!(matches!(
        GaitCycle::from_walk(&walk(min_steps(true) - 1)),
        Err(CycleError::NoSteadyCycle { .. })
    ));
    // the right leg alone, as `klaw walk --cycle-out` averages it from the stream
    let right = |n: usize| {
        let prepared = klaw::Simulation::default().steps(n).prepare().unwrap();
        let gather = klaw::Gather {
            clinical: true,
            ..klaw::Gather::default()
        };
        let mut stream = prepared.stream(100.0, gather).unwrap();
        (&mut stream).for_each(|f| {
            f.unwrap();
        });
        klaw::analysis::cycle::cycle_average(&stream.clinical, &stream.right_heel_strikes, 1)
    };
    assert!(right(min_steps(false)).is_ok());
    assert!(matches!(
        right(min_steps(false) - 1),
        Err(CycleError::NoSteadyCycle { .. })
    ));
}

/// The overlay of two walks' cycles (`measure/compare_modes.rs`): its legend lies in a row of
/// its own, outside every panel's plotting area and inside the image, so no curve runs under
/// it. Curves that fill their panels' upper left corners (where a legend inside the chart sat,
/// over the hip's and the ankle's curves): none of their points is in a legend entry's box.
#[test]
fn the_overlay_legend_covers_no_curve() {
    use klaw::plot::overlay::write_overlay;
    // high at both ends and at the start, where the upper corners are
    let first = synthetic(|_, _, p| 40.0 * (2.0 * PI * p / 100.0).cos());
    let second = synthetic(|_, _, p| 38.0 * (2.0 * PI * p / 100.0).cos() - 3.0);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("overlay.png");
    let layout = write_overlay(
        ("dynamic mode", &first),
        ("kinematic mode", &second),
        "synthetic",
        &path,
    )
    .unwrap();
    let img = image::open(&path).unwrap().to_rgb8();
    let (w, h) = img.dimensions();
    assert_eq!(layout.legend.len(), 2);
    let apart = |a: (i32, i32, i32, i32), b: (i32, i32, i32, i32)| {
        a.2 < b.0 || b.2 < a.0 || a.3 < b.1 || b.3 < a.1
    };
    for &entry in &layout.legend {
        let (l, t, r, b) = entry;
        assert!(
            0 <= l && r < w as i32 && 0 <= t && b < h as i32,
            "{entry:?}"
        );
        for &panel in &layout.panels {
            assert!(apart(entry, panel), "legend {entry:?} over panel {panel:?}");
        }
        for (k, curve) in layout.curves.iter().enumerate() {
            assert_eq!(curve.len(), 202, "panel {k}");
            for &(x, y) in curve {
                assert!(
                    !(l <= x && x <= r && t <= y && y <= b),
                    "panel {k}'s curve at ({x}, {y}) under the legend {entry:?}"
                );
            }
        }
    }
    // the curves are inside their panels
    for (panel, curve) in layout.panels.iter().zip(&layout.curves) {
        for &(x, y) in curve {
            assert!(panel.0 <= x && x <= panel.2 + 1 && panel.1 <= y && y <= panel.3 + 1);
        }
    }
}
