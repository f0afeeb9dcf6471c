//! `klaw plot-sweep`: heat maps of a sweep's column over two swept parameters, drawn from a
//! hand-written sweep output (known values and failures) and from a real sweep.
use std::fs;
use std::path::Path;
use std::process::Command;

use klaw::Error;
use klaw::model::InputError;
use klaw::plot::heat_map::{FAILED_COLOR, HEAT_MAP_SIZE, HeatMap, heat_map};

/// 3 velocities × 2 heights; (1.2, 1.8) failed; mean_iterations 4..8 with the minimum at
/// (1.0, 1.6) and the maximum at (1.4, 1.8).
const GRID: &str = "\
point,velocity,height,converged,error,mean_iterations
0,1.0,1.6,true,,4
1,1.0,1.8,true,,5
2,1.2,1.6,true,,6
3,1.2,1.8,false,\"no, it failed\",
4,1.4,1.6,true,,7
5,1.4,1.8,true,,8
";

fn grid(dir: &Path) -> std::path::PathBuf {
    let path = dir.join("grid.csv");
    fs::write(&path, GRID).unwrap();
    path
}

fn pixel(img: &image::RgbImage, x: i32, y: i32) -> [u8; 3] {
    img.get_pixel(x as u32, y as u32).0
}

#[test]
fn cells_have_their_colours_and_failed_cells_the_failure_colour() {
    let dir = tempfile::tempdir().unwrap();
    let input = grid(dir.path());
    let out = dir.path().join("map.png");
    let map = heat_map(&input, "velocity", "height", "mean_iterations", &out).unwrap();
    assert_eq!(map.xs, vec![1.0, 1.2, 1.4]);
    assert_eq!(map.ys, vec![1.6, 1.8]);
    assert_eq!(map.cells.len(), 6);
    let img = image::open(&out).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), HEAT_MAP_SIZE);
    let cell = |x: f64, y: f64| {
        map.cells
            .iter()
            .find(|c| c.x == x && c.y == y)
            .unwrap()
            .clone()
    };
    // a point a quarter down from the top centre: inside the cell, off the cross's diagonals
    let probe = |x: f64, y: f64| {
        let c = cell(x, y);
        let (l, t, r, b) = c.pixels;
        assert!(r - l > 40 && b - t > 40, "cell {:?}", c.pixels);
        pixel(&img, (l + r) / 2, t + (b - t) / 4)
    };
    let failed = cell(1.2, 1.8);
    assert!(failed.failed() && failed.value.is_none());
    assert_eq!(
        probe(1.2, 1.8),
        [FAILED_COLOR.0, FAILED_COLOR.1, FAILED_COLOR.2]
    );
    // the cross: the cell's centre is dark
    let (l, t, r, b) = failed.pixels;
    let centre = pixel(&img, (l + r) / 2, (t + b) / 2);
    assert!(centre.iter().all(|&c| c < 120), "{centre:?}");
    // the extremes of the scale are viridis' ends (matplotlib: #440154 and #fde725)
    assert_eq!(probe(1.0, 1.6), [0x44, 0x01, 0x54]);
    assert_eq!(probe(1.4, 1.8), [0xfd, 0xe7, 0x25]);
    // cells are laid out by value: velocity grows to the right, height upwards
    assert!(cell(1.0, 1.6).pixels.0 < cell(1.2, 1.6).pixels.0);
    assert!(cell(1.0, 1.8).pixels.1 < cell(1.0, 1.6).pixels.1);
    // no other cell has the failure colour
    for c in &map.cells {
        if !c.failed() {
            assert_ne!(
                probe(c.x, c.y),
                [FAILED_COLOR.0, FAILED_COLOR.1, FAILED_COLOR.2]
            );
        }
    }
}

#[test]
fn convergence_map_and_svg() {
    let dir = tempfile::tempdir().unwrap();
    let input = grid(dir.path());
    let out = dir.path().join("conv.svg");
    let map = heat_map(&input, "height", "velocity", "converged", &out).unwrap();
    let conv: Vec<Option<f64>> = map.cells.iter().map(|c| c.value).collect();
    assert_eq!(conv.iter().filter(|v| **v == Some(1.0)).count(), 5);
    assert_eq!(conv.iter().filter(|v| **v == Some(0.0)).count(), 1);
    let svg = fs::read_to_string(&out).unwrap();
    assert!(
        svg.starts_with("<svg") && svg.contains("width=\"1200\""),
        "{}",
        &svg[..80]
    );
}

#[test]
fn several_rows_per_cell_are_averaged_over_the_converged_ones() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("g.jsonl");
    fs::write(
        &path,
        "{\"point\":0,\"velocity\":1.0,\"height\":1.6,\"bounciness\":0.2,\"converged\":true,\"mean_iterations\":4}\n\
         {\"point\":1,\"velocity\":1.0,\"height\":1.6,\"bounciness\":0.4,\"converged\":true,\"mean_iterations\":6}\n\
         {\"point\":2,\"velocity\":1.0,\"height\":1.6,\"bounciness\":0.6,\"converged\":false,\"mean_iterations\":null}\n\
         {\"point\":3,\"velocity\":1.2,\"height\":1.6,\"bounciness\":0.2,\"converged\":false,\"mean_iterations\":null}\n",
    )
    .unwrap();
    let m = HeatMap::read(&path, "velocity", "height", "iterations").unwrap();
    assert_eq!(m.column, "mean_iterations");
    assert_eq!(m.cells[0].rows, 3);
    assert_eq!(m.cells[0].value, Some(5.0));
    assert!(m.cells[1].failed());
    let c = HeatMap::read(&path, "velocity", "height", "converged").unwrap();
    assert!((c.cells[0].value.unwrap() - 2.0 / 3.0).abs() < 1e-15);
}

#[test]
fn bad_names_are_input_errors() {
    let dir = tempfile::tempdir().unwrap();
    let input = grid(dir.path());
    let out = dir.path().join("m.png");
    for (x, y, column, flag, text) in [
        ("speed", "height", "converged", "x", "no column `speed`"),
        ("velocity", "heigth", "converged", "y", "no column `heigth`"),
        (
            "velocity",
            "height",
            "knee",
            "column",
            "its columns: point, velocity",
        ),
        ("velocity", "velocity", "converged", "y", "also the x axis"),
        ("velocity", "height", "error", "column", "not numeric"),
        (
            "velocity",
            "mean_iterations",
            "converged",
            "y",
            "was it swept?",
        ),
    ] {
        let e = heat_map(&input, x, y, column, &out).unwrap_err();
        match &e {
            Error::Input(InputError::BadValue { parameter: f, .. }) => assert_eq!(f, flag, "{e}"),
            _ => panic!("{x} {y} {column}: {e}"),
        }
        assert!(e.to_string().contains(text), "{e}");
    }
    let e = heat_map(
        &input,
        "velocity",
        "height",
        "converged",
        &dir.path().join("m.jpg"),
    )
    .unwrap_err();
    assert!(
        matches!(e, Error::Input(InputError::Malformed { .. })),
        "{e}"
    );
    assert!(!out.exists());
}

#[test]
fn plot_sweep_of_a_real_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let run = |args: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_klaw"))
            .args(args)
            .current_dir(dir.path())
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    run(&[
        "sweep",
        "--velocity",
        "1.0,1.4,3.0",
        "--height",
        "1.6,1.8",
        "--steps",
        "1",
        "--out",
        "s.csv",
    ]);
    run(&[
        "plot-sweep",
        "s.csv",
        "--x",
        "velocity",
        "--y",
        "height",
        "--column",
        "peak_knee",
        "--out",
        "knee.png",
    ]);
    let img = image::open(dir.path().join("knee.png")).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), HEAT_MAP_SIZE);
    let failed = img
        .pixels()
        .filter(|p| p.0 == [FAILED_COLOR.0, FAILED_COLOR.1, FAILED_COLOR.2])
        .count();
    // two failed cells (v = 3 m/s) of ≈ 1/3 × 1/2 of the plotting area
    assert!(failed > 20_000, "{failed} failure-coloured pixels");
    let out = Command::new(env!("CARGO_BIN_EXE_klaw"))
        .args(["plot-sweep", "s.csv", "--x", "velocity", "--y", "height"])
        .args(["--column", "nope", "--out", "x.png"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--column: no column `nope`"));
}

/// The axes' ticks are the swept values, whatever they are: off-round velocities (0.35, 0.55, …)
/// and heights (1.53, 1.61, …), where plotters' round ticks (0.4, 0.6, …) would fall between the
/// cells. A tick per value at its cells' centres, a dark mark below (left of) the plotting area
/// there and none halfway to the next, labelled with the value itself; on a dense axis (47
/// values) the labels that would overlap are left out, every value keeps its mark.
#[test]
fn ticks_are_the_swept_values_at_the_cells_centres() {
    let dir = tempfile::tempdir().unwrap();
    let (vs, hs) = (
        [0.35, 0.55, 0.75, 0.95, 1.15, 1.35],
        [1.53, 1.61, 1.69, 1.77],
    );
    let mut csv = String::from("point,velocity,height,converged,error,mean_iterations\n");
    for (i, v) in vs.iter().enumerate() {
        for (j, h) in hs.iter().enumerate() {
            csv += &format!("{},{v},{h},true,,{}\n", i * 4 + j, 4 + i + j);
        }
    }
    let input = dir.path().join("offround.csv");
    fs::write(&input, csv).unwrap();
    let out = dir.path().join("offround.png");
    let map = heat_map(&input, "velocity", "height", "mean_iterations", &out).unwrap();
    let img = image::open(&out).unwrap().to_rgb8();
    let dark = |x: i32, y: i32| pixel(&img, x, y).iter().all(|&c| c < 80);
    assert_eq!(
        map.x_ticks.iter().map(|t| t.value).collect::<Vec<_>>(),
        vs.to_vec()
    );
    assert_eq!(
        map.y_ticks.iter().map(|t| t.value).collect::<Vec<_>>(),
        hs.to_vec()
    );
    let labels = |ticks: &[klaw::plot::heat_map::Tick]| {
        ticks
            .iter()
            .map(|t| t.label.clone().unwrap_or_default())
            .collect::<Vec<_>>()
    };
    assert_eq!(
        labels(&map.x_ticks),
        ["0.35", "0.55", "0.75", "0.95", "1.15", "1.35"]
    );
    assert_eq!(labels(&map.y_ticks), ["1.53", "1.61", "1.69", "1.77"]);
    // the plotting area's bottom and left edges: the cells' extremes
    let bottom = map.cells.iter().map(|c| c.pixels.3).max().unwrap();
    let left = map.cells.iter().map(|c| c.pixels.0).min().unwrap();
    for t in &map.x_ticks {
        let c = map.cells.iter().find(|c| c.x == t.value).unwrap();
        assert!(
            (t.pixel - (c.pixels.0 + c.pixels.2) / 2).abs() <= 1,
            "{t:?}"
        );
        assert!(dark(t.pixel, bottom + 3), "no tick mark at {t:?}");
    }
    for t in &map.y_ticks {
        let c = map.cells.iter().find(|c| c.y == t.value).unwrap();
        assert!(
            (t.pixel - (c.pixels.1 + c.pixels.3) / 2).abs() <= 1,
            "{t:?}"
        );
        assert!(dark(left - 3, t.pixel), "no tick mark at {t:?}");
    }
    // halfway between two values (a cell's edge) no mark
    for w in map.x_ticks.windows(2) {
        let mid = (w[0].pixel + w[1].pixel) / 2;
        assert!(!dark(mid, bottom + 3), "a mark at column {mid}");
    }
    for w in map.y_ticks.windows(2) {
        let mid = (w[0].pixel + w[1].pixel) / 2;
        assert!(!dark(left - 3, mid), "a mark at row {mid}");
    }

    // a dense axis: 0.3, 0.35, …, 2.6 m/s × two heights
    let mut csv = String::from("point,velocity,height,converged,error,mean_iterations\n");
    let vs: Vec<f64> = (0..47).map(|k| (30 + 5 * k) as f64 / 100.0).collect();
    for (i, v) in vs.iter().enumerate() {
        for (j, h) in [1.6, 1.8].iter().enumerate() {
            csv += &format!("{},{v},{h},true,,{}\n", i * 2 + j, 4 + j);
        }
    }
    let input = dir.path().join("dense.csv");
    fs::write(&input, csv).unwrap();
    let out = dir.path().join("dense.png");
    let map = heat_map(&input, "velocity", "height", "mean_iterations", &out).unwrap();
    let (w, h) = HEAT_MAP_SIZE;
    assert_eq!(map.x_ticks.len(), 47);
    let labelled: Vec<_> = map.x_ticks.iter().filter(|t| t.label.is_some()).collect();
    assert!(
        labelled.len() >= 10 && labelled.len() < 47,
        "{} labels",
        labelled.len()
    );
    assert_eq!(map.x_ticks[0].label.as_deref(), Some("0.30"));
    for t in &labelled {
        assert_eq!(t.label.as_ref().unwrap().parse::<f64>().unwrap(), t.value);
        let (l, top, r, b) = t.label_box.unwrap();
        assert!(0 <= l && r < w as i32 && 0 <= top && b < h as i32, "{t:?}");
    }
    for p in labelled.windows(2) {
        let (a, b) = (p[0].label_box.unwrap(), p[1].label_box.unwrap());
        assert!(a.2 < b.0, "labels overlap: {:?} {:?}", p[0], p[1]);
    }
}
