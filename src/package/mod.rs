//! Packs an FMU: modelDescription.xml, the shared library of each platform under the model's
//! name, and a documentation page, zipped as `<out_dir>/<modelIdentifier>.fmu`; a scene file's
//! FMU also carries the file in resources/.

mod documentation;
pub mod platforms;
pub mod ssp;

use crate::scene_file::{self, SceneFile};
use std::fs::File;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use zip::write::SimpleFileOptions;

include!(concat!(env!("OUT_DIR"), "/model_descriptions.rs"));

/// The platform folder of binaries/ for the machine this library was built for; None where
/// FMI 2.0 names none (an aarch64 or riscv build is no linux64 library).
pub fn platform() -> Option<&'static str> {
    match (std::env::consts::OS, std::env::consts::ARCH) {
        ("linux", "x86_64") => Some("linux64"),
        ("linux", "x86") => Some("linux32"),
        ("windows", "x86_64") => Some("win64"),
        ("windows", "x86") => Some("win32"),
        ("macos", "x86_64" | "aarch64") => Some("darwin64"),
        _ => None,
    }
}

/// The file extension of a platform's shared libraries.
fn library_extension(platform: &str) -> &'static str {
    match platform {
        "win64" | "win32" => "dll",
        "darwin64" => "dylib",
        _ => "so",
    }
}

/// A compiled library and the platform folder it goes to.
pub struct Library {
    pub platform: &'static str,
    pub path: PathBuf,
}

/// The cdylib next to a binary of this crate (target/<profile>/libfriction_fmu.so).
pub fn library_beside(dir: &Path) -> PathBuf {
    let name = format!(
        "{}friction_fmu{}",
        std::env::consts::DLL_PREFIX,
        std::env::consts::DLL_SUFFIX
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

fn write_fmu(contents: &Contents, libraries: &[Library], out_dir: &Path) -> io::Result<PathBuf> {
    let binaries = libraries
        .iter()
        .map(|library| {
            std::fs::read(&library.path).map_err(|e| {
                io::Error::new(
                    e.kind(),
                    format!(
                        "cannot read the FMU library {}: {e}",
                        library.path.display()
                    ),
                )
            })
        })
        .collect::<io::Result<Vec<_>>>()?;
    std::fs::create_dir_all(out_dir)?;
    let id = contents.model_identifier;
    let path = out_dir.join(format!("{id}.fmu"));
    let mut zip = zip::ZipWriter::new(File::create(&path)?);
    let options = SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    zip.start_file("modelDescription.xml", options)?;
    zip.write_all(contents.xml.as_bytes())?;
    for (library, binary) in libraries.iter().zip(&binaries) {
        let platform = library.platform;
        let binary_path = format!("binaries/{platform}/{id}.{}", library_extension(platform));
        zip.start_file(binary_path, options.unix_permissions(0o755))?;
        zip.write_all(binary)?;
    }
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
pub fn pack(model_identifier: &str, libraries: &[Library], out_dir: &Path) -> io::Result<PathBuf> {
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
    write_fmu(&contents, libraries, out_dir)
}

/// Writes `<out_dir>/<name>.fmu` for a scene file: its trimmed modelDescription.xml, the same
/// library under the scene's name, its documentation page, and the file itself as
/// resources/scene.toml, where the library finds it again at fmi2Instantiate.
pub fn pack_scene(scene: &SceneFile, libraries: &[Library], out_dir: &Path) -> io::Result<PathBuf> {
    let (_, xml) = scene.model_description();
    let contents = Contents {
        model_identifier: &scene.name,
        xml: &xml,
        documentation: &documentation::scene_page(scene),
        resources: &[(scene_file::RESOURCE, scene.text.as_bytes())],
    };
    write_fmu(&contents, libraries, out_dir)
}
