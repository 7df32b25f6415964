#!/usr/bin/env bash
# Every Rust example and every example scene runs (short durations).
set -euo pipefail
cd "$(dirname "$0")/../.."
out=target/examples-out
mkdir -p "$out"
cargo run -q --example coupled_rotor -- --quick
cargo run -q --example vibration -- examples/scenes/6205-outer-spall.toml 0.3 0.1
cargo run -q --example vibration -- examples/scenes/7008ce-waviness.toml 0.1 0.02
cargo run -q --example wear_thermal -- all > /dev/null
cargo run -q --example cage_whirl -- --quick > /dev/null
cargo run -q --example full_probe -- --window 0.0004 > /dev/null
cargo run -q --example full_probe -- --exudyn 3000 --step 1e-4 --window 0.0005 > /dev/null
cargo run -q --example skid_window -- ros34pw2 0.0005 1e-5 > /dev/null
for s in examples/scenes/*.toml; do
  name=$(basename "$s" .toml)
  cargo run -q -- scene --check "$s" > /dev/null
  cargo run -q -- run "$s" --quiet --duration 0.05 --out "$out/$name"
  test -s "$out/$name/spectrum.png"
done
cargo run -q -- run --quiet --duration 0.05 --out "$out/default-scene"
cargo run -q -- bearings > /dev/null
cargo run -q -- quasi-static > /dev/null
cargo run -q -- scene --explain > /dev/null
