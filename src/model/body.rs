//! Anthropometry: segment lengths, masses, centres of mass and inertias for a body of height H
//! and mass M, from a body table in `models/` (KLAW 1989, Appendix B, Table B-1).
use serde::Deserialize;
use std::path::Path;

use crate::model::error::{InputError, Shown};

/// The table bundled with klaw: Winter's (Dempster's) data as printed in Table B-1.
pub(crate) const BUILTIN_TABLE: &str = include_str!("../../models/body-winter.toml");

/// The name of the default body table.
pub const DEFAULT_BODY_TABLE: &str = "winter";

/// The bundled body tables (`--body-table NAME`), by name: Winter's (Dempster's) data of Table
/// B-1, and de Leva 1996's adjusted Zatsiorsky–Seluyanov parameters of young adult men and
/// women (Table 4; derived by `scripts/body_deleva.py`, docs/bodies.md), whose thigh-to-shank
/// ratios differ from Winter's and from each other.
pub const BODY_TABLES: &[(&str, &str)] = &[
    (DEFAULT_BODY_TABLE, BUILTIN_TABLE),
    (
        "deleva-male",
        include_str!("../../models/body-deleva-male.toml"),
    ),
    (
        "deleva-female",
        include_str!("../../models/body-deleva-female.toml"),
    ),
];

/// A segment row of the body table (fractions of H and M).
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SegmentRow {
    /// Length as a fraction of body height.
    pub(crate) length: f64,
    /// Mass as a fraction of body mass.
    pub(crate) mass: f64,
    /// Centre of mass from the proximal end, fraction of the length.
    pub(crate) r: f64,
    /// Radius of gyration about the centre of mass, fraction of the length.
    pub(crate) gamma: f64,
}

/// Segment 0, the pelvis: its width only.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PelvisRow {
    /// Hip joint to hip joint, fraction of body height.
    pub(crate) length: f64,
}

/// Segment 1, the whole leg: its length and mass are the thigh's and the shank's sums.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct LegRow {
    /// Centre of mass from the distal end (the ankle), fraction of the length.
    pub(crate) r: f64,
    /// Radius of gyration about the centre of mass, fraction of the length.
    pub(crate) gamma: f64,
}

/// Foot distances of Table B-1 (fractions of H).
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct FootRow {
    /// l5, mid foot: in the table for completeness, the model's foot does not use it.
    pub(crate) mid_foot: f64,
    /// l6, toe: in the table for completeness, the model's foot does not use it.
    pub(crate) toe: f64,
    /// l8, hind foot: heel to ankle, horizontal.
    pub(crate) hind_foot: f64,
    /// l9, ankle to the foot's base with the foot flat.
    pub(crate) ankle_height: f64,
    /// l11, heel to ankle.
    pub(crate) heel_to_ankle: f64,
    /// l12, ankle to the 1st metatarsal joint.
    pub(crate) ankle_to_metatarsal: f64,
    /// l13, 1st metatarsal joint to toe tip.
    pub(crate) metatarsal_to_toe: f64,
}

/// Dimensions of the kinematic figure (fractions of H): the upper body and arms that dress the
/// dynamic model, which lumps them into segment 2.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct FigureRow {
    /// Hip-joint level to shoulder level.
    pub spine: f64,
    /// Shoulder joint to shoulder joint.
    pub shoulder_width: f64,
    /// Shoulder level to chin.
    pub neck: f64,
    /// Chin to top of the head.
    pub head: f64,
    /// Shoulder to elbow.
    pub upper_arm: f64,
    /// Elbow to wrist.
    pub forearm: f64,
    /// Wrist to finger tip.
    pub hand: f64,
}

/// Bodies a table is valid for.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Limits {
    pub(crate) height: [f64; 2],
    pub(crate) mass: [f64; 2],
}

/// How far the segment mass fractions, upper_body + 2 × (thigh + shank), may add up from 1: the
/// rounding of a published table (de Leva's 14 segments sum to 1 within 1e-4; the bundled
/// tables' to 1e-15).
pub const MASS_SUM_TOLERANCE: f64 = 1e-4;

/// How far heel_to_ankle may lie from √(hind_foot² + ankle_height²), and the segments stacked
/// standing above 1 (fractions of H): Table B-1's l11 misses the right triangle by 4e-6, its
/// rounding to 5 decimals.
pub const FOOT_TOLERANCE: f64 = 1e-4;

/// An anthropometric table: segment lengths, masses, centres of mass and radii of gyration as
/// fractions of body height H, body mass M and segment length, in the layout of
/// `models/body-*.toml` (docs/bodies.md, "Your own table"). [`Body::new`] scales it to a body.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodyTable {
    /// The table's name: a name of [`BODY_TABLES`], or the file's path as given.
    #[serde(skip, default = "default_table_name")]
    pub(crate) key: &'static str,
    /// What the table is and where it comes from.
    pub(crate) name: String,
    pub(crate) pelvis: PelvisRow,
    pub(crate) leg: LegRow,
    pub(crate) upper_body: SegmentRow,
    pub(crate) thigh: SegmentRow,
    pub(crate) shank: SegmentRow,
    pub(crate) foot: FootRow,
    pub(crate) figure: FigureRow,
    pub(crate) limits: Limits,
}

fn default_table_name() -> &'static str {
    DEFAULT_BODY_TABLE
}

/// `name` as a `&'static str`: a bundled table's own, or a copy leaked once per distinct name
/// (a table file's path), so that [`Body`] stays `Copy` with its table's name in it and a
/// program that loads one file a thousand times holds one copy of its name.
fn intern(name: &str) -> &'static str {
    use std::sync::{Mutex, PoisonError};
    static NAMES: Mutex<Vec<&'static str>> = Mutex::new(Vec::new());
    if let Some((n, _)) = BODY_TABLES.iter().find(|(n, _)| *n == name) {
        return n;
    }
    let mut names = NAMES.lock().unwrap_or_else(PoisonError::into_inner);
    if let Some(n) = names.iter().find(|n| **n == name) {
        return n;
    }
    let n: &'static str = Box::leak(name.into());
    names.push(n);
    n
}

impl BodyTable {
    /// The bundled table.
    pub(crate) fn builtin() -> Self {
        Self::from_text(BUILTIN_TABLE, Path::new("models/body-winter.toml"))
            .expect("the bundled body table parses (tested)")
    }

    /// The bundled table `name` of [`BODY_TABLES`]; an unknown name is an error listing them.
    pub fn named(name: &str) -> Result<Self, InputError> {
        let (key, text) = BODY_TABLES
            .iter()
            .find(|(n, _)| *n == name)
            .ok_or_else(|| InputError::bad_value("body-table", unknown_body_table(name)))?;
        let path = format!("models/body-{}.toml", key);
        let mut table = Self::from_text(text, Path::new(&path))?;
        table.key = key;
        Ok(table)
    }

    /// Read and check the table file `path` (the layout of `models/body-*.toml`); its name is
    /// the path as given.
    pub fn read(path: &Path) -> Result<Self, InputError> {
        Self::parse(&crate::model::file::read_text("body table", path)?, path)
    }

    /// A bundled table by name, or a table file: `spec` names a file when it ends in `.toml` or
    /// contains a `/` ([`crate::model::file::names_a_file`]), a relative one relative to `base`
    /// when given (a scenario's folder), else to the working directory.
    pub fn load(spec: &str, base: Option<&Path>) -> Result<Self, InputError> {
        if !crate::model::file::names_a_file(spec) {
            return Self::named(spec);
        }
        match base {
            Some(dir) => Self::read(&dir.join(spec)),
            None => Self::read(Path::new(spec)),
        }
    }

    /// Parse and check a table from TOML text in the layout of `models/body-*.toml`; `path`
    /// names it in errors and is its name. Every key of the layout must be given and no other;
    /// the rules are [`BodyTable::check`]'s.
    pub fn parse(text: &str, path: &Path) -> Result<Self, InputError> {
        let mut table = Self::from_text(text, path)?;
        table.key = intern(&path.display().to_string());
        Ok(table)
    }

    /// [`BodyTable::parse`] without naming the table.
    fn from_text(text: &str, path: &Path) -> Result<Self, InputError> {
        let malformed = |reason: String| InputError::malformed("body table", path, reason);
        let table: BodyTable = crate::model::file::parse_toml(text).map_err(malformed)?;
        table.check().map_err(malformed)?;
        Ok(table)
    }

    /// The table's name: a name of [`BODY_TABLES`], or the path of the file it was read from.
    pub fn name(&self) -> &'static str {
        self.key
    }

    /// What the table is and where it comes from: its `name = "…"` line.
    pub fn title(&self) -> &str {
        &self.name
    }

    /// The rules a table must keep, the first broken in words naming its keys:
    ///
    /// - every length, mass fraction, `r` and `gamma` is a finite number in (0, 1] (a fraction
    ///   of H, of M or of the segment's length);
    /// - the segment masses make the body: upper_body.mass + 2 × (thigh.mass + shank.mass) = 1
    ///   within [`MASS_SUM_TOLERANCE`] (the model's body is the upper body and two legs of a
    ///   thigh and a shank with its foot);
    /// - the hind foot closes: heel_to_ankle = √(hind_foot² + ankle_height²) within
    ///   [`FOOT_TOLERANCE`] (the heel is placed by hind_foot and ankle_height, l11 derived);
    /// - ankle_to_metatarsal > ankle_height (the metatarsal joint on the ground lies
    ///   √(l12² − l9²) ahead of the ankle);
    /// - the segments stacked standing fit in the body: foot.ankle_height + thigh.length +
    ///   shank.length + upper_body.length ≤ 1 + [`FOOT_TOLERANCE`];
    /// - the limits are ordered: 0 < low < high, finite, for height and mass.
    pub fn check(&self) -> Result<(), String> {
        let (f, fig) = (&self.foot, &self.figure);
        let fractions = [
            ("pelvis.length", self.pelvis.length),
            ("leg.r", self.leg.r),
            ("leg.gamma", self.leg.gamma),
            ("upper_body.length", self.upper_body.length),
            ("upper_body.mass", self.upper_body.mass),
            ("upper_body.r", self.upper_body.r),
            ("upper_body.gamma", self.upper_body.gamma),
            ("thigh.length", self.thigh.length),
            ("thigh.mass", self.thigh.mass),
            ("thigh.r", self.thigh.r),
            ("thigh.gamma", self.thigh.gamma),
            ("shank.length", self.shank.length),
            ("shank.mass", self.shank.mass),
            ("shank.r", self.shank.r),
            ("shank.gamma", self.shank.gamma),
            ("foot.mid_foot", f.mid_foot),
            ("foot.toe", f.toe),
            ("foot.hind_foot", f.hind_foot),
            ("foot.ankle_height", f.ankle_height),
            ("foot.heel_to_ankle", f.heel_to_ankle),
            ("foot.ankle_to_metatarsal", f.ankle_to_metatarsal),
            ("foot.metatarsal_to_toe", f.metatarsal_to_toe),
            ("figure.spine", fig.spine),
            ("figure.shoulder_width", fig.shoulder_width),
            ("figure.neck", fig.neck),
            ("figure.head", fig.head),
            ("figure.upper_arm", fig.upper_arm),
            ("figure.forearm", fig.forearm),
            ("figure.hand", fig.hand),
        ];
        for (key, v) in fractions {
            if !(v.is_finite() && v > 0.0 && v <= 1.0) {
                return Err(format!(
                    "{key} = {}: every length, mass, r and gamma must be a fraction in (0, 1] \
                     (of H, of M or of the segment's length)",
                    Shown(v)
                ));
            }
        }
        let (ub, th, sh) = (self.upper_body.mass, self.thigh.mass, self.shank.mass);
        let sum = ub + 2.0 * (th + sh);
        if (sum - 1.0).abs() > MASS_SUM_TOLERANCE {
            return Err(format!(
                "the segment masses must make the body: upper_body.mass + 2 × (thigh.mass + \
                 shank.mass) = {} + 2 × ({} + {}) = {}, not 1 (within {})",
                Shown(ub),
                Shown(th),
                Shown(sh),
                Shown(sum),
                Shown(MASS_SUM_TOLERANCE)
            ));
        }
        let closed = f.hind_foot.hypot(f.ankle_height);
        if (f.heel_to_ankle - closed).abs() > FOOT_TOLERANCE {
            return Err(format!(
                "the hind foot must close: foot.heel_to_ankle = {} must be √(foot.hind_foot² + \
                 foot.ankle_height²) = {} (within {})",
                Shown(f.heel_to_ankle),
                Shown(closed),
                Shown(FOOT_TOLERANCE)
            ));
        }
        if f.ankle_to_metatarsal <= f.ankle_height {
            return Err(format!(
                "foot.ankle_to_metatarsal = {} must exceed foot.ankle_height = {} (the \
                 metatarsal joint on the ground lies ahead of the ankle)",
                Shown(f.ankle_to_metatarsal),
                Shown(f.ankle_height)
            ));
        }
        let stack = f.ankle_height + self.thigh.length + self.shank.length + self.upper_body.length;
        if stack > 1.0 + FOOT_TOLERANCE {
            return Err(format!(
                "the segments stacked standing must fit in the body: foot.ankle_height + \
                 thigh.length + shank.length + upper_body.length = {} exceeds 1 (H, within {})",
                Shown(stack),
                Shown(FOOT_TOLERANCE)
            ));
        }
        for (key, [lo, hi], unit) in [
            ("limits.height", self.limits.height, "m"),
            ("limits.mass", self.limits.mass, "kg"),
        ] {
            if !(lo.is_finite() && hi.is_finite() && lo > 0.0 && lo < hi) {
                return Err(format!(
                    "{key} = [{}, {}] must be ordered: 0 < low < high {unit}, finite",
                    Shown(lo),
                    Shown(hi)
                ));
            }
        }
        Ok(())
    }
}

/// Why a body table name is unknown: the name, and the bundled tables.
pub fn unknown_body_table(name: &str) -> String {
    let known: Vec<&str> = BODY_TABLES.iter().map(|(n, _)| *n).collect();
    format!(
        "unknown body table `{name}`; the tables are {}, or a file of your own (a value ending \
         in .toml or containing a /)",
        known.join(", ")
    )
}

/// A body of height H and mass M in SI units. Names follow Table B-1: l_i lengths, m_i masses,
/// `r_i` centre-of-mass distances in metres (r1 from the ankle, r2 from the hip, r3 from the hip,
/// r4 from the knee), `i_i` moments of inertia about the centre of mass, I = m (γ l)².
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Body {
    /// The body table it is scaled from: a name of [`BODY_TABLES`], or the path of the table
    /// file ([`BodyTable::name`]).
    pub table: &'static str,
    /// Body height H (m).
    pub height: f64,
    /// Body mass M (kg).
    pub mass: f64,
    /// l0, pelvis width, hip joint to hip joint (m).
    pub l0: f64,
    /// l1, whole leg, ankle to hip: l3 + l4 (m).
    pub l1: f64,
    /// l2, upper body (head, arms and trunk), hip to the top of the head (m).
    pub l2: f64,
    /// l3, thigh, hip to knee (m).
    pub l3: f64,
    /// l4, shank (the foot included), knee to ankle (m).
    pub l4: f64,
    /// l8, hind foot: heel to ankle, horizontal (m).
    pub l8: f64,
    /// l9, ankle height with the foot flat (m).
    pub l9: f64,
    /// l11, heel to ankle, √(l8² + l9²) (m).
    pub l11: f64,
    /// l12, ankle to 1st metatarsal joint (m).
    pub l12: f64,
    /// l13, 1st metatarsal joint to toe tip (m).
    pub l13: f64,
    /// m1, whole leg: m3 + m4 (kg).
    pub m1: f64,
    /// m2, upper body: head, arms and trunk (kg).
    pub m2: f64,
    /// m3, thigh (kg).
    pub m3: f64,
    /// m4, shank and foot (kg).
    pub m4: f64,
    /// r1, the whole leg's centre of mass from the ankle (m).
    pub r1: f64,
    /// r2, the upper body's centre of mass from the hip (m).
    pub r2: f64,
    /// r3, the thigh's centre of mass from the hip (m).
    pub r3: f64,
    /// r4, the shank's centre of mass from the knee (m).
    pub r4: f64,
    /// I1, the whole leg's moment of inertia about its centre of mass, m1 (γ1 l1)² (kg m²).
    pub i1: f64,
    /// I2, the upper body's moment of inertia about its centre of mass (kg m²).
    pub i2: f64,
    /// I3, the thigh's moment of inertia about its centre of mass (kg m²).
    pub i3: f64,
    /// I4, the shank's moment of inertia about its centre of mass (kg m²).
    pub i4: f64,
    /// The kinematic figure's dimensions, in metres (the table's fractions × H).
    pub figure: FigureRow,
}

impl Body {
    /// Scale `table` to height `height` (m) and mass `mass` (kg), checking both against the
    /// table's limits.
    pub fn new(table: &BodyTable, height: f64, mass: f64) -> Result<Self, InputError> {
        let [hmin, hmax] = table.limits.height;
        let [mmin, mmax] = table.limits.mass;
        InputError::check_range("height", height, hmin, hmax, "m")?;
        InputError::check_range("mass", mass, mmin, mmax, "kg")?;
        let (h, m) = (height, mass);
        let l3 = table.thigh.length * h;
        let l4 = table.shank.length * h;
        let l1 = l3 + l4;
        let m3 = table.thigh.mass * m;
        let m4 = table.shank.mass * m;
        let m1 = m3 + m4;
        let l2 = table.upper_body.length * h;
        let m2 = table.upper_body.mass * m;
        let inertia = |mass: f64, gamma: f64, length: f64| mass * (gamma * length).powi(2);
        Ok(Body {
            table: table.key,
            height,
            mass,
            l0: table.pelvis.length * h,
            l1,
            l2,
            l3,
            l4,
            l8: table.foot.hind_foot * h,
            l9: table.foot.ankle_height * h,
            // the table's l11 = 0.04853 H agrees with √(l8² + l9²) to 4e-6 H; the heel is placed
            // by (l8, l9) everywhere, so l11 is derived from them to keep the foot one rigid shape
            l11: table.foot.hind_foot.hypot(table.foot.ankle_height) * h,
            l12: table.foot.ankle_to_metatarsal * h,
            l13: table.foot.metatarsal_to_toe * h,
            m1,
            m2,
            m3,
            m4,
            r1: table.leg.r * l1,
            r2: table.upper_body.r * l2,
            r3: table.thigh.r * l3,
            r4: table.shank.r * l4,
            i1: inertia(m1, table.leg.gamma, l1),
            i2: inertia(m2, table.upper_body.gamma, l2),
            i3: inertia(m3, table.thigh.gamma, l3),
            i4: inertia(m4, table.shank.gamma, l4),
            figure: {
                let f = table.figure;
                FigureRow {
                    spine: f.spine * h,
                    shoulder_width: f.shoulder_width * h,
                    neck: f.neck * h,
                    head: f.head * h,
                    upper_arm: f.upper_arm * h,
                    forearm: f.forearm * h,
                    hand: f.hand * h,
                }
            },
        })
    }

    /// The bundled table scaled to `height` and `mass`.
    pub fn standard(height: f64, mass: f64) -> Result<Self, InputError> {
        Self::new(&BodyTable::builtin(), height, mass)
    }

    /// The table `table` scaled to `height` and `mass`: a name of [`BODY_TABLES`], or a table
    /// file of your own (a value ending in `.toml` or containing a `/`, relative to the working
    /// directory; [`BodyTable::load`]), read and checked first.
    pub fn from_table(table: &str, height: f64, mass: f64) -> Result<Self, InputError> {
        Self::new(&BodyTable::load(table, None)?, height, mass)
    }

    /// The table file `path` (the layout of `models/body-*.toml`), read and checked, scaled to
    /// `height` and `mass`.
    pub fn from_file(path: &Path, height: f64, mass: f64) -> Result<Self, InputError> {
        Self::new(&BodyTable::read(path)?, height, mass)
    }

    /// Horizontal distance from the ankle to the 1st metatarsal joint with the foot flat
    /// (the metatarsal joint on the ground): √(l12² − l9²).
    pub fn ankle_to_metatarsal_horizontal(&self) -> f64 {
        (self.l12 * self.l12 - self.l9 * self.l9).sqrt()
    }

    /// Hip–ankle distance of a leg whose knee is flexed by `knee` (rad), by the cosine law:
    /// a² = l3² + l4² + 2 l3 l4 cos κ.
    pub fn hip_ankle_distance(&self, knee: f64) -> f64 {
        (self.l3 * self.l3 + self.l4 * self.l4 + 2.0 * self.l3 * self.l4 * knee.cos()).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The paper's own example (Appendix B): H = 1.8 m, M = 80 kg gives m3 = 8 kg,
    /// l3 = 0.426 m, γ3·l3 = 0.138 m, r3·l3 = 0.184 m; I3 = m (γ l)² = 0.1515 kg m² (spec §2).
    #[test]
    fn paper_example_thigh() {
        let b = Body::standard(1.8, 80.0).unwrap();
        assert!((b.m3 - 8.0).abs() < 1e-12);
        assert!((b.l3 - 0.426).abs() < 5e-4);
        assert!((b.r3 - 0.184).abs() < 5e-4);
        assert!((b.i3 / b.m3).sqrt() - 0.138 < 5e-4);
        assert!((b.i3 - 0.1515).abs() < 5e-4);
    }

    /// l8² + l9² ≈ l11²: hind foot, ankle height and heel–ankle form a right triangle (spec §2).
    #[test]
    fn hind_foot_right_triangle() {
        let t = BodyTable::builtin();
        let f = &t.foot;
        assert!((f.hind_foot.hypot(f.ankle_height) - f.heel_to_ankle).abs() < 5e-6);
        let b = Body::new(&t, 1.5, 70.0).unwrap();
        assert!((b.l8.hypot(b.l9) - b.l11).abs() < 1e-15);
    }

    /// Segment masses of the whole body: upper body + 2 legs = 100 % of M.
    #[test]
    fn masses_add_up_to_the_body() {
        let b = Body::standard(1.75, 70.0).unwrap();
        assert!((b.m2 + 2.0 * b.m1 - b.mass).abs() < 1e-9);
    }

    #[test]
    fn hip_ankle_distance_limits() {
        let b = Body::standard(1.8, 80.0).unwrap();
        assert!((b.hip_ankle_distance(0.0) - b.l1).abs() < 1e-12);
        let right = (b.l3.powi(2) + b.l4.powi(2)).sqrt();
        assert!((b.hip_ankle_distance(std::f64::consts::FRAC_PI_2) - right).abs() < 1e-12);
    }

    #[test]
    fn out_of_range_bodies_are_named_errors() {
        let e = Body::standard(3.0, 80.0).unwrap_err().to_string();
        assert!(e.contains("height") && e.contains("[1.2, 2.2]"), "{e}");
        let e = Body::standard(1.8, f64::NAN).unwrap_err().to_string();
        assert!(e.contains("mass") && e.contains("NaN"), "{e}");
    }

    /// Every bundled table scales to a body whose segment masses add up to M and whose standing
    /// height l9 + l1 + l2 is H (de Leva's: the upper body is the rest of the stature).
    #[test]
    fn every_bundled_table_makes_a_whole_body() {
        for (name, _) in BODY_TABLES {
            let b = Body::from_table(name, 1.7, 65.0).unwrap();
            assert_eq!(b.table, *name);
            assert!((b.m2 + 2.0 * b.m1 - b.mass).abs() < 1e-9, "{name}");
            assert!((b.l1 - b.l3 - b.l4).abs() < 1e-15, "{name}");
        }
        for name in ["deleva-male", "deleva-female"] {
            let b = Body::from_table(name, 1.7, 65.0).unwrap();
            assert!((b.l9 + b.l1 + b.l2 - 1.7).abs() < 1e-9, "{name}");
        }
    }

    /// de Leva 1996, Table 4, at its mean statures: thigh (HJC–KJC) 422.2 / 368.5 mm and shank
    /// (KJC–LMAL) 434.0 / 432.3 mm for men / women of 1741 / 1735 mm; thigh 14.16 / 14.78 %
    /// of the body mass, shank and foot 4.33 + 1.37 / 4.81 + 1.29 %.
    #[test]
    fn de_leva_bodies_have_the_published_segments() {
        let men = Body::from_table("deleva-male", 1.741, 73.0).unwrap();
        let women = Body::from_table("deleva-female", 1.735, 61.9).unwrap();
        for (b, thigh, shank, m3, m4) in [
            (men, 0.4222, 0.4340, 14.16, 4.33 + 1.37),
            (women, 0.3685, 0.4323, 14.78, 4.81 + 1.29),
        ] {
            assert!((b.l3 - thigh).abs() < 1e-6 && (b.l4 - shank).abs() < 1e-6);
            assert!((b.m3 / b.mass * 100.0 - m3).abs() < 1e-9);
            assert!((b.m4 / b.mass * 100.0 - m4).abs() < 1e-9);
        }
    }

    /// The tables' bodies are not similar: the thigh-to-shank ratio is Winter's 0.964, de
    /// Leva's men's 0.973 and women's 0.852.
    #[test]
    fn the_tables_differ_in_proportions() {
        let ratio = |name: &str| {
            let b = Body::from_table(name, 1.8, 80.0).unwrap();
            b.l3 / b.l4
        };
        assert!((ratio("winter") - 0.23669 / 0.24556).abs() < 1e-12);
        assert!((ratio("deleva-male") - 422.2 / 434.0).abs() < 1e-6);
        assert!((ratio("deleva-female") - 368.5 / 432.3).abs() < 1e-6);
    }

    #[test]
    fn unknown_tables_are_named_errors() {
        let e = Body::from_table("dempster", 1.8, 80.0)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("`dempster`") && e.contains("deleva-female"),
            "{e}"
        );
    }

    #[test]
    fn malformed_tables_are_rejected() {
        let bad = BUILTIN_TABLE.replace("length = 0.23669", "length = -0.2");
        let e = BodyTable::parse(&bad, Path::new("x.toml"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("thigh.length = -0.2"), "{e}");
        let e = BodyTable::parse("name = 3", Path::new("y.toml")).unwrap_err();
        assert!(matches!(e, InputError::Malformed { .. }));
    }

    /// Each rule of [`BodyTable::check`] refuses a table that breaks it, naming its keys; a
    /// missing or an unknown key is named by the parser.
    #[test]
    fn every_rule_is_named() {
        let refused = |from: &str, to: &str, expect: &str| {
            assert!(BUILTIN_TABLE.contains(from), "{from}");
            let text = BUILTIN_TABLE.replacen(from, to, 1);
            let e = BodyTable::parse(&text, Path::new("t.toml"))
                .unwrap_err()
                .to_string();
            assert!(e.starts_with("malformed body table t.toml: "), "{e}");
            assert!(e.contains(expect), "{to}: `{expect}` not in {e}");
        };
        refused("gamma = 0.323", "gamma = inf", "thigh.gamma = inf");
        refused(
            "mass = 0.1\n",
            "mass = 0.0\n",
            "thigh.mass = 0: every length",
        );
        refused(
            "mass = 0.1\n",
            "mass = 0.12\n",
            "= 1.04, not 1 (within 0.0001)",
        );
        refused(
            "heel_to_ankle = 0.04853",
            "heel_to_ankle = 0.05",
            "foot.heel_to_ankle = 0.05 must be √(foot.hind_foot² + foot.ankle_height²) = 0.0485",
        );
        refused(
            "ankle_to_metatarsal = 0.08901",
            "ankle_to_metatarsal = 0.03",
            "foot.ankle_to_metatarsal = 0.03 must exceed foot.ankle_height = 0.03846",
        );
        refused("length = 0.47", "length = 0.6", "= 1.12071 exceeds 1");
        refused(
            "height = [1.2, 2.2]",
            "height = [2.2, 1.2]",
            "limits.height = [2.2, 1.2] must be ordered",
        );
        refused(
            "mass = [25.0, 200.0]",
            "mass = [0.0, 200.0]",
            "limits.mass = [0, 200]",
        );
        refused("r = 0.553\n", "", "missing field `r`");
        refused(
            "gamma = 0.326\n",
            "gamma = 0.326\nlength = 0.48\n",
            "unknown field `length`",
        );
    }

    /// A table read from a file is named by its path, interned once: two readings share one
    /// name.
    #[test]
    fn a_file_table_is_named_by_its_path() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("mine.toml");
        std::fs::write(&path, BUILTIN_TABLE).unwrap();
        let a = Body::from_file(&path, 1.8, 80.0).unwrap();
        let b = Body::from_table(path.to_str().unwrap(), 1.8, 80.0).unwrap();
        assert_eq!(a.table, path.display().to_string());
        assert!(std::ptr::eq(a.table, b.table));
        let winter = Body::standard(1.8, 80.0).unwrap();
        assert_eq!(
            Body {
                table: "winter",
                ..a
            },
            winter
        );
        let e = Body::from_table("missing.toml", 1.8, 80.0).unwrap_err();
        assert!(matches!(e, InputError::Unreadable { .. }), "{e}");
    }
}
