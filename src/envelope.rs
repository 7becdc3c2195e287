//! The one envelope of the project's saved data, bed files and saved FMU states alike: what is inside is
//! the caller's (`codec` bytes, or the FMU state's fields), the envelope says what it is, which format
//! version, how long, and whether it arrived whole.
//!
//! Layout: magic (8 bytes), format version (u32 little-endian), payload length (u64 little-endian), the
//! payload, and the FNV-1a 64 checksum of the payload (u64 little-endian). The reader checks each in
//! that order and names what is wrong; an old version is told apart from damage, so the caller can say
//! what to do about it.

/// What kind of saved data an envelope holds.
#[derive(Debug, Clone, Copy)]
pub struct Format {
    /// The first eight bytes.
    pub magic: &'static [u8; 8],
    /// The version this build writes and reads.
    pub version: u32,
}

/// Bytes before the payload: magic, version, length.
pub const HEADER: usize = 20;
/// Bytes after the payload: the checksum.
pub const TRAILER: usize = 8;

/// Why an envelope was refused.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum EnvelopeError {
    /// The bytes do not start with the expected magic, or are too short to hold magic and version; holds
    /// the expected magic.
    #[error("it does not start with the magic bytes `{}`", String::from_utf8_lossy(&.0[..]).trim_end_matches('\0'))]
    NotThisKind(&'static [u8; 8]),
    /// A well-formed header of another format version (the caller says what that version was).
    #[error("format version {found}, this build reads version {reads}")]
    Version {
        /// The version in the header.
        found: u32,
        /// The version this build reads.
        reads: u32,
    },
    /// Fewer bytes than the header's payload length (plus header and trailer) requires, or too few to
    /// hold the length at all.
    #[error("truncated: {len} bytes, the header promises {promised}")]
    Truncated {
        /// The number of bytes given.
        len: u64,
        /// The number of bytes the header promises (header, payload and trailer).
        promised: u64,
    },
    /// More bytes than the header's payload length (plus header and trailer) accounts for.
    #[error("{len} bytes, the header promises {promised}: trailing data")]
    Trailing {
        /// The number of bytes given.
        len: u64,
        /// The number of bytes the header promises (header, payload and trailer).
        promised: u64,
    },
    /// The payload's FNV-1a 64 checksum differs from the one in the trailer.
    #[error("checksum mismatch: the bytes are corrupt")]
    Checksum,
}

/// The payload in its envelope.
pub fn seal(format: Format, payload: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(HEADER + payload.len() + TRAILER);
    out.extend_from_slice(format.magic);
    out.extend_from_slice(&format.version.to_le_bytes());
    out.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    out.extend_from_slice(payload);
    out.extend_from_slice(&fnv1a64(payload, FNV_OFFSET).to_le_bytes());
    out
}

/// The format version an envelope of this kind claims, before anything else is checked (None: not this
/// kind, or too short to say).
pub fn version(format: Format, bytes: &[u8]) -> Option<u32> {
    (bytes.len() >= 12 && &bytes[..8] == format.magic).then(|| u32::from_le_bytes(bytes[8..12].try_into().expect("4 bytes")))
}

/// The payload of an envelope of `format`, or why not.
pub fn open(format: Format, bytes: &[u8]) -> Result<&[u8], EnvelopeError> {
    let found = version(format, bytes).ok_or(EnvelopeError::NotThisKind(format.magic))?;
    if found != format.version {
        return Err(EnvelopeError::Version { found, reads: format.version });
    }
    let len = bytes.len() as u64;
    let promised = bytes
        .get(12..HEADER)
        .map(|b| u64::from_le_bytes(b.try_into().expect("8 bytes")).saturating_add((HEADER + TRAILER) as u64))
        .ok_or(EnvelopeError::Truncated { len, promised: (HEADER + TRAILER) as u64 })?;
    if len < promised {
        return Err(EnvelopeError::Truncated { len, promised });
    }
    if len > promised {
        return Err(EnvelopeError::Trailing { len, promised });
    }
    let (payload, sum) = bytes[HEADER..].split_at(bytes.len() - HEADER - TRAILER);
    if fnv1a64(payload, FNV_OFFSET) != u64::from_le_bytes(sum.try_into().expect("8 bytes")) {
        return Err(EnvelopeError::Checksum);
    }
    Ok(payload)
}

/// FNV-1a's standard 64-bit offset basis.
pub const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;

/// FNV-1a, 64 bit, from `seed` (`FNV_OFFSET` is the standard start). A checksum against damage, not
/// against tampering.
pub fn fnv1a64(bytes: &[u8], seed: u64) -> u64 {
    let mut h = seed;
    for b in bytes {
        h ^= u64::from(*b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    const F: Format = Format { magic: b"TESTFMT\0", version: 7 };

    #[test]
    fn a_sealed_payload_opens_to_itself_and_every_damage_is_named() {
        let payload = b"the payload, any bytes \x00\xff";
        let sealed = seal(F, payload);
        assert_eq!(sealed.len(), HEADER + payload.len() + TRAILER);
        assert_eq!(open(F, &sealed).unwrap(), payload);
        assert_eq!(open(F, &seal(F, b"")).unwrap(), b"");
        // Not this kind; another version (told before the checksum, so an old file is named as old).
        assert_eq!(open(F, b"short"), Err(EnvelopeError::NotThisKind(F.magic)));
        let other = Format { magic: b"OTHERFMT", version: 7 };
        assert_eq!(open(other, &sealed), Err(EnvelopeError::NotThisKind(other.magic)));
        let mut old = sealed.clone();
        old[8..12].copy_from_slice(&6u32.to_le_bytes());
        assert_eq!(open(F, &old), Err(EnvelopeError::Version { found: 6, reads: 7 }));
        assert_eq!(version(F, &old), Some(6));
        // Cut, grown, flipped.
        assert!(matches!(open(F, &sealed[..sealed.len() - 1]), Err(EnvelopeError::Truncated { .. })));
        assert!(matches!(open(F, &sealed[..14]), Err(EnvelopeError::Truncated { .. })));
        let mut longer = sealed.clone();
        longer.push(0);
        assert!(matches!(open(F, &longer), Err(EnvelopeError::Trailing { .. })));
        for at in HEADER..sealed.len() {
            let mut bad = sealed.clone();
            bad[at] ^= 0x04;
            assert_eq!(open(F, &bad), Err(EnvelopeError::Checksum), "a flipped bit at {at}");
        }
        // A length that promises more than any file holds.
        let mut huge = sealed.clone();
        huge[12..20].copy_from_slice(&u64::MAX.to_le_bytes());
        assert!(matches!(open(F, &huge), Err(EnvelopeError::Truncated { .. })));
    }

    #[test]
    fn the_checksum_is_fnv1a_64() {
        // The published test vectors of FNV-1a 64.
        assert_eq!(fnv1a64(b"", FNV_OFFSET), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a64(b"a", FNV_OFFSET), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(fnv1a64(b"foobar", FNV_OFFSET), 0x8594_4171_f739_67e8);
    }

    #[test]
    fn the_error_texts_say_what_is_wrong() {
        assert_eq!(EnvelopeError::NotThisKind(b"PFBED\0\0\0").to_string(), "it does not start with the magic bytes `PFBED`");
        assert_eq!(EnvelopeError::Version { found: 2, reads: 3 }.to_string(), "format version 2, this build reads version 3");
    }
}
