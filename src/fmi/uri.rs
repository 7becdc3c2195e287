//! `fmuResourceLocation` (FMI 2.0 Sec. 2.1.5): a `file:` URI of the unzipped `resources` folder.

use std::path::PathBuf;

/// The directory a `file:` URI names: `file:///a/b`, `file:/a/b` or `file://localhost/a/b`, with
/// percent-escapes decoded; on Windows `file:///C:/a/b` is `C:/a/b`. Anything else is an error that says
/// what was expected.
pub fn file_uri_to_path(uri: &str) -> Result<PathBuf, String> {
    uri_to_path(uri, cfg!(windows))
}

/// `file_uri_to_path` with the Windows reading (a drive letter after the root slash) chosen by `windows`,
/// so that both readings are tested on any host.
fn uri_to_path(uri: &str, windows: bool) -> Result<PathBuf, String> {
    let rest = uri
        .strip_prefix("file://localhost/")
        .map(|r| format!("/{r}"))
        .or_else(|| uri.strip_prefix("file:///").map(|r| format!("/{r}")))
        .or_else(|| uri.strip_prefix("file:/").filter(|r| !r.starts_with('/')).map(|r| format!("/{r}")))
        .ok_or_else(|| format!("fmuResourceLocation \"{uri}\" is not a file URI (expected file:///path/to/resources)"))?;
    let bytes = rest.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = bytes.get(i + 1..i + 3).and_then(|h| std::str::from_utf8(h).ok()).and_then(|h| u8::from_str_radix(h, 16).ok());
            let Some(x) = hex else {
                return Err(format!("fmuResourceLocation \"{uri}\" has a malformed percent-escape at byte {i}"));
            };
            out.push(x);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    let path = String::from_utf8(out).map_err(|_| format!("fmuResourceLocation \"{uri}\" does not decode to UTF-8"))?;
    // `/C:/x` (or `/C|/x`, the old form) is the drive C: on Windows, where a leading `/` would mean the
    // root of the current drive.
    let b = path.as_bytes();
    if windows
        && b.len() >= 3
        && b[0] == b'/'
        && b[1].is_ascii_alphabetic()
        && (b[2] == b':' || b[2] == b'|')
        && !matches!(b.get(3), Some(c) if *c != b'/' && *c != b'\\')
    {
        return Ok(PathBuf::from(format!("{}:{}", &path[1..2], &path[3..])));
    }
    Ok(PathBuf::from(path))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_three_forms_and_escapes() {
        assert_eq!(file_uri_to_path("file:///tmp/a%20b/resources/").unwrap(), PathBuf::from("/tmp/a b/resources/"));
        assert_eq!(file_uri_to_path("file:/tmp/x").unwrap(), PathBuf::from("/tmp/x"));
        assert_eq!(file_uri_to_path("file://localhost/tmp/x").unwrap(), PathBuf::from("/tmp/x"));
        assert!(file_uri_to_path("http://example.org/x").unwrap_err().contains("not a file URI"));
        assert!(file_uri_to_path("/tmp/x").is_err());
        assert!(file_uri_to_path("file:///tmp/%zz").unwrap_err().contains("percent-escape"));
    }

    #[test]
    fn windows_drive_letters() {
        assert_eq!(uri_to_path("file:///C:/Users/a%20b/resources/", true).unwrap(), PathBuf::from("C:/Users/a b/resources/"));
        assert_eq!(uri_to_path("file:/Z:/tmp/x", true).unwrap(), PathBuf::from("Z:/tmp/x"));
        assert_eq!(uri_to_path("file:///c|/x", true).unwrap(), PathBuf::from("c:/x"));
        assert_eq!(uri_to_path("file:///C:", true).unwrap(), PathBuf::from("C:"));
        // Not a drive: left alone; and elsewhere than Windows `/C:/x` is an ordinary path.
        assert_eq!(uri_to_path("file:///CD:/x", true).unwrap(), PathBuf::from("/CD:/x"));
        assert_eq!(uri_to_path("file:///C:/x", false).unwrap(), PathBuf::from("/C:/x"));
    }
}
