#!/usr/bin/env bash
# Study [2]'s wear page, short version (2 cycles, short windows): the command runs and
# writes its page and plots (into out/study-wear/, not docs/).
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo run -q --example study_wear -- --quick > /dev/null
test -s out/study-wear/study-wear.md
for p in asperity-share map-sigma-0.20 map-sigma-0.42 map-dry orbit-dry dry-bursts; do
  test -s "out/study-wear/study-wear-$p.png"
done
# The dry-map probe (issue #15's ball-spacing pattern), a short window.
cargo run -q --example wear_map_probe -- --settle 0.02 --window 0.2 --cells 90 > /dev/null
