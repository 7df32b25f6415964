"""A tapered roller bearing (30206, catalogue geometry) under combined radial and axial load
through the FMUs (FMI 2 and FMI 3, motion- and load-driven), against the quasi-static table of
the command line (`raceway quasi-static --bearing 30206 --fy -4000 --fz 2000 --json`).

The physics: the table solves the 5-DOF equilibrium of the rollers (cup, cone and back flange,
docs/physics.md §R7) under Fy = -4 kN, Fz = +2 kN, at rest. Given that displacement, the
motion-driven FMU's ring level (5 DOF, the same roller law on massless rollers) returns the
rollers' force the table reports (the load's opposite: axial/radial ratio -0.5); the load-driven
FMU's static start under the same load lands on the table's displacement. Nothing here is a
value the test computes itself: both sides come from the shipped binaries."""

import json
import os
import shutil
import subprocess

import pytest

from conftest import LOAD_VERSIONS, ROOT, VERSIONS

LOAD = [0.0, -4000.0, 2000.0, 0.0, 0.0]
MOTION = ["shaft.x", "shaft.y", "shaft.z", "shaft.rx", "shaft.ry"]
FORCE = ["force.x", "force.y", "force.z", "moment.x", "moment.y"]
RING5 = 'bearing = "30206"\n[model]\nlevel = "ring"\nring_dof = 5\n'
RING5_LOAD = RING5 + 'causality = "load"\ncontact_damping = 3000.0\nattached_mass_kg = 1.0\n'


def raceway_cli():
    """The command line: $RACEWAY_CLI, else the release or debug build under the target
    folder, else `cargo run --release`."""
    if os.environ.get("RACEWAY_CLI"):
        return [os.environ["RACEWAY_CLI"]]
    target = ROOT / os.environ.get("CARGO_TARGET_DIR", "target")
    for profile in ("release", "debug"):
        exe = target / profile / "raceway"
        if exe.exists():
            return [str(exe)]
    return [shutil.which("cargo") or "cargo", "run", "-q", "--release", "--bin", "raceway", "--"]


@pytest.fixture(scope="module")
def table():
    """The quasi-static table's solution: displacement q (m, rad) and the rollers' force."""
    args = ["quasi-static", "--bearing", "30206", "--fy", str(LOAD[1]), "--fz", str(LOAD[2]),
            "--json"]
    proc = subprocess.run(raceway_cli() + args, cwd=ROOT, capture_output=True, text=True,
                          timeout=900)
    assert proc.returncode == 0, proc.stderr
    d = json.loads(proc.stdout)
    assert d["element"] == "roller" and d["speed [rpm]"] == 0.0
    s = d["solution"]
    axes = (("x", "m", "N"), ("y", "m", "N"), ("z", "m", "N"), ("rx", "rad", "N.m"),
            ("ry", "rad", "N.m"))
    return ([s[f"displacement.{a} [{m}]"] for a, m, _ in axes],
            [s[f"force.{a} [{n}]"] for a, _, n in axes])


def close(a, b, scale, rel=1e-6):
    return abs(a - b) <= rel * scale


@pytest.mark.parametrize("version", VERSIONS)
def test_trb_motion_driven_returns_the_quasi_static_force(host, version, table):
    q, f_qs = table
    # The table balances the load: the rollers push back with its opposite.
    assert f_qs[1] == pytest.approx(-LOAD[1], rel=1e-9)
    assert f_qs[2] == pytest.approx(-LOAD[2], rel=1e-9)
    start = {"scene": RING5, "input_rule": "hold", "shaft.omega": 0.0}
    start.update(dict(zip(MOTION, q)))
    h = host(version).init(start_values=start)
    f = h.get(FORCE)
    scale = abs(LOAD[1])
    for name, got, want in zip(FORCE[:3], f[:3], f_qs[:3]):
        assert close(got, want, scale), (name, got, want)
    # combined load: the axial/radial ratio of the table, -0.5
    assert f[2] / f[1] == pytest.approx(-0.5, rel=1e-6)
    # a tapered bearing under combined load: several rollers carry it, none is in tension
    assert h.get(["balls.loaded"])[0] >= 5
    assert h.get(["contact.max_pressure"])[0] > 1e9
    # held still, a step changes nothing (the rollers stay at their azimuths at rest)
    h.step(0.0, 1e-4)
    f1 = h.get(FORCE)
    for name, a, b in zip(FORCE[:3], f1[:3], f[:3]):
        assert close(a, b, scale, rel=1e-9), (name, a, b)


@pytest.mark.parametrize("version", LOAD_VERSIONS)
def test_trb_load_driven_starts_at_the_quasi_static_displacement(host, version, table):
    q, _ = table
    start = {"scene": RING5_LOAD, "shaft.omega": 0.0}
    start.update({n: v for n, v in zip(["load.x", "load.y", "load.z", "load.mx", "load.my"],
                                       LOAD)})
    h = host(version).init(start_values=start)
    x = h.get(MOTION)
    # translations to 1e-4 of the radial displacement, tilts to 1e-4 of the table's
    for name, got, want, scale in zip(MOTION, x, q, [abs(q[1])] * 3 + [abs(q[3])] * 2):
        assert close(got, want, scale, rel=1e-4), (name, got, want)
    fy, fz = h.get(["force.y", "force.z"])
    assert fy == pytest.approx(-LOAD[1], rel=1e-6)
    assert fz == pytest.approx(-LOAD[2], rel=1e-6)
    # it stays there: 100 steps of 0.1 ms at rest move the ring by less than 1 nm
    t = 0.0
    for _ in range(100):
        h.step(t, 1e-4)
        t += 1e-4
    x1 = h.get(MOTION)
    assert all(abs(a - b) < 1e-9 for a, b in zip(x1[:3], x[:3])), (x1, x)
    fy, fz = h.get(["force.y", "force.z"])
    assert fz / fy == pytest.approx(-0.5, rel=1e-4)

