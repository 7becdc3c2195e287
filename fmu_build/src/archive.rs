//! A reproducible zip archive: entries sorted by name, every timestamp 1980-01-01 00:00, fixed
//! attributes, no extra fields, raw deflate at a fixed level (or stored when that is smaller). The same files give the same bytes on
//! every machine, so a built `.fmu` can be compared by its hash.

use std::io::{self, Write};

/// One file of the archive: its path inside the archive (forward slashes) and its bytes.
pub struct Entry {
    pub name: String,
    pub data: Vec<u8>,
}

/// Writes `entries` as a zip archive to `out`. Names must be unique, relative and use `/`.
pub fn write_zip<W: Write>(mut entries: Vec<Entry>, out: &mut W) -> io::Result<()> {
    entries.sort_by(|a, b| a.name.cmp(&b.name));
    for pair in entries.windows(2) {
        if pair[0].name == pair[1].name {
            return Err(io::Error::new(io::ErrorKind::InvalidInput, format!("duplicate archive entry `{}`", pair[0].name)));
        }
    }
    const DOS_DATE_1980_01_01: u16 = (1 << 5) | 1;
    let mut central = Vec::new();
    let mut offset: u32 = 0;
    let n = u16::try_from(entries.len()).map_err(|_| too_big("more than 65535 entries"))?;
    for e in &entries {
        if e.name.is_empty() || e.name.starts_with('/') || e.name.contains('\\') || e.name.split('/').any(|p| p == "..") {
            return Err(io::Error::new(io::ErrorKind::InvalidInput, format!("archive entry name `{}` must be relative with `/`", e.name)));
        }
        let crc = crc32(&e.data);
        let size = u32::try_from(e.data.len()).map_err(|_| too_big("an entry of 4 GiB or more"))?;
        let deflated = miniz_oxide::deflate::compress_to_vec(&e.data, 6);
        let (method, packed): (u16, &[u8]) = if deflated.len() < e.data.len() { (8, &deflated) } else { (0, &e.data) };
        let packed_size = packed.len() as u32;
        let name = e.name.as_bytes();
        let name_len = u16::try_from(name.len()).map_err(|_| too_big("an entry name of 64 KiB or more"))?;
        let mut local = Vec::with_capacity(30 + name.len());
        local.extend_from_slice(&0x0403_4b50u32.to_le_bytes());
        local.extend_from_slice(&20u16.to_le_bytes()); // version needed
        local.extend_from_slice(&0x0800u16.to_le_bytes()); // flags: UTF-8 names
        local.extend_from_slice(&method.to_le_bytes()); // 0 stored, 8 deflate
        local.extend_from_slice(&0u16.to_le_bytes()); // time
        local.extend_from_slice(&DOS_DATE_1980_01_01.to_le_bytes());
        local.extend_from_slice(&crc.to_le_bytes());
        local.extend_from_slice(&packed_size.to_le_bytes());
        local.extend_from_slice(&size.to_le_bytes());
        local.extend_from_slice(&name_len.to_le_bytes());
        local.extend_from_slice(&0u16.to_le_bytes()); // extra
        local.extend_from_slice(name);
        out.write_all(&local)?;
        out.write_all(packed)?;

        central.extend_from_slice(&0x0201_4b50u32.to_le_bytes());
        central.extend_from_slice(&((3u16 << 8) | 20).to_le_bytes()); // made by: Unix, 2.0
        central.extend_from_slice(&20u16.to_le_bytes());
        central.extend_from_slice(&0x0800u16.to_le_bytes());
        central.extend_from_slice(&method.to_le_bytes());
        central.extend_from_slice(&0u16.to_le_bytes());
        central.extend_from_slice(&DOS_DATE_1980_01_01.to_le_bytes());
        central.extend_from_slice(&crc.to_le_bytes());
        central.extend_from_slice(&packed_size.to_le_bytes());
        central.extend_from_slice(&size.to_le_bytes());
        central.extend_from_slice(&name_len.to_le_bytes());
        central.extend_from_slice(&[0u8; 8]); // extra, comment, disk, internal attributes
        central.extend_from_slice(&(0o100644u32 << 16).to_le_bytes()); // -rw-r--r--
        central.extend_from_slice(&offset.to_le_bytes());
        central.extend_from_slice(name);
        offset =
            offset.checked_add(local.len() as u32).and_then(|o| o.checked_add(packed_size)).ok_or_else(|| too_big("an archive of 4 GiB or more"))?;
    }
    out.write_all(&central)?;
    let mut end = Vec::with_capacity(22);
    end.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
    end.extend_from_slice(&[0u8; 4]); // disk numbers
    end.extend_from_slice(&n.to_le_bytes());
    end.extend_from_slice(&n.to_le_bytes());
    end.extend_from_slice(&(central.len() as u32).to_le_bytes());
    end.extend_from_slice(&offset.to_le_bytes());
    end.extend_from_slice(&0u16.to_le_bytes());
    out.write_all(&end)
}

fn too_big(what: &str) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, format!("zip without the 64-bit extension cannot hold {what}"))
}

/// CRC-32 (IEEE 802.3, reflected, as zip uses it).
pub fn crc32(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &byte in data {
        crc ^= u32::from(byte);
        for _ in 0..8 {
            crc = if crc & 1 != 0 { (crc >> 1) ^ 0xEDB8_8320 } else { crc >> 1 };
        }
    }
    !crc
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entries() -> Vec<Entry> {
        vec![
            Entry { name: "modelDescription.xml".into(), data: b"<fmiModelDescription/>".to_vec() },
            Entry { name: "binaries/linux64/Unit.so".into(), data: vec![0x7f, b'E', b'L', b'F', 0, 1, 2] },
            Entry { name: "documentation/index.html".into(), data: b"<html></html>".to_vec() },
            Entry { name: "resources/repeated.txt".into(), data: b"powder ".repeat(500) },
        ]
    }

    #[test]
    fn crc32_matches_the_standard_check_value() {
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
    }

    #[test]
    fn the_same_files_in_any_order_give_the_same_bytes() {
        let mut a = Vec::new();
        write_zip(entries(), &mut a).unwrap();
        let mut reversed = entries();
        reversed.reverse();
        let mut b = Vec::new();
        write_zip(reversed, &mut b).unwrap();
        assert_eq!(a, b);
    }

    #[test]
    fn the_archive_reads_back_entry_by_entry() {
        let mut z = Vec::new();
        write_zip(entries(), &mut z).unwrap();
        let mut sorted = entries();
        sorted.sort_by(|x, y| x.name.cmp(&y.name));
        let mut at = 0;
        for e in &sorted {
            let u16_at = |i: usize| u16::from_le_bytes([z[i], z[i + 1]]) as usize;
            let u32_at = |i: usize| u32::from_le_bytes([z[i], z[i + 1], z[i + 2], z[i + 3]]);
            assert_eq!(u32_at(at), 0x0403_4b50);
            let method = u16_at(at + 8);
            let size = u32_at(at + 18) as usize;
            let name_len = u16_at(at + 26);
            let name = std::str::from_utf8(&z[at + 30..at + 30 + name_len]).unwrap();
            let packed = &z[at + 30 + name_len..at + 30 + name_len + size];
            let data = match method {
                0 => packed.to_vec(),
                8 => miniz_oxide::inflate::decompress_to_vec(packed).unwrap(),
                m => panic!("method {m}"),
            };
            assert_eq!(name, e.name);
            assert_eq!(data, e.data);
            assert_eq!(u32_at(at + 22) as usize, e.data.len());
            assert_eq!(u32_at(at + 14), crc32(&data));
            at += 30 + name_len + size;
        }
        // Then the central directory and the end record, which points back at it.
        let end = z.len() - 22;
        assert_eq!(u32::from_le_bytes(z[end..end + 4].try_into().unwrap()), 0x0605_4b50);
        assert_eq!(u32::from_le_bytes(z[end + 16..end + 20].try_into().unwrap()) as usize, at);
    }

    #[test]
    fn repetitive_files_are_deflated() {
        let mut z = Vec::new();
        write_zip(entries(), &mut z).unwrap();
        assert!(z.len() < 3500 / 2, "{} bytes for a 3500-byte repetitive entry", z.len());
    }

    #[test]
    fn bad_names_and_duplicates_are_refused() {
        let mut sink = Vec::new();
        let dup = vec![Entry { name: "a".into(), data: vec![] }, Entry { name: "a".into(), data: vec![1] }];
        assert!(write_zip(dup, &mut sink).is_err());
        for bad in ["/abs", "../up", "win\\path", ""] {
            assert!(write_zip(vec![Entry { name: bad.into(), data: vec![] }], &mut sink).is_err(), "{bad}");
        }
    }
}
