#!/usr/bin/env bash
# A ROSS rotor on two raceway locations in the time domain (examples/python/ross_two_locations.py),
# short version (20 ms): with the raceway package and ROSS that 50-python.sh and
# 55-python-examples.sh install into target/venv (no install of its own). The example checks
# its own physics (exit 1 when a check fails).
set -euo pipefail
cd "$(dirname "$0")/../.."
target="${CARGO_TARGET_DIR:-target}"
py="$target/venv/bin/python"
if [ ! -f python/pyproject.toml ]; then
  echo "56-ross-two-locations: SKIPPED: no python/ package in this tree"
  exit 0
fi
"$py" -c "import raceway, ross" > /dev/null 2>&1 || {
  echo "56-ross-two-locations: raceway or ross is not installed in $target/venv" >&2
  exit 1
}
out="$target/python-examples/ross_two_locations"
mkdir -p "$out"
start=$(date +%s.%N)
# ROSS's fluid-property dependency prints a notice that REFPROP is absent: keep the log, show
# it only on failure.
if ! MPLBACKEND=Agg "$py" examples/python/ross_two_locations.py --quick --out "$out" > "$out/log" 2>&1; then
  cat "$out/log"
  echo "56-ross-two-locations: failed" >&2
  exit 1
fi
grep -E "^(disk deflection|bearings'|check ok)" "$out/log" | sed "s/^/  ross_two_locations: /"
test -s "$out/disk-deflection.png"
echo "  ross_two_locations: $(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }') s wall (load average $(cut -d' ' -f1-3 /proc/loadavg))"
