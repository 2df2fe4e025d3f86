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
//!   link-time optimisation; without either, one line saying the FMUs carry linux64 only.
//!
//! On a machine that is not x86_64 Linux, this machine's platform alone, with its own cargo.

use super::Library;
use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::Command;

const LINUX_TARGET: &str = "x86_64-unknown-linux-gnu";
const WINDOWS_TARGET: &str = "x86_64-pc-windows-gnu";
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
    /// cargo-zigbuild at this path, for linux64 with glibc 2.17.
    Zig(PathBuf),
    /// This machine's cargo with its installed Windows standard library, for win64.
    Windows,
    /// Debian's cargo with -Zbuild-std, for win64.
    DebianWindows,
}

/// Builds every model's libraries (full, and variant where `trimmable` says a variant can trim
/// the model) for every platform this machine can build, and returns them. `root` is the
/// source tree.
pub fn libraries(root: &Path, trimmable: impl Fn(&str) -> bool) -> Result<Vec<Library>, String> {
    let host_platform = super::platform().ok_or_else(|| {
        format!(
            "no FMI 2.0 platform for {}/{}: expected x86_64 or x86 Linux or Windows, or macOS",
            std::env::consts::OS,
            std::env::consts::ARCH
        )
    })?;
    let mut toolchains = Vec::new();
    if host_platform == "linux64" {
        match find_zigbuild(root) {
            Some(zigbuild) => toolchains.push(("linux64", Toolchain::Zig(zigbuild))),
            None => {
                eprintln!(
                    "note: linux64 is linked against this machine's glibc; for glibc 2.17, install cargo-zigbuild and ziglang (pip install -r tests/python/requirements.txt into .venv)"
                );
                toolchains.push(("linux64", Toolchain::Host));
            }
        }
    } else {
        toolchains.push((host_platform, Toolchain::Host));
    }
    if host_platform != "win64" {
        if on_path(MINGW_GCC).is_some() && windows_std_installed() {
            toolchains.push(("win64", Toolchain::Windows));
        } else if on_path(MINGW_GCC).is_some() && debian_windows_toolchain() {
            toolchains.push(("win64", Toolchain::DebianWindows));
        } else {
            eprintln!(
                "note: packing {host_platform} only; for win64 too: apt-get install mingw-w64, and rustup target add {WINDOWS_TARGET} (or apt-get install rustc-web cargo-web rust-web-src)"
            );
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
    Ok(libraries)
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
    let rustc = std::env::var_os("RUSTC").unwrap_or("rustc".into());
    Command::new(rustc)
        .args(["--print", "target-libdir", "--target", WINDOWS_TARGET])
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
        Toolchain::Zig(zigbuild) => {
            let mut command = Command::new(zigbuild);
            command
                .arg("zigbuild")
                .args(args)
                .arg("--target")
                .arg(format!("{LINUX_TARGET}.2.17"));
            // cargo-zigbuild runs zig as `python3 -m ziglang`: the python beside it has it.
            if let Some(bin) = zigbuild.parent() {
                command.env("PATH", path_with(bin));
            }
            (
                command,
                root.join(format!("target/{LINUX_TARGET}/{PROFILE}/examples")),
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
