//! A reproducible zip archive, written with the `zip` crate: entries sorted by name, every timestamp
//! 1980-01-01 00:00, permissions 0644, deflate at a fixed level, no extra fields. The same files give the
//! same bytes on every machine, so a built `.fmu` can be compared by its hash.

use std::io::{self, Cursor, Seek, Write};
use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, DateTime, ZipWriter};

/// One file of the archive: its path inside the archive (forward slashes) and its bytes.
pub struct Entry {
    pub name: String,
    pub data: Vec<u8>,
}

/// Writes `entries` as a zip archive to `out`. Names must be unique, relative and use `/`.
pub fn write_zip<W: Write + Seek>(mut entries: Vec<Entry>, out: W) -> io::Result<()> {
    entries.sort_by(|a, b| a.name.cmp(&b.name));
    for pair in entries.windows(2) {
        if pair[0].name == pair[1].name {
            return Err(invalid(format!("duplicate archive entry `{}`", pair[0].name)));
        }
    }
    for e in &entries {
        if e.name.is_empty() || e.name.starts_with('/') || e.name.contains('\\') || e.name.split('/').any(|p| p == "..") {
            return Err(invalid(format!("archive entry name `{}` must be relative with `/`", e.name)));
        }
    }
    let options = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Deflated)
        .compression_level(Some(6))
        .last_modified_time(DateTime::default())
        .unix_permissions(0o644);
    let mut zip = ZipWriter::new(out);
    for e in &entries {
        zip.start_file(e.name.as_str(), options).map_err(to_io)?;
        zip.write_all(&e.data)?;
    }
    zip.finish().map_err(to_io)?;
    Ok(())
}

/// The archive as bytes.
pub fn zip_bytes(entries: Vec<Entry>) -> io::Result<Vec<u8>> {
    let mut out = Cursor::new(Vec::new());
    write_zip(entries, &mut out)?;
    Ok(out.into_inner())
}

fn invalid(why: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, why)
}

fn to_io(e: zip::result::ZipError) -> io::Error {
    io::Error::other(e)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Read;

    fn entries() -> Vec<Entry> {
        vec![
            Entry { name: "modelDescription.xml".into(), data: b"<fmiModelDescription/>".to_vec() },
            Entry { name: "binaries/linux64/Unit.so".into(), data: vec![0x7f, b'E', b'L', b'F', 0, 1, 2] },
            Entry { name: "documentation/index.html".into(), data: b"<html></html>".to_vec() },
            Entry { name: "resources/repeated.txt".into(), data: b"powder ".repeat(500) },
        ]
    }

    #[test]
    fn the_same_files_in_any_order_give_the_same_bytes() {
        let a = zip_bytes(entries()).unwrap();
        let mut reversed = entries();
        reversed.reverse();
        assert_eq!(a, zip_bytes(reversed).unwrap());
    }

    #[test]
    fn the_archive_reads_back_with_fixed_times_and_permissions() {
        let z = zip_bytes(entries()).unwrap();
        let mut archive = zip::ZipArchive::new(Cursor::new(z)).unwrap();
        let mut sorted = entries();
        sorted.sort_by(|x, y| x.name.cmp(&y.name));
        assert_eq!(archive.len(), sorted.len());
        for (i, e) in sorted.iter().enumerate() {
            let mut f = archive.by_index(i).unwrap();
            assert_eq!(f.name(), e.name);
            assert_eq!(f.unix_mode().map(|m| m & 0o777), Some(0o644));
            let t = f.last_modified().unwrap();
            assert_eq!((t.year(), t.month(), t.day(), t.hour(), t.minute()), (1980, 1, 1, 0, 0));
            let mut data = Vec::new();
            f.read_to_end(&mut data).unwrap();
            assert_eq!(data, e.data);
        }
    }

    #[test]
    fn repetitive_files_are_deflated() {
        let z = zip_bytes(entries()).unwrap();
        assert!(z.len() < 3500 / 2, "{} bytes for a 3500-byte repetitive entry", z.len());
    }

    #[test]
    fn bad_names_and_duplicates_are_refused() {
        let dup = vec![Entry { name: "a".into(), data: vec![] }, Entry { name: "a".into(), data: vec![1] }];
        assert!(zip_bytes(dup).is_err());
        for bad in ["/abs", "../up", "win\\path", ""] {
            assert!(zip_bytes(vec![Entry { name: bad.into(), data: vec![] }]).is_err(), "{bad}");
        }
    }
}
