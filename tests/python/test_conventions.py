"""The FMUs by the Reference-FMUs conventions, and outputs valid whenever a host reads them:
- every output read at t0 (right after exitInitializationMode) is the value after a first
  step of 1 ns from the same inputs (no zero-length step exists in FMI), and so after
  setFMUstate and after reset;
- display units, min/max, documentation/index.html and the license in the archive;
- a directional derivative with a huge finite seed is finite or refused, never infinite;
- a second, independent checker (fmu-manipulation-toolbox's XSD check) passes both FMUs."""

import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
import zipfile

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException

from conftest import LOAD_VERSIONS, ROOT, VERSIONS, fmu_path

# quasi-static level (the default scene), motion held inside a step, shaft 10 µm down
START = {"input_rule": "hold", "shaft.x": 2e-6, "shaft.y": -10e-6, "shaft.omega": 183.26}


def outputs(h):
    return [v.name for v in h.md.modelVariables if v.causality == "output"]


def assert_same(t0, after, names):
    t0, after = np.asarray(t0), np.asarray(after)
    big = np.abs(t0).max()
    tol = 1e-6 * np.maximum(np.abs(t0), np.abs(after)) + 1e-8 * big
    bad = [(n, a, b) for n, a, b, t in zip(names, t0, after, tol) if abs(a - b) > t]
    assert not bad, bad


@pytest.mark.parametrize("version", VERSIONS)
def test_every_output_at_t0_is_the_value_after_the_first_step(host, version):
    h = host(version).init(start_values=START)
    names = outputs(h)
    t0 = h.get(names)
    assert t0[names.index("force.y")] > 100.0  # pushed down: the bearing pushes up
    assert t0[names.index("K.y.y")] > 1e7
    state = h.get_state()
    # a changed input is seen by the next read
    h.set("shaft.y", -20e-6)
    assert h.get(["force.y"])[0] > 1.5 * t0[names.index("force.y")]
    # setFMUstate: the outputs of that moment
    h.set_state(state)
    assert h.get(names) == t0
    h.free_state(state)
    h.step(0.0, 1e-9)
    assert_same(t0, h.get(names), names)
    # reset: the same again after a new initialisation
    h.fmu.reset()
    h.init(start_values=START)
    assert h.get(names) == t0


@pytest.mark.parametrize("version", VERSIONS)
def test_huge_seed_gives_a_finite_value_or_an_error(host, version):
    h = host(version).init(start_values=START)
    k = h.get(["K.y.y"])[0]
    d = h.directional_derivative(["force.y"], ["shaft.y"], [1e290])[0]
    assert np.isfinite(d) and d == pytest.approx(-k * 1e290, rel=1e-12)
    with pytest.raises(FMICallException):
        h.directional_derivative(["force.y"], ["shaft.y"], [1e308])
    assert "seed" in h.log_text()


@pytest.mark.parametrize("version", VERSIONS)
def test_display_units_and_ranges_are_declared(version):
    with zipfile.ZipFile(fmu_path(version)) as z:
        root = ET.fromstring(z.read("modelDescription.xml"))
        names = z.namelist()
        html = z.read("documentation/index.html").decode()
        assert "license" in z.read("documentation/licenses/license.txt").decode().lower()
    shown = {u.get("name"): {d.get("name"): float(d.get("factor"))
                             for d in u.iter("DisplayUnit")}
             for u in root.iter("Unit")}
    assert shown["rad/s"]["rpm"] == pytest.approx(60 / (2 * np.pi))
    assert shown["m"]["µm"] == 1e6 and shown["Pa"]["GPa"] == 1e-9 and shown["N"]["kN"] == 1e-3
    assert shown["rad"]["deg"] == pytest.approx(180 / np.pi)
    for v in root.find("ModelVariables"):
        typed = v[0] if version == "fmi2" else v
        if v.get("causality") in ("input", "parameter") and typed.tag in ("Real", "Float64"):
            lo, hi = float(typed.get("min")), float(typed.get("max"))
            assert lo <= float(typed.get("start")) <= hi, v.get("name")
        unit = typed.get("unit")
        if unit in shown and shown[unit]:
            assert typed.get("displayUnit") in shown[unit], v.get("name")
    assert "linux64" in html and "K.y.y" in html
    assert "documentation/index.html" in names


@pytest.mark.parametrize("version", VERSIONS)
def test_a_value_outside_the_declared_range_is_refused(host, version):
    h = host(version)
    with pytest.raises(FMICallException):
        h.set("shaft.y", 2e-3)
    assert "shaft.y" in h.log_text() and "-0.001, 0.001" in h.log_text()


def toolbox():
    exe = shutil.which("fmutool", path=str(ROOT / "target" / "venv" / "bin")) or shutil.which(
        "fmutool")
    if exe is None:
        pytest.fail("fmutool (fmu-manipulation-toolbox) is not installed: see requirements.txt")
    return exe


@pytest.mark.parametrize("version", VERSIONS)
def test_toolbox_xsd_check_passes(version):
    proc = subprocess.run([toolbox(), "-input", str(fmu_path(version)), "-check"],
                          capture_output=True, text=True, timeout=300)
    text = proc.stdout + proc.stderr
    assert proc.returncode == 0, text
    assert "ERROR" not in text, text
    assert "compliant with FMI" in text and "No semantic error" in text, text


# Run in a process of its own: in the pytest process libcosimpy's libraries (loaded by
# test_libcosim.py) interpose symbols the container's binary resolves, and it crashes.
CONTAINER_RUN = """
import sys
from fmpy import read_model_description, simulate_fmu
path = sys.argv[1]
names = [v.name for v in read_model_description(path).modelVariables]
port = {n: next(v for v in names if v == n or v.endswith("." + n))
        for n in ("shaft.y", "shaft.omega", "force.y")}
res = simulate_fmu(path, stop_time=2e-3, output_interval=1e-4,
                   start_values={port["shaft.y"]: -10e-6, port["shaft.omega"]: 183.26},
                   output=[port["force.y"]])
print(" ".join(repr(float(x)) for x in res[port["force.y"]]))
"""


@pytest.mark.parametrize("version", VERSIONS)
def test_toolbox_container_runs_the_fmu_in_fmpy(version, tmp_path):
    """fmu-manipulation-toolbox's C container (its own FMI host, linux64 binary shipped in
    the package) embeds the FMU; fmpy runs the container: the bearing's force comes out."""
    name = f"raceway-{version}.fmu"
    shutil.copy(fmu_path(version), tmp_path / name)
    (tmp_path / "bearing.csv").write_text(f"rule;from_fmu;from_port;to_fmu;to_port\nFMU;{name};;;\n")
    exe = toolbox().replace("fmutool", "fmucontainer")
    proc = subprocess.run([exe, "-fmu-directory", str(tmp_path), "-container", "bearing.csv:1e-4"],
                          capture_output=True, text=True, timeout=300)
    container = tmp_path / "bearing.fmu"
    assert proc.returncode == 0 and container.exists(), proc.stdout + proc.stderr
    run = subprocess.run([sys.executable, "-c", CONTAINER_RUN, str(container)],
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    fy = np.array([float(x) for x in run.stdout.strip().splitlines()[-1].split()])
    assert fy.size == 21 and np.all(np.isfinite(fy)) and fy[-1] > 100.0, run.stdout


@pytest.mark.parametrize("version", VERSIONS + LOAD_VERSIONS)
def test_unset_inputs_hold_the_start_values_the_model_description_gives(host, version):
    """One rule for unset inputs: an input the host never sets holds the scene's initial
    value, and the model description's `start` is that value (default scene: shaft 10 µm
    down at 1750 rpm; the load-driven FMU keeps only the speed, its loads start at 0)."""
    h = host(version)
    inputs = [v for v in h.md.modelVariables if v.causality == "input"]
    starts = {v.name: float(v.start) for v in inputs}
    assert starts["shaft.omega"] == pytest.approx(1750 * np.pi / 30, rel=1e-15)
    if version in VERSIONS:
        assert starts["shaft.y"] == -10e-6
    assert sum(1 for s in starts.values() if s != 0.0) == (2 if version in VERSIONS else 1)
    h.init()
    assert h.get(list(starts)) == list(starts.values())


@pytest.mark.parametrize("version", VERSIONS)
def test_nothing_set_gives_the_force_of_the_clis_first_rows(host, version, cli_first_rows):
    """The default scene stepped without setting anything: its force at t = 0 and after one
    step of 1e-4 s equals `raceway run`'s first two rows."""
    h = host(version).init()
    got = [tuple(h.get(["force.x", "force.y"]))]
    h.step(0.0, 1e-4)
    got.append(tuple(h.get(["force.x", "force.y"])))
    scale = abs(cli_first_rows[0][1])
    assert scale > 500.0
    for g, w in zip(got, cli_first_rows):
        assert g == pytest.approx(w, abs=1e-9 * scale)
