#!/usr/bin/env bash
# Runs every test: formatting and lints, the Rust unit and integration tests (one of which loads
# the packed FMU through the `fmi` crate), the call-sequence fuzzer once more under valgrind's
# memcheck, then the fmpy tests against fmu-out/*.fmu.
# Installs what it needs: libclang-dev (bindgen, for the `fmi` crate), valgrind, and a .venv with
# fmpy.
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
target/release/friction-fmu build scenes/*.toml --out fmu-out/scenes
echo "== cargo test"
cargo test --release
echo "== fuzzing under valgrind memcheck (invalid reads and writes, use after free)"
if ! command -v valgrind >/dev/null; then
    SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq valgrind >/dev/null
fi
FUZZ_BIN=$(cargo test --release --test fuzz_calls --no-run 2>&1 | grep -o 'target/release/deps/fuzz_calls-[0-9a-f]*' | head -1)
FUZZ_SEQUENCES=20000 valgrind --error-exitcode=9 --leak-check=no -q "$FUZZ_BIN" random_call_sequences
echo "== pytest (fmpy)"
.venv/bin/python -m pytest tests/python
