#!/usr/bin/env bash
# The Python sweep examples (examples/python/sweeps/, docs/python-examples.md), short versions,
# with the raceway package the package step installed into target/venv and ROSS beside it.
# Each example checks its own physics (exit 1 when a check fails); this step times them.
set -euo pipefail
cd "$(dirname "$0")/../.."
target="${CARGO_TARGET_DIR:-target}"
venv="$target/venv"
py="$venv/bin/python"
start=$(date +%s.%N)
if [ ! -f python/pyproject.toml ]; then
  echo "55-python-examples: SKIPPED: no python/ package in this tree (examples/python/sweeps/ needs it)"
  exit 0
fi
"$py" -c "import raceway" 2> /dev/null || { echo "55-python-examples: the raceway package is not installed in $venv" >&2; exit 1; }
"$py" -m pip install --quiet --disable-pip-version-check -r examples/python/sweeps/requirements.txt
installed=$(date +%s.%N)

out="$target/python-examples"
mkdir -p "$out"
for example in rotor_campbell fault_dataset preload_speed; do
  t0=$(date +%s.%N)
  # ROSS's fluid-property dependency prints a notice that REFPROP is absent: keep the log,
  # show it only on failure.
  if ! MPLBACKEND=Agg "$py" "examples/python/sweeps/$example.py" --quick --out "$out/$example" > "$out/$example.log" 2>&1; then
    cat "$out/$example.log"
    echo "55-python-examples: $example failed" >&2
    exit 1
  fi
  grep -E "^(check ok|.*thread CPU time)" "$out/$example.log" | sed "s/^/  $example: /"
  for f in "$out/$example"/*.png; do test -s "$f"; done
  echo "  $example: $(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }') s"
done
test "$(wc -l < "$out/fault_dataset/labels.csv")" -eq 5
times > "$out/times" # children's user and system CPU time on the second line, as 1m2.345s
cpu=$(tail -1 "$out/times" | awk '{ for (i = 1; i <= 2; i++) { split($i, p, "m"); c += p[1] * 60 + p[2] } printf "%.1f", c }')
echo "python examples: install $(awk -v a="$start" -v b="$installed" 'BEGIN { printf "%.1f", b - a }') s, total $(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }') s wall, ${cpu} s CPU of the processes (load average $(cut -d' ' -f1-3 /proc/loadavg))"
