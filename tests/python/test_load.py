"""The load-driven FMUs (raceway-load-fmi2/3.fmu): loads in, ring motion out, from the same
binary as the motion-driven ones; the GUID a host instantiates with decides the causality.

The physics check: a ring released from rest under a load, with contact damping, settles
where the quasi-static level balances that load: the motion-driven FMU (quasi-static level)
given the settled displacement returns the load, and the load-driven FMU's static start
(a Newton solve on the quasi-static forces) lands on the same displacement. The shaft stands
still there (omega = 0): turning, the balls' passage makes the equilibrium a steady ripple
at the outer-race ball-pass frequency (varying compliance; 0.13 µm peak to peak, 0.6 %, at
1750 rpm for this case), not a fixed point."""

import subprocess

import numpy as np
import pytest
from fmpy.fmi1 import FMICallException
from fmpy.validation import validate_fmu

from conftest import LOAD_VERSIONS, Host, fmu_path
from test_conventions import toolbox

# 6205 with 10 µm diametral clearance, quasi-static level (Jones–Harris balls at their
# kinematic cage positions), 1 kg on the inner ring, 1 kN downward on it.
BEARING = 'bearing = { preset = "6205", clearance_um = 10.0 }\n'
RELEASED = BEARING + (
    '[model]\nlevel = "quasi_static"\nstart = "rest"\nattached_mass_kg = 1.0\n'
    "contact_damping = 3000.0\n"
)
AT_EQUILIBRIUM = BEARING + '[model]\nlevel = "quasi_static"\nattached_mass_kg = 1.0\n'
MOTION_SCENE = BEARING + '[model]\nlevel = "quasi_static"\n'
LOAD = {"load.y": -1000.0, "shaft.omega": 183.26}
STILL = {"load.y": -1000.0, "shaft.omega": 0.0}
MOTION_OUT = ["shaft.x", "shaft.y", "shaft.z", "shaft.rx", "shaft.ry"]


def motion_version(version):
    return version.replace("load-", "")


@pytest.mark.parametrize("version", LOAD_VERSIONS)
def test_load_fmu_validates_and_declares_the_load_causality(host, version):
    assert validate_fmu(str(fmu_path(version))) == []
    proc = subprocess.run([toolbox(), "-input", str(fmu_path(version)), "-check"],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0 and "No semantic error" in proc.stdout + proc.stderr
    h = host(version, instantiate=False)
    caus = {v.name: v.causality for v in h.md.modelVariables}
    assert sorted(n for n, c in caus.items() if c == "input") == sorted(
        ["shaft.omega", "load.x", "load.y", "load.z", "load.mx", "load.my"])
    for n in MOTION_OUT + ["shaft.vy", "force.y", "K.y.y"]:
        assert caus[n] == "output", n
    assert h.md.guid != read_guid(motion_version(version))


def read_guid(version):
    from fmpy import read_model_description

    return read_model_description(str(fmu_path(version))).guid


@pytest.mark.parametrize("version", LOAD_VERSIONS)
def test_the_guid_decides_the_causality(host, version):
    """The same binary instantiated with the motion-driven GUID is a motion-driven
    instance: the loads are not inputs there, the shaft's motion is."""
    h = host(version, guid=read_guid(motion_version(version)))
    h.set("shaft.y", -1e-6)  # accepted: an input of the motion-driven variant
    with pytest.raises(FMICallException):
        h.set("load.y", -1.0)
    assert "`load.y`" in h.log_text() and "motion-driven" in h.log_text()
    # and a made-up token is refused, naming both known ones
    bad = Host(version, h.fmu.unzipDirectory, guid="{00000000-0000-0000-0000-000000000000}")
    with pytest.raises(Exception):
        bad.instantiate()
    assert "load-driven" in bad.log_text() and "motion-driven" in bad.log_text()


def settle(host, version):
    """The released ring (shaft still) and its shaft.y after each of 300 steps of 0.1 ms."""
    h = host(version).init(start_values={"scene": RELEASED, **STILL})
    t0 = h.get(MOTION_OUT)
    assert t0 == [0.0] * 5  # start = "rest": at the centre
    ys = []
    t = 0.0
    for _ in range(300):
        h.step(t, 1e-4)
        t += 1e-4
        ys.append(h.get(["shaft.y"])[0])
    return h, np.array(ys)


@pytest.mark.parametrize("version", LOAD_VERSIONS)
def test_released_ring_settles_at_the_quasi_static_equilibrium(host, version):
    h, ys = settle(host, version)
    x, y = h.get(["shaft.x", "shaft.y"])
    # it fell through the radial play (5 µm) and came to rest
    assert y < -5e-6
    late = ys[-100:]
    assert late.max() - late.min() < 1e-9 * abs(y), (late.min(), late.max())
    fx, fy = h.get(["force.x", "force.y"])
    assert fy == pytest.approx(1000.0, rel=1e-6) and abs(fx) < 1e-6
    # the motion-driven FMU, quasi-static level, at that displacement returns the load
    m = host(motion_version(version)).init(
        start_values={"scene": MOTION_SCENE, "input_rule": "hold", "shaft.x": x, "shaft.y": y,
                      "shaft.omega": 0.0})
    mfx, mfy = m.get(["force.x", "force.y"])
    assert mfy == pytest.approx(1000.0, rel=1e-6) and abs(mfx) < 1e-6
    # the load-driven FMU's static start solves for the host's load: the same place
    s = host(version).init(start_values={"scene": AT_EQUILIBRIUM, **STILL})
    sx, sy = s.get(["shaft.x", "shaft.y"])
    assert sy == pytest.approx(y, rel=1e-6) and sx == pytest.approx(x, rel=1e-4, abs=1e-12)
    assert s.get(["force.y"])[0] == pytest.approx(1000.0, rel=1e-6)


@pytest.mark.parametrize("version", LOAD_VERSIONS)
def test_load_fmu_state_round_trip_and_the_other_variants_state_is_refused(host, version):
    h = host(version).init(start_values={"scene": RELEASED, **LOAD})
    for k in range(5):
        h.step(k * 1e-4, 1e-4)
    s = h.get_state()
    blob = h.serialize(s)
    first = []
    for k in range(5, 10):
        h.step(k * 1e-4, 1e-4)
        first.append(h.get(MOTION_OUT + ["force.y", "balls.loaded"]))
    h.set_state(h.deserialize(blob))
    again = []
    for k in range(5, 10):
        h.step(k * 1e-4, 1e-4)
        again.append(h.get(MOTION_OUT + ["force.y", "balls.loaded"]))
    assert first == again
    # a motion-driven instance refuses the load-driven state bytes
    m = host(motion_version(version)).init()
    with pytest.raises(FMICallException):
        m.deserialize(blob)
    assert "load-driven" in m.log_text()


@pytest.mark.parametrize("version", LOAD_VERSIONS)
def test_default_scene_runs_load_driven_and_counts_are_integers(host, version):
    h = host(version).init(start_values={"load.y": -500.0})
    y0, fy0 = h.get(["shaft.y", "force.y"])
    # default scene, quasi-static level, starting in equilibrium under the host's load
    assert y0 < 0.0 and fy0 == pytest.approx(500.0, rel=1e-6)
    n = h.get(["balls.loaded"])[0]
    assert isinstance(n, int) and 1 <= n <= 9
    assert h.get_item("level") == "scene"
