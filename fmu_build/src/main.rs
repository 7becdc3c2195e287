//! `fmu_build`: builds the powderfmu cdylib (profile `fmu-release`: release without debug info) and writes
//! `target/fmu/<Unit>.fmu` (FMI 2.0) and `target/fmu/fmi3/<Unit>.fmu` (FMI 3.0, `binaries/x86_64-linux`,
//! `binaries/x86_64-windows`) for every unit: `modelDescription.xml`, `binaries/linux64/<Unit>.so` and,
//! cross-compiled with mingw-w64, `binaries/win64/<Unit>.dll`, `documentation/` (the unit's page, the
//! model equations, an index) and `resources/` (the default scene). Archives are reproducible: sorted
//! entries, fixed timestamps.
//!
//! Usage: `cargo run -p fmu_build [-- --out DIR] [--skip-build] [--linux-only] [--update-interface]`.
//! `--update-interface` rewrites the checked-in `modelDescription/*.xml` and docs tables instead.

use fmu_build::archive::{zip_bytes, Entry};
use fmu_build::{beds, interface};
use powderfmu::units::{self, model_description, UnitInfo};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("fmu_build: error: {e}");
            ExitCode::from(1)
        }
    }
}

struct Options {
    out: PathBuf,
    skip_build: bool,
    update_interface: bool,
    /// Build and ship binaries/linux64 only (no cross-build for Windows).
    linux_only: bool,
}

/// The Windows target of the cross-build: Rust's `x86_64-pc-windows-gnu`, linked by Debian's mingw-w64.
const WINDOWS_TARGET: &str = "x86_64-pc-windows-gnu";

fn options() -> Result<Options, String> {
    let root = interface::root();
    let target = std::env::var_os("CARGO_TARGET_DIR").map(PathBuf::from).unwrap_or_else(|| root.join("target"));
    let mut o = Options { out: target.join("fmu"), skip_build: false, update_interface: false, linux_only: false };
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--out" => o.out = PathBuf::from(args.next().ok_or("--out needs a directory")?),
            "--skip-build" => o.skip_build = true,
            "--update-interface" => o.update_interface = true,
            "--linux-only" => o.linux_only = true,
            "-h" | "--help" => {
                println!("usage: fmu_build [--out DIR] [--skip-build] [--linux-only] [--update-interface]");
                println!("  builds the cdylib (cargo profile `fmu-release`) for linux64 and, cross-compiled, win64, and writes");
                println!("  DIR/<Unit>.fmu (default target/fmu) with binaries/linux64/<Unit>.so and binaries/win64/<Unit>.dll");
                println!("  --linux-only  skip the Windows cross-build (which needs `rustup target add {WINDOWS_TARGET}`");
                println!("                and the linker x86_64-w64-mingw32-gcc, Debian's gcc-mingw-w64-x86-64)");
                println!("  --update-interface  rewrite modelDescription/<Unit>.xml, modelDescription/fmi3/<Unit>.xml and the docs tables");
                std::process::exit(0);
            }
            other => return Err(format!("unknown argument `{other}` (see --help)")),
        }
    }
    Ok(o)
}

fn run() -> Result<(), String> {
    let o = options()?;
    if o.update_interface {
        for unit in units::all() {
            for path in interface::update(unit)? {
                println!("fmu_build: updated {}", path.display());
            }
        }
        println!("fmu_build: interface files are up to date");
        return Ok(());
    }
    let root = interface::root();
    let target = std::env::var_os("CARGO_TARGET_DIR").map(PathBuf::from).unwrap_or_else(|| root.join("target"));
    if !o.skip_build {
        build(&root, None)?;
        if !o.linux_only {
            windows_toolchain()?;
            build(&root, Some(WINDOWS_TARGET))?;
        }
    }
    let read_library = |path: PathBuf| {
        std::fs::read(&path).map_err(|e| format!("cannot read the built library {}: {e} (build without --skip-build)", path.display()))
    };
    let linux = read_library(target.join("fmu-release").join("libpowderfmu.so"))?;
    let windows = if o.linux_only { None } else { Some(read_library(target.join(WINDOWS_TARGET).join("fmu-release").join("powderfmu.dll"))?) };
    let binaries = Binaries { linux: &linux, windows: windows.as_deref() };
    std::fs::create_dir_all(&o.out).map_err(|e| format!("cannot create {}: {e}", o.out.display()))?;
    for unit in units::all() {
        let checked_in = std::fs::read_to_string(interface::model_description_path(unit)).unwrap_or_default();
        let checked_in_fmi3 = std::fs::read_to_string(interface::model_description_fmi3_path(unit)).unwrap_or_default();
        if checked_in != unit.model_description() || checked_in_fmi3 != unit.model_description_fmi3() {
            eprintln!(
                "fmu_build: warning: modelDescription/{}.xml differs from the variable table; run `cargo run -p fmu_build -- --update-interface` and commit",
                unit.model_identifier
            );
        }
        let path = o.out.join(format!("{}.fmu", unit.model_identifier));
        let bytes = zip_bytes(entries(unit, &binaries, &root, Version::Fmi2)?).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        interface::write_atomic(&path, &bytes)?;
        println!("fmu_build: wrote {} ({:.1} MiB, GUID {})", path.display(), bytes.len() as f64 / 1048576.0, unit.guid());
        // The FMI 3.0 FMU: the same binary (it exports both ABIs), its own description and platform folders.
        let path = o.out.join("fmi3").join(format!("{}.fmu", unit.model_identifier));
        let bytes = zip_bytes(entries(unit, &binaries, &root, Version::Fmi3)?).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        interface::write_atomic(&path, &bytes)?;
        println!(
            "fmu_build: wrote {} ({:.1} MiB, instantiationToken {})",
            path.display(),
            bytes.len() as f64 / 1048576.0,
            unit.instantiation_token()
        );
    }
    Ok(())
}

/// `cargo build --profile fmu-release --lib -p powderfmu [--target T]`.
fn build(root: &Path, target: Option<&str>) -> Result<(), String> {
    let mut args = vec!["build", "--profile", "fmu-release", "--lib", "-p", "powderfmu", "--no-default-features"];
    args.extend(target.iter().flat_map(|t| ["--target", t]));
    println!("fmu_build: building the cdylib (cargo {})", args.join(" "));
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let status = Command::new(cargo).args(&args).current_dir(root).status().map_err(|e| format!("cannot run cargo: {e}"))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!("cargo build failed ({status})"))
    }
}

/// Says in one line what the Windows cross-build lacks, before cargo fails with pages of linker errors.
fn windows_toolchain() -> Result<(), String> {
    let installed =
        Command::new("rustup").args(["target", "list", "--installed"]).output().map(|o| String::from_utf8_lossy(&o.stdout).contains(WINDOWS_TARGET));
    if installed.is_ok_and(|yes| !yes) {
        return Err(format!("the Windows cross-build needs the Rust target: `rustup target add {WINDOWS_TARGET}` (or build with --linux-only)"));
    }
    if Command::new("x86_64-w64-mingw32-gcc").arg("--version").output().is_err() {
        return Err(
            "the Windows cross-build needs the linker x86_64-w64-mingw32-gcc: `apt-get install gcc-mingw-w64-x86-64` (or build with --linux-only)"
                .into(),
        );
    }
    Ok(())
}

/// The unit's binaries: the same library for every unit, one per platform.
struct Binaries<'a> {
    linux: &'a [u8],
    windows: Option<&'a [u8]>,
}

fn read(root: &Path, rel: &str) -> Result<Vec<u8>, String> {
    std::fs::read(root.join(rel)).map_err(|e| format!("cannot read {rel}: {e}"))
}

/// Which standard an archive is for.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Version {
    Fmi2,
    Fmi3,
}

fn entries(unit: &UnitInfo, binaries: &Binaries, root: &Path, version: Version) -> Result<Vec<Entry>, String> {
    let id = unit.model_identifier;
    let page = format!("docs/units/{id}.md");
    // The platform folders: FMI 2.0's names, and FMI 3.0's platform tuples (FMI 3.0 Sec. 2.5.1.1).
    let (description, linux, windows) = match version {
        Version::Fmi2 => (unit.model_description(), "linux64", "win64"),
        Version::Fmi3 => (unit.model_description_fmi3(), "x86_64-linux", "x86_64-windows"),
    };
    let mut entries = vec![
        Entry { name: "modelDescription.xml".into(), data: description.into_bytes() },
        Entry { name: format!("binaries/{linux}/{id}.so"), data: binaries.linux.to_vec() },
        Entry { name: "documentation/index.html".into(), data: index_html(unit).into_bytes() },
        Entry { name: format!("documentation/{id}.md"), data: read(root, &page)? },
        Entry { name: "documentation/models.md".into(), data: read(root, "docs/models.md")? },
    ];
    if let Some(dll) = binaries.windows {
        entries.push(Entry { name: format!("binaries/{windows}/{id}.dll"), data: dll.to_vec() });
    }
    if id == units::ball_indentation::MODEL_IDENTIFIER {
        let scene = units::ball_indentation::DEFAULT_BED_SCENE.as_bytes().to_vec();
        entries.push(Entry { name: format!("resources/{}", units::ball_indentation::RESOURCE_BED), data: beds::shipped(root)? });
        entries.push(Entry { name: format!("resources/{}", units::ball_indentation::RESOURCE_QUARTER_BED), data: beds::shipped_quarter(root)? });
        for (name, data) in beds::shipped_quarter_replicas(root)? {
            entries.push(Entry { name: format!("resources/{name}"), data });
        }
        entries.push(Entry { name: "resources/bed_scene.json".into(), data: scene });
        entries.push(Entry { name: "documentation/bed.md".into(), data: read(root, "docs/bed.md")? });
    } else if id == units::unconfined_compression::MODEL_IDENTIFIER {
        let specimen = beds::shipped_specimen(root)?;
        entries.push(Entry { name: format!("resources/{}", units::unconfined_compression::RESOURCE_SPECIMEN), data: specimen });
        for (name, data) in beds::shipped_specimen_replicas(root)? {
            entries.push(Entry { name: format!("resources/{name}"), data });
        }
        entries.push(Entry { name: "resources/specimen_scene.json".into(), data: units::unconfined_compression::SPECIMEN_SCENE.as_bytes().to_vec() });
        entries.push(Entry { name: "documentation/bed.md".into(), data: read(root, "docs/bed.md")? });
    } else {
        entries.push(Entry { name: "resources/default_scene.json".into(), data: units::DEFAULT_SCENE.as_bytes().to_vec() });
    }
    Ok(entries)
}

/// A self-contained documentation page: what the unit is, where the equations are, every variable.
fn index_html(unit: &UnitInfo) -> String {
    let esc = model_description::escape;
    let mut rows = String::new();
    for v in &unit.variables {
        let start = v.start.as_ref().map(|s| s.xml_text()).unwrap_or_else(|| "calculated".into());
        rows.push_str(&format!(
            "<tr><td><code>{}</code></td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
            esc(&v.name),
            v.causality.xml_name(),
            v.var_type.xml_name(),
            if v.unit.is_empty() { "-" } else { v.unit },
            esc(&start),
            esc(&v.description)
        ));
    }
    format!(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>{id}</title></head><body>\n<h1>{id}</h1>\n<p>{desc}</p>\n\
<p>The unit's page is <a href=\"{id}.md\">{id}.md</a>; the contact laws, their equations with seed references and every modelling \
choice are in <a href=\"models.md\">models.md</a>. powderfmu {ver}.</p>\n<table border=\"1\">\n<tr><th>name</th><th>causality</th><th>type</th>\
<th>unit</th><th>start</th><th>description</th></tr>\n{rows}</table>\n</body></html>\n",
        id = unit.model_identifier,
        desc = esc(unit.description),
        ver = env!("CARGO_PKG_VERSION"),
    )
}
