#!/usr/bin/env bash
# docs/validation.md: the table of comparisons with published and standard figures is
# regenerated (into a temporary directory, not docs/) and no row that holds in the committed
# docs/validation.csv may stop holding or disappear.
set -euo pipefail
cd "$(dirname "$0")/../.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cargo run -q --example validation -- --out "$tmp" --check docs/validation.csv
test -s "$tmp/validation.md"
