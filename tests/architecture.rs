//! The crate's imports run one way, down the levels of `docs/architecture.md`: every reference
//! `crate::<module>` in a file of `src/<level module>/` names a module of a lower level (or its
//! own), and the modules of one folder import each other without a cycle. The crate's error
//! type (`crate::error`) is the union of the levels' errors: it names any level, and only the
//! outer levels return it. Unit tests (`#[cfg(test)]`, at the end of a file) may build on
//! higher levels. Read from the source text, so a new arrow up the hierarchy fails here before
//! anyone draws the graph.
use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// The top-level modules by level, lowest first (docs/architecture.md). Modules on one level
/// may not import each other.
const LEVELS: &[&[&str]] = &[
    &["memory", "numerics"],
    &["model"],
    &["kinematics", "dynamics"],
    &["plan"],
    &["control"],
    &["engine"],
    &["figure"],
    &["analysis"],
    &["nrs"],
    &["generalize"],
    &["export", "input", "ik"],
    &["simulation", "sweep", "scenario"],
    &["plot", "poulaine"],
];

/// The union of the levels' errors, and the lowest level that returns it (the levels below
/// return their own error types, which the union wraps).
const UNION: &str = "error";
const UNION_FROM: &str = "export";

fn level(module: &str) -> Option<usize> {
    LEVELS.iter().position(|l| l.contains(&module))
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The module path of a file under src/ (`src/control/stance/run.rs` → control::stance::run).
fn module_of(src: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Vec<String> = rel
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    if parts.last().is_some_and(|p| p == "mod" || p == "lib") {
        parts.pop();
    }
    parts
}

/// Every `crate::a::b…` path in the text outside comments, as its segments; `super::` paths
/// are resolved against `module`, the file's own module path (so `super::sibling::x` in
/// `a::b::c` is `a::b::sibling::x`).
fn crate_paths(text: &str, module: &[String]) -> Vec<Vec<String>> {
    let mut found = Vec::new();
    for line in text.lines() {
        let code = line.split("//").next().unwrap_or("");
        let mut rest = code;
        while let Some(i) = [rest.find("crate::"), rest.find("super::")]
            .into_iter()
            .flatten()
            .min()
        {
            let preceded = rest[..i]
                .ends_with(|c: char| c.is_alphanumeric() || c == '_' || c == '$' || c == ':');
            let (mut base, mut after): (Vec<String>, &str) = if rest[i..].starts_with("crate::") {
                (Vec::new(), &rest[i + "crate::".len()..])
            } else {
                let up = module.len().saturating_sub(1);
                (module[..up].to_vec(), &rest[i + "super::".len()..])
            };
            while let Some(more) = after.strip_prefix("super::") {
                base.pop();
                after = more;
            }
            if preceded {
                rest = after;
                continue;
            }
            // segments up to the first that ends the path (`x;`, `x(`, `{a, b}`) or names a type
            for segment in after.split("::") {
                let ident: String = segment
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if ident.is_empty() || !ident.starts_with(|c: char| c.is_lowercase()) {
                    break;
                }
                let whole = ident.len() == segment.len();
                base.push(ident);
                if !whole {
                    break;
                }
            }
            if !base.is_empty() {
                found.push(base);
            }
            rest = after;
        }
    }
    found
}

/// (file module, referenced module path) for every file of the library.
fn references() -> Vec<(Vec<String>, Vec<String>)> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut refs = Vec::new();
    for file in files {
        if file.starts_with(src.join("bin")) {
            continue;
        }
        let module = module_of(&src, &file);
        let text = fs::read_to_string(&file).unwrap();
        // unit tests may build on higher levels (a walk to test a stance formula)
        let code = text.split("#[cfg(test)]").next().unwrap_or("");
        for path in crate_paths(code, &module) {
            refs.push((module.clone(), path));
        }
    }
    refs
}

#[test]
fn imports_run_down_the_levels() {
    let mut wrong = Vec::new();
    for (module, path) in references() {
        let Some(from) = module.first() else { continue };
        let to = &path[0];
        if from == UNION {
            continue;
        }
        if to == UNION {
            if level(from).is_some_and(|l| Some(l) < level(UNION_FROM)) {
                wrong.push(format!(
                    "{} -> crate::{}: below {UNION_FROM}, a level returns its own error",
                    module.join("::"),
                    path.join("::")
                ));
            }
            continue;
        }
        let (Some(lf), Some(lt)) = (level(from), level(to)) else {
            // a root re-export (crate::Body) or a module missing from LEVELS
            if level(from).is_none() {
                wrong.push(format!("{}: module not in LEVELS", module.join("::")));
            }
            continue;
        };
        if from != to && lt >= lf {
            wrong.push(format!(
                "{} -> crate::{}",
                module.join("::"),
                path.join("::")
            ));
        }
    }
    wrong.sort();
    wrong.dedup();
    assert!(
        wrong.is_empty(),
        "imports that run up or across the levels:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn modules_of_a_folder_form_no_cycle() {
    // edges between sibling modules: a::b -> a::c (not out of the union of the errors, which
    // wraps the errors of the outer levels that return it)
    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (module, path) in references() {
        if module.first().is_some_and(|m| m == UNION) {
            continue;
        }
        let depth = module.len().min(path.len());
        // the first segment where the two paths part, under a common parent
        let common = module.iter().zip(&path).take_while(|(a, b)| a == b).count();
        if common >= depth || common == 0 && module.len() > 1 {
            continue;
        }
        let parent = module[..common].join("::");
        let from = format!("{parent}::{}", module[common]);
        let to = format!("{parent}::{}", path[common]);
        edges.entry(from).or_default().insert(to);
    }
    // depth-first search for a back edge
    fn visit(
        n: &str,
        edges: &BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<String, u8>,
        stack: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        state.insert(n.to_string(), 1);
        stack.push(n.to_string());
        for m in edges.get(n).into_iter().flatten() {
            match state.get(m.as_str()) {
                Some(1) => {
                    let i = stack.iter().position(|s| s == m).unwrap();
                    let mut cycle = stack[i..].to_vec();
                    cycle.push(m.clone());
                    return Some(cycle);
                }
                Some(_) => {}
                None => {
                    if let Some(c) = visit(m, edges, state, stack) {
                        return Some(c);
                    }
                }
            }
        }
        stack.pop();
        state.insert(n.to_string(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for n in edges.keys() {
        if !state.contains_key(n.as_str()) {
            let cycle = visit(n, &edges, &mut state, &mut Vec::new());
            assert!(
                cycle.is_none(),
                "import cycle: {}",
                cycle.unwrap().join(" -> ")
            );
        }
    }
}

#[test]
fn the_reader_finds_paths_in_code_and_not_in_comments() {
    let strings = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    let here = strings(&["engine", "walker", "stance"]);
    let text = "use crate::engine::walker::Step; // crate::plot\n\
                let x = crate::numerics::trig::sin_cos(1.0);\n\
                use super::swing::hip_path; use super::super::step::Step;";
    assert_eq!(
        crate_paths(text, &here),
        vec![
            strings(&["engine", "walker"]),
            strings(&["numerics", "trig", "sin_cos"]),
            strings(&["engine", "walker", "swing", "hip_path"]),
            strings(&["engine", "step"]),
        ]
    );
    assert!(crate_paths("klaw_crate::x; $crate::y", &here).is_empty());
    assert!(level("dynamics") < level("plan") && level("kinematics") < level("control"));
}
