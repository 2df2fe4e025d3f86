#!/usr/bin/env bash
# Runs every test: formatting and lints, the Rust unit and integration tests (one of which loads
# the packed FMU through the `fmi` crate), then the fmpy tests against fmu-out/*.fmu.
# Installs what it needs: libclang-dev (bindgen, for the `fmi` crate) and a .venv with fmpy.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! compgen -G "/usr/lib/llvm-*/lib/libclang*.so*" >/dev/null; then
    echo "== installing libclang-dev (needed by the fmi crate's bindgen)"
    SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq libclang-dev >/dev/null
fi

if [ ! -x .venv/bin/python ]; then
    echo "== creating .venv"
    python3 -m venv .venv
fi
.venv/bin/pip install -q --disable-pip-version-check -r tests/python/requirements.txt

echo "== cargo fmt --check"
cargo fmt --check
echo "== cargo clippy"
cargo clippy --all-targets --release -- -D warnings
echo "== building the FMUs"
cargo build --release
target/release/friction-fmu build
echo "== cargo test"
cargo test --release
echo "== pytest (fmpy)"
.venv/bin/python -m pytest tests/python
