#!/usr/bin/env bash
# Every shipped scene at its default duration, in release: the promised lines found, no
# line found beyond its tolerance, the 24 000 rpm cage slip as its README row states
# (tests/cli.rs, shipped_scenes_find_the_lines_they_promise_at_their_default_duration).
# CI (`cargo test`) runs the same test on the ring, quasi-static and linear scenes; this
# adds the skidding and full levels (minutes in the test profile, about 2 min here).
set -euo pipefail
cd "$(dirname "$0")/.."
RACEWAY_SCENE_SWEEP=all nice -n 10 cargo test --release --test cli \
    shipped_scenes_find_the_lines_they_promise_at_their_default_duration -- --nocapture
