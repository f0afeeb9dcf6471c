//! klaw's frame CSV read back (`docs/export.md`, "CSV"; a measured walk in the same columns):
//! lines starting with `#` (comments: a measured file's source) skipped, a header line, then one
//! row per frame: `time_s` (s), `step`, `pelvis_tx_m`, `pelvis_ty_m`,
//! `pelvis_tz_m` (m, y up from the ground), the angles `*_deg` in degrees with klaw's clinical
//! signs. Needed, optional and ignored columns: the parent module's doc.
use super::{Frames, MotionFileError, Table, absent, set_angle};
use crate::analysis::criteria::segments::{DOFS, POSE_NAMES};
use crate::figure::clinical::Clinical;
use crate::model::body::Body;

const LUMBAR: [&str; 3] = ["lumbar_extension", "lumbar_bending", "lumbar_rotation"];
const ANKLES: [&str; 2] = ["ankle_dorsiflexion_r", "ankle_dorsiflexion_l"];
const POSITION: [&str; 3] = ["pelvis_tx_m", "pelvis_ty_m", "pelvis_tz_m"];

/// The frames of a frame CSV's text (`_body` unused: the CSV holds the pelvis centre itself).
pub(crate) fn parse(text: &str, _body: &Body) -> Result<Frames, MotionFileError> {
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(true)
        .comment(Some(b'#'))
        .flexible(true)
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let names: Vec<String> = reader.headers()?.iter().map(str::to_string).collect();
    let mut cells = Vec::new();
    for record in reader.records() {
        let record = record?;
        let line = record.position().map_or(0, |p| p.line() as usize);
        cells.push((line, record.iter().map(str::to_string).collect()));
    }
    let table = Table::new(names, 1, cells, "time_s")?;
    let deg = |name: &str| format!("{name}_deg");
    let needed: Vec<String> = std::iter::once("time_s".to_string())
        .chain(DOFS.iter().map(|&i| deg(POSE_NAMES[i])))
        .collect();
    let needed_at = table.needed(&needed)?;
    let optional = |names: &[&str], suffix: fn(&str) -> String| -> Option<Vec<usize>> {
        names.iter().map(|n| table.column(&suffix(n))).collect()
    };
    let step = table.column("step");
    let position = optional(&POSITION, |n| n.to_string());
    let lumbar = optional(&LUMBAR, |n| format!("{n}_deg"));
    let ankles: Vec<Option<usize>> = ANKLES.iter().map(|n| table.column(&deg(n))).collect();
    let mut frames = Vec::with_capacity(table.rows.len());
    for (row, &line) in table.rows.iter().zip(&table.lines) {
        let mut c = Clinical {
            time: row[needed_at[0]],
            pelvis: [f64::NAN; 3],
            ..Default::default()
        };
        if let Some(k) = step {
            let s = row[k];
            if s < 0.0 || s.fract() != 0.0 {
                return Err(MotionFileError::Step {
                    line,
                    cell: s.to_string(),
                });
            }
            c.step = s as usize;
        }
        for (&k, &i) in needed_at[1..].iter().zip(&DOFS) {
            set_angle(&mut c, POSE_NAMES[i], row[k].to_radians());
        }
        if let Some(p) = &position {
            c.pelvis = [row[p[0]], row[p[1]], row[p[2]]];
        }
        if let Some(l) = &lumbar {
            for (&k, name) in l.iter().zip(LUMBAR) {
                set_angle(&mut c, name, row[k].to_radians());
            }
        }
        for (k, name) in ankles.iter().zip(ANKLES) {
            set_angle(&mut c, name, k.map_or(f64::NAN, |k| row[k].to_radians()));
        }
        frames.push(c);
    }
    let absent = absent(
        position.is_some(),
        lumbar.is_some(),
        ankles.iter().all(Option::is_some),
    );
    Ok(Frames {
        frames,
        format: "klaw frame CSV".to_string(),
        has_steps: step.is_some(),
        absent,
    })
}
