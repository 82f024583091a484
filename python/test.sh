#!/usr/bin/env bash
# The Python package's tests: builds the package with pip (maturin) into a
# virtual environment (target/python), builds the release CLI it is compared
# with, and runs pytest (python/tests) against both. Under CI=true nothing
# is skipped.
set -euo pipefail
cd "$(dirname "$0")/.."
python3 -m venv target/python
target/python/bin/pip install --quiet ./python pytest openexr 'dask[distributed]' tqdm
# `--bin`, not `-p prismatic-cli`: the default members' features, as the
# README's `cargo run --release -- render` builds it, so CI builds it once.
cargo build --release --locked --bin prismatic
PRISMATIC="$PWD/target/release/prismatic" target/python/bin/python -m pytest -q python/tests
