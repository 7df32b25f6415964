#!/usr/bin/env bash
# report.html in a real browser: headless Chromium (Debian's package, installed if missing)
# loads the page of the default run and of a defect run (short), takes a screenshot (kept in
# target/report-shots/ as the CI artefact) and dumps the DOM; the test checks the title, the
# summary tables, the inline SVG plots and that the console reported no error.
set -euo pipefail
cd "$(dirname "$0")/../.."
if ! command -v chromium >/dev/null; then
  if [ "$(id -u)" = 0 ]; then
    apt-get install -y chromium >/dev/null || { apt-get update >/dev/null && apt-get install -y chromium >/dev/null; }
  else
    sudo apt-get install -y chromium >/dev/null
  fi
fi
shots=target/report-shots
rm -rf "$shots" target/report-runs
mkdir -p "$shots"
cargo run --quiet -- run --out target/report-runs/default --quiet
cargo run --quiet -- run examples/scenes/6205-outer-spall.toml --duration 0.3 \
  --out target/report-runs/6205-outer-spall --quiet
for name in default 6205-outer-spall; do
  page="$PWD/target/report-runs/$name/report.html"
  profile=$(mktemp -d)
  flags=(--headless --no-sandbox --disable-gpu --disable-quic --no-first-run
    --disable-background-networking --disable-component-update --disable-sync
    --user-data-dir="$profile" --enable-logging=stderr --v=0)
  chromium "${flags[@]}" --window-size=1280,4000 --screenshot="$PWD/$shots/$name.png" \
    "file://$page" 2>"$shots/$name.log" >/dev/null || { cat "$shots/$name.log"; exit 1; }
  chromium "${flags[@]}" --dump-dom "file://$page" >"$shots/$name.dom.html" 2>>"$shots/$name.log"
  rm -rf "$profile"
  python3 - "$shots/$name.dom.html" "$shots/$name.log" "$shots/$name.png" "$name" <<'PY'
import re, sys
dom, log, png, name = sys.argv[1:]
d = open(dom, encoding="utf-8").read()
title = re.search(r"<title>(.*?)</title>", d, re.S)
assert title and f"raceway run: {name}" in title.group(1), f"title: {title and title.group(1)}"
tables = d.count("<table")
assert tables >= 6, f"{tables} tables"
svgs = len(re.findall(r"<svg[^>]*>", d))
assert svgs >= 4, f"{svgs} inline SVG plots"
for h in ["Summary", "Characteristic lines", "Plots", "Scene as run"]:
    assert f">{h}</h2>" in d, f"section {h} missing"
assert "found" in d
bad = [l for l in open(log, errors="replace") if "Uncaught" in l or "ERROR:CONSOLE" in l or ":CONSOLE(" in l]
assert not bad, "console errors:\n" + "".join(bad)
# A rendered screenshot: a PNG of the window's size, not a blank page.
b = open(png, "rb").read()
assert b[1:4] == b"PNG" and len(b) > 50_000, f"screenshot {len(b)} bytes"
print(f"report.html of {name} ok in Chromium: {tables} tables, {svgs} plots, screenshot {len(b)} bytes")
PY
done
