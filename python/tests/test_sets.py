"""A bearing set as one raceway.Component: the 7008CE DB pair of
examples/scenes/7008ce-db-pair.toml from Python, its rows' outputs, its stiffness the set
module's (raceway.shaft on the same pair), and a run's DataFrame carrying its rows."""

import math

import pytest

import raceway

ZERO = {n: 0.0 for n in ("shaft.x", "shaft.y", "shaft.z", "shaft.rx", "shaft.ry",
                         "shaft.vx", "shaft.vy", "shaft.vz", "shaft.wx", "shaft.wy")}
OMEGA = 1256.637061
SHAFT = """speed_rpm = 12000
[[location]]
position_mm = 0
bearing = "7008CE"
arrangement = "db"
preload_n = 300
"""


@pytest.fixture
def pair(root):
    return root / "examples" / "scenes" / "7008ce-db-pair.toml"


def test_a_db_pair_component_balances_its_preload_and_has_the_set_modules_k(pair):
    c = raceway.Component(pair)
    # At rest the rigid preload is the 300 N it was set by, in both rows.
    c.set({**ZERO, "shaft.omega": 0.0})
    c.do_step(0.0, 1e-4)
    f0, f1 = c.get("row0.force.z"), c.get("row1.force.z")
    assert f1 == pytest.approx(300.0, rel=1e-6) and f0 == pytest.approx(-f1, rel=1e-9)
    assert abs(c.get("force.z")) < 1e-6
    assert c.get("row0.lift_off") == 0.0
    # At 12 000 rpm the balls' centrifugal force raises the rigid preload (to about 335 N,
    # still balanced), and K is the set module's at that speed.
    c.set("shaft.omega", OMEGA)
    c.do_step(1e-4, 1e-4)
    f0, f1 = c.get("row0.force.z"), c.get("row1.force.z")
    assert f1 > 300.0 and f0 == pytest.approx(-f1, rel=1e-9)
    k = raceway.shaft(SHAFT)["stiffness [SI]"]
    assert c.get("K.z.z") == pytest.approx(k[2][2], rel=0.01)
    assert c.get("K.rx.rx") == pytest.approx(k[3][3], rel=0.01)
    # A shaft pushed 60 µm toward +z loads the row at -z (orientation +1) and lifts the
    # row at +z (orientation -1, carrying thrust toward -z) off; at 12 000 rpm a 30 µm
    # push still leaves it about 24 N (measured).
    c.set("shaft.z", 60e-6)
    c.do_step(2e-4, 1e-4)
    assert c.get("row1.lift_off") == 1.0 and c.get("row0.lift_off") == 0.0
    assert c.get("row1.force.z") == 0.0
    assert c.get("force.z") == pytest.approx(c.get("row0.force.z"), rel=1e-12)


def test_a_set_run_records_its_rows_and_a_single_bearing_does_not(pair):
    df, _ = raceway.run(pair, 2e-3)
    rows = [c for c in df.columns if c.startswith("row") and c[3:4].isdigit()]
    assert any(c.startswith("row0.force.z") for c in rows)
    assert any(c.startswith("row1.contact_angle") for c in rows)
    assert not any(c.startswith("row2.") for c in rows)
    single, _ = raceway.run(None, 2e-3)
    assert not any(c.startswith("row") and c[3:4].isdigit() for c in single.columns)
    assert all(math.isfinite(v) for v in df.iloc[-1])
