//! The shear cell at the preshear's end as a file (`powderfmu bed shear --save-preshear`, `--from-preshear`):
//! `shear::Presheared` (the engine's state with the rings and the lid, the neighbour list's build positions,
//! the preshear's curve and settings) in the project's envelope (`envelope`, magic `PFSHEAR\0`) around its
//! `codec` bytes. Shears from the file read, sample for sample, what they read in the run that saved it.
//! On the 30-diameter cells of docs/bed.md "The shear cell" the 5 d preshear is 45-75 minutes of a 62- or
//! 103-minute test; the shears at other normal stresses (a point near sigma_pre, a lower one) are the
//! experiments that follow it.

use super::any::BedError;
use super::file;
use super::shear::Presheared;
use crate::envelope::{self, EnvelopeError, Format};

/// The magic bytes that open a saved preshear's envelope.
pub const MAGIC: &[u8; 8] = b"PFSHEAR\0";
/// 1: the first.
pub const VERSION: u32 = 1;
/// The saved preshear's envelope.
pub const FORMAT: Format = Format { magic: MAGIC, version: VERSION };

/// The file's bytes.
pub fn encode(state: &Presheared) -> Result<Vec<u8>, BedError> {
    let payload = crate::codec::to_bytes(state).map_err(|e| BedError::Setup(format!("saved preshear: cannot be written ({e})")))?;
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
        EnvelopeError::Version { found, .. } => {
            bad(format!("format version {found}, this powderfmu reads version {VERSION}; run the preshear again"))
        }
        other => bad(other.to_string()),
    })?;
    crate::codec::from_bytes(payload).map_err(|e| bad(format!("payload unreadable ({e})")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_saved_preshear_reads_back_whole_and_a_bad_file_is_named() {
        let s = crate::bed::shear::tests::saved_state();
        let bytes = encode(&s).unwrap();
        assert_eq!(decode(&bytes).unwrap(), s);
        let err = decode(&bytes[..bytes.len() - 3]).unwrap_err().to_string();
        assert!(err.contains("not a usable saved preshear") && err.contains("truncated"), "{err}");
        let mut bed = file::MAGIC.to_vec();
        bed.extend_from_slice(&[3, 0, 0, 0]);
        let err = decode(&bed).unwrap_err().to_string();
        assert!(err.contains("it is a bed file") && err.contains("--save-preshear"), "{err}");
        let newer = envelope::seal(Format { magic: MAGIC, version: VERSION + 1 }, &[]);
        let err = decode(&newer).unwrap_err().to_string();
        assert!(err.contains(&format!("format version {}", VERSION + 1)) && err.contains("run the preshear again"), "{err}");
    }
}
