"""The examples run, and what they print or write is physically right."""

import json
import math
import re
import subprocess
import sys

from conftest import ROOT, fmu_path


def test_docs_snippet_is_the_quickstart_and_runs():
    doc = (ROOT / "docs" / "fmi.md").read_text()
    snippet = re.search(r"## Shortest use.*?```python\n(.*?)```", doc, re.S).group(1)
    quickstart = (ROOT / "examples" / "python" / "quickstart.py").read_text()
    assert snippet.strip() in quickstart
    fmu_path("fmi2")
    proc = subprocess.run([sys.executable, "examples/python/quickstart.py"], cwd=ROOT,
                          capture_output=True, text=True, check=True)
    # every input has a column: fmpy prints no "missing input" warning
    assert "arning" not in proc.stdout + proc.stderr, proc.stdout + proc.stderr
    force, unit = proc.stdout.split()[-2:]
    assert unit == "N"
    # the shaft is pushed 20 µm down: the bearing pushes it back up
    assert math.isfinite(float(force)) and float(force) > 0.0


def test_rotor_on_two_bearing_fmus(tmp_path):
    out = tmp_path / "plots"
    proc = subprocess.run(
        [sys.executable, "examples/python/rotor_two_bearings.py", str(out), "--duration", "0.06",
         "--fmu", str(fmu_path("fmi2"))],
        cwd=ROOT, capture_output=True, text=True, env={"MPLBACKEND": "Agg", **_env()},
    )
    assert proc.returncode == 0, proc.stderr
    for png in ("orbits.png", "forces.png"):
        data = (out / png).read_bytes()
        assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10_000
    s = json.loads((out / "summary.json").read_text())
    assert s["all_finite"]
    # momentum balance over whole revolutions: the bearings carry the rotor's weight (the
    # unbalance force averages out), and nothing pushes sideways on average
    w = s["rotor_weight [N]"]
    assert abs(s["mean_vertical_bearing_force [N]"] - w) < 0.02 * w
    assert abs(s["mean_horizontal_bearing_force [N]"]) < 0.02 * w
    assert 0.0 < s["max_journal_displacement [m]"] < 1e-3


def _env():
    import os

    return dict(os.environ)


def test_load_driven_example_comes_to_rest_carrying_the_load():
    proc = subprocess.run(
        [sys.executable, "examples/python/load_driven.py", str(fmu_path("load-fmi2"))],
        cwd=ROOT, capture_output=True, text=True, check=True,
    )
    assert "arning" not in proc.stdout + proc.stderr, proc.stdout + proc.stderr
    m = re.search(r"sag (\S+) µm, bearing force (\S+) N, K.y.y (\S+) N/µm, (\d+) balls",
                  proc.stdout)
    sag, force, k, balls = float(m[1]), float(m[2]), float(m[3]), int(m[4])
    # through the radial play (5 µm) into the contacts, the load carried, a few balls loaded
    assert sag < -5.0 and abs(force - 1000.0) < 1.0 and k > 0.0 and 1 < balls < 9
