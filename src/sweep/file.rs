//! Sweep files (`klaw sweep --file`): a flat TOML table of the sweep's entries.
use std::path::Path;

use super::product::{Axis, Entry, QUANTITIES};
use super::spec::{parse_body_tables, parse_styles, values};
use crate::error::{Error, Result};
use crate::model::InputError;
use crate::model::attributes::AttributeTable;

/// Why a sweep file cannot be read (an [`InputError::Malformed`] of the file).
#[derive(Debug, thiserror::Error)]
pub enum SweepFileError {
    /// Not a TOML table.
    #[error("{}", .0.to_string().trim_end())]
    Toml(#[source] toml::de::Error),
    /// A key that is neither a quantity of the sweep (`velocity`, …, `style`) nor a locomotion
    /// attribute.
    #[error(
        "unknown key `{key}`: a key is one of {} or a locomotion attribute of \
         models/attributes.toml",
        QUANTITIES.join(", ")
    )]
    UnknownKey {
        /// The key.
        key: String,
    },
    /// Two keys for one quantity (`step_length` and `step-length`).
    #[error("`{key}` is given twice (as `{name}`)")]
    Twice {
        /// The second key.
        key: String,
        /// The quantity's name, as a column of the sweep's output.
        name: String,
    },
    /// A value that is neither a number, a string spec nor an array of numbers.
    #[error(
        "`{key}` must be a number, a string \"START:STOP:STEP\" or \"A,B,C\", or an array of \
         numbers"
    )]
    Shape {
        /// The key.
        key: String,
    },
    /// A `style` or `body_table` array with an item that is not a string.
    #[error("`{key}` must be names")]
    Names {
        /// The key.
        key: String,
    },
    /// An empty array of values.
    #[error("`{key}` is an empty array")]
    EmptyArray {
        /// The key.
        key: String,
    },
    /// A value that is NaN or infinite.
    #[error("`{key}`: {value} is not a finite number")]
    NotFinite {
        /// The key.
        key: String,
        /// The value given.
        value: f64,
    },
    /// The value of `key` cannot be used: its spec or its style names.
    #[error("`{key}`: {reason}")]
    Value {
        /// The key.
        key: String,
        /// Why the value cannot be used.
        #[source]
        reason: crate::model::error::Reason,
    },
}

/// A parser of a list of names (styles, body tables) into the axis's values.
type NamesParser<'a> = dyn Fn(&str) -> Result<Vec<f64>, InputError> + 'a;

/// Read a sweep file: a flat TOML table whose keys are the quantities of `klaw sweep`
/// (`velocity`, `step_length` or `step-length`, …, `steps`) or locomotion attribute names, and
/// whose values are a number, a string spec (`"0.6:2.0:0.1"`, `"1.5,1.7"`) or an array of numbers;
/// `style` and `body_table` take names (a body table file relative to the sweep file's folder).
/// Entries come in key order (alphabetical).
pub fn read_sweep_file(path: &Path, table: &AttributeTable) -> Result<Vec<Entry>> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::Io {
        action: "reading",
        path: path.to_path_buf(),
        source: e,
    })?;
    parse_sweep_toml(&text, table, path.parent())
        .map_err(|e| InputError::malformed("sweep file", path, e).into())
}

/// `read_sweep_file` on text, body table files relative to `base`; errors are the reason only.
pub(crate) fn parse_sweep_toml(
    text: &str,
    table: &AttributeTable,
    base: Option<&Path>,
) -> Result<Vec<Entry>, SweepFileError> {
    let doc: toml::Table = toml::from_str(text).map_err(SweepFileError::Toml)?;
    let mut entries: Vec<Entry> = Vec::new();
    for (key, value) in &doc {
        let key_name = || key.to_string();
        let axis = Axis::from_name(key, table)
            .ok_or_else(|| SweepFileError::UnknownKey { key: key_name() })?;
        if entries.iter().any(|(a, _)| *a == axis) {
            let name = axis.name().to_string();
            return Err(SweepFileError::Twice {
                key: key_name(),
                name,
            });
        }
        let shape = || SweepFileError::Shape { key: key_name() };
        // the value's error without its parameter: the key names it
        let value_error = |e: InputError| SweepFileError::Value {
            key: key_name(),
            reason: match e {
                InputError::BadValue { reason, .. } => reason,
                e => Box::new(e),
            },
        };
        let as_number = |v: &toml::Value| match v {
            toml::Value::Integer(i) => Some(*i as f64),
            toml::Value::Float(x) => Some(*x),
            _ => None,
        };
        let body_tables = |spec: &str| parse_body_tables(spec, base);
        let names: Option<&NamesParser> = match axis {
            Axis::Style => Some(&parse_styles),
            Axis::BodyTable => Some(&body_tables),
            _ => None,
        };
        let values = match value {
            toml::Value::String(spec) if let Some(parse) = names => {
                parse(spec).map_err(value_error)?
            }
            toml::Value::Array(items) if let Some(parse) = names => {
                let list: Option<Vec<&str>> = items.iter().map(|v| v.as_str()).collect();
                let list = list.ok_or_else(|| SweepFileError::Names { key: key_name() })?;
                parse(&list.join(",")).map_err(value_error)?
            }
            toml::Value::String(spec) => values(spec).map_err(|e| SweepFileError::Value {
                key: key_name(),
                reason: Box::new(e),
            })?,
            toml::Value::Array(items) => {
                if items.is_empty() {
                    return Err(SweepFileError::EmptyArray { key: key_name() });
                }
                items
                    .iter()
                    .map(|v| as_number(v).ok_or_else(shape))
                    .collect::<Result<Vec<_>, _>>()?
            }
            v => vec![as_number(v).ok_or_else(shape)?],
        };
        if let Some(&value) = values.iter().find(|x| !x.is_finite()) {
            return Err(SweepFileError::NotFinite {
                key: key_name(),
                value,
            });
        }
        entries.push((axis, values));
    }
    Ok(entries)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table() -> AttributeTable {
        AttributeTable::builtin()
    }

    #[test]
    fn sweep_file_values_and_keys() {
        let entries = parse_sweep_toml(
            "velocity = \"0.6:1.0:0.2\"\nstep-length = 0.7\nheight = [1.5, 1.7]\nsteps = 2\nbounciness = [0.2, 0.5]\n",
            &table(),
            None,
        )
        .unwrap();
        let get = |a: Axis| {
            entries
                .iter()
                .find(|(x, _)| *x == a)
                .map(|(_, v)| v.clone())
        };
        assert_eq!(get(Axis::Velocity), Some(vec![0.6, 0.8, 1.0]));
        assert_eq!(get(Axis::StepLength), Some(vec![0.7]));
        assert_eq!(get(Axis::Height), Some(vec![1.5, 1.7]));
        assert_eq!(get(Axis::Steps), Some(vec![2.0]));
        assert_eq!(
            get(Axis::Attribute("bounciness".into())),
            Some(vec![0.2, 0.5])
        );
    }

    #[test]
    fn malformed_sweep_files_say_what_is_wrong() {
        for (text, expect) in [
            ("velocity = ", "velocity"),
            ("speed = 1.2", "unknown key `speed`"),
            ("velocity = true", "`velocity` must be a number"),
            ("velocity = []", "empty array"),
            ("velocity = [1.0, \"x\"]", "`velocity` must be a number"),
            ("velocity = \"1:2\"", "START:STOP:STEP"),
            (
                "velocity = 1.0\nstep_length = 0.7\nstep-length = 0.8",
                "given twice",
            ),
            ("[velocity]\nx = 1", "`velocity` must be a number"),
            ("velocity = nan", "not a finite number"),
        ] {
            let e = parse_sweep_toml(text, &table(), None)
                .unwrap_err()
                .to_string();
            assert!(e.contains(expect), "{text:?}: {e}");
        }
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("bad.toml");
        std::fs::write(&path, "speed = 1").unwrap();
        let e = read_sweep_file(&path, &table()).unwrap_err();
        assert!(
            matches!(
                e,
                Error::Input(InputError::Malformed {
                    what: "sweep file",
                    ..
                })
            ),
            "{e}"
        );
        let e = read_sweep_file(&dir.path().join("none.toml"), &table()).unwrap_err();
        assert!(matches!(e, Error::Io { .. }), "{e}");
    }
}
