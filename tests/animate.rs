//! `klaw animate`: the animated GIF of a walk. Decoded frame by frame: the frame count and
//! delay from the walk's duration and the frame rate, the image size, the ground where the view
//! map puts it, a contact dot under a flat foot and none under a foot in the air; bad paths,
//! options and frames are typed errors that leave no file.
use std::fs;
use std::path::Path;

mod common;

use common::default_walk;
use image::{AnimationDecoder, RgbaImage};
use klaw::Error;
use klaw::figure::{FigureError, Landmarks};
use klaw::model::InputError;
use klaw::plot::animation::{AnimationOptions, animate_walk, check_path, parse_size, write_gif};

/// The decoded frames (RGBA) and each frame's delay in ms.
fn decode(path: &Path) -> Vec<(RgbaImage, u32)> {
    let file = std::io::BufReader::new(fs::File::open(path).unwrap());
    let decoder = image::codecs::gif::GifDecoder::new(file).unwrap();
    decoder
        .into_frames()
        .collect_frames()
        .unwrap()
        .into_iter()
        .map(|f| {
            let (n, d) = f.delay().numer_denom_ms();
            (f.into_buffer(), n / d)
        })
        .collect()
}

fn dark(img: &RgbaImage, x: i32, y: i32) -> bool {
    let p = img.get_pixel(x as u32, y as u32).0;
    p[0] < 50 && p[1] < 50 && p[2] < 50
}

fn grey(img: &RgbaImage, x: i32, y: i32) -> bool {
    let p = img.get_pixel(x as u32, y as u32).0;
    (110..=170).contains(&p[0]) && (110..=170).contains(&p[1]) && (110..=170).contains(&p[2])
}

#[test]
fn gif_has_a_frame_per_interval_and_dots_under_flat_feet() {
    let walk = default_walk(3);
    let fps = 20.0;
    let options = AnimationOptions::new(fps, (480, 240)).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("walk.gif");
    let summary = animate_walk(&walk, "test walk", &path, &options).unwrap();
    // t = 0, 1/fps, … up to the last heel strike
    let expected = (walk.duration() * fps + 1e-9).floor() as usize + 1;
    let frames = decode(&path);
    assert_eq!(frames.len(), expected);
    assert_eq!(summary.frames, expected);
    for (img, delay) in &frames {
        assert_eq!(img.dimensions(), (480, 240));
        assert_eq!(*delay, 50);
    }
    let landmarks: Vec<Landmarks> = klaw::figure::frames(&walk, fps)
        .collect::<Result<_, _>>()
        .unwrap();
    assert_eq!(landmarks.len(), expected);

    // a frame with the right foot flat (heel and metatarsal joint on the ground) and the left
    // heel in the air, not above the right foot
    let k = landmarks
        .iter()
        .position(|lm| {
            let apart = [lm.right.heel, lm.right.mtp, lm.right.toe]
                .iter()
                .all(|p| (p[0] - lm.left.heel[0]).abs() > 0.08);
            lm.right.heel[1].abs() < 1e-4
                && lm.right.mtp[1].abs() < 1e-4
                && lm.left.heel[1] > 0.04
                && apart
        })
        .expect("a frame of single support on a flat right foot");
    let (img, _) = &frames[k];
    let lm = &landmarks[k];
    let view = summary.views[k].clone();
    // the side view's map: the camera on the pelvis (the centre of the left two thirds), the
    // ground line where the map puts y = 0
    let (px, _) = view.side.pixel(lm.pelvis[0], lm.pelvis[1]);
    assert!((px - 480 * 2 / 3 / 2).abs() <= 2, "pelvis at column {px}");
    let (_, ground) = view.side.pixel(lm.pelvis[0], 0.0);
    assert!(
        (-1..=1).any(|d| grey(img, 12, ground + d)),
        "no ground line at row {ground}"
    );
    // the dot: filled, radius 4, around the heel: dark 2 px above the ground line
    let (hx, hy) = view.side.pixel(lm.right.heel[0], 0.0);
    assert!(
        dark(img, hx, hy - 2) && dark(img, hx + 2, hy - 1),
        "no dot at the right heel"
    );
    // none under the swinging left heel (nothing dark within 3 px of its ground point)
    let (lx, ly) = view.side.pixel(lm.left.heel[0], 0.0);
    for dx in -3..=3 {
        for dy in -3..=0 {
            assert!(
                !dark(img, lx + dx, ly + dy),
                "dark pixel under the left heel"
            );
        }
    }
    // front view: the right foot (figure's right = +z) drawn at −z, a dot there too
    let (fx, fy) = view.front.pixel(-lm.right.heel[2], 0.0);
    assert!(
        fx > 480 * 2 / 3,
        "front view starts at two thirds of the width"
    );
    assert!(dark(img, fx, fy - 2), "no dot in the front view");

    // the first frame (heel strike of the right foot, toe of the left on the ground)
    // has a dot under the right heel too
    let lm0 = &landmarks[0];
    assert!(lm0.right.heel[1].abs() < 1e-3);
    let (hx, hy) = summary.views[0].side.pixel(lm0.right.heel[0], 0.0);
    assert!(dark(&frames[0].0, hx, hy - 2));
}

#[test]
fn bad_paths_options_and_frames_are_typed_errors() {
    let dir = tempfile::tempdir().unwrap();
    for bad in ["walk.png", "walk", "walk.gif.txt"] {
        let e = check_path(Path::new(bad)).unwrap_err();
        assert!(matches!(e, InputError::Malformed { .. }), "{e}");
    }
    assert!(check_path(Path::new("a/walk.GIF")).is_ok());
    for (fps, size) in [
        (0.0, (900, 450)),
        (101.0, (900, 450)),
        (f64::NAN, (900, 450)),
        (25.0, (100, 450)),
        (25.0, (900, 50)),
        (25.0, (5000, 450)),
    ] {
        let e = AnimationOptions::new(fps, size).unwrap_err();
        assert!(
            matches!(
                e,
                InputError::OutOfRange { .. } | InputError::NotFinite { .. }
            ),
            "{e}"
        );
    }
    assert_eq!(parse_size("900x450").unwrap(), (900, 450));
    assert_eq!(parse_size(" 640X360 ").unwrap(), (640, 360));
    for bad in ["900", "x450", "900x", "a x b"] {
        let e = parse_size(bad).unwrap_err();
        assert!(matches!(e, InputError::BadValue { .. }), "{bad}: {e}");
    }
    // a negative size is a size, out of range
    let e = parse_size("-1x3").unwrap_err();
    assert!(matches!(e, InputError::OutOfRange { .. }), "{e}");

    let walk = default_walk(1);
    let options = AnimationOptions::new(10.0, (300, 150)).unwrap();
    let png = dir.path().join("walk.png");
    let e = animate_walk(&walk, "t", &png, &options).unwrap_err();
    assert!(
        matches!(e, Error::Input(InputError::Malformed { .. })),
        "{e}"
    );
    assert!(!png.exists());

    // a frame that cannot be drawn: an error, no file, an existing file untouched
    let mut frames: Vec<Landmarks> = klaw::figure::frames(&walk, 10.0)
        .collect::<Result<_, _>>()
        .unwrap();
    let path = dir.path().join("walk.gif");
    fs::write(&path, b"old").unwrap();
    frames[2].right.knee[1] = f64::NAN;
    let e = write_gif(&frames, &walk.body, "t", &path, &options).unwrap_err();
    assert!(
        matches!(e, Error::Figure(FigureError::NotFinite { .. })),
        "{e}"
    );
    assert_eq!(fs::read(&path).unwrap(), b"old");
    let e = write_gif(&[], &walk.body, "t", &path, &options).unwrap_err();
    assert!(matches!(e, Error::Export(_)), "{e}");
    let names: Vec<String> = fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, vec!["walk.gif".to_string()], "temporary files left");
}

/// `klaw animate`: a GIF of the requested size; a bad extension or size exits 2 and writes
/// nothing.
#[test]
fn cli_writes_the_gif() {
    let dir = tempfile::tempdir().unwrap();
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_klaw"))
            .args(args)
            .output()
            .unwrap()
    };
    let out = dir.path().join("w.gif");
    let o = run(&[
        "animate",
        "--steps",
        "1",
        "--fps",
        "10",
        "--size",
        "300x150",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let frames = decode(&out);
    assert!(!frames.is_empty());
    assert_eq!(frames[0].0.dimensions(), (300, 150));
    for args in [
        vec!["animate", "--out", "w.png"],
        vec!["animate", "--size", "300", "--out", "v.gif"],
        vec!["animate", "--fps", "0", "--out", "v.gif"],
    ] {
        let mut args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
        let last = args.len() - 1;
        args[last] = dir.path().join(&args[last]).to_string_lossy().into_owned();
        let refs: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = run(&refs);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
    }
    let mut names: Vec<String> = fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, vec!["w.gif".to_string()]);
}

/// The text above the views fits: the header across the image and each view's caption, at
/// most two lines each and not below the smallest font, inside the image and its view's column,
/// apart from each other, and all of it within the top 45 % of the frame, at every size from
/// the least allowed (200 × 100) to large; at the README's doorway size (600 × 225) and the
/// default (900 × 450) every caption is there and nothing is cut ("…"). (The doorway's front
/// caption took five lines of the 108 px column at 600 × 225.)
#[test]
fn captions_fit_at_every_size() {
    use klaw::plot::animation::{MAX_LINES, MIN_FONT_PX, write_scenario_gif};
    let dir = tempfile::tempdir().unwrap();
    let scenario = klaw::scenario::read_scenario(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenarios/doorway.toml"),
    )
    .unwrap();
    let motion = klaw::scenario::run(&scenario, 2.0).unwrap();
    let walk = default_walk(3);
    let title = "scenario examples/scenarios/doorway.toml";
    for size in [(200, 100), (300, 150), (600, 225), (900, 450), (1600, 800)] {
        let options = AnimationOptions::new(2.0, size).unwrap();
        let path = dir.path().join("text.gif");
        let summaries = [
            (
                "doorway",
                write_scenario_gif(&motion, &scenario.body, title, &path, &options).unwrap(),
            ),
            (
                "walk",
                animate_walk(
                    &walk,
                    "v 1.40 m/s, sl 0.778 m, sf 108.0 steps/min, H 1.80 m, M 80 kg, style \
                     default",
                    &path,
                    &options,
                )
                .unwrap(),
            ),
        ];
        let (w, h) = (size.0 as i32, size.1 as i32);
        for (what, summary) in &summaries {
            for views in &summary.views {
                let blocks = &views.text;
                assert!(!blocks.is_empty(), "{what} {size:?}: no header");
                for (k, b) in blocks.iter().enumerate() {
                    let at = format!("{what} {size:?} block {k}: {b:?}");
                    assert!(
                        b.lines.len() <= MAX_LINES && b.font_px >= MIN_FONT_PX,
                        "{at}"
                    );
                    let (l, t, r, bottom) = b.bbox;
                    assert!(0 <= l && r < w && 0 <= t && bottom < h, "{at}");
                    assert!(f64::from(bottom) <= 8.0 + 0.45 * f64::from(h - 16), "{at}");
                    if k > 0 {
                        let (c0, c1) = views.columns[k - 1];
                        assert!(c0 <= l && r <= c1, "{at} outside its column {c0}..{c1}");
                    }
                    for other in &blocks[k + 1..] {
                        let o = other.bbox;
                        assert!(
                            r < o.0 || o.2 < l || bottom < o.1 || o.3 < t,
                            "{at} over {o:?}"
                        );
                    }
                }
                if matches!(size, (600, 225) | (900, 450)) {
                    assert_eq!(blocks.len(), 1 + views.columns.len(), "{what} {size:?}");
                    for b in blocks {
                        assert!(
                            b.lines.iter().all(|l| !l.ends_with('…')),
                            "{what} {size:?}: {b:?}"
                        );
                    }
                }
            }
        }
    }
}
