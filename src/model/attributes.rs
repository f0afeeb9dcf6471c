//! Locomotion attributes (KLAW 1989 §2.1: "up to 28 attributes individualize the walk"): the
//! table of defaults, units and valid ranges in `models/attributes.toml`, user overrides from
//! attribute files, and the typed, SI-unit values the engine reads.
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::Path;

use crate::model::error::{InputError, Reason};

/// The bundled attribute table.
pub(crate) const BUILTIN_TABLE: &str = include_str!("../../models/attributes.toml");

/// The bundled style presets (`--style NAME`): attribute files in `models/styles/`.
pub const STYLES: &[(&str, &str)] = &[
    ("normal", include_str!("../../models/styles/normal.toml")),
    ("brisk", include_str!("../../models/styles/brisk.toml")),
    ("elderly", include_str!("../../models/styles/elderly.toml")),
    ("march", include_str!("../../models/styles/march.toml")),
    (
        "long-stride",
        include_str!("../../models/styles/long-stride.toml"),
    ),
    ("paper", include_str!("../../models/styles/paper.toml")),
];

/// The overrides of the style preset `name` (an error lists the known styles).
pub fn style(name: &str) -> Result<BTreeMap<String, f64>, InputError> {
    let (_, text) = STYLES
        .iter()
        .find(|(n, _)| *n == name)
        .ok_or_else(|| InputError::bad_value("style", unknown_style(name)))?;
    parse_overrides(text, Path::new(&format!("models/styles/{name}.toml")))
}

/// [`InputError::UnknownStyle`] for `name`, listing the styles.
pub fn unknown_style(name: &str) -> InputError {
    InputError::UnknownStyle {
        name: name.to_string(),
        known: STYLES
            .iter()
            .map(|(n, _)| *n)
            .collect::<Vec<_>>()
            .join(", "),
    }
}

/// One row of the attribute table: default, unit, valid range, meaning and source.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AttributeSpec {
    /// The attribute's symbol in the paper or the spec (δ_hs, κ_hs, ε, …).
    pub symbol: String,
    /// The user's unit of `default`, `min`, `max` and of attribute files: "deg" and "%" are
    /// converted to radians and fractions by [`AttributeTable::resolve`], the others are kept.
    pub unit: String,
    /// The default value, in `unit`.
    pub default: f64,
    /// The smallest valid value, in `unit`.
    pub min: f64,
    /// The largest valid value, in `unit`.
    pub max: f64,
    /// What the attribute sets.
    pub doc: String,
    /// Where the default and the range come from (paper, spec §, gait norms) or why.
    pub source: String,
}

/// The attribute table, by name.
#[derive(Clone, Debug)]
pub struct AttributeTable(pub BTreeMap<String, AttributeSpec>);

impl AttributeTable {
    /// The bundled table (parsed once per process: it is compiled-in text, the same every
    /// time; a user's values come through [`Self::resolve`] and attribute files).
    pub fn builtin() -> Self {
        static TABLE: std::sync::OnceLock<AttributeTable> = std::sync::OnceLock::new();
        TABLE
            .get_or_init(|| {
                Self::parse(BUILTIN_TABLE, Path::new("models/attributes.toml"))
                    .expect("the bundled attribute table parses (tested)")
            })
            .clone()
    }

    /// Parse a table; every attribute the engine reads must be present, with
    /// min ≤ default ≤ max.
    pub(crate) fn parse(text: &str, path: &Path) -> Result<Self, InputError> {
        let malformed = |reason: Reason| InputError::malformed("attribute table", path, reason);
        let rows: BTreeMap<String, AttributeSpec> =
            toml::from_str(text).map_err(|e| malformed(Box::new(e)))?;
        for name in Attributes::NAMES {
            let spec = rows
                .get(*name)
                .ok_or_else(|| malformed(format!("attribute `{name}` is missing").into()))?;
            if !(spec.min <= spec.default && spec.default <= spec.max) {
                return Err(malformed(
                    format!(
                        "attribute `{name}`: default {} is outside [{}, {}]",
                        spec.default, spec.min, spec.max
                    )
                    .into(),
                ));
            }
        }
        if let Some(extra) = rows
            .keys()
            .find(|k| !Attributes::NAMES.contains(&k.as_str()))
        {
            return Err(malformed(
                format!("attribute `{extra}` is not read by the engine").into(),
            ));
        }
        Ok(AttributeTable(rows))
    }

    /// Attributes with every default, then `overrides` (user units) applied by name.
    pub fn resolve(
        &self,
        overrides: &BTreeMap<String, f64>,
        source_name: &str,
    ) -> Result<Attributes, InputError> {
        let mut values = BTreeMap::new();
        for (name, spec) in &self.0 {
            values.insert(name.as_str(), spec.default);
        }
        for (name, &value) in overrides {
            let spec = self
                .0
                .get(name)
                .ok_or_else(|| InputError::UnknownAttribute {
                    name: name.clone(),
                    source_name: source_name.to_string(),
                    known: Attributes::NAMES.join(", "),
                })?;
            let unit = if spec.unit == "1" {
                ""
            } else {
                spec.unit.as_str()
            };
            InputError::check_range(name, value, spec.min, spec.max, unit)?;
            values.insert(name.as_str(), value);
        }
        if values["hip_lead_slope"] > 0.0 {
            let name = "heel_off_dorsiflexion with a hip lead (hip_lead_slope > 0)";
            InputError::check_range(
                name,
                values["heel_off_dorsiflexion"],
                0.0,
                LEAD_HEEL_OFF_MAX,
                "deg",
            )?;
        }
        let si = |name: &str| {
            let v = values[name];
            match self.0[name].unit.as_str() {
                "deg" => v.to_radians(),
                "%" => v / 100.0,
                _ => v,
            }
        };
        Ok(Attributes::from_fn(si))
    }

    /// The defaults.
    pub fn defaults(&self) -> Attributes {
        self.resolve(&BTreeMap::new(), "defaults")
            .expect("defaults lie in their ranges (checked at parse)")
    }
}

/// The largest `heel_off_dorsiflexion` (deg) with a hip lead (`hip_lead_slope` > 0) \[ours\]:
/// over the valid box (v 0.4 m/s to the walk–run transition × H 1.2–2.2 m) the lead walks every
/// point at 8° (k_φ 0.595 and 1.5) and fails 19 and 42 of 181 at the default 12°.
pub const LEAD_HEEL_OFF_MAX: f64 = 8.0;

/// Read an attribute file: a flat TOML table `name = number` (user units; an optional
/// `description = "…"` is ignored). Later files override earlier ones.
pub(crate) fn parse_overrides(
    text: &str,
    path: &Path,
) -> Result<BTreeMap<String, f64>, InputError> {
    let table: toml::Table = toml::from_str(text)
        .map_err(|e| InputError::malformed("attribute file", path, Box::new(e)))?;
    overrides_of_table(table, "attribute file", path)
}

/// The overrides of a parsed flat table `name = number` (user units; a `description = "…"` is
/// ignored), `what` at `path` naming it in errors (an attribute file, a scenario's
/// `[attributes]`).
pub fn overrides_of_table(
    table: toml::Table,
    what: &'static str,
    path: &Path,
) -> Result<BTreeMap<String, f64>, InputError> {
    let malformed = |reason: Reason| InputError::malformed(what, path, reason);
    let mut out = BTreeMap::new();
    for (key, value) in table {
        if key == "description" {
            continue;
        }
        let number = match value {
            toml::Value::Float(f) => f,
            toml::Value::Integer(i) => i as f64,
            other => {
                return Err(malformed(
                    format!("`{key}` must be a number, found {}", other.type_str()).into(),
                ));
            }
        };
        out.insert(key, number);
    }
    Ok(out)
}

macro_rules! attribute_struct {
    ($($(#[$doc:meta])* $field:ident),* $(,)?) => {
        /// Resolved locomotion attributes in SI units (angles in radians). Field names are the
        /// attribute names of `models/attributes.toml`, where units, ranges and sources are.
        #[derive(Clone, Debug, PartialEq, serde::Serialize)]
        pub struct Attributes { $($(#[$doc])* pub $field: f64,)* }

        impl Attributes {
            /// Every attribute name the engine reads.
            pub const NAMES: &'static [&'static str] = &[$(stringify!($field)),*];

            fn from_fn(get: impl Fn(&str) -> f64) -> Self {
                Attributes { $($field: get(stringify!($field)),)* }
            }
        }
    };
}

attribute_struct! {
    /// δ_hs: ankle dorsiflexion at heel strike (rad).
    heel_strike_ankle,
    /// κ_hs: knee flexion at heel strike (rad).
    heel_strike_knee,
    /// k_φ: the hip's lead at heel strike grows by k_φ per unit of sl/H (see
    /// [`StepConstraints::new`](crate::plan::StepConstraints::new)).
    hip_lead_slope,
    /// s_φ: the sl/H at which the hip is midway between the ankles at heel strike.
    hip_lead_neutral,
    /// φ_max: the largest hip lead at heel strike (below `hip_lead_rise_froude`).
    hip_lead_max,
    /// Δφ_max: how much φ_max grows from `hip_lead_rise_froude` to `hip_lead_froude` (see
    /// [`lead_cap`](crate::plan::constraints::lead_cap)).
    hip_lead_max_rise,
    /// Fr_φ0: the Froude number from which φ_max grows by `hip_lead_max_rise`.
    hip_lead_rise_froude,
    /// Fr_φ: the Froude number from which the hip's lead fades to none at `froude_max` (see
    /// [`lead_fade`](crate::plan::constraints::lead_fade)).
    hip_lead_froude,
    /// The step length per leg length sl / l1 from which the hip's lead fades (see
    /// [`lead_fade`](crate::plan::constraints::lead_fade)).
    hip_lead_step_from,
    /// How much later (sl / l1) the step length's fade starts in fast walks (see
    /// [`lead_fade`](crate::plan::constraints::lead_fade)).
    hip_lead_step_rise,
    /// The step length per leg length sl / l1 at which the hip's lead has faded to none.
    hip_lead_step_to,
    /// ε: hip excursion as a fraction of the step's height budget.
    bounciness,
    /// θ2_ref: forward lean of the upper body (rad).
    trunk_lean,
    /// κ_TO: knee flexion at toe-off (rad).
    toe_off_knee,
    /// θ6_max: metatarsal dorsiflexion limit (rad).
    metatarsal_limit,
    /// Expected minimum toe clearance in swing (m).
    toe_clearance,
    /// ρ_hs: the fraction of the new stance leg's axial velocity the heel-strike impulse removes.
    heel_strike_impulse,
    /// Downward heel velocity at contact (m/s).
    heel_strike_velocity,
    /// sf_max (steps/min).
    step_frequency_max,
    /// sf_min (steps/min).
    step_frequency_min,
    /// v_min (m/s).
    velocity_min,
    /// v_max (m/s).
    velocity_max,
    /// Fr_max: the largest Froude number v² / (g l1), the walk–run transition.
    froude_max,
    /// v_pref (m/s): the speed walked when no gait is given.
    preferred_velocity,
    /// sl_min as a fraction of the leg length.
    step_length_min,
    /// sl_max as a fraction of the leg length.
    step_length_max,
    /// Pelvic rotation amplitude (rad).
    pelvic_rotation,
    /// Pelvic list amplitude (rad).
    pelvic_list,
    /// How much the list and rotation follow the walk's speed, 0 (fixed) to 1 (see
    /// [`PelvisSpeedLaw`](crate::model::pelvis_speed::PelvisSpeedLaw)).
    pelvis_speed_law,
    /// Lateral displacement amplitude of the pelvis centre (m).
    lateral_displacement,
    /// Distance between the feet (m).
    step_width,
    /// Anterior pelvic tilt at the trunk's lean reference (rad).
    pelvis_tilt,
    /// Shoulder flexion range, peak to peak (rad).
    arm_swing,
    /// Heel strike to foot flat, fraction of the gait cycle (the file's % / 100).
    foot_flat_time,
    /// Flat-foot ankle dorsiflexion at which the heel rises (rad).
    heel_off_dorsiflexion,
    /// Step length relative to the normalizing formula.
    stride_factor,
}

impl Default for Attributes {
    /// The bundled table's defaults (resolved once per process, like the table).
    fn default() -> Self {
        static DEFAULTS: std::sync::OnceLock<Attributes> = std::sync::OnceLock::new();
        DEFAULTS
            .get_or_init(|| AttributeTable::builtin().defaults())
            .clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A hip lead with the heel rising later than LEAD_HEEL_OFF_MAX is refused up front, naming
    /// the range; at the bound, or with no lead, the same heel-off resolves.
    #[test]
    fn a_hip_lead_needs_an_early_heel_off() {
        let t = AttributeTable::builtin();
        let with = |lead: f64, heel_off: f64| {
            let o = BTreeMap::from([
                ("hip_lead_slope".to_string(), lead),
                ("heel_off_dorsiflexion".to_string(), heel_off),
            ]);
            t.resolve(&o, "test")
        };
        let e = with(0.595, 12.0).unwrap_err();
        assert!(matches!(e, InputError::OutOfRange { max, .. } if max == LEAD_HEEL_OFF_MAX));
        assert!(e.to_string().contains("hip_lead_slope > 0"), "{e}");
        assert!(with(0.595, LEAD_HEEL_OFF_MAX).is_ok());
        assert!(with(0.0, 12.0).is_ok());
    }

    #[test]
    fn builtin_table_covers_every_attribute_with_a_source() {
        let t = AttributeTable::builtin();
        assert_eq!(t.0.len(), Attributes::NAMES.len());
        for (name, spec) in &t.0 {
            assert!(!spec.doc.is_empty() && !spec.source.is_empty(), "{name}");
        }
    }

    #[test]
    fn degrees_become_radians() {
        let t = AttributeTable::builtin();
        let mut o = BTreeMap::new();
        o.insert("heel_strike_knee".to_string(), 90.0);
        o.insert("toe_off_knee".to_string(), 30.0);
        let a = t.resolve(&o, "test").unwrap_err();
        assert!(a.to_string().contains("[4, 15]"), "{a}");
        o.insert("heel_strike_knee".to_string(), 6.0);
        let a = t.resolve(&o, "test").unwrap();
        assert!((a.heel_strike_knee - 6.0_f64.to_radians()).abs() < 1e-15);
        assert!((a.toe_off_knee - std::f64::consts::PI / 6.0).abs() < 1e-15);
        assert_eq!(a.bounciness, 0.8);
    }

    /// Every bundled style parses and resolves inside the attribute ranges; an unknown style
    /// is named with the list of known ones.
    #[test]
    fn styles_resolve() {
        let t = AttributeTable::builtin();
        for (name, _) in STYLES {
            t.resolve(&style(name).unwrap(), name).unwrap();
        }
        let e = style("sneaky").unwrap_err().to_string();
        assert!(e.contains("sneaky") && e.contains("long-stride"), "{e}");
    }

    #[test]
    fn bad_attribute_files_are_named() {
        let p = Path::new("a.toml");
        let e = parse_overrides("bounciness = \"high\"", p)
            .unwrap_err()
            .to_string();
        assert!(e.contains("bounciness") && e.contains("number"), "{e}");
        let e = parse_overrides("bounciness = ", p).unwrap_err();
        assert!(matches!(e, InputError::Malformed { .. }));
        let o = parse_overrides("bouncyness = 0.5", p).unwrap();
        let e = AttributeTable::builtin()
            .resolve(&o, "a.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("bouncyness") && e.contains("bounciness"), "{e}");
        let o = parse_overrides("bounciness = nan", p).unwrap();
        let e = AttributeTable::builtin()
            .resolve(&o, "a.toml")
            .unwrap_err()
            .to_string();
        assert!(e.contains("finite"), "{e}");
    }
}
