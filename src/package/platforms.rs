//! The libraries an FMU carries, one per platform: linux64 linked against glibc 2.17 (so it loads
//! on RHEL 7 and later, Ubuntu 14.04 and later), win64 cross-built, each when its toolchain is
//! installed; otherwise the library this machine built, and one line saying what is missing.
//!
//! - linux64: `cargo-zigbuild` and `ziglang` from PyPI (in `.venv` or on PATH) link against
//!   glibc 2.17's symbol versions;
//! - win64: Debian's `rustc-web`, `cargo-web` and `rust-web-src` build the standard library for
//!   `x86_64-pc-windows-gnu` (the rustup toolchain here has no Windows target), `mingw-w64` links.

use super::Library;
use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::Command;

const LINUX_TARGET: &str = "x86_64-unknown-linux-gnu";
const WINDOWS_TARGET: &str = "x86_64-pc-windows-gnu";
const MINGW_GCC: &str = "x86_64-w64-mingw32-gcc";
const MINGW_STRIP: &str = "x86_64-w64-mingw32-strip";
/// Debian's Rust toolchain (rustc-web, cargo-web) and the standard library's source.
const DEBIAN_CARGO: &str = "/usr/bin/cargo";
const DEBIAN_RUSTC: &str = "/usr/bin/rustc";
const DEBIAN_STD_SOURCE: &str = "/usr/lib/rustlib/src/rust/library";

/// Builds what the installed toolchains can build and returns every platform's library, with
/// `host` (this machine's build of the crate) for the platform it was built for when nothing
/// better is installed. `root` is the source tree.
pub fn libraries(host: &Path, root: &Path) -> Result<Vec<Library>, String> {
    let host_platform = super::platform().ok_or_else(|| {
        format!(
            "no FMI 2.0 platform for {}/{}: expected x86_64 or x86 Linux or Windows, or macOS",
            std::env::consts::OS,
            std::env::consts::ARCH
        )
    })?;
    let mut libraries = Vec::new();
    if host_platform == "linux64" {
        libraries.push(match find_zigbuild(root) {
            Some(zigbuild) => Library {
                platform: "linux64",
                path: linux64_for_glibc_2_17(&zigbuild, root)?,
            },
            None => {
                eprintln!(
                    "note: linux64 is linked against this machine's glibc; for glibc 2.17, install cargo-zigbuild and ziglang (pip install -r tests/python/requirements.txt into .venv)"
                );
                Library {
                    platform: "linux64",
                    path: host.to_path_buf(),
                }
            }
        });
    } else {
        libraries.push(Library {
            platform: host_platform,
            path: host.to_path_buf(),
        });
    }
    if host_platform != "win64" {
        if windows_toolchain() {
            libraries.push(Library {
                platform: "win64",
                path: win64(root)?,
            });
        } else {
            eprintln!(
                "note: packing {host_platform} only; for win64 too: apt-get install rustc-web cargo-web rust-web-src mingw-w64"
            );
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

fn windows_toolchain() -> bool {
    on_path(MINGW_GCC).is_some()
        && Path::new(DEBIAN_CARGO).is_file()
        && Path::new(DEBIAN_RUSTC).is_file()
        && Path::new(DEBIAN_STD_SOURCE).is_dir()
}

/// PATH with `first` in front.
fn path_with(first: &Path) -> OsString {
    let rest = std::env::var_os("PATH").unwrap_or_default();
    std::env::join_paths(std::iter::once(first.to_path_buf()).chain(std::env::split_paths(&rest)))
        .unwrap_or(rest)
}

fn run(command: &mut Command, what: &str) -> Result<(), String> {
    let output = command
        .output()
        .map_err(|e| format!("{what}: cannot start: {e}"))?;
    if output.status.success() {
        return Ok(());
    }
    let stderr = String::from_utf8_lossy(&output.stderr);
    let tail: Vec<&str> = stderr.lines().rev().take(20).collect();
    let tail: Vec<&str> = tail.into_iter().rev().collect();
    Err(format!(
        "{what} failed ({}):\n{}",
        output.status,
        tail.join("\n")
    ))
}

fn linux64_for_glibc_2_17(zigbuild: &Path, root: &Path) -> Result<PathBuf, String> {
    let mut command = Command::new(zigbuild);
    command
        .args(["zigbuild", "--release", "--lib", "--quiet", "--target"])
        .arg(format!("{LINUX_TARGET}.2.17"))
        .current_dir(root);
    // cargo-zigbuild runs zig as `python3 -m ziglang`: the python next to it has the package.
    if let Some(bin) = zigbuild.parent() {
        command.env("PATH", path_with(bin));
    }
    run(&mut command, "cargo zigbuild (linux64, glibc 2.17)")?;
    Ok(root.join(format!("target/{LINUX_TARGET}/release/libfriction_fmu.so")))
}

fn win64(root: &Path) -> Result<PathBuf, String> {
    let target_dir = root.join("target/win64");
    let mut command = Command::new(DEBIAN_CARGO);
    command
        .args(["build", "--release", "--lib", "--quiet", "-Zbuild-std=std"])
        .args(["--target", WINDOWS_TARGET])
        .current_dir(root)
        .env("PATH", path_with(Path::new("/usr/bin")))
        .env("RUSTC", DEBIAN_RUSTC)
        // -Zbuild-std is unstable: Debian's stable compiler allows it so.
        .env("RUSTC_BOOTSTRAP", "1")
        .env("CARGO_TARGET_DIR", &target_dir)
        .env("CARGO_TARGET_X86_64_PC_WINDOWS_GNU_LINKER", MINGW_GCC)
        .env_remove("RUSTUP_TOOLCHAIN")
        .env_remove("RUSTC_WRAPPER")
        .env_remove("CARGO");
    run(&mut command, "cargo build (win64)")?;
    let built = target_dir.join(format!("{WINDOWS_TARGET}/release/friction_fmu.dll"));
    let stripped = target_dir.join("friction_fmu.dll");
    run(
        Command::new(MINGW_STRIP)
            .arg("-o")
            .arg(&stripped)
            .arg(&built),
        "strip (win64)",
    )?;
    Ok(stripped)
}
