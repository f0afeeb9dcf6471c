//! The speed-dependent norms (`[norm.by_speed]` of models/gait-norms.toml, issue 16): the
//! interpolation in the dimensionless speed worked by hand on tables of a few dyadic numbers,
//! the walk's dimensionless speed, the check taking each range at the walk's speed, the typed
//! errors of malformed rows, tables in m/s, and the bundled rows against Schwartz et al. 2008's
//! workbook (values typed from its ANOVA sheet, docs/realism.md "Speed dependence") and
//! Orendurff et al. 2004's abstract.
use std::path::Path;

use klaw::analysis::cycle::{GaitCycle, Panel, PanelCurve};
use klaw::analysis::norms::{BySpeed, NormRange, NormTable, SpeedScale, WalkSpeed, check};
use klaw::figure::skeleton::Side;
use klaw::model::InputError;

/// A table of one knee-swing row: `range` is `low`/`high` lines or a `[norm.by_speed]` table.
fn table(measure: &str, range: &str) -> String {
    format!(
        "[[norm]]\npanel = \"knee_flexion\"\nname = \"swing\"\nlabel = \"swing\"\n\
         measure = \"{measure}\"\nunit = \"deg\"\nwindows = [[60.0, 85.0]]\n\
         window_source = \"test\"\nsource = \"test\"\n{range}"
    )
}

/// `[norm.by_speed]` with the given speeds, span, means and SDs, 1 SD wide.
fn by_speed(speed: &str, span: &str, mean: &str, sd: &str) -> String {
    format!(
        "[norm.by_speed]\ncite = \"test\"\nspeed = {speed}\nspan = {span}\nmean = {mean}\n\
         sd = {sd}\nsd_multiple = 1.0\n"
    )
}

fn parse(text: &str) -> Result<NormTable, InputError> {
    NormTable::parse(text, Path::new("norms.toml"))
}

/// The one row's by-speed table.
fn speed_table(text: &str) -> BySpeed {
    match &parse(text).unwrap().norms[0].range {
        NormRange::BySpeed(b) => b.clone(),
        r => panic!("not by speed: {r:?}"),
    }
}

/// A walk of dimensionless speed `v_hat`: leg length 4/g, so that √(g l) = 2 (to an ulp).
fn speed(v_hat: f64) -> WalkSpeed {
    WalkSpeed {
        velocity: 2.0 * v_hat,
        leg_length: 4.0 / klaw::model::GRAVITY,
    }
}

/// A range given at two speeds: midway it is the mean of the ends' means ± the mean of their
/// SDs, a quarter of the way a quarter; at a listed speed its own values; `sd_multiple` scales
/// the half-width only.
#[test]
fn a_range_at_two_speeds_is_linear_between_them() {
    let b = speed_table(&table(
        "max",
        &by_speed("[0.25, 0.75]", "[0.25, 0.75]", "[10.0, 30.0]", "[2.0, 4.0]"),
    ));
    assert_eq!(b.range(0.5), Some((17.0, 23.0)));
    assert_eq!(b.range(0.375), Some((12.5, 17.5)));
    assert_eq!(b.range(0.25), Some((8.0, 12.0)));
    assert_eq!(b.range(0.75), Some((26.0, 34.0)));
    let wide = BySpeed {
        sd_multiple: 2.0,
        ..b.clone()
    };
    assert_eq!(wide.range(0.5), Some((14.0, 26.0)));
}

/// Several listed speeds: each speed reads its own segment (a peak in the middle).
#[test]
fn each_speed_reads_its_own_segment() {
    let b = speed_table(&table(
        "max",
        &by_speed(
            "[0.25, 0.5, 0.75]",
            "[0.25, 0.75]",
            "[10.0, 30.0, 20.0]",
            "[1.0, 1.0, 3.0]",
        ),
    ));
    assert_eq!(b.range(0.375), Some((19.0, 21.0)));
    assert_eq!(b.range(0.5), Some((29.0, 31.0)));
    assert_eq!(b.range(0.625), Some((23.0, 27.0)));
}

/// Between the listed speeds and the span's ends the end values hold; outside the span (and for
/// a speed that is not a number) there is no range.
#[test]
fn the_ends_hold_to_the_span_and_nothing_beyond() {
    let b = speed_table(&table(
        "max",
        &by_speed(
            "[0.25, 0.75]",
            "[0.125, 0.875]",
            "[10.0, 30.0]",
            "[2.0, 4.0]",
        ),
    ));
    assert_eq!(b.range(0.125), Some((8.0, 12.0)));
    assert_eq!(b.range(0.2), Some((8.0, 12.0)));
    assert_eq!(b.range(0.875), Some((26.0, 34.0)));
    assert_eq!(b.range(0.124), None);
    assert_eq!(b.range(0.876), None);
    assert_eq!(b.range(f64::NAN), None);
    // a fixed range is the same at every speed, even one no table spans
    let fixed = &parse(&table("max", "low = 55.0\nhigh = 65.0\n"))
        .unwrap()
        .norms[0];
    assert_eq!(fixed.range.at(speed(5.0)), Some((55.0, 65.0)));
}

/// v̂ = v / √(g l1), against numbers worked out by hand (g = 9.81 m/s²).
#[test]
fn the_dimensionless_speed_is_hofs() {
    let s = WalkSpeed {
        velocity: 1.4,
        leg_length: 0.9,
    };
    // √(9.81 · 0.9) = √8.829 = 2.971363321…; 1.4 / 2.971363321 = 0.4711642…
    assert!((s.dimensionless() - 0.471_164_2).abs() < 1e-7);
    let s = WalkSpeed {
        velocity: 3.0,
        leg_length: 0.09 / 9.81,
    };
    // √(g · 0.09 / g) = 0.3
    assert!((s.dimensionless() - 10.0).abs() < 1e-12);
}

/// A knee whose swing peak is 60° at 72 %.
fn knee_cycle() -> GaitCycle {
    let values = (0..=100)
        .map(|p| 60.0 * (-((p as f64 - 72.0) / 8.0).powi(2)).exp())
        .collect();
    GaitCycle {
        curves: vec![PanelCurve {
            panel: Panel::KneeFlexion,
            side: Some(Side::Right),
            values,
        }],
        cycles: (1, 1),
        toe_off_pct: [None, None],
    }
}

/// The check takes a speed-dependent range at the walk's speed: the same 60° peak is outside
/// the range of the slow end (48…52°), inside midway (58…62°), and not checked outside the
/// span; the check records the speed it was taken at, a fixed row none.
#[test]
fn the_check_takes_the_range_at_the_walks_speed() {
    let t = parse(&format!(
        "{}\n{}",
        table(
            "max",
            &by_speed("[0.25, 0.75]", "[0.25, 0.75]", "[50.0, 70.0]", "[2.0, 2.0]")
        ),
        table("max", "low = 55.0\nhigh = 65.0\n").replace("\"swing\"", "\"fixed\""),
    ))
    .unwrap();
    let cycle = knee_cycle();
    let slow = check(&cycle, &t, speed(0.25));
    assert_eq!(slow.len(), 2);
    assert_eq!((slow[0].low, slow[0].high), (48.0, 52.0));
    assert!((slow[0].value - 60.0).abs() < 1e-12 && slow[0].at_pct == Some(72.0));
    assert!(!slow[0].inside());
    assert!(
        (slow[0].speed.unwrap().0 - 0.25).abs() < 1e-12
            && slow[0].speed.unwrap().1 == SpeedScale::Dimensionless
    );
    assert!(slow[0].describe().contains("48.0…52.0° at v/√(g l1) 0.25"));
    assert_eq!((slow[1].name.as_str(), slow[1].speed), ("fixed", None));
    let mid = check(&cycle, &t, speed(0.5));
    assert!((mid[0].low - 58.0).abs() < 1e-9 && (mid[0].high - 62.0).abs() < 1e-9);
    assert!(mid[0].inside());
    let beyond = check(&cycle, &t, speed(0.8));
    assert_eq!(beyond.len(), 1);
    assert_eq!(beyond[0].name, "fixed");
}

/// Malformed rows are typed errors naming the row and the rule broken.
#[test]
fn malformed_speed_rows_are_typed_errors() {
    let ok = by_speed("[0.25, 0.75]", "[0.25, 0.75]", "[1.0, 2.0]", "[0.5, 0.5]");
    assert!(parse(&table("max", &ok)).is_ok());
    let cases = [
        (format!("low = 1.0\nhigh = 2.0\n{ok}"), "not parts of both"),
        ("low = 1.0\n".to_string(), "not parts of both"),
        (String::new(), "needs low and high, or by_speed"),
        (
            by_speed("[0.75, 0.25]", "[0.25, 0.75]", "[1.0, 2.0]", "[0.5, 0.5]"),
            "strictly increasing",
        ),
        (
            by_speed("[0.5, 0.5]", "[0.25, 0.75]", "[1.0, 2.0]", "[0.5, 0.5]"),
            "strictly increasing",
        ),
        (
            by_speed("[]", "[0.25, 0.75]", "[]", "[]"),
            "strictly increasing",
        ),
        (
            by_speed("[0.25, nan]", "[0.25, 0.75]", "[1.0, 2.0]", "[0.5, 0.5]"),
            "strictly increasing",
        ),
        (
            by_speed("[0.25, 0.75]", "[0.3, 0.75]", "[1.0, 2.0]", "[0.5, 0.5]"),
            "hold the speeds",
        ),
        (
            by_speed("[0.25, 0.75]", "[0.25, 0.7]", "[1.0, 2.0]", "[0.5, 0.5]"),
            "hold the speeds",
        ),
        (
            by_speed("[0.25, 0.75]", "[0.25, 0.75]", "[1.0]", "[0.5, 0.5]"),
            "as many means and SDs",
        ),
        (
            by_speed(
                "[0.25, 0.75]",
                "[0.25, 0.75]",
                "[1.0, 2.0]",
                "[0.5, 0.5, 0.5]",
            ),
            "as many means and SDs",
        ),
        (
            by_speed("[0.25, 0.75]", "[0.25, 0.75]", "[1.0, 2.0]", "[0.5, 0.0]"),
            "SDs finite and > 0",
        ),
        (
            by_speed("[0.25, 0.75]", "[0.25, 0.75]", "[1.0, 2.0]", "[-0.5, 0.5]"),
            "SDs finite and > 0",
        ),
        (
            by_speed("[0.25, 0.75]", "[0.25, 0.75]", "[inf, 2.0]", "[0.5, 0.5]"),
            "means must be finite",
        ),
        (
            ok.replace("sd_multiple = 1.0", "sd_multiple = 0.0"),
            "sd_multiple must be finite and > 0",
        ),
        (ok.replace("cite = \"test\"\n", ""), "cite"),
        (format!("{ok}extra = 1.0\n"), "extra"),
    ];
    for (range, reason) in &cases {
        let e = parse(&table("max", range)).unwrap_err();
        let shown = e.to_string();
        assert!(
            matches!(e, InputError::Malformed { .. }),
            "{range}: {shown}"
        );
        assert!(shown.contains(reason), "{range}: {shown} lacks {reason:?}");
    }
    // a peak-to-peak range whose low end is negative at a listed speed
    let negative = by_speed("[0.25, 0.75]", "[0.25, 0.75]", "[1.0, 4.0]", "[1.5, 0.5]");
    let e = parse(&table("peak_to_peak", &negative)).unwrap_err();
    assert!(e.to_string().contains("cannot be negative"), "{e}");
    let positive = by_speed("[0.25, 0.75]", "[0.25, 0.75]", "[2.0, 4.0]", "[1.5, 0.5]");
    assert!(parse(&table("peak_to_peak", &positive)).is_ok());
}

/// The bundled rows "…, by speed" hold Schwartz et al. 2008's numbers (their workbook's ANOVA
/// sheet, typed here to 3 decimals; the table keeps 2): the five categories' dimensionless
/// speeds, the span of the slowest and fastest subject, mean and SD of three quantities; every
/// row 1 SD wide over the same speeds. The last row, in m/s, is Orendurff et al. 2004's.
#[test]
fn the_bundled_speed_rows_are_schwartz_2008() {
    let t = NormTable::builtin();
    let row = |name: &str| -> BySpeed {
        let n = t.norms.iter().find(|n| n.name == name).unwrap();
        match &n.range {
            NormRange::BySpeed(b) => b.clone(),
            r => panic!("{name}: {r:?}"),
        }
    };
    let close = |got: &[f64], want: &[f64], name: &str| {
        assert_eq!(got.len(), want.len(), "{name}");
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() <= 0.0051, "{name}: {got:?} vs {want:?}");
        }
    };
    let speeds = [0.172, 0.290, 0.429, 0.560, 0.694];
    let published = [
        (
            "knee peak swing flexion, by speed",
            [50.615, 56.107, 60.456, 61.522, 62.523],
            [5.948, 5.443, 4.797, 5.530, 6.442],
        ),
        (
            "ankle peak dorsiflexion in stance, by speed",
            [13.571, 14.283, 12.799, 11.333, 9.476],
            [3.125, 3.022, 3.564, 3.791, 4.246],
        ),
        (
            "ankle peak plantarflexion, by speed",
            [-12.125, -16.188, -22.450, -22.341, -23.237],
            [7.689, 6.619, 7.372, 7.555, 6.691],
        ),
        (
            "pelvic list, left side up (left stance), by speed",
            [-2.992, -3.429, -4.404, -5.540, -6.374],
            [0.994, 1.066, 1.099, 1.590, 1.898],
        ),
    ];
    for (name, mean, sd) in published {
        let b = row(name);
        close(&b.speed, &speeds, name);
        close(&b.mean, &mean, name);
        close(&b.sd, &sd, name);
        close(&b.span, &[0.090, 0.844], name);
    }
    let speed_rows: Vec<&BySpeed> = t.norms.iter().filter_map(|n| n.range.by_speed()).collect();
    assert_eq!(speed_rows.len(), 13);
    for b in speed_rows
        .iter()
        .filter(|b| b.scale == SpeedScale::Dimensionless)
    {
        assert_eq!(b.sd_multiple, 1.0);
        close(&b.speed, &speeds, &b.cite);
    }
    // the last, in m/s: Orendurff et al. 2004's abstract, 2.7 ± 0.5 cm at 0.7 m/s and
    // 4.8 ± 0.9 cm at 1.6 m/s
    let excursion = row("vertical excursion, by speed");
    assert_eq!(excursion.scale, SpeedScale::MetresPerSecond);
    close(&excursion.speed, &[0.7, 1.6], "excursion");
    close(&excursion.span, &[0.7, 1.6], "excursion");
    close(&excursion.mean, &[2.7, 4.8], "excursion");
    close(&excursion.sd, &[0.5, 0.9], "excursion");
}

/// A table in m/s (`scale = "m/s"`) reads the walk's velocity, whatever its leg: midway between
/// 0.5 and 1.5 m/s the mean of the ends ± the mean of their SDs, for legs of 0.5 and 1 m alike
/// (a v̂ table would read two speeds); its span's ends hold to a few ulps of the velocity
/// (a walk's speed is a sum over its steps), not to 1e-6; an unknown scale is malformed.
#[test]
fn a_table_in_metres_per_second_reads_the_velocity() {
    let text = table(
        "max",
        &by_speed("[0.5, 1.5]", "[0.5, 1.5]", "[10.0, 30.0]", "[2.0, 4.0]"),
    )
    .replace("cite = \"test\"\n", "cite = \"test\"\nscale = \"m/s\"\n");
    let t = parse(&text).unwrap();
    let range = &t.norms[0].range;
    for leg in [0.5, 1.0] {
        let walk = WalkSpeed {
            velocity: 1.0,
            leg_length: leg,
        };
        assert_eq!(range.at(walk), Some((17.0, 23.0)), "leg {leg}");
    }
    let b = range.by_speed().unwrap();
    assert_eq!(b.scale, SpeedScale::MetresPerSecond);
    assert_eq!(b.range(1.5 + 4.0 * f64::EPSILON), Some((26.0, 34.0)));
    assert_eq!(b.range(1.5 + 1e-6), None);
    assert_eq!(b.range(0.5 - 1e-6), None);
    assert_eq!(SpeedScale::MetresPerSecond.describe(1.2), "1.20 m/s");
    let bad = text.replace("\"m/s\"", "\"km/h\"");
    assert!(matches!(parse(&bad), Err(InputError::Malformed { .. })));
}
