//! User attribute files (`klaw walk --attributes`): flat TOML `name = number` in user units.
use std::collections::BTreeMap;
use std::path::Path;

use super::read_text;
use crate::error::Result;
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
    let table = AttributeTable::builtin();
    let mut overrides = match style {
        Some(name) => attributes::style(name)?,
        None => Default::default(),
    };
    let mut source = style.map_or(String::new(), |s| format!("style {s}"));
    if let Some(p) = path {
        overrides.extend(read_attributes(p)?);
        source = p.display().to_string();
    }
    Ok(table.resolve(&overrides, &source)?)
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
