"""raceway.quasi_static on roller bearings, raceway.shaft and the duty cycle against the
command line: the same solver and the same JSON, so the same numbers bit for bit."""

import numpy as np
import pytest

import raceway

ROLLER_CASES = [
    # (designation, keyword loads, the command line's flags)
    ("NU206", dict(fy=-8000.0), ["--fy", "-8000"]),
    ("30206", dict(fy=-5000.0, fz=2000.0), ["--fy", "-5000", "--fz", "2000"]),
]


@pytest.mark.parametrize("name,loads,flags", ROLLER_CASES, ids=[c[0] for c in ROLLER_CASES])
def test_roller_bearing_is_the_command_lines(cli, name, loads, flags):
    r = raceway.quasi_static(name, **loads)
    ref = cli.json("quasi-static", "--bearing", name, *flags, "--json")
    assert isinstance(r, raceway.RollerQuasiStaticResult)
    assert r.data == ref
    sol = ref["solution"]
    np.testing.assert_array_equal(r.K, np.array(sol["stiffness [SI]"]))
    axes = (("x", "m"), ("y", "m"), ("z", "m"), ("rx", "rad"), ("ry", "rad"))
    np.testing.assert_array_equal(r.displacement, [sol[f"displacement.{a} [{u}]"] for a, u in axes])
    np.testing.assert_array_equal(r.lamina_pressure[0], sol["rollers"][0]["lamina_pressure [Pa]"])
    # One row per roller, one column per lamina.
    z = len(sol["rollers"])
    assert len(r.rollers) == z and r.rollers.index.name == "roller"
    assert r.lamina_load.shape == (z, len(sol["rollers"][0]["lamina_load_outer [N]"]))
    # Equilibrium: the rollers' force on the shaft balances the load.
    load = np.array([loads.get(k, 0.0) for k in ("fx", "fy", "fz", "mx", "my")])
    np.testing.assert_allclose(r.forces[:3], -load[:3], atol=1e-6 * np.abs(load).max())
    # The largest lamina pressure is the report's and bounds each roller's peak pressure.
    assert r.lamina_pressure.max() == ref["max_pressure [Pa]"]
    assert (r.rollers["p_i [Pa]"] <= ref["max_pressure [Pa]"] * (1 + 1e-12)).all()
    # ISO/TS 16281's lamina life and the lamina static safety come with the table; the
    # edge-stress factor (>= 1 on every lamina) can only shorten the life.
    s0 = (4000e6 / ref["max_pressure [Pa]"]) ** 2
    assert ref["S0_lamina [1]"] == pytest.approx(s0, rel=1e-12)
    with_edge = ref["lamina_life"]["L10r [Mrev]"]
    assert 0 < with_edge <= ref["lamina_life_without_edge_factor"]["L10r [Mrev]"]
    assert any("UNSOURCED" in n for n in ref["notes"])


def test_cylindrical_roller_loads_add_up_to_the_radial_load():
    # NU206 at rest: contact normals are radial, so the roller loads, each along its
    # azimuth, add up to the 8 kN radial load.
    r = raceway.quasi_static("NU206", fy=-8000.0).rollers
    psi, q = r["psi [rad]"], r["q_i [N]"]
    total = np.hypot((q * np.cos(psi)).sum(), (q * np.sin(psi)).sum())
    assert total == pytest.approx(8000.0, rel=1e-9)
    assert (r["flange [N]"] == 0.0).all()


def test_ball_bearing_result_is_unchanged(cli):
    q = raceway.quasi_static("6205", fy=2000.0)
    assert isinstance(q, raceway.QuasiStaticResult)
    assert q.data == cli.json("quasi-static", "--bearing", "6205", "--fy", "2000", "--json")


def test_ball_only_options_are_refused_for_a_roller_bearing():
    with pytest.raises(raceway.Error) as e:
        raceway.quasi_static("NU206", fy=-8000.0, kappa=2.0)
    assert e.value.field == "kappa"
    with pytest.raises(raceway.Error) as e:
        raceway.quasi_static("NU206", speed_rpm=-1.0, fy=-8000.0)
    assert e.value.field == "speed_rpm"


def test_shaft_is_the_command_lines(cli, root):
    path = root / "examples" / "shafts" / "spindle.toml"
    ref = cli.json("shaft", str(path), "--json")
    assert raceway.shaft(path) == ref
    assert raceway.shaft(str(path)) == ref
    assert raceway.shaft(path.read_text()) == ref
    # The locations' reactions balance the load at the origin.
    axes = ("x", "y", "z")
    total = np.sum(
        [[loc["set"][f"force.{a} [N]"] for a in axes] for loc in ref["locations"]], axis=0
    )
    load = np.array([ref[f"load.{a} [N]"] for a in axes])
    np.testing.assert_allclose(total, -load, atol=1e-6)


def test_single_bearing_shaft_is_refused_by_field():
    text = """
speed_rpm = 1000
[[load]]
position_mm = 0
force_n = [0, -500, 100]
[[location]]
name = "only"
position_mm = 0
bearing = "6205"
"""
    with pytest.raises(raceway.Error) as e:
        raceway.shaft(text)
    assert e.value.field == "location"
    assert "single-row bearing cannot hold" in str(e.value)


DUTY = "fr_n, fa_n, speed_rpm, time_share\n2000, 0, 3000, 0.5\n4000, 500, 1500, 0.5\n"


def test_duty_is_the_command_lines(cli, tmp_path):
    f = tmp_path / "duty.csv"
    f.write_text(DUTY)
    ref = cli.json("quasi-static", "--bearing", "6205", "--fy", "2000", "--oil", "VG68",
                   "--contamination", "0.5", "--duty", str(f), "--json")
    kw = dict(fy=2000.0, oil="VG68", contamination=0.5)
    q = raceway.quasi_static("6205", duty=f, **kw)
    assert q.data == ref and ref["calculator"]["duty"] is not None
    # The same spectrum as text and as rows.
    assert raceway.quasi_static("6205", duty=DUTY, **kw).data == ref
    rows = [(2000, 0, 3000, 0.5), (4000, 500, 1500, 0.5)]
    assert raceway.quasi_static("6205", duty=rows, **kw).data == ref
    # Without --duty no duty life.
    assert raceway.quasi_static("6205", **kw).data["calculator"].get("duty") is None


def test_bad_duty_and_shaft_arguments_name_the_argument(tmp_path):
    for bad in (tmp_path / "missing.csv", [(1.0, "x", 3.0, 1.0)]):
        with pytest.raises(raceway.Error) as e:
            raceway.quasi_static("6205", fy=2000.0, duty=bad)
        assert e.value.field == "duty"
    # A row of 3 numbers: the library's parser, naming the line.
    with pytest.raises(raceway.Error) as e:
        raceway.quasi_static("6205", fy=2000.0, duty="1000, 0, 3000\n")
    assert "line 1" in str(e.value)
    with pytest.raises(raceway.Error) as e:
        raceway.shaft({"speed_rpm": 0})
    assert e.value.field == "shaft"
