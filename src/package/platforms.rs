//! The libraries the FMUs carry: one per model and kind (a full model's, or a variant FMU's that
//! also reads its variant), all built from `binary/` in one cargo run for every platform whose
//! toolchain is installed, in the `fmu` profile (stripped):
//!
//! - linux64: `cargo-zigbuild` and `ziglang` from PyPI (in `.venv` or on PATH) link against
//!   glibc 2.17's symbol versions; without them, this machine's cargo and glibc, and one line
//!   saying so;
//! - win64: this machine's toolchain with its `x86_64-pc-windows-gnu` standard library (`rustup
//!   target add x86_64-pc-windows-gnu`), or else Debian's `rustc-web`, `cargo-web` and
//!   `rust-web-src`, which build that standard library from source; `mingw-w64` links, with
//!   link-time optimisation;
//! - aarch64-linux (FMI 3.0 only: FMI 2.0 names no such platform): `cargo-zigbuild` again, for
//!   glibc 2.17, with the `aarch64-unknown-linux-gnu` standard library (`rustup target add
//!   aarch64-unknown-linux-gnu`).
//!
//! What cannot be built is left out, and [`Built::missing`] says which platforms and the one
//! command that adds them, for the main command to print at the end of its output.
//!
//! On a machine that is not x86_64 Linux, this machine's platform alone, with its own cargo.

use super::Library;
use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::Command;

const LINUX_TARGET: &str = "x86_64-unknown-linux-gnu";
const WINDOWS_TARGET: &str = "x86_64-pc-windows-gnu";
const AARCH64_TARGET: &str = "aarch64-unknown-linux-gnu";
/// The oldest glibc whose symbol versions the Linux libraries link against.
const GLIBC: &str = "2.17";
const MINGW_GCC: &str = "x86_64-w64-mingw32-gcc";
/// Debian's Rust toolchain (rustc-web, cargo-web) and the standard library's source.
const DEBIAN_CARGO: &str = "/usr/bin/cargo";
const DEBIAN_RUSTC: &str = "/usr/bin/rustc";
const DEBIAN_STD_SOURCE: &str = "/usr/lib/rustlib/src/rust/library";
const PACKAGE: &str = "friction-fmu-binary";
/// mingw-w64's linker keeps unreferenced code in a DLL (every model's); link-time optimisation
/// leaves out what the one model does not reach. Fat rather than thin: the dependencies are then
/// compiled to bitcode alone, and the whole build takes less CPU (docs/platforms.md).
const WINDOWS_LTO: &str = "fat";
const PROFILE: &str = "fmu";

/// How one platform's libraries are built.
enum Toolchain {
    /// This machine's cargo, for its own platform.
    Host,
    /// cargo-zigbuild at this path, for a Linux target with glibc 2.17.
    Zig(PathBuf, &'static str),
    /// This machine's cargo with its installed Windows standard library, for win64.
    Windows,
    /// Debian's cargo with -Zbuild-std, for win64.
    DebianWindows,
}

/// The libraries built, and what could not be.
pub struct Built {
    pub libraries: Vec<Library>,
    pub missing: Missing,
}

/// Platforms left out (or built short of what they should be), and what adds them.
#[derive(Debug, Default, PartialEq)]
pub struct Missing {
    /// One line per platform: its name and why.
    pub platforms: Vec<String>,
    /// rustup targets to add.
    targets: Vec<&'static str>,
    /// Debian packages to install.
    apt: Vec<&'static str>,
    /// Whether cargo-zigbuild and ziglang are to be installed into .venv.
    zig: bool,
}

impl Missing {
    /// The one shell command that adds every missing platform; None when nothing is missing.
    pub fn command(&self) -> Option<String> {
        let mut parts = Vec::new();
        if !self.targets.is_empty() {
            parts.push(format!("rustup target add {}", self.targets.join(" ")));
        }
        if !self.apt.is_empty() {
            parts.push(format!("sudo apt-get install -y {}", self.apt.join(" ")));
        }
        if self.zig {
            parts.push(
                "(test -d .venv || python3 -m venv .venv) && .venv/bin/pip install cargo-zigbuild ziglang"
                    .to_string(),
            );
        }
        (!parts.is_empty()).then(|| parts.join(" && "))
    }

    /// What the main command prints last: nothing when every platform was built.
    pub fn report(&self) -> Option<String> {
        let command = self.command()?;
        let mut text = String::from("platforms not built, so the FMUs go without them:\n");
        for line in &self.platforms {
            text.push_str(&format!("  {line}\n"));
        }
        text.push_str(&format!(
            "to add them, run from the source tree, then build again:\n  {command}"
        ));
        Some(text)
    }
}

/// Builds every model's libraries (full, and variant where `trimmable` says a variant can trim
/// the model) for every platform this machine can build, and returns them with what could not
/// be built. `root` is the source tree.
pub fn libraries(root: &Path, trimmable: impl Fn(&str) -> bool) -> Result<Built, String> {
    let host_platform = super::platform().ok_or_else(|| {
        format!(
            "no FMI 2.0 platform for {}/{}: expected x86_64 or x86 Linux or Windows, or macOS",
            std::env::consts::OS,
            std::env::consts::ARCH
        )
    })?;
    let mut toolchains = Vec::new();
    let mut missing = Missing::default();
    let zigbuild = find_zigbuild(root);
    if host_platform == "linux64" {
        match &zigbuild {
            Some(zigbuild) => {
                toolchains.push(("linux64", Toolchain::Zig(zigbuild.clone(), LINUX_TARGET)))
            }
            None => {
                missing.platforms.push(format!(
                    "x86_64-linux for glibc {GLIBC} (linux64 is linked against this machine's glibc instead): cargo-zigbuild and ziglang are not in .venv"
                ));
                missing.zig = true;
                toolchains.push(("linux64", Toolchain::Host));
            }
        }
    } else {
        toolchains.push((host_platform, Toolchain::Host));
    }
    if host_platform != "win64" {
        let mingw = on_path(MINGW_GCC).is_some();
        if mingw && windows_std_installed() {
            toolchains.push(("win64", Toolchain::Windows));
        } else if mingw && debian_windows_toolchain() {
            toolchains.push(("win64", Toolchain::DebianWindows));
        } else {
            let mut why = Vec::new();
            if !mingw {
                why.push("mingw-w64 is not installed");
                missing.apt.push("mingw-w64");
            }
            if !windows_std_installed() {
                why.push("rustup has no x86_64-pc-windows-gnu standard library");
                missing.targets.push(WINDOWS_TARGET);
            }
            missing
                .platforms
                .push(format!("x86_64-windows (win64): {}", why.join(", ")));
        }
    }
    if host_platform == "linux64" {
        let std = std_installed(AARCH64_TARGET);
        match (&zigbuild, std) {
            (Some(zigbuild), true) => toolchains.push((
                super::standard::AARCH64_LINUX,
                Toolchain::Zig(zigbuild.clone(), AARCH64_TARGET),
            )),
            _ => {
                let mut why = Vec::new();
                if zigbuild.is_none() {
                    why.push("cargo-zigbuild and ziglang are not in .venv");
                    missing.zig = true;
                }
                if !std {
                    why.push("rustup has no aarch64-unknown-linux-gnu standard library");
                    missing.targets.push(AARCH64_TARGET);
                }
                missing.platforms.push(format!(
                    "aarch64-linux (FMI 3.0 FMUs only): {}",
                    why.join(", ")
                ));
            }
        }
    }
    let mut libraries = Vec::new();
    for (platform, toolchain) in &toolchains {
        let built = build(toolchain, root).map_err(|e| format!("{platform} libraries: {e}"))?;
        for model in crate::models::MODELS {
            let model = model.table.model_identifier;
            for variant in [false, true] {
                if variant && !trimmable(model) {
                    continue;
                }
                let name = if variant {
                    format!("{model}_variant")
                } else {
                    model.to_string()
                };
                let prefix = if *platform == "win64" { "" } else { "lib" };
                let extension = super::library_extension(platform);
                libraries.push(Library {
                    platform,
                    model,
                    variant,
                    path: built.join(format!("{prefix}{name}.{extension}")),
                });
            }
        }
    }
    Ok(Built { libraries, missing })
}

fn on_path(program: &str) -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|dir| dir.join(program))
        .find(|candidate| candidate.is_file())
}

fn find_zigbuild(root: &Path) -> Option<PathBuf> {
    let venv = root.join(".venv/bin/cargo-zigbuild");
    venv.is_file()
        .then_some(venv)
        .or_else(|| on_path("cargo-zigbuild"))
}

/// Whether this machine's compiler has the Windows standard library (rustup's rust-std
/// component for the target).
fn windows_std_installed() -> bool {
    std_installed(WINDOWS_TARGET)
}

/// Whether this machine's compiler has the standard library of `target` (rustup's rust-std
/// component for it).
fn std_installed(target: &str) -> bool {
    let rustc = std::env::var_os("RUSTC").unwrap_or("rustc".into());
    Command::new(rustc)
        .args(["--print", "target-libdir", "--target", target])
        .output()
        .ok()
        .filter(|output| output.status.success())
        .map(|output| PathBuf::from(String::from_utf8_lossy(&output.stdout).trim()))
        .is_some_and(|libdir| has_std(&libdir))
}

/// Whether `libdir` holds a compiled standard library.
fn has_std(libdir: &Path) -> bool {
    std::fs::read_dir(libdir).is_ok_and(|entries| {
        entries.filter_map(Result::ok).any(|entry| {
            let name = entry.file_name();
            let name = name.to_string_lossy();
            name.starts_with("libstd-") && name.ends_with(".rlib")
        })
    })
}

fn debian_windows_toolchain() -> bool {
    Path::new(DEBIAN_CARGO).is_file()
        && Path::new(DEBIAN_RUSTC).is_file()
        && Path::new(DEBIAN_STD_SOURCE).is_dir()
}

/// PATH with `first` in front.
fn path_with(first: &Path) -> OsString {
    let rest = std::env::var_os("PATH").unwrap_or_default();
    std::env::join_paths(std::iter::once(first.to_path_buf()).chain(std::env::split_paths(&rest)))
        .unwrap_or(rest)
}

/// Builds every library of `binary/`; returns the directory cargo wrote them to.
fn build(toolchain: &Toolchain, root: &Path) -> Result<PathBuf, String> {
    let args = [
        "--quiet",
        "--examples",
        "--package",
        PACKAGE,
        "--profile",
        PROFILE,
    ];
    let (mut command, built) = match toolchain {
        Toolchain::Host => {
            let mut command = Command::new(std::env::var_os("CARGO").unwrap_or("cargo".into()));
            command.arg("build").args(args);
            (command, root.join("target").join(PROFILE).join("examples"))
        }
        Toolchain::Zig(zigbuild, target) => {
            let mut command = Command::new(zigbuild);
            command
                .arg("zigbuild")
                .args(args)
                .arg("--target")
                .arg(format!("{target}.{GLIBC}"));
            // cargo-zigbuild runs zig as `python3 -m ziglang`: the python beside it has it.
            if let Some(bin) = zigbuild.parent() {
                command.env("PATH", path_with(bin));
            }
            (
                command,
                root.join(format!("target/{target}/{PROFILE}/examples")),
            )
        }
        Toolchain::Windows => {
            let mut command = Command::new(std::env::var_os("CARGO").unwrap_or("cargo".into()));
            command
                .arg("build")
                .args(args)
                .args(["--target", WINDOWS_TARGET])
                .env("CARGO_TARGET_X86_64_PC_WINDOWS_GNU_LINKER", MINGW_GCC)
                // As for DebianWindows.
                .env("CARGO_PROFILE_FMU_LTO", WINDOWS_LTO);
            (
                command,
                root.join(format!("target/{WINDOWS_TARGET}/{PROFILE}/examples")),
            )
        }
        Toolchain::DebianWindows => {
            let target_dir = root.join("target/win64");
            let mut command = Command::new(DEBIAN_CARGO);
            command
                .arg("build")
                .args(args)
                .args(["-Zbuild-std=std", "--target", WINDOWS_TARGET])
                .env("PATH", path_with(Path::new("/usr/bin")))
                .env("RUSTC", DEBIAN_RUSTC)
                // -Zbuild-std is unstable: Debian's stable compiler allows it so.
                .env("RUSTC_BOOTSTRAP", "1")
                .env("CARGO_TARGET_DIR", &target_dir)
                .env("CARGO_TARGET_X86_64_PC_WINDOWS_GNU_LINKER", MINGW_GCC)
                .env("CARGO_PROFILE_FMU_LTO", WINDOWS_LTO)
                .env_remove("RUSTUP_TOOLCHAIN")
                .env_remove("RUSTC_WRAPPER")
                .env_remove("CARGO");
            let built = target_dir.join(format!("{WINDOWS_TARGET}/{PROFILE}/examples"));
            (command, built)
        }
    };
    command.current_dir(root);
    let output = command
        .output()
        .map_err(|e| format!("cannot start cargo: {e}"))?;
    if !output.status.success() {
        let stderr = String::from_utf8_lossy(&output.stderr);
        let lines: Vec<&str> = stderr.lines().collect();
        let tail = lines[lines.len().saturating_sub(20)..].join("\n");
        return Err(format!("the build failed ({}):\n{tail}", output.status));
    }
    Ok(built)
}

#[cfg(test)]
mod tests {
    use super::Missing;

    /// The library targets of binary/Cargo.toml follow the model list: one `<Model>` target a
    /// model, one `<Model>_variant` a model a variant can trim, and no other; each target's
    /// source exports its kind. Adding a model to src/models/list.rs without its targets fails
    /// here, naming what to add.
    #[test]
    fn the_library_targets_follow_the_model_list() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
        let manifest =
            std::fs::read_to_string(root.join("binary/Cargo.toml")).expect("binary/Cargo.toml");
        let parsed: toml::Table = manifest.parse().expect("binary/Cargo.toml is TOML");
        let targets: Vec<(String, String)> = parsed["example"]
            .as_array()
            .expect("[[example]] targets")
            .iter()
            .map(|t| {
                (
                    t["name"].as_str().unwrap().to_string(),
                    t["path"].as_str().unwrap().to_string(),
                )
            })
            .collect();
        let mut expected = Vec::new();
        for model in crate::models::MODELS {
            let id = model.table.model_identifier;
            expected.push((id.to_string(), "full"));
            if crate::variant::trimmable(id) {
                expected.push((format!("{id}_variant"), "variant"));
            }
        }
        let names: Vec<&str> = targets.iter().map(|(name, _)| name.as_str()).collect();
        for (name, kind) in &expected {
            let Some((_, path)) = targets.iter().find(|(n, _)| n == name) else {
                panic!("binary/Cargo.toml has no [[example]] {name:?} (crate-type cdylib, exporting the {kind} library): it has {names:?}");
            };
            let source = std::fs::read_to_string(root.join("binary").join(path))
                .expect("the target's source");
            assert!(
                source.contains("export_fmu_library!(") && source.contains(&format!(", {kind});")),
                "binary/{path} does not export the {kind} library of {name}"
            );
        }
        assert_eq!(
            names.len(),
            expected.len(),
            "binary/Cargo.toml has targets no model needs: {names:?}"
        );
    }

    /// Oracle: the commands docs/platforms.md gives for each platform, joined into one line.
    #[test]
    fn the_missing_platforms_name_one_command() {
        assert_eq!(Missing::default().report(), None);
        let missing = Missing {
            platforms: vec!["x86_64-windows (win64): mingw-w64 is not installed".into()],
            targets: vec!["x86_64-pc-windows-gnu", "aarch64-unknown-linux-gnu"],
            apt: vec!["mingw-w64"],
            zig: true,
        };
        assert_eq!(
            missing.command().unwrap(),
            "rustup target add x86_64-pc-windows-gnu aarch64-unknown-linux-gnu && sudo apt-get install -y mingw-w64 && (test -d .venv || python3 -m venv .venv) && .venv/bin/pip install cargo-zigbuild ziglang"
        );
        let report = missing.report().unwrap();
        assert!(report.starts_with("platforms not built"));
        assert!(report.ends_with(&missing.command().unwrap()));
    }
}
