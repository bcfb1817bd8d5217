//! The order of folders inside each crate. Cargo keeps the crates in
//! their order (a lower crate cannot name a higher one); inside a crate it
//! cannot, so this test reads every source file, its `#[cfg(test)]` modules
//! left out, and fails on an import of a folder from one below it
//! (ARCHITECTURE.md).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Each crate's source folder and its top-level modules, lowest first: a
/// module may import from those before it, never from those after it.
const CRATES: &[(&str, &[&str])] = &[
    ("crates/core/src", &["base", "model", "solver"]),
    ("crates/io/src", &["fsio", "readers", "scene", "identify"]),
    ("crates/report/src", &["output", "analysis", "studies"]),
];

/// Every `.rs` file below `dir`.
pub(crate) fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap().flatten() {
        let path = entry.path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// `text` without its `#[cfg(test)]` items (a `mod … { … }` block to its
/// closing brace, or a `mod …;` line) and without comment lines: what the
/// crate builds outside its tests. Braces inside strings and comments are
/// not counted, which the source files respect.
pub(crate) fn code(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find("#[cfg(test)]") {
        out.push_str(&rest[..at]);
        let after = &rest[at + "#[cfg(test)]".len()..];
        // the item the attribute applies to: up to `;` or a balanced block
        let (mut depth, mut end) = (0usize, after.len());
        for (k, c) in after.char_indices() {
            match c {
                '{' => depth += 1,
                // the closing brace of what holds an attributed field or arm
                '}' if depth == 0 => {
                    end = k;
                    break;
                }
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = k + 1;
                        break;
                    }
                }
                ';' if depth == 0 => {
                    end = k + 1;
                    break;
                }
                _ => {}
            }
        }
        rest = &after[end..];
    }
    out.push_str(rest);
    out.lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The top-level modules a source text imports through `crate::`.
fn imports(text: &str) -> Vec<String> {
    let code = code(text);
    let mut out = Vec::new();
    for (k, _) in code.match_indices("crate::") {
        // `tirecontact_core::` and the like are other crates
        if code[..k].ends_with(|c: char| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let rest = &code[k + "crate::".len()..];
        if let Some(list) = rest.strip_prefix('{') {
            let list = list.split('}').next().unwrap_or("");
            for name in list.split(',').map(str::trim) {
                out.push(name.split("::").next().unwrap_or("").to_string());
            }
        } else {
            out.push(
                rest.chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect(),
            );
        }
    }
    out
}

#[test]
fn every_import_inside_a_crate_points_down_or_sideways() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut upward: BTreeMap<String, Vec<String>> = BTreeMap::new();
    let mut seen = 0;
    for (dir, order) in CRATES {
        let src = root.join(dir);
        let mut files = Vec::new();
        sources(&src, &mut files);
        for file in &files {
            let rel = file.strip_prefix(&src).unwrap();
            let first = rel
                .components()
                .next()
                .unwrap()
                .as_os_str()
                .to_string_lossy();
            let module = first.trim_end_matches(".rs");
            let Some(own) = order.iter().position(|m| *m == module) else {
                assert!(
                    module == "lib",
                    "{dir}/{}: module `{module}` is in no folder of the crate's order: add it (CRATES, ARCHITECTURE.md)",
                    rel.display()
                );
                continue;
            };
            let text = std::fs::read_to_string(file).unwrap();
            for target in imports(&text) {
                seen += 1;
                if let Some(t) = order.iter().position(|m| *m == target)
                    && t > own
                {
                    upward
                        .entry(format!("{dir}/{}", rel.display()))
                        .or_default()
                        .push(format!("{target} (above {module})"));
                }
            }
        }
    }
    assert!(seen > 100, "only {seen} imports read: the scan is broken");
    assert!(upward.is_empty(), "imports pointing up: {upward:#?}");
}

#[test]
fn the_scan_sees_every_import_form_and_skips_only_test_items() {
    let text = "use crate::scene::Mode;\nuse crate::{identify, fsio::read};\n// crate::studies\n\
                fn f() { tirecontact_core::solver::x(); crate::readers::y(); }\n\
                #[cfg(test)]\nmod tests { fn g() { if true { crate::identify::z(); } } }\n\
                #[cfg(test)]\nmod more;\nfn h() { crate::scene::w(); }\n\
                struct S { #[cfg(test)] t: u8 }\nfn k() { crate::fsio::v(); }";
    assert_eq!(
        imports(text),
        ["scene", "identify", "fsio", "readers", "scene", "fsio"]
    );
}
