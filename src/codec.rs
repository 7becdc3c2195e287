//! The one serde format of the project's own byte blobs (bed files, the models' part of saved FMU states):
//! postcard, a maintained, compact, stable format (varint integers, little-endian floats). Its wire format
//! is versioned by postcard itself (1.x), and our files carry their own format version around it.

/// The bytes of `value`.
pub fn to_bytes<T: serde::Serialize>(value: &T) -> Result<Vec<u8>, String> {
    postcard::to_allocvec(value).map_err(|e| e.to_string())
}

/// Reads `bytes` as a `T`, refusing bytes left over. A corrupt length cannot ask for more memory than
/// the input holds: postcard reads sequences element by element and stops at the end of the bytes.
pub fn from_bytes<T: serde::de::DeserializeOwned>(bytes: &[u8]) -> Result<T, String> {
    let (value, rest) = postcard::take_from_bytes(bytes).map_err(|e| e.to_string())?;
    if rest.is_empty() {
        Ok(value)
    } else {
        Err(format!("{} bytes left over after the data", rest.len()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_is_exact_and_leftovers_and_truncation_are_refused() {
        let v: Vec<(u32, [f64; 3], f64)> = vec![(7, [1.0, -0.0, f64::MIN_POSITIVE], 1e-300), (u32::MAX, [f64::MAX; 3], -2.5)];
        let b = to_bytes(&v).unwrap();
        let back: Vec<(u32, [f64; 3], f64)> = from_bytes(&b).unwrap();
        assert_eq!(back.len(), 2);
        for (a, b) in v.iter().zip(&back) {
            assert_eq!(a.0, b.0);
            assert_eq!(a.1.map(f64::to_bits), b.1.map(f64::to_bits));
            assert_eq!(a.2.to_bits(), b.2.to_bits());
        }
        let mut longer = b.clone();
        longer.push(0);
        assert!(from_bytes::<Vec<(u32, [f64; 3], f64)>>(&longer).unwrap_err().contains("left over"));
        assert!(from_bytes::<Vec<(u32, [f64; 3], f64)>>(&b[..b.len() - 1]).is_err());
    }

    #[test]
    fn a_bed_vector_is_written_as_three_plain_f64() {
        // Bed files of format 3 were written while the bed's vectors were [f64; 3]; nalgebra's Vector3
        // must keep their bytes, signs of zero included.
        let x = [1.5e-3, -0.0, f64::MIN_POSITIVE];
        let v = crate::bed::Vec3::new(x[0], x[1], x[2]);
        assert_eq!(to_bytes(&v).unwrap(), to_bytes(&x).unwrap());
        let back: crate::bed::Vec3 = from_bytes(&to_bytes(&x).unwrap()).unwrap();
        assert_eq!(back.map(f64::to_bits), v.map(f64::to_bits));
    }

    #[test]
    fn a_huge_length_prefix_fails_without_allocating_it() {
        // A varint length of 2^62 elements followed by nothing.
        let bytes = [0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x3f];
        assert!(from_bytes::<Vec<f64>>(&bytes).is_err());
    }
}
