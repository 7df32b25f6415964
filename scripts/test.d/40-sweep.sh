#!/usr/bin/env bash
# raceway sweep: the example sweep runs, a second run resumes (nothing left to run), and the
# table has one line a point with the same number of fields.
set -euo pipefail
cd "$(dirname "$0")/../.."
out=target/sweep-example
rm -rf "$out"
cargo run --quiet -- sweep examples/sweeps/6205-speed-displacement.toml --out "$out" --quiet
again=$(cargo run --quiet -- sweep examples/sweeps/6205-speed-displacement.toml --out "$out" --quiet)
echo "$again" | grep -q "ran 0, skipped 18" || { echo "resume ran points again: $again"; exit 1; }
cargo run --quiet -- sweep examples/sweeps/bench-qs-1000.toml --check
python3 - "$out/sweep.csv" <<'PY'
import csv, sys
rows = list(csv.reader(open(sys.argv[1], newline="")))
assert len(rows) == 19, len(rows)
assert len({len(r) for r in rows}) == 1, "ragged table"
h = rows[0]
y = [float(r[h.index("peak_force.y [N]")]) for r in rows[1:]]
assert all(v > 0 for v in y) and not any(r[h.index("error")] for r in rows[1:])
print("sweep example ok:", len(rows) - 1, "rows,", len(h), "columns")
PY
