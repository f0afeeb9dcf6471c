//! OpenSim storage (`.mot`, `.sto`) read back: the header up to `endheader` with `nRows` and
//! `nColumns` (or the older `datarows` / `datacolumns`) and `inDegrees` (yes or no: the angles'
//! unit), all three required; then a line of column names (whitespace-separated, `time` among
//! them) and `nRows` rows of `nColumns` numbers. The coordinates are those [`super::super::opensim`]
//! writes (gait2392; Rajagopal 2015 when the file has its arm coordinates, `arm_flex_r`), turned
//! back into klaw's clinical angles: the pelvis from the model's `R_z(tilt) R_x(list)
//! R_y(rotation)`, its centre from the model's origin `pelvis_tx/ty/tz` less the hip-joint offset
//! scaled to the body's height, the knee flexion from `knee_angle` (gait2392: its negative), the
//! lumbar angles from the model's `R_z R_x R_y` back joint, the ankle dorsiflexion from
//! `ankle_angle`.
use glam::DVec3;

use super::{Frames, MotionFileError, Table, absent, set_angle};
use crate::export::opensim::OpenSimModel;
use crate::figure::clinical::Clinical;
use crate::figure::euler::{nearest_turn, yxz_angles, zxy_matrix};
use crate::model::body::Body;

/// The coordinates needed, in the order they are read.
const NEEDED: [&str; 12] = [
    "time",
    "pelvis_tilt",
    "pelvis_list",
    "pelvis_rotation",
    "hip_flexion_r",
    "hip_adduction_r",
    "hip_rotation_r",
    "knee_angle_r",
    "hip_flexion_l",
    "hip_adduction_l",
    "hip_rotation_l",
    "knee_angle_l",
];

/// The header's keys: (nRows, nColumns, inDegrees) with their lines, and the line of
/// `endheader`.
struct Header {
    rows: (usize, usize),
    columns: (usize, usize),
    in_degrees: bool,
    end: usize,
}

fn header(lines: &[&str]) -> Result<Header, MotionFileError> {
    let bad = |line: usize, reason: String| MotionFileError::Header { line, reason };
    let (mut rows, mut columns, mut degrees) = (None, None, None);
    for (i, l) in lines.iter().enumerate() {
        let line = i + 1;
        let l = l.trim();
        if l == "endheader" {
            let missing = |what: &str| {
                bad(
                    line,
                    format!(
                        "the header has no {what} before endheader; OpenSim storage needs nRows, nColumns and inDegrees"
                    ),
                )
            };
            return Ok(Header {
                rows: rows.ok_or_else(|| missing("nRows"))?,
                columns: columns.ok_or_else(|| missing("nColumns"))?,
                in_degrees: degrees
                    .ok_or_else(|| missing("inDegrees=yes or no (the angles' unit)"))?,
                end: line,
            });
        }
        let (key, value) = match l.split_once('=') {
            Some((k, v)) => (k.trim(), v.trim()),
            None => match l.split_once(char::is_whitespace) {
                Some((k @ ("datarows" | "datacolumns"), v)) => (k, v.trim()),
                _ => continue,
            },
        };
        let count = || {
            value
                .parse::<usize>()
                .map(|n| (n, line))
                .map_err(|_| bad(line, format!("{key} `{value}` is not a whole number")))
        };
        match key {
            "nRows" | "datarows" => rows = Some(count()?),
            "nColumns" | "datacolumns" => columns = Some(count()?),
            "inDegrees" => {
                degrees = Some(match value {
                    "yes" => true,
                    "no" => false,
                    _ => {
                        return Err(bad(
                            line,
                            format!("inDegrees `{value}`: expected yes or no"),
                        ));
                    }
                })
            }
            _ => {}
        }
    }
    Err(bad(
        lines.len(),
        "no `endheader` line: OpenSim storage has a header ending with endheader".to_string(),
    ))
}

/// The frames of a storage file's text for a body of `body.height`.
pub(crate) fn parse(text: &str, body: &Body) -> Result<Frames, MotionFileError> {
    let lines: Vec<&str> = text.lines().collect();
    let h = header(&lines)?;
    let mut rest = lines
        .iter()
        .enumerate()
        .skip(h.end)
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, l)| {
            (
                i + 1,
                l.split_whitespace().map(str::to_string).collect::<Vec<_>>(),
            )
        });
    let Some((names_line, names)) = rest.next() else {
        return Err(MotionFileError::Header {
            line: h.end,
            reason: "no column names after endheader".to_string(),
        });
    };
    if names.len() != h.columns.0 {
        return Err(MotionFileError::Header {
            line: names_line,
            reason: format!(
                "{} column names where nColumns={} (line {})",
                names.len(),
                h.columns.0,
                h.columns.1
            ),
        });
    }
    let cells: Vec<(usize, Vec<String>)> = rest.collect();
    if cells.len() != h.rows.0 {
        return Err(MotionFileError::Header {
            line: h.rows.1,
            reason: format!("nRows={} but the file has {} rows", h.rows.0, cells.len()),
        });
    }
    let table = Table::new(names, names_line, cells, "time")?;
    let needed: Vec<String> = NEEDED.iter().map(|s| s.to_string()).collect();
    let at = table.needed(&needed)?;
    let model = match table.column("arm_flex_r") {
        Some(_) => OpenSimModel::Rajagopal2015,
        None => OpenSimModel::Gait2392,
    };
    let unit = if h.in_degrees { 1f64.to_radians() } else { 1.0 };
    let optional = |names: [&str; 3]| -> Option<[usize; 3]> {
        Some([
            table.column(names[0])?,
            table.column(names[1])?,
            table.column(names[2])?,
        ])
    };
    let position = optional(["pelvis_tx", "pelvis_ty", "pelvis_tz"]);
    let lumbar = optional(["lumbar_extension", "lumbar_bending", "lumbar_rotation"]);
    let ankles = [table.column("ankle_angle_r"), table.column("ankle_angle_l")];
    let offset = model.pelvis_origin_from_hips() * (body.height / model.reference_height());
    let frames = table
        .rows
        .iter()
        .map(|row| {
            let angle = |k: usize| row[k] * unit;
            let mut c = Clinical {
                time: row[at[0]],
                ..Default::default()
            };
            let (tilt, list, rotation) = (angle(at[1]), angle(at[2]), angle(at[3]));
            let pelvis = zxy_matrix(tilt, list, rotation);
            let [r, p, q] = yxz_angles(&pelvis);
            c.pelvis_rotation = nearest_turn(r, rotation);
            c.pelvis_list = -p;
            c.pelvis_tilt = -q;
            c.pelvis = position.map_or([f64::NAN; 3], |[x, y, z]| {
                (DVec3::new(row[x], row[y], row[z]) - pelvis * offset).to_array()
            });
            for (side, k) in [("r", 4), ("l", 8)] {
                set_angle(&mut c, &format!("hip_flexion_{side}"), angle(at[k]));
                set_angle(&mut c, &format!("hip_adduction_{side}"), angle(at[k + 1]));
                set_angle(&mut c, &format!("hip_rotation_{side}"), angle(at[k + 2]));
                let knee = model.knee_sign() * angle(at[k + 3]);
                set_angle(&mut c, &format!("knee_flexion_{side}"), knee);
            }
            if let Some([e, b, r]) = lumbar {
                let [lr, lb, le] = yxz_angles(&zxy_matrix(angle(e), angle(b), angle(r)));
                (c.lumbar_rotation, c.lumbar_bending, c.lumbar_extension) = (lr, lb, le);
            }
            c.right.ankle.flexion = ankles[0].map_or(f64::NAN, angle);
            c.left.ankle.flexion = ankles[1].map_or(f64::NAN, angle);
            c
        })
        .collect();
    let absent = absent(
        position.is_some(),
        lumbar.is_some(),
        ankles.iter().all(Option::is_some),
    );
    Ok(Frames {
        frames,
        format: format!("OpenSim storage ({model:?})"),
        has_steps: false,
        absent,
    })
}
