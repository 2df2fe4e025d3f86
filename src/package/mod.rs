//! Packs an FMU: modelDescription.xml, the shared library of each platform under the model's
//! name, and a documentation page, zipped as `<out_dir>/<modelIdentifier>.fmu`; a variant's
//! FMU also carries the file in resources/. The FMI 3.0 FMU of a model or variant carries the
//! same library, under FMI 3.0's platform names, beside its FMI 3.0 modelDescription.xml.

mod documentation;
pub mod osp;
pub mod platforms;
pub mod ssp;
pub mod standard;

pub use standard::Standard;

use crate::variant::{self, Variant};
use std::fs::File;
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use zip::write::SimpleFileOptions;

include!(concat!(env!("OUT_DIR"), "/model_descriptions.rs"));
include!(concat!(env!("OUT_DIR"), "/model_descriptions_fmi3.rs"));

/// The platform folder of binaries/ for the machine this library was built for; None where
/// FMI 2.0 names none (an aarch64 or riscv build is no linux64 library).
pub fn platform() -> Option<&'static str> {
    platform_of(std::env::consts::OS, std::env::consts::ARCH)
}

/// The platform folder of binaries/ for an operating system and architecture as Rust names them.
fn platform_of(os: &str, arch: &str) -> Option<&'static str> {
    match (os, arch) {
        ("linux", "x86_64") => Some("linux64"),
        ("linux", "x86") => Some("linux32"),
        ("windows", "x86_64") => Some("win64"),
        ("windows", "x86") => Some("win32"),
        ("macos", "x86_64" | "aarch64") => Some("darwin64"),
        _ => None,
    }
}

/// The file extension of a platform's shared libraries.
pub(crate) fn library_extension(platform: &str) -> &'static str {
    match platform {
        "win64" | "win32" => "dll",
        "darwin64" => "dylib",
        _ => "so",
    }
}

/// A compiled library: the platform it is for, and the FMUs it is for (a model's full FMU, or
/// its variant FMUs).
pub struct Library {
    /// FMI 2.0's binaries/ folder (linux64, win64), or for a platform FMI 2.0 names none,
    /// FMI 3.0's ([`standard::AARCH64_LINUX`]); [`Standard::binaries_folder`] names each
    /// standard's folder.
    pub platform: &'static str,
    pub model: &'static str,
    pub variant: bool,
    pub path: PathBuf,
}

/// A model's FMI 2.0 modelDescription.xml.
pub fn model_description(model_identifier: &str) -> Option<&'static str> {
    model_description_for(Standard::Fmi2, model_identifier)
}

/// A model's modelDescription.xml for `standard`; the FMI 3.0 one's instantiationToken is the
/// FMI 2.0 one's GUID.
pub fn model_description_for(standard: Standard, model_identifier: &str) -> Option<&'static str> {
    let xmls = match standard {
        Standard::Fmi2 => XMLS,
        Standard::Fmi3 => FMI3_XMLS,
    };
    xmls.iter()
        .find(|(id, _)| *id == model_identifier)
        .map(|(_, xml)| *xml)
}

/// The source tree's copy of every model's modelDescription.xml (committed, so that interface
/// changes show in diffs).
pub const COMMITTED_XML_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/modelDescription");

/// The committed copies of the FMI 3.0 ones, in `fmi3/` under [`COMMITTED_XML_DIR`].
pub const COMMITTED_FMI3_XML_DIR: &str =
    concat!(env!("CARGO_MANIFEST_DIR"), "/modelDescription/fmi3");

/// The committed copy of a model's modelDescription.xml for `standard`.
pub fn committed_xml_path(standard: Standard, model_identifier: &str) -> PathBuf {
    let dir = match standard {
        Standard::Fmi2 => COMMITTED_XML_DIR,
        Standard::Fmi3 => COMMITTED_FMI3_XML_DIR,
    };
    Path::new(dir).join(format!("{model_identifier}.xml"))
}

/// Refreshes the committed copies of both standards when run from the source tree
/// ([`COMMITTED_XML_DIR`] exists); returns the files it rewrote.
pub fn refresh_committed_xml() -> io::Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    if !Path::new(COMMITTED_XML_DIR).is_dir() {
        return Ok(written);
    }
    std::fs::create_dir_all(COMMITTED_FMI3_XML_DIR)?;
    for (standard, xmls) in [(Standard::Fmi2, XMLS), (Standard::Fmi3, FMI3_XMLS)] {
        for (id, xml) in xmls {
            let path = committed_xml_path(standard, id);
            if std::fs::read_to_string(&path).ok().as_deref() != Some(*xml) {
                std::fs::write(&path, xml)?;
                written.push(path);
            }
        }
    }
    Ok(written)
}

/// What one FMU holds besides the library.
struct Contents<'a> {
    standard: Standard,
    model_identifier: &'a str,
    xml: &'a str,
    documentation: &'a str,
    /// Files under resources/: (name, bytes).
    resources: &'a [(&'a str, &'a [u8])],
}

/// Writes the FMU with the libraries of `model` (its variant FMUs' when `variant`), one per
/// platform the FMU's standard names.
fn write_fmu(
    contents: &Contents,
    libraries: &[Library],
    (model, variant): (&str, bool),
    out_dir: &Path,
) -> io::Result<PathBuf> {
    let libraries: Vec<(&str, &Library)> = libraries
        .iter()
        .filter(|l| l.model == model && l.variant == variant)
        .filter_map(|l| Some((contents.standard.binaries_folder(l.platform)?, l)))
        .collect();
    if libraries.is_empty() {
        return Err(io::Error::new(
            io::ErrorKind::NotFound,
            format!("no library was built for {model}"),
        ));
    }
    let binaries = libraries
        .iter()
        .map(|(_, library)| {
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
    for ((folder, library), binary) in libraries.iter().zip(&binaries) {
        let extension = library_extension(library.platform);
        let binary_path = format!("binaries/{folder}/{id}.{extension}");
        zip.start_file(binary_path, options.unix_permissions(0o755))?;
        zip.write_all(binary)?;
    }
    zip.start_file("documentation/index.html", options)?;
    zip.write_all(contents.documentation.as_bytes())?;
    // FMI 2.0, 2.3 (and FMI 3.0, 2.5.1): the licenses of the FMU's code, where importers look
    // for them.
    for (name, text) in LICENSES {
        zip.start_file(format!("documentation/licenses/{name}"), options)?;
        zip.write_all(text.as_bytes())?;
    }
    for (name, bytes) in contents.resources {
        zip.start_file(format!("resources/{name}"), options)?;
        zip.write_all(bytes)?;
    }
    zip.finish()?;
    Ok(path)
}

/// The project's licenses (Cargo.toml: MIT OR Apache-2.0), which every FMU carries.
const LICENSES: [(&str, &str); 2] = [
    ("LICENSE-MIT.txt", include_str!("../../LICENSE-MIT")),
    ("LICENSE-APACHE.txt", include_str!("../../LICENSE-APACHE")),
];

/// Writes `<out_dir>/<model_identifier>.fmu` (FMI 2.0) from the compiled `libraries` and
/// returns its path.
pub fn pack(model_identifier: &str, libraries: &[Library], out_dir: &Path) -> io::Result<PathBuf> {
    pack_for(Standard::Fmi2, model_identifier, libraries, out_dir)
}

/// Writes `<out_dir>/<model_identifier>.fmu` for `standard` from the compiled `libraries` and
/// returns its path.
pub fn pack_for(
    standard: Standard,
    model_identifier: &str,
    libraries: &[Library],
    out_dir: &Path,
) -> io::Result<PathBuf> {
    let not_found = |what: String| io::Error::new(io::ErrorKind::NotFound, what);
    let xml = model_description_for(standard, model_identifier)
        .ok_or_else(|| not_found(format!("no model {model_identifier} in this build")))?;
    let model = crate::models::model(model_identifier)
        .ok_or_else(|| not_found(format!("no simulation for {model_identifier}")))?;
    let contents = Contents {
        standard,
        model_identifier,
        xml,
        documentation: &documentation::page(model, standard),
        resources: &[],
    };
    write_fmu(&contents, libraries, (model_identifier, false), out_dir)
}

/// Writes `<out_dir>/<name>.fmu` (FMI 2.0) for a variant: its trimmed modelDescription.xml, the
/// same library under the simulation's name, its documentation page, and the file itself as
/// resources/variant.toml, where the library finds it again at instantiation.
pub fn pack_variant(
    variant: &Variant,
    libraries: &[Library],
    out_dir: &Path,
) -> io::Result<PathBuf> {
    pack_variant_for(Standard::Fmi2, variant, libraries, out_dir)
}

/// Writes a variant's FMU for `standard`, as [`pack_variant`] does for FMI 2.0.
pub fn pack_variant_for(
    standard: Standard,
    variant: &Variant,
    libraries: &[Library],
    out_dir: &Path,
) -> io::Result<PathBuf> {
    let xml = match standard {
        Standard::Fmi2 => variant.model_description().1,
        Standard::Fmi3 => variant.model_description_fmi3().1,
    };
    let contents = Contents {
        standard,
        model_identifier: &variant.name,
        xml: &xml,
        documentation: &documentation::variant_page(variant, standard),
        resources: &[(variant::RESOURCE, variant.text.as_bytes())],
    };
    let model = variant.model.table.model_identifier;
    write_fmu(&contents, libraries, (model, true), out_dir)
}

#[cfg(test)]
mod tests {
    use super::platform_of;

    #[test]
    fn only_the_platforms_fmi_names_have_a_binaries_folder() {
        assert_eq!(platform_of("linux", "x86_64"), Some("linux64"));
        assert_eq!(platform_of("windows", "x86_64"), Some("win64"));
        assert_eq!(platform_of("macos", "aarch64"), Some("darwin64"));
        for (os, arch) in [
            ("linux", "aarch64"),
            ("linux", "riscv64"),
            ("freebsd", "x86_64"),
        ] {
            assert_eq!(platform_of(os, arch), None, "{os}/{arch}");
        }
    }
}
