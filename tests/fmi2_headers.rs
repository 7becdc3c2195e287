//! Every exported `fmi2*` signature against the official FMI 2.0 headers. cbindgen writes the C
//! declarations of our Rust exports and type aliases; gcc compiles them after `fmi2Functions.h`, where a
//! prototype or typedef that differs from the standard's is a hard error. The status enums and the two
//! structs are C enums and structs in the headers, so they are compared by value, size and field offset.
//!
//! The official headers come with fmpy (its `c-code` folder) in the project's virtual environment
//! (`bash tools/venv.sh`, which `tests/run_all.sh` runs first), or from the folder in FMI2_HEADERS.

use powderfmu::fmi2::types::{fmi2CallbackFunctions, fmi2EventInfo};
use std::mem::{offset_of, size_of};
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn headers() -> PathBuf {
    if let Some(dir) = std::env::var_os("FMI2_HEADERS") {
        return PathBuf::from(dir);
    }
    let lib = root().join(".venv/lib");
    let found = std::fs::read_dir(&lib)
        .ok()
        .and_then(|dirs| dirs.flatten().map(|d| d.path().join("site-packages/fmpy/c-code")).find(|p| p.join("fmi2Functions.h").is_file()));
    found.unwrap_or_else(|| {
        panic!("the official FMI 2.0 headers were not found: run `bash tools/venv.sh` (installs fmpy, which carries them) or set FMI2_HEADERS to a folder with fmi2Functions.h")
    })
}

fn our_declarations(out: &Path) {
    let mut config = cbindgen::Config { language: cbindgen::Language::C, no_includes: true, usize_is_size_t: true, ..Default::default() };
    // C enums and structs in the headers: compared below by value, size and offset instead.
    config.export.exclude = [
        "fmi2Status",
        "fmi2Type",
        "fmi2StatusKind",
        "fmi2CallbackFunctions",
        "fmi2EventInfo",
        "fmi2CallbackLogger",
        "fmi2CallbackAllocateMemory",
        "fmi2CallbackFreeMemory",
        "fmi2StepFinished",
    ]
    .map(String::from)
    .to_vec();
    cbindgen::Builder::new()
        .with_config(config)
        .with_src(root().join("src/fmi2/types.rs"))
        .with_src(root().join("src/fmi2/exports.rs"))
        .generate()
        .expect("cbindgen reads src/fmi2")
        .write_to_file(out);
}

#[test]
fn every_export_matches_the_official_fmi2_headers() {
    let dir = std::env::temp_dir().join(format!("powderfmu-headers-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let ours = dir.join("ours.h");
    our_declarations(&ours);
    let text = std::fs::read_to_string(&ours).unwrap();
    // Declarations may wrap; count the fmi2 names followed by their parameter list.
    let exported = text
        .match_indices("fmi2")
        .filter(|(i, _)| {
            let name: String = text[*i..].chars().take_while(|c| c.is_alphanumeric()).collect();
            text[i + name.len()..].starts_with('(')
        })
        .count();
    assert_eq!(exported, 44, "cbindgen should see 44 fmi2 functions:\n{text}");

    let check = format!(
        r#"#include <stddef.h>
#include "fmi2Functions.h"
#include "ours.h"
_Static_assert(sizeof(fmi2Status) == sizeof(int), "fmi2Status is int-sized");
_Static_assert(fmi2OK == 0 && fmi2Warning == 1 && fmi2Discard == 2 && fmi2Error == 3 && fmi2Fatal == 4 && fmi2Pending == 5, "fmi2Status values");
_Static_assert(fmi2ModelExchange == 0 && fmi2CoSimulation == 1, "fmi2Type values");
_Static_assert(fmi2DoStepStatus == 0 && fmi2PendingStatus == 1 && fmi2LastSuccessfulTime == 2 && fmi2Terminated == 3, "fmi2StatusKind values");
_Static_assert(sizeof(fmi2EventInfo) == {ei}, "fmi2EventInfo size");
_Static_assert(offsetof(fmi2EventInfo, valuesOfContinuousStatesChanged) == {ei_v}, "fmi2EventInfo offsets");
_Static_assert(offsetof(fmi2EventInfo, nextEventTime) == {ei_t}, "fmi2EventInfo offsets");
_Static_assert(sizeof(fmi2CallbackFunctions) == {cb}, "fmi2CallbackFunctions size");
_Static_assert(offsetof(fmi2CallbackFunctions, stepFinished) == {cb_s}, "fmi2CallbackFunctions offsets");
_Static_assert(offsetof(fmi2CallbackFunctions, componentEnvironment) == {cb_e}, "fmi2CallbackFunctions offsets");
"#,
        ei = size_of::<fmi2EventInfo>(),
        ei_v = offset_of!(fmi2EventInfo, valuesOfContinuousStatesChanged),
        ei_t = offset_of!(fmi2EventInfo, nextEventTime),
        cb = size_of::<fmi2CallbackFunctions>(),
        cb_s = offset_of!(fmi2CallbackFunctions, stepFinished),
        cb_e = offset_of!(fmi2CallbackFunctions, componentEnvironment),
    );
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
        "our signatures differ from the FMI 2.0 headers:\n{}\n--- ours.h ---\n{text}",
        String::from_utf8_lossy(&output.stderr)
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_wrong_signature_would_be_caught() {
    // The check must be able to fail: a declaration with one wrong parameter type does not compile.
    let dir = std::env::temp_dir().join(format!("powderfmu-headers-neg-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let c_file = dir.join("wrong.c");
    std::fs::write(&c_file, "#include \"fmi2Functions.h\"\nfmi2Status fmi2DoStep(fmi2Component c, float t, fmi2Real h, fmi2Boolean b);\n").unwrap();
    let status = Command::new("gcc").args(["-std=c11", "-fsyntax-only", "-I"]).arg(headers()).arg(&c_file).output().expect("gcc runs").status;
    assert!(!status.success());
    std::fs::remove_dir_all(&dir).ok();
}
