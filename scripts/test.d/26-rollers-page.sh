#!/usr/bin/env bash
# The rollers page, short version (1000-lamina reference, four tilts, 0.3 s of the defect scene's run):
# the command runs and writes its page and plots (into out/rollers/, not docs/).
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo run -q --example rollers_page -- --quick > /dev/null
test -s out/rollers/rollers.md
for p in convergence pressure-aligned pressure-tilted life-tilt envelope; do
  test -s "out/rollers/rollers-$p.png"
done
