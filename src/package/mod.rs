//! Packs an FMU: modelDescription.xml, the shared library under the model's name, and a
//! documentation page, zipped as `<out_dir>/<modelIdentifier>.fmu`; a scene file's FMU also
//! carries the file in resources/.

mod documentation;

use crate::scene_file::{self, SceneFile};
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

/// What one FMU holds besides the library.
struct Contents<'a> {
    model_identifier: &'a str,
    xml: &'a str,
    documentation: &'a str,
    /// Files under resources/: (name, bytes).
    resources: &'a [(&'a str, &'a [u8])],
}

fn write_fmu(contents: &Contents, library: &Path, out_dir: &Path) -> io::Result<PathBuf> {
    let binary = std::fs::read(library).map_err(|e| {
        io::Error::new(
            e.kind(),
            format!("cannot read the FMU library {}: {e}", library.display()),
        )
    })?;
    std::fs::create_dir_all(out_dir)?;
    let id = contents.model_identifier;
    let path = out_dir.join(format!("{id}.fmu"));
    let mut zip = zip::ZipWriter::new(File::create(&path)?);
    let options = SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    zip.start_file("modelDescription.xml", options)?;
    zip.write_all(contents.xml.as_bytes())?;
    let binary_path = format!("binaries/{}/{id}.{}", platform(), library_extension());
    zip.start_file(binary_path, options.unix_permissions(0o755))?;
    zip.write_all(&binary)?;
    zip.start_file("documentation/index.html", options)?;
    zip.write_all(contents.documentation.as_bytes())?;
    for (name, bytes) in contents.resources {
        zip.start_file(format!("resources/{name}"), options)?;
        zip.write_all(bytes)?;
    }
    zip.finish()?;
    Ok(path)
}

/// Writes `<out_dir>/<model_identifier>.fmu` from the compiled `library` and returns its path.
pub fn pack(model_identifier: &str, library: &Path, out_dir: &Path) -> io::Result<PathBuf> {
    let not_found = |what: String| io::Error::new(io::ErrorKind::NotFound, what);
    let xml = model_description(model_identifier)
        .ok_or_else(|| not_found(format!("no model {model_identifier} in this build")))?;
    let table = crate::scenes::model(model_identifier)
        .ok_or_else(|| not_found(format!("no scene for {model_identifier}")))?
        .table;
    let contents = Contents {
        model_identifier,
        xml,
        documentation: &documentation::page(table),
        resources: &[],
    };
    write_fmu(&contents, library, out_dir)
}

/// Writes `<out_dir>/<name>.fmu` for a scene file: its trimmed modelDescription.xml, the same
/// library under the scene's name, its documentation page, and the file itself as
/// resources/scene.toml, where the library finds it again at fmi2Instantiate.
pub fn pack_scene(scene: &SceneFile, library: &Path, out_dir: &Path) -> io::Result<PathBuf> {
    let (_, xml) = scene.model_description();
    let contents = Contents {
        model_identifier: &scene.name,
        xml: &xml,
        documentation: &documentation::scene_page(scene),
        resources: &[(scene_file::RESOURCE, scene.text.as_bytes())],
    };
    write_fmu(&contents, library, out_dir)
}
