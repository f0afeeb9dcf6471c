//! A sweep's values checked before any walk runs: each against the range it has whatever the
//! other values of its point (issue 14 class 3). A value outside it cannot be walked by any point
//! and is bad input; a point whose values each lie in range but do not go together (a derived
//! step length outside its body's limits, a velocity outside its own attributes' limits) is a
//! failed row of the sweep, with the reason.
use super::product::{Axis, Sweep};
use crate::model::InputError;
use crate::model::attributes::AttributeTable;
use crate::model::body::{BODY_TABLES, Body, BodyTable};

impl Sweep {
    /// Check every value against the range it has whatever the rest of its point (the module
    /// doc); the first outside it is the error, naming the quantity, the value and the range.
    pub fn check_values(&self, table: &AttributeTable) -> Result<(), InputError> {
        check_values(self, table)
    }
}

fn check_values(sweep: &Sweep, table: &AttributeTable) -> Result<(), InputError> {
    // the bundled tables and the sweep's own files
    let mut tables: Vec<BodyTable> = (0..BODY_TABLES.len()).map(super::tables::table).collect();
    for (axis, values) in &sweep.axes {
        if *axis == Axis::BodyTable {
            let files = values
                .iter()
                .map(|&i| i as usize)
                .filter(|&i| i >= BODY_TABLES.len());
            tables.extend(files.map(super::tables::table));
        }
    }
    for (axis, values) in &sweep.axes {
        let Some((min, max, unit, why)) = range(axis, table, &tables) else {
            continue;
        };
        for &x in values {
            InputError::check_range(axis.name(), x, min, max, unit)
                .map_err(|e| e.with_note(&format!("a value of the sweep; {why}")))?;
        }
    }
    Ok(())
}

/// The range of a value of `axis` whatever the rest of its point: the gait's loosest anatomical
/// limits (the widest the limit attributes may be set to, over the body tables' heights for the
/// step length), the body tables' heights and masses, the mass per height² that some height of
/// a table makes a mass of the tables, 1 to 1 000 000 steps, an attribute's own range; `tables`
/// the bundled ones and the sweep's files. `None` for a style or a body table (checked by name
/// or read when parsed).
fn range(
    axis: &Axis,
    table: &AttributeTable,
    tables: &[BodyTable],
) -> Option<(f64, f64, &'static str, &'static str)> {
    let spec = |name: &str| &table.0[name];
    let limit = |f: fn(&BodyTable) -> f64, pick: fn(f64, f64) -> f64| {
        tables.iter().map(f).reduce(pick).unwrap_or(f64::NAN)
    };
    let (hmin, hmax) = (
        limit(|t| t.limits.height[0], f64::min),
        limit(|t| t.limits.height[1], f64::max),
    );
    let (mmin, mmax) = (
        limit(|t| t.limits.mass[0], f64::min),
        limit(|t| t.limits.mass[1], f64::max),
    );
    // the shortest and the longest leg of any table at height h
    let leg = |h: f64, pick: fn(f64, f64) -> f64| {
        tables
            .iter()
            .filter_map(|t| Body::new(t, h, mmin).ok())
            .map(|b| b.l1)
            .reduce(pick)
            .unwrap_or(f64::NAN)
    };
    Some(match axis {
        Axis::Velocity => (
            spec("velocity_min").min,
            spec("velocity_max").max,
            "m/s",
            "the widest [velocity_min, velocity_max] the attributes allow",
        ),
        Axis::StepFrequency => (
            spec("step_frequency_min").min,
            spec("step_frequency_max").max,
            "steps/min",
            "the widest [step_frequency_min, step_frequency_max] the attributes allow",
        ),
        Axis::StepLength => (
            spec("step_length_min").min * leg(hmin, f64::min),
            spec("step_length_max").max * leg(hmax, f64::max),
            "m",
            "the widest [step_length_min, step_length_max] leg lengths the attributes allow, \
             for the shortest and the tallest body of any body table",
        ),
        Axis::Height => (hmin, hmax, "m", "the body tables' heights"),
        Axis::Mass => (mmin, mmax, "kg", "the body tables' masses"),
        Axis::MassPerHeight2 => (
            mmin / (hmax * hmax),
            mmax / (hmin * hmin),
            "kg/m²",
            "some height of the body tables must make it a mass of the tables",
        ),
        Axis::Steps => (1.0, super::run::MAX_STEPS as f64, "steps", "a walk's steps"),
        Axis::Attribute(name) => {
            let s = spec(name);
            (
                s.min,
                s.max,
                "",
                "the attribute's range (models/attributes.toml)",
            )
        }
        Axis::Style | Axis::BodyTable => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bundled() -> Vec<BodyTable> {
        (0..BODY_TABLES.len())
            .map(crate::sweep::tables::table)
            .collect()
    }

    fn sweep(axis: Axis, values: Vec<f64>) -> Sweep {
        Sweep::build(Vec::new(), vec![(axis, values)]).unwrap()
    }

    /// A value outside its range is refused with the range; a value just inside passes, and
    /// the ranges agree with what a walk accepts (the body table, the attribute table).
    #[test]
    fn values_outside_their_range_are_refused() {
        let table = AttributeTable::builtin();
        // (a valid value first: the bad one is found in a list)
        let bad = |axis: Axis, x: f64| {
            let good = match &axis {
                Axis::Mass => 80.0,
                Axis::Steps => 2.0,
                Axis::Attribute(_) => 0.7,
                _ => 1.5,
            };
            check_values(&sweep(axis, vec![good, x]), &table)
                .unwrap_err()
                .to_string()
        };
        let m = bad(Axis::Velocity, -1.0);
        assert!(
            m.contains("velocity = -1 m/s") && m.contains("[0.1, 3]"),
            "{m}"
        );
        assert!(bad(Axis::Mass, -80.0).contains("mass = -80 kg"));
        assert!(bad(Axis::Height, 1.0).contains("height = 1 m"));
        assert!(bad(Axis::Steps, 0.0).contains("steps = 0"));
        let m = bad(Axis::Attribute("bounciness".into()), 5.0);
        assert!(
            m.contains("bounciness = 5") && m.contains("[0.7, 0.88]"),
            "{m}"
        );
        // the body table's limits are those of Body::standard
        let body = BodyTable::builtin();
        let [hmin, hmax] = body.limits.height;
        assert!(Body::standard(hmin, 80.0).is_ok() && Body::standard(hmin - 1e-3, 80.0).is_err());
        for h in [hmin, hmax] {
            assert!(check_values(&sweep(Axis::Height, vec![h]), &table).is_ok());
        }
        // the step length's bound is the longest step of the tallest body's longest leg, de
        // Leva's men's (l1 = 0.4918 H against Winter's 0.4823 H)
        let (_, max, ..) = range(&Axis::StepLength, &table, &bundled()).unwrap();
        let tall = Body::from_table("deleva-male", hmax, 80.0).unwrap();
        assert!(tall.l1 > Body::standard(hmax, 80.0).unwrap().l1);
        assert!((max - 1.6 * tall.l1).abs() < 1e-12, "{max}");
        // a style is not range-checked here
        assert!(range(&Axis::Style, &table, &bundled()).is_none());
    }
}
