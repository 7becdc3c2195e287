//! Every exported `fmi3*` signature against the official FMI 3.0 headers, as `fmi2_headers.rs` does for
//! FMI 2.0: cbindgen writes the C declarations of our Rust exports and type aliases; gcc compiles them
//! after `fmi3Functions.h`, where a prototype or typedef that differs from the standard's is a hard
//! error. fmi3Boolean is C's `bool`: a Rust `bool` declared where the header has an int would fail here.
//!
//! The official headers come with fmpy (its `c-code` folder) in the project's virtual environment
//! (`bash tools/venv.sh`, which `tests/run_all.sh` runs first), or from the folder in FMI3_HEADERS.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn headers() -> PathBuf {
    if let Some(dir) = std::env::var_os("FMI3_HEADERS") {
        return PathBuf::from(dir);
    }
    let lib = root().join(".venv/lib");
    let found = std::fs::read_dir(&lib)
        .ok()
        .and_then(|dirs| dirs.flatten().map(|d| d.path().join("site-packages/fmpy/c-code")).find(|p| p.join("fmi3Functions.h").is_file()));
    found.unwrap_or_else(|| {
        panic!("the official FMI 3.0 headers were not found: run `bash tools/venv.sh` (installs fmpy, which carries them) or set FMI3_HEADERS to a folder with fmi3Functions.h")
    })
}

fn our_declarations(out: &Path) {
    let mut config = cbindgen::Config { language: cbindgen::Language::C, no_includes: true, usize_is_size_t: true, ..Default::default() };
    // C enums and callback typedefs in the headers; the enums' values are compared below.
    config.export.exclude = [
        "fmi3Status",
        "fmi3DependencyKind",
        "fmi3IntervalQualifier",
        "fmi3LogMessageCallback",
        "fmi3ClockUpdateCallback",
        "fmi3IntermediateUpdateCallback",
        "fmi3LockPreemptionCallback",
        "fmi3UnlockPreemptionCallback",
    ]
    .map(String::from)
    .to_vec();
    cbindgen::Builder::new()
        .with_config(config)
        .with_src(root().join("src/fmi3/types.rs"))
        .with_src(root().join("src/fmi3/exports.rs"))
        .generate()
        .expect("cbindgen reads src/fmi3")
        .write_to_file(out);
}

/// The names of the functions a header declares (a name followed by its parameter list).
fn declared_functions(text: &str) -> Vec<String> {
    let mut names: Vec<String> = text
        .match_indices("fmi3")
        .filter_map(|(i, _)| {
            let name: String = text[i..].chars().take_while(|c| c.is_alphanumeric()).collect();
            text[i + name.len()..].starts_with('(').then_some(name)
        })
        .collect();
    names.sort();
    names.dedup();
    names
}

#[test]
fn every_export_matches_the_official_fmi3_headers() {
    let dir = std::env::temp_dir().join(format!("powderfmu-headers3-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let ours = dir.join("ours.h");
    our_declarations(&ours);
    let text = std::fs::read_to_string(&ours).unwrap();
    // Every function the standard names (fmi3Functions.h declares each as `FMI3_Export fmi3XTYPE fmi3X;`).
    let official = std::fs::read_to_string(headers().join("fmi3Functions.h")).unwrap();
    let mut standard: Vec<String> = official
        .lines()
        .filter_map(|l| l.strip_prefix("FMI3_Export "))
        .filter_map(|l| l.split_whitespace().nth(1))
        .map(|n| n.trim_end_matches(';').to_string())
        .collect();
    standard.sort();
    assert_eq!(standard.len(), 75, "fmi3Functions.h declares 75 functions");
    assert_eq!(declared_functions(&text), standard, "we export exactly the standard's functions");

    let check = r#"#include <stddef.h>
#include "fmi3Functions.h"
#include "ours.h"
_Static_assert(sizeof(fmi3Status) == sizeof(int), "fmi3Status is int-sized");
_Static_assert(fmi3OK == 0 && fmi3Warning == 1 && fmi3Discard == 2 && fmi3Error == 3 && fmi3Fatal == 4, "fmi3Status values");
_Static_assert(sizeof(fmi3DependencyKind) == sizeof(int) && sizeof(fmi3IntervalQualifier) == sizeof(int), "enums are int-sized");
_Static_assert(sizeof(fmi3Boolean) == 1, "fmi3Boolean is a one-byte bool");
"#;
    let c_file = dir.join("check.c");
    std::fs::write(&c_file, check).unwrap();
    let output = Command::new("gcc")
        .args(["-std=c11", "-Wall", "-Werror", "-fsyntax-only", "-I"])
        .arg(headers())
        .arg("-I")
        .arg(&dir)
        .arg(&c_file)
        .output()
        .expect("gcc runs");
    assert!(
        output.status.success(),
        "our signatures differ from the FMI 3.0 headers:\n{}\n--- ours.h ---\n{text}",
        String::from_utf8_lossy(&output.stderr)
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_wrong_prototype_would_be_caught() {
    // The check must be able to fail: our fmi3DoStep with one output as an int* instead of a bool* (the
    // FMI 2.0 habit) does not compile after the official header.
    let dir = std::env::temp_dir().join(format!("powderfmu-headers3-neg-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let c_file = dir.join("wrong.c");
    std::fs::write(
        &c_file,
        "#include \"fmi3Functions.h\"\nfmi3Status fmi3DoStep(fmi3Instance i, fmi3Float64 t, fmi3Float64 h, fmi3Boolean n, int* e, fmi3Boolean* s, fmi3Boolean* r, fmi3Float64* l);\n",
    )
    .unwrap();
    let status = Command::new("gcc").args(["-std=c11", "-fsyntax-only", "-I"]).arg(headers()).arg(&c_file).output().expect("gcc runs").status;
    assert!(!status.success());
    // And the same line with the right types compiles: the failure above is the wrong type, not the file.
    std::fs::write(
        &c_file,
        "#include \"fmi3Functions.h\"\nfmi3Status fmi3DoStep(fmi3Instance i, fmi3Float64 t, fmi3Float64 h, fmi3Boolean n, fmi3Boolean* e, fmi3Boolean* s, fmi3Boolean* r, fmi3Float64* l);\n",
    )
    .unwrap();
    let status = Command::new("gcc").args(["-std=c11", "-fsyntax-only", "-I"]).arg(headers()).arg(&c_file).output().expect("gcc runs").status;
    assert!(status.success());
    std::fs::remove_dir_all(&dir).ok();
}
