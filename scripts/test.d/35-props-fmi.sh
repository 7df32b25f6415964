#!/usr/bin/env bash
# Property tests of the FMI 2/3 state machines (the `fmi` feature is off in the main test
# run, which runs the scene and C ABI property tests): about 128 sequences per version.
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo test --quiet --features fmi --test props_fmi --test small_stack
