#!/usr/bin/env bash
# Runs every test: formatting, lints and the API documentation's links, the Rust unit and
# integration tests (one of which loads the packed FMU through the `fmi` crate), the call-sequence
# fuzzers of both standards once more under valgrind's memcheck, then the Python tests against
# fmu-out/: fmpy, the co-simulation engines libcosim and ecos, and C hosts of both standards
# natively, on the win64 libraries under wine and on the aarch64-linux libraries under
# qemu-aarch64.
# Installs what it needs with apt (below) and a .venv with fmpy, the engines, and cargo-zigbuild
# with ziglang (the linux64 library for glibc 2.17).
set -euo pipefail
cd "$(dirname "$0")/.."

# libclang-dev: bindgen, for the fmi crate; libzstd-dev and pkg-config: the zstd library the fmi
# crate's zip links (.cargo/config.toml); valgrind: memcheck; libtbb12: ecos; mingw-w64: links
# the win64 library; wine64: runs the C host on it; gcc-aarch64-linux-gnu and libc6-arm64-cross:
# build the C host for aarch64 (binutils-aarch64-linux-gnu, which comes with it, reads the aarch64
# library's symbols); qemu-user: runs it on the aarch64-linux library. The win64 standard library
# comes with rustup; where rustup cannot add it, Debian's Rust builds it from source (slower).
# The aarch64 standard library comes with rustup only (cargo-zigbuild links it).
APT_PACKAGES="libclang-dev libzstd-dev pkg-config valgrind libtbb12 mingw-w64 wine64 qemu-user gcc-aarch64-linux-gnu libc6-arm64-cross"
if ! rustup target add x86_64-pc-windows-gnu >/dev/null 2>&1; then
    echo "== rustup cannot add x86_64-pc-windows-gnu: Debian's Rust builds its standard library"
    APT_PACKAGES="$APT_PACKAGES rustc-web cargo-web rust-web-src"
fi
rustup target add aarch64-unknown-linux-gnu >/dev/null 2>&1 ||
    echo "== rustup cannot add aarch64-unknown-linux-gnu: the FMI 3.0 FMUs go without aarch64-linux"
missing=""
for package in $APT_PACKAGES; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing="$missing $package"
done
if [ -n "$missing" ]; then
    echo "== installing$missing"
    SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq $missing >/dev/null
fi

if [ ! -x .venv/bin/python ]; then
    echo "== creating .venv"
    python3 -m venv .venv
fi
.venv/bin/pip install -q --disable-pip-version-check -r tests/python/requirements.txt

# Each stage's heading says the CPU time the command has used so far (user + system, children
# included), so a log shows where the time goes.
stage() {
    local times_file cpu
    times_file=$(mktemp)
    times > "$times_file"
    cpu=$(awk '{ for (i = 1; i <= 2; i++) { split($i, t, /[ms]/); sum += t[1] * 60 + t[2] } } END { printf "%.0f", sum }' "$times_file")
    rm -f "$times_file"
    echo "== $1 ($cpu s of CPU so far)"
}

# Clippy lints the crate as the tests' build compiles it. clippy-driver is rustc with clippy's
# lints; as cargo's workspace wrapper it compiles every target of this package that `cargo test`
# builds (the library, its unit tests, the integration tests, the examples, the command) with the
# warnings denied, as `cargo clippy --all-targets -- -D warnings` would, while the dependencies
# are compiled once, by rustc: a `cargo clippy` of its own would check every one of them again.
linted() {
    RUSTC_WORKSPACE_WRAPPER="$(rustc --print sysroot)/bin/clippy-driver" CLIPPY_ARGS="-Dwarnings" "$@"
}

stage "cargo fmt --check"
cargo fmt --check
# The benchmarks' standalone crates, by rustfmt alone: cargo would resolve their dependencies
# (SUNDIALS bindings, diffsol), which the test command does not need. rustfmt follows each crate's
# modules from its main.rs.
rustfmt --check --edition 2021 benches/compiled_peers/src/main.rs benches/diffsol_compare/src/main.rs
stage "cargo test, linted by clippy"
# The testing profile (Cargo.toml) builds in target/testing: the main command's target/release is
# left as it is, so neither rebuilds the other. It also builds the friction-fmu command, which
# packs the FMUs below (the release build would compile everything again, with fat LTO). Before
# that packing, which refreshes modelDescription/: a test checks the committed copy.
linted cargo test --profile testing
stage "cargo doc, warnings denied (broken links in the API documentation)"
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --profile testing --quiet
BIN=target/testing/friction-fmu
stage "fuzzing under valgrind memcheck (invalid reads and writes, use after free)"
FUZZ_BIN=$(linted cargo test --profile testing --test fuzz_calls --no-run 2>&1 | grep -o 'target/testing/deps/fuzz_calls-[0-9a-f]*' | head -1)
FUZZ_SEQUENCES=5000 valgrind --error-exitcode=9 --leak-check=no -q "$FUZZ_BIN" random_call_sequences
# The same over the FMI 3.0 boundary: 4000 sequences, about 25 s of CPU under memcheck.
FUZZ3_BIN=$(linted cargo test --profile testing --test fuzz_calls_fmi3 --no-run 2>&1 | grep -o 'target/testing/deps/fuzz_calls_fmi3-[0-9a-f]*' | head -1)
FUZZ_SEQUENCES=4000 valgrind --error-exitcode=9 --leak-check=no -q "$FUZZ3_BIN" random_fmi3_call_sequences
stage "packing the FMUs"
$BIN build
$BIN build variants/*.toml --out fmu-out/variants
stage "pytest (fmpy, libcosim, ecos, the C host natively, under wine and under qemu-aarch64)"
# wine's prefix outside the source tree: cargo scans the package directory, and the prefix links
# to /.
export WINEPREFIX="${WINEPREFIX:-$HOME/.wine-friction-fmu}" WINEDEBUG=-all WINEDLLOVERRIDES="mscoree,mshtml="
FRICTION_FMU_BIN=$BIN .venv/bin/python -m pytest tests/python
stage "done"
