#!/usr/bin/env bash
# Every test of settle: the Rust crate's (unit, integration, doc tests), then the Python
# package's (scripts/test_python.sh: its own virtual environment in target/py-venv, the package
# built by maturin, pytest and mypy). Needs a Rust toolchain and Python >= 3.9 with venv.
# The tests of tests/slurm/ need a Slurm: a one-node Slurm on localhost is started first
# (scripts/slurm_local.sh, as root, with Debian's slurm-wlm and munge, installed here with apt when
# missing) and stopped at the end, also when a test fails. Without it those tests fail, saying so.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    sudo=""; [[ $(id -u) == 0 ]] || sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq slurm-wlm munge
fi
if [[ $(id -u) == 0 ]] && command -v slurmctld >/dev/null; then
    scripts/slurm_local.sh start
    trap 'scripts/slurm_local.sh stop' EXIT
else
    echo "test.sh: not root or no slurm-wlm: the tests of tests/slurm/ will fail (see scripts/slurm_local.sh)" >&2
fi
cargo test --release
scripts/test_python.sh
