//! The keys of one table of a scenario file taken one by one, typed and range-checked, with
//! the place and field of any problem (src/scenario/file.rs).
use toml::{Table, Value};

use super::file_error::{Place, Problem};
use crate::model::InputError;

/// The largest |coordinate| of a world point (m).
pub const MAX_WORLD: f64 = 1.0e4;

/// A problem at a field, before the file's path is added.
pub(super) struct FieldError {
    pub place: Place,
    pub field: String,
    pub problem: Problem,
}

/// [`Problem::WrongType`] for `found`.
pub(super) fn wrong(expected: &'static str, found: &Value) -> Problem {
    Problem::WrongType {
        expected,
        found: found.type_str(),
    }
}

/// The keys of one table, taken one by one; [`Fields::finish`] refuses any left over.
pub(super) struct Fields {
    pub place: Place,
    pub table: Table,
}

impl Fields {
    pub(super) fn new(place: Place, table: Table) -> Self {
        Fields { place, table }
    }

    pub(super) fn fail(&self, field: &str, problem: Problem) -> FieldError {
        FieldError {
            place: self.place.clone(),
            field: field.to_string(),
            problem,
        }
    }

    /// The number at `key` (an integer is taken as a float), if present.
    pub(super) fn number(&mut self, key: &str) -> Result<Option<f64>, FieldError> {
        match self.table.remove(key) {
            None => Ok(None),
            Some(Value::Float(f)) => Ok(Some(f)),
            Some(Value::Integer(i)) => Ok(Some(i as f64)),
            Some(other) => Err(self.fail(key, wrong("a number", &other))),
        }
    }

    /// The number at `key`, checked to lie in [min, max] (in `unit`), if present.
    pub(super) fn ranged(
        &mut self,
        key: &str,
        min: f64,
        max: f64,
        unit: &str,
    ) -> Result<Option<f64>, FieldError> {
        match self.number(key)? {
            None => Ok(None),
            Some(v) => InputError::check_range(key, v, min, max, unit)
                .map(Some)
                .map_err(|e| self.fail(key, e.into())),
        }
    }

    /// The string at `key`, if present.
    pub(super) fn string(&mut self, key: &str) -> Result<Option<String>, FieldError> {
        match self.table.remove(key) {
            None => Ok(None),
            Some(Value::String(s)) => Ok(Some(s)),
            Some(other) => Err(self.fail(key, wrong("a string", &other))),
        }
    }

    /// The floor point `[x, z]` at `key`, each within ±`MAX_WORLD` m, if present.
    pub(super) fn point(&mut self, key: &str) -> Result<Option<[f64; 2]>, FieldError> {
        let expected = "an array of two numbers [x, z] (m)";
        let Some(v) = self.table.remove(key) else {
            return Ok(None);
        };
        let Value::Array(a) = &v else {
            return Err(self.fail(key, wrong(expected, &v)));
        };
        let mut xz = [0.0; 2];
        if a.len() != 2 {
            return Err(self.fail(key, wrong(expected, &v)));
        }
        for (i, c) in a.iter().enumerate() {
            let x = match c {
                Value::Float(f) => *f,
                Value::Integer(n) => *n as f64,
                other => return Err(self.fail(key, wrong(expected, other))),
            };
            let name = format!("{key}[{i}]");
            xz[i] = InputError::check_range(&name, x, -MAX_WORLD, MAX_WORLD, "m")
                .map_err(|e| self.fail(key, e.into()))?;
        }
        Ok(Some(xz))
    }

    /// The choice at `key` among `(name, value)` pairs, if present.
    pub(super) fn choice<T: Copy>(
        &mut self,
        key: &str,
        choices: &[(&str, T)],
    ) -> Result<Option<T>, FieldError> {
        let Some(s) = self.string(key)? else {
            return Ok(None);
        };
        match choices.iter().find(|(n, _)| *n == s) {
            Some((_, v)) => Ok(Some(*v)),
            None => {
                let names: Vec<&str> = choices.iter().map(|(n, _)| *n).collect();
                let reason = format!("`{s}` is not one of {}", names.join(", "));
                Err(self.fail(key, InputError::bad_value(key, reason).into()))
            }
        }
    }

    /// `Problem::Missing` for `key`.
    pub(super) fn missing(&self, key: &str, what: &str) -> FieldError {
        self.fail(key, Problem::Missing { what: what.into() })
    }

    /// Refuse any key not taken; `known` lists the valid ones.
    pub(super) fn finish(self, known: &str) -> Result<(), FieldError> {
        match self.table.keys().next() {
            None => Ok(()),
            Some(k) => Err(self.fail(
                k,
                Problem::UnknownKey {
                    known: known.into(),
                },
            )),
        }
    }
}
