#!/usr/bin/env bash
# The Python package (python/): the abi3 manylinux wheel built as a release would build it
# (`maturin build --release`), checked for its licence files, installed from the wheel into
# target/venv (the venv the FMU step makes; made here when missing; nothing compiles at
# install), then its pytest suite, which compares the package with the command line (runs,
# quasi-static, bearings, sweeps, Dask on a 2-process LocalCluster), and prints the seconds
# each phase took.
set -euo pipefail
cd "$(dirname "$0")/../.."
target="${CARGO_TARGET_DIR:-target}"
venv=$(scripts/venv)
py="$venv/bin/python"
wheels="$target/wheels"
t0=$SECONDS
"$py" -m pip install --quiet --disable-pip-version-check "maturin>=1.8,<2"
rm -rf "$wheels"
# --target-dir: its own folder, so the release wheel does not churn the usual release build.
root=$PWD
case "$target" in /*) tdir="$target" ;; *) tdir="$root/$target" ;; esac
case "$venv" in /*) vdir="$venv" ;; *) vdir="$root/$venv" ;; esac
(cd python && "$vdir/bin/maturin" build --quiet --release --out "$tdir/wheels" \
  --target-dir "$tdir/wheel-build")
wheel=$(ls "$wheels"/raceway_bearing-*-abi3-manylinux*.whl)
t1=$SECONDS
"$py" python/tests/wheel_contents.py "$wheel"
# The wheel with its test extra (pytest, distributed); --force-reinstall: the same version
# number is rebuilt on every run.
"$py" -m pip install --quiet --disable-pip-version-check --force-reinstall --no-deps "$wheel"
"$py" -m pip install --quiet --disable-pip-version-check "$wheel[test]"
t2=$SECONDS
# The serial reference the tests compare with.
cargo build --quiet --bin raceway
RACEWAY_BIN="$(pwd)/$target/debug/raceway" "$py" -m pytest -q -p no:cacheprovider python/tests
echo "python package: wheel build $((t1 - t0)) s ($(basename "$wheel")), pip install $((t2 - t1)) s, tests $((SECONDS - t2)) s"
