#!/usr/bin/env bash
# The Python package's tests (issue 25): a virtual environment in target/py-venv, the package
# built into it by maturin (release), then pytest on python/tests. The tests compare with the
# command line, so the release binary is built first. Needs a Rust toolchain and Python >= 3.9
# with venv; reaches PyPI (maturin, pandas, pytest, python-ags4, openpyxl; dask, distributed and
# submitit for the executor tests) when a requirement is missing. The executor tests use the
# Slurm that scripts/test.sh starts (scripts/slurm_local.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT="$PWD"
VENV="$ROOT/target/py-venv"
PY="${PYTHON:-python3}"

# The binary as `cargo test --release` builds it (dev-dependencies unify some features, e.g.
# bitflags' std): after scripts/test.sh's Rust tests this is a no-op, where `cargo build
# --release` would compile rapier, parry and settle a second time with other features.
cargo test --release --no-run -q
if [ ! -x "$VENV/bin/python" ]; then
    "$PY" -m venv "$VENV"
fi
"$VENV/bin/python" -m pip install -q --disable-pip-version-check "maturin>=1.5,<2" pandas pytest mypy pandas-stubs matplotlib nbformat nbclient ipykernel python-ags4 openpyxl dask distributed submitit
(cd python && VIRTUAL_ENV="$VENV" PATH="$VENV/bin:$PATH" maturin develop --release -q)
SETTLE_BIN="$ROOT/target/release/settle" "$VENV/bin/python" -m pytest -q python/tests "$@"
