"""A bearing set as one FMU (FMI 2 and 3 through fmpy): the 7008CE DB pair of
examples/scenes/7008ce-db-pair.toml, motion-driven, publishes the single bearing's
variables at its reference point and its rows' own; its axial stiffness from two small
displacements agrees with `raceway shaft` on the same pair."""

import json
import subprocess

import pytest

from conftest import ROOT, VERSIONS

PAIR = (ROOT / "examples" / "scenes" / "7008ce-db-pair.toml").read_text()
OMEGA = 1256.637061  # 12 000 rpm, as the scene
ZERO = {n: 0.0 for n in ("shaft.x", "shaft.y", "shaft.z", "shaft.rx", "shaft.ry",
                         "shaft.vx", "shaft.vy", "shaft.vz", "shaft.wx", "shaft.wy")}

SHAFT = """speed_rpm = 12000
[[location]]
name = "pair"
position_mm = 0
bearing = "7008CE"
arrangement = "db"
spacer_mm = 0
preload_n = 300
"""


def _pair_force_z(host, version, dz):
    h = host(version)
    h.init(start_values={"scene": PAIR, **ZERO, "shaft.z": dz, "shaft.omega": OMEGA})
    h.step(0.0, 1e-4)
    fz, f0, f1, kzz = h.get(["force.z", "row0.force.z", "row1.force.z", "K.z.z"])
    return fz, f0, f1, kzz


@pytest.fixture(scope="module")
def shaft_k(tmp_path_factory):
    """K.z.z of the same pair from `raceway shaft --json` (the set module's)."""
    path = tmp_path_factory.mktemp("shaft") / "pair.toml"
    path.write_text(SHAFT)
    out = subprocess.run(
        ["cargo", "run", "-q", "--bin", "raceway", "--", "shaft", str(path), "--json"],
        cwd=ROOT, capture_output=True, text=True, check=True,
    ).stdout
    return json.loads(out)["stiffness [SI]"][2][2]


@pytest.mark.parametrize("version", VERSIONS)
def test_a_db_pair_fmu_has_the_set_modules_axial_stiffness(host, version, shaft_k):
    # at rest in the housing: equal and opposite row loads, no net axial force
    fz, f0, f1, _ = _pair_force_z(host, version, 0.0)
    assert abs(fz) < 1e-6 and f0 == pytest.approx(-f1, rel=1e-9) and f1 > 0.0
    dz = 0.2e-6
    fp, *_ , kp = _pair_force_z(host, version, dz)
    fm, *_ = _pair_force_z(host, version, -dz)
    k = -(fp - fm) / (2.0 * dz)
    assert k == pytest.approx(shaft_k, rel=0.01)
    assert kp == pytest.approx(shaft_k, rel=0.01)


@pytest.mark.parametrize("version", VERSIONS)
def test_per_row_outputs_are_declared_once_for_every_face(host, version):
    h = host(version)
    for i in range(4):
        for k in ("force.x", "force.y", "force.z", "moment.x", "moment.y", "contact_angle",
                  "lift_off", "life.L10"):
            assert f"row{i}.{k}" in h.vr
    assert h.types["row0.lift_off"] in ("Integer", "Int32")
