"""The GIL is released while Rust works: another Python thread runs meanwhile."""

import threading
import time

import raceway



def scene(duration):
    return {
        "bearing": "6205",
        "model": {"level": "ring"},
        "run": {"duration_s": duration},
        "inputs": {"speed_rpm": 1750.0, "initial": {"shaft.y": -10e-6}},
    }


def long_scene():
    """A ring-level run of about 0.3 s of wall time on this build and machine."""
    a = time.perf_counter()
    raceway.run(scene(0.02))
    took = max(time.perf_counter() - a, 1e-4)
    return scene(min(max(0.02 * 0.3 / took, 0.02), 5.0))


def test_python_runs_while_rust_computes():
    done = threading.Event()
    span = []
    work_scene = long_scene()

    def work():
        a = time.perf_counter()
        raceway.run(work_scene)
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
