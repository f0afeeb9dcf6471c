//! User attribute files (`klaw walk --attributes`): flat TOML `name = number` in user units.
use std::collections::BTreeMap;
use std::path::Path;

use super::read_text;
use crate::error::Result;
use crate::model::InputError;
use crate::model::attributes::{self, AttributeTable, Attributes};

/// Read a user attribute file (flat TOML `name = number`, user units) into overrides, to be
/// resolved by `AttributeTable::resolve`.
fn read_attributes(path: &Path) -> Result<BTreeMap<String, f64>> {
    let text = read_text(path)?;
    Ok(attributes::parse_overrides(&text, path)?)
}

/// The attributes of a walk: the bundled defaults, then the values of the style preset `style`,
/// then those of the attribute file `path`, name by name, each checked against its range.
pub fn load_attributes(style: Option<&str>, path: Option<&Path>) -> Result<Attributes> {
    let (overrides, source) = match path {
        Some(p) => (read_attributes(p)?, p.display().to_string()),
        None => (BTreeMap::new(), String::new()),
    };
    Ok(attributes_with(style, overrides, &source)?)
}

/// The attributes of the bundled defaults, then the values of the style preset `style`, then
/// `overrides` (user units, from `source`: a file, a scenario's `[attributes]`), name by name,
/// each checked against its range.
pub fn attributes_with(
    style: Option<&str>,
    overrides: BTreeMap<String, f64>,
    source: &str,
) -> Result<Attributes, InputError> {
    let table = AttributeTable::builtin();
    let mut all = match style {
        Some(name) => attributes::style(name)?,
        None => Default::default(),
    };
    let source = match (style, overrides.is_empty()) {
        (Some(s), true) => format!("style {s}"),
        _ => source.to_string(),
    };
    all.extend(overrides);
    table.resolve(&all, &source)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;
    use crate::model::InputError;
    use std::fs;
    use std::path::PathBuf;

    fn write_file(dir: &Path, name: &str, text: &str) -> PathBuf {
        let p = dir.join(name);
        fs::write(&p, text).unwrap();
        p
    }

    #[test]
    fn a_missing_attribute_file_is_an_io_error() {
        let dir = tempfile::tempdir().unwrap();
        let e = read_attributes(&dir.path().join("none.toml")).unwrap_err();
        assert!(
            matches!(
                e,
                Error::Io {
                    action: "reading",
                    ..
                }
            ),
            "{e:?}"
        );
    }

    #[test]
    fn attribute_files_are_read() {
        let dir = tempfile::tempdir().unwrap();
        let p = write_file(
            dir.path(),
            "a.toml",
            "description = \"x\"\nbounciness = 0.5\ntrunk_lean = 3\n",
        );
        let o = read_attributes(&p).unwrap();
        assert_eq!(o.len(), 2);
        assert_eq!(o["bounciness"], 0.5);
        assert_eq!(o["trunk_lean"], 3.0);
        let p = write_file(dir.path(), "b.toml", "bounciness = [1]\n");
        let e = read_attributes(&p).unwrap_err();
        assert!(
            matches!(e, Error::Input(InputError::Malformed { .. }))
                && e.to_string().contains("b.toml"),
            "{e}"
        );
    }
}
