//! The two standards an FMU is packed for, and what each calls a platform's binaries/ folder.
//! One library serves both (it exports the fmi2 and the fmi3 functions); only the folder it is
//! packed under and the modelDescription.xml beside it differ.

/// The FMI standard of one FMU.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Standard {
    Fmi2,
    Fmi3,
}

/// The platform FMI 3.0 names for a library built for aarch64 Linux; FMI 2.0 names none, so
/// such a library goes into FMI 3.0 FMUs only.
pub const AARCH64_LINUX: &str = "aarch64-linux";

impl Standard {
    /// The binaries/ folder of `platform` ([`super::Library::platform`]), or None where the
    /// standard names no such platform.
    pub fn binaries_folder(self, platform: &'static str) -> Option<&'static str> {
        match self {
            Standard::Fmi2 => (platform != AARCH64_LINUX).then_some(platform),
            Standard::Fmi3 => fmi3_platform(platform, std::env::consts::ARCH),
        }
    }
}

/// FMI 3.0's `<architecture>-<operating system>` name of a platform; `host_arch` tells a macOS
/// library's architecture, which FMI 2.0's darwin64 leaves open.
fn fmi3_platform(platform: &str, host_arch: &str) -> Option<&'static str> {
    match platform {
        "linux64" => Some("x86_64-linux"),
        "linux32" => Some("x86-linux"),
        "win64" => Some("x86_64-windows"),
        "win32" => Some("x86-windows"),
        "darwin64" if host_arch == "aarch64" => Some("aarch64-darwin"),
        "darwin64" => Some("x86_64-darwin"),
        AARCH64_LINUX => Some(AARCH64_LINUX),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::{fmi3_platform, Standard, AARCH64_LINUX};

    #[test]
    fn each_standard_names_its_own_folders() {
        assert_eq!(Standard::Fmi2.binaries_folder("linux64"), Some("linux64"));
        assert_eq!(Standard::Fmi2.binaries_folder("win64"), Some("win64"));
        assert_eq!(Standard::Fmi2.binaries_folder(AARCH64_LINUX), None);
        assert_eq!(
            Standard::Fmi3.binaries_folder("linux64"),
            Some("x86_64-linux")
        );
        assert_eq!(
            Standard::Fmi3.binaries_folder("win64"),
            Some("x86_64-windows")
        );
        assert_eq!(
            Standard::Fmi3.binaries_folder(AARCH64_LINUX),
            Some("aarch64-linux")
        );
        assert_eq!(fmi3_platform("darwin64", "aarch64"), Some("aarch64-darwin"));
        assert_eq!(fmi3_platform("darwin64", "x86_64"), Some("x86_64-darwin"));
    }
}
