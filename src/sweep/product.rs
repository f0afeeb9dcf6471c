//! The sweep as a Cartesian product: its axes in product order, built from a sweep file's and
//! the flags' entries, its points numbered 0.. in row-major order, and the inputs of the walk of
//! each point.
use super::spec::{SpecError, bad, tidy};
use crate::model::InputError;
use crate::model::attributes::AttributeTable;
use crate::plan::gait::GaitRequest;

/// Largest number of points (walks) of a sweep.
pub(crate) const MAX_POINTS: usize = 10_000_000;

/// What a swept dimension sets.
#[derive(Clone, Debug, PartialEq)]
pub enum Axis {
    /// Walking speed v (m/s).
    Velocity,
    /// Step length sl (m).
    StepLength,
    /// Step frequency sf (steps/min).
    StepFrequency,
    /// Body height H (m).
    Height,
    /// Body mass M (kg).
    Mass,
    /// M = K · H² (K in kg/m²).
    MassPerHeight2,
    /// Steps per walk (count).
    Steps,
    /// A style preset of `models/styles/`, by its index in `attributes::STYLES`.
    Style,
    /// A body table, bundled or a file, by its index in the sweep's tables (`sweep::tables`).
    BodyTable,
    /// The locomotion attribute of this name (`models/attributes.toml`), in its units there.
    Attribute(String),
}

/// The quantities a sweep names besides the attributes, in product order.
pub(crate) const QUANTITIES: [&str; 9] = [
    "velocity",
    "step_length",
    "step_frequency",
    "height",
    "mass",
    "mass_per_height2",
    "steps",
    "style",
    "body_table",
];

impl Axis {
    /// The column name.
    pub(crate) fn name(&self) -> &str {
        match self {
            Axis::Velocity => "velocity",
            Axis::StepLength => "step_length",
            Axis::StepFrequency => "step_frequency",
            Axis::Height => "height",
            Axis::Mass => "mass",
            Axis::MassPerHeight2 => "mass_per_height2",
            Axis::Steps => "steps",
            Axis::Style => "style",
            Axis::BodyTable => "body_table",
            Axis::Attribute(n) => n,
        }
    }

    /// The axis of a flag or sweep-file key (`step-length` or `step_length`), or of a locomotion
    /// attribute of `table`; `None` for an unknown name.
    pub(crate) fn from_name(name: &str, table: &AttributeTable) -> Option<Axis> {
        let key = name.trim().replace('-', "_");
        Some(match key.as_str() {
            "velocity" => Axis::Velocity,
            "step_length" => Axis::StepLength,
            "step_frequency" => Axis::StepFrequency,
            "height" => Axis::Height,
            "mass" => Axis::Mass,
            "mass_per_height2" => Axis::MassPerHeight2,
            "steps" => Axis::Steps,
            "style" => Axis::Style,
            "body_table" => Axis::BodyTable,
            _ if table.0.contains_key(&key) => Axis::Attribute(key),
            _ => return None,
        })
    }

    /// Position in the product order: the quantities in `QUANTITIES` order, then the attributes.
    fn rank(&self) -> usize {
        QUANTITIES
            .iter()
            .position(|q| *q == self.name() && !matches!(self, Axis::Attribute(_)))
            .unwrap_or(QUANTITIES.len())
    }
}

/// A sweep: axes in product order (the first varies slowest, the last fastest).
#[derive(Clone, Debug, Default)]
pub struct Sweep {
    pub(crate) axes: Vec<(Axis, Vec<f64>)>,
}

/// A swept axis with its values, as a flag or a sweep file gives it.
pub(crate) type Entry = (Axis, Vec<f64>);

/// The inputs of one walk, decoded from a point of the product.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Inputs {
    /// The point's index in product order.
    pub point: usize,
    pub request: GaitRequest,
    pub height: f64,
    pub mass_per_height2: Option<f64>,
    pub mass: f64,
    pub steps: f64,
    /// The style preset (index in `attributes::STYLES`), when swept.
    pub style: Option<usize>,
    /// The body table (index in the sweep's tables, `sweep::tables`), when swept.
    pub body_table: Option<usize>,
    pub attributes: Vec<(String, f64)>,
}

impl Sweep {
    /// The sweep of a sweep file's entries and the flags' entries: a flag replaces the file's
    /// entry of the same axis, and a flag `mass` or `mass_per_height2` drops the file's entries
    /// of both. The axes are put in product order: the quantities in `QUANTITIES` order, then
    /// the attributes (the file's, then the flags' new ones, each in their given order).
    pub fn build(file: Vec<Entry>, flags: Vec<Entry>) -> Result<Sweep, InputError> {
        let mut axes: Vec<Entry> = Vec::new();
        for (i, (axis, _)) in flags.iter().enumerate() {
            if flags[..i].iter().any(|(a, _)| a == axis) {
                return Err(bad(axis.name(), SpecError::GivenTwice));
            }
        }
        let flags_mass = flags
            .iter()
            .any(|(a, _)| matches!(a, Axis::Mass | Axis::MassPerHeight2));
        for entry in file {
            if flags_mass && matches!(entry.0, Axis::Mass | Axis::MassPerHeight2) {
                continue;
            }
            axes.push(entry);
        }
        for (axis, values) in flags {
            match axes.iter_mut().find(|(a, _)| *a == axis) {
                Some(slot) => slot.1 = values,
                None => axes.push((axis, values)),
            }
        }
        if axes.iter().any(|(a, _)| *a == Axis::Mass)
            && axes.iter().any(|(a, _)| *a == Axis::MassPerHeight2)
        {
            return Err(bad("mass-per-height2", SpecError::MassTwice));
        }
        for (axis, values) in &axes {
            if values.is_empty() {
                return Err(bad(axis.name(), SpecError::NoValues));
            }
            if *axis == Axis::Steps
                && let Some(x) = values.iter().find(|x| x.fract() != 0.0)
            {
                return Err(bad("steps", SpecError::NotWholeSteps { value: *x }));
            }
        }
        // stable: attributes keep their order
        axes.sort_by_key(|(a, _)| a.rank());
        let sweep = Sweep { axes };
        let total = sweep.len();
        if total > MAX_POINTS {
            return Err(InputError::OutOfRange {
                name: "sweep size (product of the value counts)".into(),
                value: total as f64,
                min: 1.0,
                max: MAX_POINTS as f64,
                unit: "walks".into(),
                note: String::new(),
            });
        }
        Ok(sweep)
    }

    /// Number of points (walks): the product of the axis lengths.
    pub fn len(&self) -> usize {
        self.axes
            .iter()
            .try_fold(1usize, |n, (_, v)| n.checked_mul(v.len()))
            .unwrap_or(usize::MAX)
    }

    /// Whether the product has no point (an empty value list).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Point `k` of the product (row-major: the last axis varies fastest).
    pub(crate) fn point(&self, mut k: usize) -> Vec<f64> {
        let mut p = vec![0.0; self.axes.len()];
        for (i, (_, values)) in self.axes.iter().enumerate().rev() {
            p[i] = values[k % values.len()];
            k /= values.len();
        }
        p
    }

    /// Every point, in product order (the unit tests' view of the product).
    #[cfg(test)]
    pub(crate) fn points(&self) -> Vec<Vec<f64>> {
        (0..self.len()).map(|k| self.point(k)).collect()
    }

    /// The inputs of the walk of point `k`; unswept quantities take the `klaw walk` defaults
    /// (H 1.8 m, M 80 kg, 10 steps; with no gait quantity swept, the request is empty and the
    /// walk goes at the attributes' preferred velocity, [`super::run::run_walk`]).
    pub(crate) fn inputs(&self, k: usize) -> Inputs {
        let point = self.point(k);
        let mut inputs = Inputs {
            point: k,
            request: GaitRequest::default(),
            height: 1.8,
            mass_per_height2: None,
            mass: 80.0,
            steps: 10.0,
            style: None,
            body_table: None,
            attributes: Vec::new(),
        };
        let mut mass = None;
        for ((axis, _), &x) in self.axes.iter().zip(&point) {
            match axis {
                Axis::Velocity => inputs.request.velocity = Some(x),
                Axis::StepLength => inputs.request.step_length = Some(x),
                Axis::StepFrequency => inputs.request.step_frequency = Some(x),
                Axis::Height => inputs.height = x,
                Axis::Mass => mass = Some(x),
                Axis::MassPerHeight2 => inputs.mass_per_height2 = Some(x),
                Axis::Steps => inputs.steps = x,
                Axis::Style => inputs.style = Some(x as usize),
                Axis::BodyTable => inputs.body_table = Some(x as usize),
                Axis::Attribute(n) => inputs.attributes.push((n.clone(), x)),
            }
        }
        inputs.mass = match (inputs.mass_per_height2, mass) {
            (Some(k), _) => tidy(k * inputs.height * inputs.height),
            (None, Some(m)) => m,
            (None, None) => 80.0,
        };
        inputs
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sweep::rows::OUTPUT_COLUMNS;

    #[test]
    fn product_order_is_row_major() {
        let s = Sweep {
            axes: vec![
                (Axis::Velocity, vec![1.0, 1.2]),
                (Axis::Height, vec![1.6, 1.7, 1.8]),
            ],
        };
        assert_eq!(s.len(), 6);
        assert_eq!(
            s.points(),
            vec![
                vec![1.0, 1.6],
                vec![1.0, 1.7],
                vec![1.0, 1.8],
                vec![1.2, 1.6],
                vec![1.2, 1.7],
                vec![1.2, 1.8],
            ]
        );
        let empty = Sweep::default();
        assert_eq!(empty.points(), vec![Vec::<f64>::new()]);
    }

    #[test]
    fn inputs_take_walk_defaults_and_mass_per_height2() {
        let s = Sweep {
            axes: vec![
                (Axis::Height, vec![1.5]),
                (Axis::MassPerHeight2, vec![20.0]),
            ],
        };
        let i = s.inputs(0);
        // no gait swept: the walk goes at the attributes' preferred velocity (run_walk)
        assert_eq!(i.request, GaitRequest::default());
        assert!((i.mass - 45.0).abs() < 1e-12);
        assert_eq!(i.steps, 10.0);
        let h = s.header();
        assert!(h.contains(&"mass_per_height2".to_string()));
        assert_eq!(h.len(), 8 + OUTPUT_COLUMNS.len());
        assert_eq!(h[0], "point");
    }

    fn table() -> AttributeTable {
        AttributeTable::builtin()
    }

    #[test]
    fn flags_override_the_file_and_axes_take_product_order() {
        let bounce = Axis::Attribute("bounciness".into());
        let lean = Axis::Attribute("trunk_lean".into());
        let file = vec![
            (bounce.clone(), vec![0.2, 0.5]),
            (Axis::Height, vec![1.6, 1.7]),
            (Axis::Mass, vec![60.0]),
            (Axis::Velocity, vec![1.0]),
        ];
        let flags = vec![
            (lean.clone(), vec![5.0]),
            (Axis::Velocity, vec![1.2, 1.4]),
            (Axis::MassPerHeight2, vec![22.0]),
        ];
        let s = Sweep::build(file, flags).unwrap();
        let axes: Vec<(&str, &[f64])> = s
            .axes
            .iter()
            .map(|(a, v)| (a.name(), v.as_slice()))
            .collect();
        assert_eq!(
            axes,
            vec![
                ("velocity", &[1.2, 1.4][..]),
                ("height", &[1.6, 1.7][..]),
                ("mass_per_height2", &[22.0][..]),
                ("bounciness", &[0.2, 0.5][..]),
                ("trunk_lean", &[5.0][..]),
            ]
        );
        // both masses from the file, or the same flag twice, are errors
        let e = Sweep::build(
            vec![(Axis::Mass, vec![60.0]), (Axis::MassPerHeight2, vec![20.0])],
            vec![],
        )
        .unwrap_err();
        assert!(
            matches!(e, InputError::BadValue { .. }) && e.to_string().contains("exclude"),
            "{e}"
        );
        let e = Sweep::build(
            vec![],
            vec![(bounce.clone(), vec![0.1]), (bounce, vec![0.2])],
        )
        .unwrap_err();
        assert!(e.to_string().contains("given twice"), "{e}");
        let e = Sweep::build(vec![(Axis::Steps, vec![1.5])], vec![]).unwrap_err();
        assert!(e.to_string().contains("whole number"), "{e}");
        assert_eq!(
            Axis::from_name("step-frequency", &table()),
            Some(Axis::StepFrequency)
        );
        assert_eq!(Axis::from_name("nonsense", &table()), None);
    }
}
