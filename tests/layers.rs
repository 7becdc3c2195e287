//! The library's rooms use only the rooms below them (docs/architecture.md, "Layers"): every `crate::`
//! path in `src` (comments and test modules aside) is checked against the documented order, so an
//! import that runs up or sideways (and so any circle) fails here with the file that holds it.

use std::collections::BTreeMap;
use std::path::Path;

/// The layer of each room, as docs/architecture.md's table gives it. A room uses only rooms of lower
/// layers.
const LAYERS: &[(&str, u32)] = &[
    ("error", 0),
    ("numeric", 1),
    ("codec", 1),
    ("envelope", 1),
    ("vocabulary", 1),
    ("law", 2),
    ("scene", 3),
    ("theory", 3),
    ("analysis", 4),
    ("curves", 4),
    ("impact", 5),
    ("bed", 5),
    ("units", 6),
    ("fmi", 7),
    ("fmi2", 8),
    ("fmi3", 8),
];

/// `text` without `//` comments and without `#[cfg(test)]` / `#[cfg(all(test, ...))]` modules.
fn code_of(text: &str) -> String {
    let mut out = String::new();
    for line in text.lines() {
        out.push_str(line.split("//").next().unwrap_or(""));
        out.push('\n');
    }
    loop {
        let Some(at) = out.find("#[cfg(test)]").or_else(|| out.find("#[cfg(all(test")) else { return out };
        let open = at + out[at..].find('{').expect("a test module has a body");
        let mut depth = 0;
        let mut end = out.len();
        for (k, c) in out[open..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = open + k + 1;
                        break;
                    }
                }
                _ => {}
            }
        }
        out.replace_range(at..end, "");
    }
}

fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let p = entry.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// The room a path below `src` belongs to (None: the crate root and the command-line tool).
fn room_of(rel: &Path) -> Option<String> {
    let first = rel.components().next()?.as_os_str().to_string_lossy().trim_end_matches(".rs").to_string();
    (first != "lib" && first != "bin").then_some(first)
}

#[test]
fn every_import_runs_down_the_documented_layers() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let layer: BTreeMap<&str, u32> = LAYERS.iter().copied().collect();
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    // Names the crate root exports that are defined in a room: `#[macro_export]` macros and `pub use`.
    let mut defined_in: BTreeMap<String, String> = BTreeMap::new();
    for f in &files {
        let Some(room) = room_of(f.strip_prefix(&src).unwrap()) else { continue };
        let text = std::fs::read_to_string(f).unwrap();
        let mut exported = false;
        for line in text.lines() {
            let t = line.trim();
            if t == "#[macro_export]" {
                exported = true;
            } else if let (true, Some(rest)) = (exported, t.strip_prefix("macro_rules! ")) {
                defined_in.insert(rest.trim_end_matches(" {").to_string(), room.clone());
                exported = false;
            }
        }
    }
    for line in std::fs::read_to_string(src.join("lib.rs")).unwrap().lines() {
        if let Some(rest) = line.strip_prefix("pub use ") {
            let room = rest.split("::").next().unwrap().to_string();
            for name in rest.split_once("::").unwrap().1.trim_end_matches(';').trim_matches(|c| c == '{' || c == '}').split(',') {
                defined_in.insert(name.trim().to_string(), room.clone());
            }
        }
    }
    let mut seen = 0;
    let mut wrong = Vec::new();
    for f in &files {
        let rel = f.strip_prefix(&src).unwrap();
        let Some(room) = room_of(rel) else { continue };
        let own = *layer.get(room.as_str()).unwrap_or_else(|| panic!("room `{room}` ({}) is not in the layer table", rel.display()));
        let code = code_of(&std::fs::read_to_string(f).unwrap());
        for (at, _) in code.match_indices("crate::") {
            let name: String = code[at + 7..].chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            let target = defined_in.get(&name).cloned().unwrap_or(name.clone());
            if target == room {
                continue;
            }
            seen += 1;
            let Some(&theirs) = layer.get(target.as_str()) else {
                wrong.push(format!("{}: `crate::{name}` is in no layer", rel.display()));
                continue;
            };
            if theirs >= own {
                wrong.push(format!("{}: `{room}` (layer {own}) uses `{target}` (layer {theirs})", rel.display()));
            }
        }
    }
    assert!(seen > 100, "only {seen} crate paths read: the scan is broken");
    assert!(wrong.is_empty(), "imports against docs/architecture.md's layers:\n{}", wrong.join("\n"));
}

#[test]
fn the_scan_sees_through_comments_and_test_modules_only() {
    let text = "use crate::a;\n// crate::b in a comment\n#[cfg(test)]\nmod tests {\n    fn f() { if x { crate::c } }\n}\nuse crate::d;\n";
    let code = code_of(text);
    assert!(code.contains("crate::a") && code.contains("crate::d"), "{code}");
    assert!(!code.contains("crate::b") && !code.contains("crate::c"), "{code}");
}
