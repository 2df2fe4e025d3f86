"""On a machine without a platform's toolchain, `friction-fmu build` packs what it can and ends
its output with the platforms it left out and the one command that adds them.

The fresh machine is played by a rustc that has no standard library for any cross target (it
fails `rustc --print target-libdir --target ...` for them, as rustup's rustc does for a target
not added); everything else is this machine's.
"""
import os
import pathlib
import subprocess
import zipfile

import pytest

from conftest import ROOT

# The command the FMUs were packed with: tests/run.sh names the one its cargo test built.
BINARY = pathlib.Path(os.environ.get("FRICTION_FMU_BIN", ROOT / "target" / "release" / "friction-fmu"))

RUSTC = """#!/bin/sh
case "$*" in *target-libdir*--target\\ x86_64-pc-windows-gnu*|*target-libdir*--target\\ aarch64*) exit 1;; esac
exec rustc "$@"
"""


def test_the_build_ends_with_the_platforms_it_left_out_and_the_command_that_adds_them(tmp_path):
    if pathlib.Path("/usr/lib/rustlib/src/rust/library").is_dir():
        pytest.skip("Debian's Rust is installed: win64 is built from source without rustup's target")
    rustc = tmp_path / "rustc"
    rustc.write_text(RUSTC)
    rustc.chmod(0o755)
    out = tmp_path / "out"
    done = subprocess.run([str(BINARY), "build", "--out", str(out)], capture_output=True, text=True,
                          cwd=ROOT, env={**os.environ, "RUSTC": str(rustc)}, timeout=1200)
    assert done.returncode == 0, done.stderr
    assert done.stderr.rstrip().splitlines()[-4:] == [
        "  x86_64-windows (win64): rustup has no x86_64-pc-windows-gnu standard library",
        "  aarch64-linux (FMI 3.0 FMUs only): rustup has no aarch64-unknown-linux-gnu standard library",
        "to add them, run from the source tree, then build again:",
        "  rustup target add x86_64-pc-windows-gnu aarch64-unknown-linux-gnu",
    ]
    with zipfile.ZipFile(out / "fmi3" / "DriveTrain.fmu") as fmu:
        binaries = sorted(n for n in fmu.namelist() if n.startswith("binaries/"))
    assert binaries == ["binaries/x86_64-linux/DriveTrain.so"]
