#!/usr/bin/env bash
# Every test of settle: the Rust crate's (unit, integration, doc tests), then the Python
# package's (scripts/test_python.sh: its own virtual environment in target/py-venv, the package
# built by maturin, pytest and mypy). Needs a Rust toolchain and Python >= 3.9 with venv.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --release
scripts/test_python.sh
