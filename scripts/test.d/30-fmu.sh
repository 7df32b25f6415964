#!/usr/bin/env bash
# FMU tests: build both FMUs (release), then the Python host tests (fmpy, libcosimpy) and the
# examples, in a venv under target/ that this script creates and fills.
set -euo pipefail
cd "$(dirname "$0")/../.."
venv=$(scripts/venv)
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r tests/python/requirements.txt

# unit tests of the FMI layer (the `fmi` feature is off in the main test run)
cargo test --quiet -p raceway-bearing --features fmi --lib fmi::

scripts/build-fmu --no-docs
MPLBACKEND=Agg "$venv/bin/python" -m pytest -q tests/python
