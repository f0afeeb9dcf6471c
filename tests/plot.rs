//! The figure of a walk: written as PNG and SVG at 1600 × 1000 px, whole or not at all, and by
//! `klaw walk` next to the CSV (`--plot`, `--no-plot`).
use std::fs;
use std::path::Path;
use std::process::Output;

use klaw::engine::report::StateFrame;
use klaw::model::InputError;
use klaw::plot::walk::{FIGURE_SIZE, walk_figure};
use klaw::{Error, Simulation};

mod common;

/// The frames of the default walk (H = 1.8 m, M = 80 kg, v = 1.4 m/s), 4 steps at 100 frames/s.
fn default_frames() -> Vec<StateFrame> {
    Simulation::default()
        .steps(4)
        .run()
        .unwrap()
        .state_frames(100.0)
        .unwrap()
}

fn files(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// Width and height from a PNG's signature and IHDR chunk (the first chunk).
fn png_size(bytes: &[u8]) -> (u32, u32) {
    assert!(bytes.len() > 33, "{} bytes", bytes.len());
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "PNG signature");
    let be = |i: usize| u32::from_be_bytes(bytes[i..i + 4].try_into().unwrap());
    assert_eq!(be(8), 13, "IHDR length");
    assert_eq!(&bytes[12..16], b"IHDR");
    (be(16), be(20))
}

#[test]
fn default_walk_figure_is_written_as_png_and_svg() {
    let frames = default_frames();
    assert!(frames.len() > 200, "{} frames", frames.len());
    let dir = tempfile::tempdir().unwrap();

    let png = dir.path().join("walk.png");
    walk_figure(&frames, 4, &png).unwrap();
    let bytes = fs::read(&png).unwrap();
    assert_eq!(png_size(&bytes), (1600, 1000));
    assert_eq!(png_size(&bytes), FIGURE_SIZE);
    // a drawn figure, not a blank page: it compresses to well over a flat image's size
    assert!(bytes.len() > 20_000, "{} bytes", bytes.len());

    let svg = dir.path().join("walk.SVG");
    walk_figure(&frames, 4, &svg).unwrap();
    let text = fs::read_to_string(&svg).unwrap();
    assert!(text.starts_with("<svg"), "{}", &text[..text.len().min(200)]);
    assert!(
        text.contains(r#"width="1600""#) && text.contains(r#"height="1000""#),
        "{}",
        &text[..text.len().min(200)]
    );
    assert!(text.trim_end().ends_with("</svg>"));
    // stick figures: at least two polylines per 0.1 s of walk
    let polylines = text.matches("<polyline").count();
    assert!(polylines >= 2 * 22, "{polylines} polylines");

    // rewriting replaces the file; nothing else is left in the directory
    walk_figure(&frames[..50], 1, &png).unwrap();
    assert_eq!(png_size(&fs::read(&png).unwrap()), (1600, 1000));
    assert_eq!(files(dir.path()), ["walk.SVG", "walk.png"]);
}

#[test]
fn unwritable_figure_path_errors_without_leaving_a_file() {
    let frames = default_frames();
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();

    for name in ["no/such/dir/w.png", "no/such/dir/w.svg"] {
        let e = walk_figure(&frames, 4, &d.join(name)).unwrap_err();
        assert!(
            matches!(
                e,
                Error::Io {
                    action: "writing",
                    ..
                }
            ),
            "{e:?}"
        );
        assert!(e.to_string().contains("no/such/dir"), "{e}");
        assert!(files(d).is_empty(), "{:?}", files(d));
    }

    // the path is a directory: the final rename fails, the temporary file is removed
    fs::create_dir(d.join("taken.png")).unwrap();
    let e = walk_figure(&frames, 4, &d.join("taken.png")).unwrap_err();
    assert!(matches!(e, Error::Io { .. }), "{e:?}");
    assert_eq!(files(d), ["taken.png"]);
    assert!(fs::read_dir(d.join("taken.png")).unwrap().next().is_none());

    // an extension that is neither .png nor .svg is bad input, and nothing is written
    let e = walk_figure(&frames, 4, &d.join("walk.jpg")).unwrap_err();
    assert!(
        matches!(e, Error::Input(InputError::Malformed { .. })),
        "{e:?}"
    );
    assert_eq!(files(d), ["taken.png"]);
}

fn klaw_font(dir: &Path, args: &[&str], font: Option<&str>) -> Output {
    match font {
        Some(f) => common::klaw_with(dir, args, &[(klaw::plot::FONT_ENV, f)]),
        None => common::klaw(dir, args),
    }
}

#[test]
fn klaw_walk_writes_the_figure_by_default() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = klaw_font(d, &["walk", "--steps", "2"], None);
    assert!(out.status.success(), "{out:?}");
    assert!(String::from_utf8_lossy(&out.stdout).contains("plot: walk.png"));
    assert_eq!(files(d), ["walk.csv", "walk.png"]);
    assert_eq!(
        png_size(&fs::read(d.join("walk.png")).unwrap()),
        (1600, 1000)
    );

    let out = klaw_font(d, &["walk", "--steps", "2", "--plot", "two.svg"], None);
    assert!(out.status.success(), "{out:?}");
    assert!(
        fs::read_to_string(d.join("two.svg"))
            .unwrap()
            .starts_with("<svg")
    );

    let e = tempfile::tempdir().unwrap();
    let out = klaw_font(e.path(), &["walk", "--steps", "2", "--no-plot"], None);
    assert!(out.status.success(), "{out:?}");
    assert!(!String::from_utf8_lossy(&out.stdout).contains("plot:"));
    assert_eq!(files(e.path()), ["walk.csv"]);
}

#[test]
fn klaw_walk_draws_without_text_when_no_font_is_found() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let missing = d.join("no-such-font.ttf");
    let out = klaw_font(
        d,
        &["walk", "--steps", "2"],
        Some(missing.to_str().unwrap()),
    );
    assert!(out.status.success(), "{out:?}");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("without text"), "{stdout}");
    assert_eq!(
        png_size(&fs::read(d.join("walk.png")).unwrap()),
        (1600, 1000)
    );
}

#[test]
fn klaw_walk_rejects_bad_plot_paths_before_simulating() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // every output path is checked before any work: each of these is bad input
    let cases: &[(&[&str], &str, i32)] = &[
        (&["walk", "--plot", "walk.jpg"], ".png or .svg", 2),
        (&["walk", "--plot", "no/such/dir/w.png"], "no/such/dir", 2),
        (
            &["walk", "--out", "w.csv", "--plot", "w.csv"],
            ".png or .svg",
            2,
        ),
        (
            &["walk", "--state-out", "w.png", "--plot", "w.png"],
            "--state-out: w.png: the extension must be .csv",
            2,
        ),
        (
            &[
                "walk",
                "--out",
                "w.csv",
                "--cycle-out",
                "w.csv",
                "--steps",
                "6",
            ],
            "--out and --cycle-out name the same file",
            2,
        ),
        (&["walk", "--plot", "p.png", "--no-plot"], "--no-plot", 2),
    ];
    for (args, needle, code) in cases {
        let out = klaw_font(d, args, None);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(*code), "klaw {args:?}:\n{stderr}");
        assert!(
            stderr.contains(needle),
            "klaw {args:?}: `{needle}` not in\n{stderr}"
        );
        assert!(files(d).is_empty(), "klaw {args:?} left {:?}", files(d));
    }
}
