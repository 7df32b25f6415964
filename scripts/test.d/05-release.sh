#!/usr/bin/env bash
# Release artefacts: the third-party notices are current (the licence texts, the citation
# and the changelog are checked by tests/release.rs; their presence in the FMUs by
# tests/python/test_fmu.py, in the installed C package by 40-c-install.sh).
set -euo pipefail
cd "$(dirname "$0")/../.."
python3 scripts/third-party-notices --check
