#!/usr/bin/env bash
# The sets page, short version (three speeds): the command runs and writes its page and plots
# (into out/sets/, not docs/).
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo run -q --example sets_page -- --quick > /dev/null
test -s out/sets/sets.md
for p in preload axial tilt; do
  test -s "out/sets/sets-$p-speed.png"
done
