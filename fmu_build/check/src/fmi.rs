//! The unzipped FMU: its folder, model description and loaded binary, and the instances the runs make
//! of it through `fmi_host` (the project's one Rust FMI host, shared with the test suite).

use crate::model_description::ModelDescription;
use std::path::{Path, PathBuf};

#[cfg(windows)]
pub const PLATFORM: &str = "win64";
#[cfg(not(windows))]
pub const PLATFORM: &str = "linux64";
/// FMI 3.0's name of the same platform (FMI 3.0 Sec. 2.5.1.1).
#[cfg(windows)]
pub const PLATFORM_FMI3: &str = "x86_64-windows";
#[cfg(not(windows))]
pub const PLATFORM_FMI3: &str = "x86_64-linux";
#[cfg(windows)]
const EXTENSION: &str = "dll";
#[cfg(not(windows))]
const EXTENSION: &str = "so";

pub use fmi_host::fmi2::{CO_SIMULATION, MODEL_EXCHANGE};
use fmi_host::{Binary, Log, Names};

pub struct Unpacked {
    pub dir: PathBuf,
    pub model_description: ModelDescription,
    pub binary: Binary,
}

impl Unpacked {
    /// Unzips `fmu` into a fresh temporary folder and loads the binary of this platform.
    pub fn open(fmu: &Path) -> Result<Unpacked, String> {
        let file = std::fs::File::open(fmu).map_err(|e| format!("cannot open {}: {e}", fmu.display()))?;
        let mut archive = zip::ZipArchive::new(file).map_err(|e| format!("{} is not a zip archive: {e}", fmu.display()))?;
        let stem = fmu.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        let dir = std::env::temp_dir().join(format!("fmu_check-{stem}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        archive.extract(&dir).map_err(|e| format!("cannot unzip {}: {e}", fmu.display()))?;
        let xml = std::fs::read_to_string(dir.join("modelDescription.xml")).map_err(|e| format!("modelDescription.xml: {e}"))?;
        let model_description = ModelDescription::parse(&xml)?;
        let platform = if model_description.fmi3 { PLATFORM_FMI3 } else { PLATFORM };
        let binary = Binary::load(&dir.join("binaries").join(platform).join(format!("{}.{EXTENSION}", model_description.model_identifier)))?;
        Ok(Unpacked { dir, model_description, binary })
    }

    /// The `fmuResourceLocation` URI of the unzipped resources folder (`file:///C:/...` on Windows).
    pub fn resource_uri(&self) -> String {
        let path = self.dir.join("resources");
        let text = path.to_string_lossy().replace('\\', "/");
        let text = text.strip_prefix("//?/").unwrap_or(&text).to_string();
        let escaped: String = text.chars().map(|c| if c == ' ' { "%20".to_string() } else { c.to_string() }).collect();
        if escaped.starts_with('/') {
            format!("file://{escaped}/")
        } else {
            format!("file:///{escaped}/")
        }
    }

    /// Variable names to value references, from the model description.
    fn names(&self) -> Names<'_> {
        Box::new(move |name| self.model_description.vr(name))
    }

    /// An FMI 2.0 instance of `kind` (MODEL_EXCHANGE or CO_SIMULATION).
    pub fn instance(&self, kind: i32) -> Result<fmi_host::fmi2::Instance<'_>, String> {
        fmi_host::fmi2::Instance::new(&self.binary, kind, &self.model_description.guid, &self.resource_uri(), self.names())
    }

    /// An FMI 3.0 Co-Simulation instance (Event Mode not used), early return allowed as given. FMI 3.0
    /// passes the resources folder as a path with a trailing separator.
    pub fn instance3(&self, early_return: bool) -> Result<fmi_host::fmi3::Instance<'_>, String> {
        let mut path = self.dir.join("resources").to_string_lossy().into_owned();
        path.push(std::path::MAIN_SEPARATOR);
        let kind = fmi_host::fmi3::Kind::CoSimulation { event_mode: false, early_return };
        fmi_host::fmi3::Instance::new(&self.binary, kind, &self.model_description.guid, Some(&path), self.names())
    }
}

impl Drop for Unpacked {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// Prints an instance's warnings and errors to standard error (the runs print their outputs only).
pub fn print_warnings(log: &Log) {
    for (status, category, text) in log.lock().unwrap_or_else(|e| e.into_inner()).iter().filter(|m| m.0 > fmi_host::OK) {
        eprintln!("fmu: [{category}, status {status}] {text}");
    }
}
