//! Walk data as text (docs/generalize.md, "Walk data files"): JSON (the fields of
//! [`WalkData`], by serde) and CSV (one long table: a row per number of the walk condition and
//! per sample of each timed sequence).
use std::collections::BTreeMap;
use std::fmt::Write;

use crate::generalize::condition::BodyCondition;
use crate::generalize::error::GeneralizeError;
use crate::generalize::geometry::{Character, Pelvis};
use crate::generalize::sequence::{Curve, Path};
use crate::generalize::walk_data::{Phases, Piece, WalkData};

/// The CSV's header.
pub const CSV_HEADER: &str = "name,t,a,b";

/// The walk data as JSON, checked first.
pub fn to_json(w: &WalkData) -> Result<String, GeneralizeError> {
    w.check()?;
    serde_json::to_string_pretty(w)
        .map(|s| s + "\n")
        .map_err(|e| GeneralizeError::invalid("json", e.to_string()))
}

/// Walk data from JSON text, checked ([`WalkData::check`]).
pub fn from_json(text: &str) -> Result<WalkData, GeneralizeError> {
    let w: WalkData =
        serde_json::from_str(text).map_err(|e| GeneralizeError::invalid("json", e.to_string()))?;
    w.check()?;
    Ok(w)
}

/// The names of the walk condition's numbers in the CSV.
const SCALARS: [&str; 29] = [
    "body.thigh",
    "body.shin",
    "body.heel_to_n",
    "body.ankle_to_n",
    "body.ball_to_n",
    "body.ball_to_toe",
    "body.pelvis_width",
    "step_length",
    "step_length_before",
    "pelvis.rotation",
    "pelvis.step_width",
    "character.step_length",
    "character.knee_at_strike",
    "character.foot_at_strike",
    "character.foot_at_toe_off",
    "character.meta_at_toe_off",
    "character.alpha1",
    "character.alpha2",
    "character.alpha3",
    "character.alpha4",
    "character.hip_lead",
    "character.hip_offset",
    "phases.fgm",
    "phases.heel_off",
    "phases.mom",
    "phases.tom",
    "f1.amplitude",
    "f2.amplitude",
    "meta.amplitude",
];

/// The walk condition's numbers, in the order of [`SCALARS`].
fn scalars(w: &WalkData) -> [f64; 29] {
    let (b, c, p) = (&w.body, &w.character, &w.phases);
    [
        b.thigh,
        b.shin,
        b.heel_to_n,
        b.ankle_to_n,
        b.ball_to_n,
        b.ball_to_toe,
        b.pelvis_width,
        w.step_length,
        w.step_length_before,
        w.pelvis.rotation,
        w.pelvis.step_width,
        c.step_length,
        c.knee_at_strike,
        c.foot_at_strike,
        c.foot_at_toe_off,
        c.meta_at_toe_off,
        c.alpha[0],
        c.alpha[1],
        c.alpha[2],
        c.alpha[3],
        c.hip_lead,
        c.hip_offset,
        p.fgm,
        p.heel_off,
        p.mom,
        p.tom,
        w.f1.amplitude,
        w.f2.amplitude,
        w.meta.amplitude,
    ]
}

/// The sequences' names in the CSV, and which take a second column `b`.
const SEQUENCES: [(&str, bool); 7] = [
    ("hip", true),
    ("f1", false),
    ("f2", false),
    ("f3", false),
    ("meta", false),
    ("ankle", true),
    ("trunk", false),
];

/// The walk data as CSV: a comment line with the source, the header `name,t,a,b`, a row
/// `name,,value,` per number of the walk condition, then a row `sequence,t,a,b` per sample:
/// `hip` and `ankle` a = x, b = y (m); `f1`, `f2`, `meta` a = the shape (× the amplitude: the
/// angle); `f3`, `trunk` a = the angle (rad).
pub fn to_csv(w: &WalkData) -> Result<String, GeneralizeError> {
    w.check()?;
    let mut out = String::new();
    let source = w.source.replace(['\n', '\r'], " ");
    let _ = writeln!(out, "# klaw walk data (docs/generalize.md): {source}");
    let _ = writeln!(out, "{CSV_HEADER}");
    for (name, v) in SCALARS.iter().zip(scalars(w)) {
        let _ = writeln!(out, "{name},,{v},");
    }
    let mut rows = |name: &str, t: &[f64], a: &[f64], b: Option<&[f64]>| {
        for i in 0..t.len() {
            let b = b.map_or(String::new(), |b| b[i].to_string());
            let _ = writeln!(out, "{name},{},{},{b}", t[i], a[i]);
        }
    };
    rows("hip", &w.hip.t, &w.hip.x, Some(&w.hip.y));
    rows("f1", &w.f1.t, &w.f1.shape, None);
    rows("f2", &w.f2.t, &w.f2.shape, None);
    rows("f3", &w.f3.t, &w.f3.v, None);
    rows("meta", &w.meta.t, &w.meta.shape, None);
    rows("ankle", &w.ankle.t, &w.ankle.x, Some(&w.ankle.y));
    rows("trunk", &w.trunk.t, &w.trunk.v, None);
    Ok(out)
}

/// The numbers and the samples of a sequence, (t, a, b), by name.
type Rows = (BTreeMap<String, f64>, BTreeMap<&'static str, [Vec<f64>; 3]>);

/// Walk data from the CSV of [`to_csv`], checked. Errors name the line.
pub fn from_csv(text: &str) -> Result<WalkData, GeneralizeError> {
    let (source, rows) = read_rows(text)?;
    let w = from_rows(source, rows)?;
    w.check()?;
    Ok(w)
}

/// The source (the first `#` line's text after ": ") and the rows of the CSV of [`to_csv`].
fn read_rows(text: &str) -> Result<(String, Rows), GeneralizeError> {
    let bad =
        |line: usize, reason: String| GeneralizeError::invalid(format!("line {line}"), reason);
    let mut source = String::new();
    let mut numbers: BTreeMap<String, f64> = BTreeMap::new();
    let mut seqs: BTreeMap<&'static str, [Vec<f64>; 3]> = BTreeMap::new();
    let mut header = false;
    for (i, line) in text.lines().enumerate() {
        let n = i + 1;
        if let Some(c) = line.strip_prefix('#') {
            if let Some(s) = c.split_once(": ").map(|p| p.1) {
                source = s.to_string();
            }
            continue;
        }
        if line.trim().is_empty() {
            continue;
        }
        if !header {
            if line.trim() != CSV_HEADER {
                return Err(bad(n, format!("the header must be `{CSV_HEADER}`")));
            }
            header = true;
            continue;
        }
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        if cells.len() != 4 {
            return Err(bad(n, format!("{} cells, 4 expected", cells.len())));
        }
        let num = |s: &str, what: &str| -> Result<f64, GeneralizeError> {
            s.parse::<f64>()
                .map_err(|_| bad(n, format!("{what} `{s}` is not a number")))
        };
        match SEQUENCES.iter().find(|(name, _)| *name == cells[0]) {
            Some(&(name, two)) => {
                let e = seqs.entry(name).or_default();
                e[0].push(num(cells[1], "t")?);
                e[1].push(num(cells[2], "a")?);
                if two {
                    e[2].push(num(cells[3], "b")?);
                }
            }
            None => {
                if numbers
                    .insert(cells[0].to_string(), num(cells[2], "the value")?)
                    .is_some()
                {
                    return Err(bad(n, format!("`{}` given twice", cells[0])));
                }
            }
        }
    }
    Ok((source, (numbers, seqs)))
}

/// Walk data from the rows of its CSV: every name known, every number and sequence present.
/// (Longer than 80 lines: the walk data's fields, named one by one.)
fn from_rows(source: String, (numbers, mut seqs): Rows) -> Result<WalkData, GeneralizeError> {
    if let Some(k) = numbers.keys().find(|k| !SCALARS.contains(&k.as_str())) {
        return Err(GeneralizeError::invalid(k.clone(), "unknown name"));
    }
    let get = |name: &str| {
        numbers
            .get(name)
            .copied()
            .ok_or_else(|| GeneralizeError::invalid(name, "missing"))
    };
    let mut seq = |name: &str| {
        seqs.remove(name)
            .ok_or_else(|| GeneralizeError::invalid(name, "no samples"))
    };
    let [ht, hx, hy] = seq("hip")?;
    let [at, ax, ay] = seq("ankle")?;
    let [t1, s1, _] = seq("f1")?;
    let [t2, s2, _] = seq("f2")?;
    let [t3, v3, _] = seq("f3")?;
    let [tm, sm, _] = seq("meta")?;
    let [tt, vt, _] = seq("trunk")?;
    let w = WalkData {
        source,
        body: BodyCondition {
            thigh: get("body.thigh")?,
            shin: get("body.shin")?,
            heel_to_n: get("body.heel_to_n")?,
            ankle_to_n: get("body.ankle_to_n")?,
            ball_to_n: get("body.ball_to_n")?,
            ball_to_toe: get("body.ball_to_toe")?,
            pelvis_width: get("body.pelvis_width")?,
        },
        step_length: get("step_length")?,
        step_length_before: get("step_length_before")?,
        pelvis: Pelvis {
            rotation: get("pelvis.rotation")?,
            step_width: get("pelvis.step_width")?,
        },
        character: Character {
            step_length: get("character.step_length")?,
            knee_at_strike: get("character.knee_at_strike")?,
            foot_at_strike: get("character.foot_at_strike")?,
            foot_at_toe_off: get("character.foot_at_toe_off")?,
            meta_at_toe_off: get("character.meta_at_toe_off")?,
            alpha: [
                get("character.alpha1")?,
                get("character.alpha2")?,
                get("character.alpha3")?,
                get("character.alpha4")?,
            ],
            hip_lead: get("character.hip_lead")?,
            hip_offset: get("character.hip_offset")?,
        },
        phases: Phases {
            fgm: get("phases.fgm")?,
            heel_off: get("phases.heel_off")?,
            mom: get("phases.mom")?,
            tom: get("phases.tom")?,
        },
        hip: Path {
            t: ht,
            x: hx,
            y: hy,
        },
        f1: Piece {
            t: t1,
            shape: s1,
            amplitude: get("f1.amplitude")?,
        },
        f2: Piece {
            t: t2,
            shape: s2,
            amplitude: get("f2.amplitude")?,
        },
        f3: Curve { t: t3, v: v3 },
        meta: Piece {
            t: tm,
            shape: sm,
            amplitude: get("meta.amplitude")?,
        },
        ankle: Path {
            t: at,
            x: ax,
            y: ay,
        },
        trunk: Curve { t: tt, v: vt },
    };
    Ok(w)
}
