//! The shear cell at the preshear's end, saved (`powderfmu bed shear --save-preshear`), so that shears to
//! failure start from it again without running the preshear: the engine's whole state with the rings and
//! the lid, the neighbour list's build positions (a restored state steps as the original would, so shears
//! from the file read, sample for sample, what they read in the run that saved it), the preshear's curve
//! and the settings the preshear ran with. On the 30-diameter cells of docs/bed.md "The shear cell" the 5 d
//! preshear takes 45-80 minutes of a test's 60-100, and the shears at other normal stresses (a point near
//! sigma_pre, a lower one) are the experiments that follow.
//!
//! The file: the project's envelope (`envelope`, magic `PFSHEAR\0`) around `codec` bytes of `Presheared`.

use super::any::{AnyEngine, BedError};
use super::file::{self, BedFile};
use super::scene::BedScene;
use super::shear::Sample;
use super::Vec3;
use crate::envelope::{self, EnvelopeError, Format};

/// The magic bytes that open a saved preshear's envelope.
pub const MAGIC: &[u8; 8] = b"PFSHEAR\0";
/// 1: the first.
pub const VERSION: u32 = 1;
/// The saved preshear's envelope.
pub const FORMAT: Format = Format { magic: MAGIC, version: VERSION };

/// The cell's geometry as the shears need it: the upper ring's wall index, the cross-section the lid and
/// the drive act on, the measurement slab (radius, lower and upper height) and the die's sector.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct SavedCell {
    /// Index of the upper ring among the walls.
    pub upper: u32,
    /// Cross-section of the (sector of the) die [m^2].
    pub area: f64,
    /// The slab about the shear plane: radius, lower height, upper height [m].
    pub slab: [f64; 3],
    /// Part of the die simulated.
    pub sector: f64,
}

/// The shear cell at the preshear's end.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Presheared {
    /// Normal stress the preshear ran at, sigma_pre [Pa].
    pub preshear_stress: f64,
    /// Drive speed of the preshear [m/s].
    pub shear_speed: f64,
    /// Height of the rings' meeting, a fraction of the bed's height [-].
    pub split: f64,
    /// Travel of the preshear [m].
    pub preshear_displacement: f64,
    /// The engine's time step [s].
    pub time_step: f64,
    /// Solid fraction of the bed in the cell under sigma_pre, at the preshear's start [-].
    pub solid_fraction: f64,
    /// The preshear's curve.
    pub preshear: Vec<Sample>,
    /// The cell's geometry.
    pub cell: SavedCell,
    /// The engine's state as a bed file's bytes (envelope included).
    pub bed: Vec<u8>,
    /// The neighbour list's build positions of the particles and the walls.
    pub list: Vec<Vec3>,
    /// The walls' positions at the list's build.
    pub walls: Vec<Vec3>,
}

impl Presheared {
    /// The file's bytes.
    pub fn encode(&self) -> Result<Vec<u8>, BedError> {
        let payload = crate::codec::to_bytes(self).map_err(|e| BedError::Setup(format!("saved preshear: cannot be written ({e})")))?;
        Ok(envelope::seal(FORMAT, &payload))
    }

    /// Reads a saved preshear, naming what is wrong with a bad one (a bed file given in its place is told
    /// apart).
    pub fn decode(bytes: &[u8]) -> Result<Presheared, BedError> {
        let bad = |why: String| BedError::Setup(format!("not a usable saved preshear: {why}"));
        let payload = envelope::open(FORMAT, bytes).map_err(|e| match e {
            EnvelopeError::NotThisKind(_) if bytes.starts_with(file::MAGIC) => {
                bad("it is a bed file; shear a bed with `powderfmu bed shear BED`, and save its preshear with --save-preshear".into())
            }
            EnvelopeError::Version { found, .. } => bad(format!("format version {found}, this powderfmu reads version {VERSION}; run the preshear again")),
            other => bad(other.to_string()),
        })?;
        crate::codec::from_bytes(payload).map_err(|e| bad(format!("payload unreadable ({e})")))
    }

    /// The bed scene the state was prepared with.
    pub fn scene(&self) -> Result<BedScene, BedError> {
        let bed: BedFile = file::decode(&self.bed)?;
        Ok(BedScene::from_stored_json(&bed.scene)?)
    }

    /// The engine at the preshear's end, on `threads` (default: the scene's), with its list as it was.
    pub fn engine(&self, threads: Option<usize>) -> Result<AnyEngine, BedError> {
        let bed: BedFile = file::decode(&self.bed)?;
        let (mut e, scene) = AnyEngine::from_file(&bed, threads)?;
        e.set_time_step(&scene, self.time_step)?;
        if !e.rebuild_at(&self.list, &self.walls) {
            return Err(BedError::Setup("the shear cell's preshear state did not restore".into()));
        }
        Ok(e)
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    pub(crate) fn state() -> Presheared {
        let sample = Sample { time: 0.5, displacement: 1e-4, normal_stress: 1.1e4, shear_stress: 4.5e3, ..Default::default() };
        Presheared {
            preshear_stress: 1e4,
            shear_speed: 0.01,
            split: 0.5,
            preshear_displacement: 2e-3,
            time_step: 2.5e-7,
            solid_fraction: 0.55,
            preshear: vec![sample; 3],
            cell: SavedCell { upper: 3, area: 1.7e-4, slab: [6e-3, 9e-3, 1.3e-2], sector: 0.5 },
            bed: vec![1, 2, 3],
            list: vec![Vec3::new(1.0, 2.0, 3.0)],
            walls: vec![Vec3::zeros(); 4],
        }
    }

    #[test]
    fn a_saved_preshear_reads_back_whole_and_a_bad_file_is_named() {
        let s = state();
        let bytes = s.encode().unwrap();
        assert_eq!(Presheared::decode(&bytes).unwrap(), s);
        let err = Presheared::decode(&bytes[..bytes.len() - 3]).unwrap_err().to_string();
        assert!(err.contains("not a usable saved preshear") && err.contains("truncated"), "{err}");
        let mut bed = file::MAGIC.to_vec();
        bed.extend_from_slice(&[3, 0, 0, 0]);
        let err = Presheared::decode(&bed).unwrap_err().to_string();
        assert!(err.contains("it is a bed file") && err.contains("--save-preshear"), "{err}");
        let newer = envelope::seal(Format { magic: MAGIC, version: VERSION + 1 }, &[]);
        let err = Presheared::decode(&newer).unwrap_err().to_string();
        assert!(err.contains(&format!("format version {}", VERSION + 1)) && err.contains("run the preshear again"), "{err}");
    }
}
