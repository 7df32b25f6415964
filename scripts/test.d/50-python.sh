#!/usr/bin/env bash
# The Python package (python/, issue #20): `pip install ./python` into target/venv (the venv
# the FMU step makes; made here when missing), then its pytest suite, which compares the
# package with the command line (runs, quasi-static, bearings, sweeps, Dask on a 2-process
# LocalCluster) and prints the seconds each phase took.
set -euo pipefail
cd "$(dirname "$0")/../.."
target="${CARGO_TARGET_DIR:-target}"
venv=$(scripts/venv)
t0=$SECONDS
# The package with its test extra (pytest, distributed); maturin builds the release wheel.
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "./python[test]"
t1=$SECONDS
# The serial reference the tests compare with.
cargo build --quiet --bin raceway
RACEWAY_BIN="$(pwd)/$target/debug/raceway" "$venv/bin/python" -m pytest -q -p no:cacheprovider python/tests
echo "python package: pip install $((t1 - t0)) s, tests $((SECONDS - t1)) s"
