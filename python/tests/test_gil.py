"""The GIL is released while Rust works: another Python thread runs meanwhile."""

import threading
import time

import raceway

# A run of a few tenths of a second (ring level, 0.1 s of simulated time).
SCENE = {
    "bearing": "6205",
    "model": {"level": "ring"},
    "run": {"duration_s": 0.1},
    "inputs": {"initial": {"shaft.y": -10e-6, "shaft.omega": 183.26}},
}


def test_python_runs_while_rust_computes():
    done = threading.Event()
    span = []

    def work():
        a = time.perf_counter()
        raceway.run(SCENE)
        span.append((a, time.perf_counter()))
        done.set()

    th = threading.Thread(target=work)
    th.start()
    stamps = []
    while not done.is_set():
        stamps.append(time.perf_counter())
        time.sleep(0.001)  # waking up again needs the GIL
    th.join()
    (a, b), = span
    assert b - a > 0.02, "the run is too short to tell"
    # A GIL held for the whole call would let this thread wake only before or after it;
    # released, it wakes throughout, so also in the middle half of the run.
    middle = [t for t in stamps if a + 0.25 * (b - a) < t < a + 0.75 * (b - a)]
    assert middle, (len(stamps), b - a)
