#!/usr/bin/env bash
# Release artefacts: the third-party notices are current (the licence texts, the citation
# and the changelog are checked by tests/release.rs; their presence in the FMUs by
# tests/python/test_fmu.py, in the installed C package by 40-c-install.sh, in the wheel by 50-python.sh).
set -euo pipefail
cd "$(dirname "$0")/../.."
python3 scripts/third-party-notices --check
# The wheel's licence files (python/pyproject.toml's license-files) are links to the root's.
for f in LICENSE-MIT LICENSE-APACHE THIRD-PARTY-NOTICES.md; do
  [ "$(readlink "python/$f")" = "../$f" ] || { echo "python/$f is not a link to ../$f" >&2; exit 1; }
done
