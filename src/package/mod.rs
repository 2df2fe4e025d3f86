//! Packs an FMU: modelDescription.xml, the shared library under the model's name, and a
//! documentation page, zipped as `<out_dir>/<modelIdentifier>.fmu`.

mod documentation;

use std::fs::File;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use zip::write::SimpleFileOptions;

include!(concat!(env!("OUT_DIR"), "/model_descriptions.rs"));

/// The platform folder of binaries/ for the machine this library was built for.
pub fn platform() -> &'static str {
    match (std::env::consts::OS, std::env::consts::ARCH) {
        ("linux", "x86_64") => "linux64",
        ("linux", "x86") => "linux32",
        ("windows", "x86_64") => "win64",
        ("windows", "x86") => "win32",
        ("macos", _) => "darwin64",
        _ => "linux64",
    }
}

fn library_extension() -> &'static str {
    match std::env::consts::OS {
        "windows" => "dll",
        "macos" => "dylib",
        _ => "so",
    }
}

/// The cdylib next to a binary of this crate (target/<profile>/libfriction_fmu.so).
pub fn library_beside(dir: &Path) -> PathBuf {
    let name = format!(
        "{}friction_fmu.{}",
        std::env::consts::DLL_PREFIX,
        library_extension()
    );
    dir.join(name)
}

pub fn model_description(model_identifier: &str) -> Option<&'static str> {
    XMLS.iter()
        .find(|(id, _)| *id == model_identifier)
        .map(|(_, xml)| *xml)
}

/// Writes `<out_dir>/<model_identifier>.fmu` from the compiled `library` and returns its path.
pub fn pack(model_identifier: &str, library: &Path, out_dir: &Path) -> io::Result<PathBuf> {
    let not_found = |what: String| io::Error::new(io::ErrorKind::NotFound, what);
    let xml = model_description(model_identifier)
        .ok_or_else(|| not_found(format!("no model {model_identifier} in this build")))?;
    let table = crate::scenes::model(model_identifier)
        .ok_or_else(|| not_found(format!("no scene for {model_identifier}")))?
        .table;
    let binary = std::fs::read(library).map_err(|e| {
        io::Error::new(
            e.kind(),
            format!("cannot read the FMU library {}: {e}", library.display()),
        )
    })?;
    std::fs::create_dir_all(out_dir)?;
    let path = out_dir.join(format!("{model_identifier}.fmu"));
    let mut zip = zip::ZipWriter::new(File::create(&path)?);
    let options = SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    zip.start_file("modelDescription.xml", options)?;
    zip.write_all(xml.as_bytes())?;
    let binary_path = format!(
        "binaries/{}/{model_identifier}.{}",
        platform(),
        library_extension()
    );
    zip.start_file(binary_path, options.unix_permissions(0o755))?;
    zip.write_all(&binary)?;
    zip.start_file("documentation/index.html", options)?;
    zip.write_all(documentation::page(table).as_bytes())?;
    zip.finish()?;
    Ok(path)
}
