//! Anthropometry: segment lengths, masses, centres of mass and inertias for a body of height H
//! and mass M, from a body table in `models/` (KLAW 1989, Appendix B, Table B-1).
use serde::Deserialize;
use std::path::Path;

use crate::model::error::{InputError, Reason};

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
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct SegmentRow {
    /// Length as a fraction of body height.
    #[serde(default)]
    pub(crate) length: f64,
    /// Mass as a fraction of body mass.
    #[serde(default)]
    pub(crate) mass: f64,
    /// Centre of mass from the proximal end (whole leg: distal end), fraction of the length.
    #[serde(default)]
    pub(crate) r: f64,
    /// Radius of gyration about the centre of mass, fraction of the length.
    #[serde(default)]
    pub(crate) gamma: f64,
}

/// Foot distances of Table B-1 (fractions of H).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct FootRow {
    /// l5, mid foot: in the table for completeness, the model's foot does not use it.
    #[expect(dead_code, reason = "a row of Table B-1 the model does not read")]
    pub(crate) mid_foot: f64,
    /// l6, toe: in the table for completeness, the model's foot does not use it.
    #[expect(dead_code, reason = "a row of Table B-1 the model does not read")]
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
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct Limits {
    pub(crate) height: [f64; 2],
    pub(crate) mass: [f64; 2],
}

/// A body table as stored in `models/*.toml`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct BodyTable {
    /// The table's name in [`BODY_TABLES`] (`winter` for a table parsed from elsewhere).
    #[serde(skip, default = "default_table_name")]
    pub(crate) key: &'static str,
    /// What the table is and where it comes from.
    #[expect(dead_code, reason = "the table file's title, for its readers")]
    pub(crate) name: String,
    pub(crate) pelvis: SegmentRow,
    pub(crate) leg: SegmentRow,
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

impl BodyTable {
    /// The bundled table.
    pub(crate) fn builtin() -> Self {
        Self::parse(BUILTIN_TABLE, Path::new("models/body-winter.toml"))
            .expect("the bundled body table parses (tested)")
    }

    /// The bundled table `name` of [`BODY_TABLES`]; an unknown name is an error listing them.
    pub(crate) fn named(name: &str) -> Result<Self, InputError> {
        let (key, text) = BODY_TABLES
            .iter()
            .find(|(n, _)| *n == name)
            .ok_or_else(|| InputError::bad_value("body-table", unknown_body_table(name)))?;
        let path = format!("models/body-{}.toml", key);
        let mut table = Self::parse(text, Path::new(&path))?;
        table.key = key;
        Ok(table)
    }

    /// Parse a table from TOML text; `path` only names the source in errors.
    pub(crate) fn parse(text: &str, path: &Path) -> Result<Self, InputError> {
        let malformed = |reason: Reason| InputError::malformed("body table", path, reason);
        let table: BodyTable = toml::from_str(text).map_err(|e| malformed(Box::new(e)))?;
        let rows = [
            ("pelvis.length", table.pelvis.length),
            ("leg.r", table.leg.r),
            ("leg.gamma", table.leg.gamma),
            ("upper_body.length", table.upper_body.length),
            ("upper_body.mass", table.upper_body.mass),
            ("upper_body.r", table.upper_body.r),
            ("upper_body.gamma", table.upper_body.gamma),
            ("thigh.length", table.thigh.length),
            ("thigh.mass", table.thigh.mass),
            ("thigh.r", table.thigh.r),
            ("thigh.gamma", table.thigh.gamma),
            ("shank.length", table.shank.length),
            ("shank.mass", table.shank.mass),
            ("shank.r", table.shank.r),
            ("shank.gamma", table.shank.gamma),
            ("foot.hind_foot", table.foot.hind_foot),
            ("foot.ankle_height", table.foot.ankle_height),
            ("foot.heel_to_ankle", table.foot.heel_to_ankle),
            ("foot.ankle_to_metatarsal", table.foot.ankle_to_metatarsal),
            ("foot.metatarsal_to_toe", table.foot.metatarsal_to_toe),
            ("figure.spine", table.figure.spine),
            ("figure.shoulder_width", table.figure.shoulder_width),
            ("figure.neck", table.figure.neck),
            ("figure.head", table.figure.head),
            ("figure.upper_arm", table.figure.upper_arm),
            ("figure.forearm", table.figure.forearm),
            ("figure.hand", table.figure.hand),
        ];
        for (name, v) in rows {
            InputError::check_range(name, v, 1e-6, 1.0, "(fraction)")
                .map_err(|e| malformed(Box::new(e)))?;
        }
        if table.foot.ankle_to_metatarsal <= table.foot.ankle_height {
            return Err(malformed(
                "foot.ankle_to_metatarsal must exceed foot.ankle_height".into(),
            ));
        }
        Ok(table)
    }
}

/// Why a body table name is unknown: the name, and the bundled tables.
pub fn unknown_body_table(name: &str) -> String {
    let known: Vec<&str> = BODY_TABLES.iter().map(|(n, _)| *n).collect();
    format!(
        "unknown body table `{name}`; the tables are {}",
        known.join(", ")
    )
}

/// A body of height H and mass M in SI units. Names follow Table B-1: l_i lengths, m_i masses,
/// `r_i` centre-of-mass distances in metres (r1 from the ankle, r2 from the hip, r3 from the hip,
/// r4 from the knee), `i_i` moments of inertia about the centre of mass, I = m (γ l)².
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Body {
    /// The body table it is scaled from (a name of [`BODY_TABLES`]).
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
    pub(crate) fn new(table: &BodyTable, height: f64, mass: f64) -> Result<Self, InputError> {
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

    /// The bundled table `table` (a name of [`BODY_TABLES`]) scaled to `height` and `mass`.
    pub fn from_table(table: &str, height: f64, mass: f64) -> Result<Self, InputError> {
        Self::new(&BodyTable::named(table)?, height, mass)
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
        assert!(e.contains("thigh.length"), "{e}");
        let e = BodyTable::parse("name = 3", Path::new("y.toml")).unwrap_err();
        assert!(matches!(e, InputError::Malformed { .. }));
    }
}
