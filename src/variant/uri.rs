//! fmuResourceLocation (a file: URI) to a path.

use crate::error::Error;
use std::path::PathBuf;

/// `file:///a/b%20c`, `file:/a/b` or `file://localhost/a/b` to `/a/b c`; Windows drive paths
/// (`file:///C:/x`) lose the slash before the drive; a plain absolute path (`/a/b`, `C:\x`)
/// stays as it is.
pub fn file_path(uri: &str) -> Result<PathBuf, Error> {
    let refused = |found: String, expected: &str| {
        Error::value_found(
            "fmuResourceLocation",
            format!("fmuResourceLocation {found}"),
            expected,
        )
    };
    // Some importers pass a plain absolute path, as FMI 1.0's fmuLocation could be, and FMI
    // 3.0's resourcePath is one (`C:\x\` on Windows): take it.
    let drive = uri
        .as_bytes()
        .get(1..3)
        .is_some_and(|s| s == b":\\" || s == b":/")
        && uri.as_bytes()[0].is_ascii_alphabetic();
    if uri.starts_with('/') || drive {
        return Ok(PathBuf::from(uri));
    }
    // The scheme is case-insensitive (RFC 3986, 3.1): FILE: is file:.
    let rest = uri
        .get(..5)
        .filter(|scheme| scheme.eq_ignore_ascii_case("file:"))
        .map(|_| &uri[5..])
        .ok_or_else(|| refused(format!("\"{uri}\" is not a file: URI"), "file:///..."))?;
    let rest = if let Some(authority) = rest.strip_prefix("//") {
        let slash = authority.find('/').unwrap_or(authority.len());
        let host = &authority[..slash];
        if !host.is_empty() && !host.eq_ignore_ascii_case("localhost") {
            return Err(refused(
                format!("\"{uri}\" names the host \"{host}\""),
                "a local file: URI",
            ));
        }
        &authority[slash..]
    } else {
        rest
    };
    let decoded = percent_decode(rest).ok_or_else(|| {
        refused(
            format!("\"{uri}\" has a bad %-escape"),
            "% followed by two hex digits, in UTF-8",
        )
    })?;
    let bytes = decoded.as_bytes();
    let path = if bytes.len() >= 3 && bytes[0] == b'/' && bytes[2] == b':' {
        decoded[1..].to_string()
    } else {
        decoded
    };
    if path.is_empty() {
        return Err(refused(format!("\"{uri}\" has no path"), "file:///..."));
    }
    Ok(PathBuf::from(path))
}

fn percent_decode(text: &str) -> Option<String> {
    let bytes = text.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = text.get(i + 1..i + 3)?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

#[cfg(test)]
mod tests {
    use super::file_path;
    use crate::error::Kind;
    use std::path::PathBuf;

    /// Oracle: RFC 8089's forms of a local file URI.
    #[test]
    fn file_uris_become_paths() {
        let p = |s: &str| file_path(s).map_err(|e| e.kind);
        let refused = Err(Kind::Value {
            name: "fmuResourceLocation",
        });
        assert_eq!(
            p("file:///tmp/a%20b/res"),
            Ok(PathBuf::from("/tmp/a b/res"))
        );
        assert_eq!(p("file:/tmp/x"), Ok(PathBuf::from("/tmp/x")));
        assert_eq!(p("file://localhost/tmp/x/"), Ok(PathBuf::from("/tmp/x/")));
        assert_eq!(p("file:///C:/fmu/res"), Ok(PathBuf::from("C:/fmu/res")));
        assert_eq!(p("/tmp/a b/res"), Ok(PathBuf::from("/tmp/a b/res")));
        // Schemes and host names are case-insensitive (RFC 3986, 3.1 and 3.2.2).
        assert_eq!(p("FILE:///tmp/x"), Ok(PathBuf::from("/tmp/x")));
        assert_eq!(p("File:/tmp/x"), Ok(PathBuf::from("/tmp/x")));
        assert_eq!(p("file://LocalHost/tmp/x"), Ok(PathBuf::from("/tmp/x")));
        assert_eq!(p("filex:///tmp/x"), refused);
        assert_eq!(p("http://x/y"), refused);
        assert_eq!(p("tmp/x"), refused);
        assert_eq!(p("file://server/share"), refused);
        assert_eq!(p("file:///a%2"), refused);
        assert_eq!(p("file:///a%zz"), refused);
    }
}
