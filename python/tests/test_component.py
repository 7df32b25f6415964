"""The component from Python: scenes in three forms, inputs, steps, state round trips and
errors that carry the library's message."""

import math

import pytest

import raceway

SCENE = """
bearing = "6205"
[model]
level = "ring"
[inputs]
speed_rpm = 1750.0
initial = { "shaft.x" = 0.0, "shaft.y" = -10e-6, "shaft.z" = 0.0, "shaft.rx" = 0.0,
            "shaft.ry" = 0.0, "shaft.vx" = 0.0, "shaft.vy" = 0.0, "shaft.vz" = 0.0,
            "shaft.wx" = 0.0, "shaft.wy" = 0.0 }
"""

H = 1e-4


def stepped(c, n, t0=0.0):
    for i in range(n):
        c.set("shaft.y", -10e-6 - 1e-7 * math.sin(1e3 * (t0 + i * H)))
        c.do_step(t0 + i * H, H)
    return c.outputs()


def test_scene_as_text_path_and_dict_give_the_same_bearing(tmp_path):
    path = tmp_path / "ring.toml"
    path.write_text(SCENE)
    initial = {n: 0.0 for n in ("shaft.x", "shaft.z", "shaft.rx", "shaft.ry", "shaft.vx")}
    initial.update({n: 0.0 for n in ("shaft.vy", "shaft.vz", "shaft.wx", "shaft.wy")})
    initial.update({"shaft.y": -10e-6})
    as_dict = {"bearing": "6205", "model": {"level": "ring"},
               "inputs": {"speed_rpm": 1750.0, "initial": initial}}
    outs = [stepped(raceway.Component(s), 3) for s in (SCENE, path, str(path), as_dict)]
    for o in outs[1:]:
        assert o == outs[0]
    assert outs[0]["force.y"] > 100.0  # a loaded 6205 pushes the shaft back up


def test_state_bytes_round_trip_bit_for_bit():
    c = raceway.Component(SCENE)
    stepped(c, 5)
    saved, snap, t = c.state_bytes(), c.get_state(), c.time
    ahead = stepped(c, 5, t)
    # Back by bytes, on this component and on a fresh one of the same scene.
    c.set_state_bytes(saved)
    assert c.time == t and c.state_bytes() == saved
    assert stepped(c, 5, t) == ahead
    other = raceway.Component(SCENE)
    other.set_state_bytes(saved)
    assert stepped(other, 5, t) == ahead
    # Back by the snapshot object (and its pickled copy).
    import pickle

    c.set_state(pickle.loads(pickle.dumps(snap)))
    assert bytes(snap) == saved and stepped(c, 5, t) == ahead


def test_bad_state_bytes_are_refused_and_change_nothing():
    c = raceway.Component(SCENE)
    stepped(c, 2)
    before, t = c.state_bytes(), c.time
    with pytest.raises(raceway.Error) as e:
        c.set_state_bytes(before[:-7])
    assert e.value.message == str(e.value) and e.value.message
    other_scene = raceway.Component(SCENE.replace('"ring"', '"quasi_static"'))
    with pytest.raises(raceway.Error):
        c.set_state_bytes(other_scene.state_bytes())
    assert c.state_bytes() == before and c.time == t


def test_a_bad_input_names_the_field_and_its_range_and_sets_nothing():
    c = raceway.Component(SCENE)
    before = c.inputs()
    with pytest.raises(raceway.Error) as e:
        c.set({"shaft.x": 1e-6, "shaft.omega": float("nan")})
    err = e.value
    assert err.kind == "invalid" and err.field == "shaft.omega"
    assert "shaft.omega" in err.message and "NaN" in err.message and "allowed" in err.message
    assert c.inputs() == before  # all or none
    with pytest.raises(raceway.Error) as e:
        c.get("force.q")
    assert e.value.kind == "unknown" and "force.q" in e.value.message


def test_a_bad_scene_lists_every_problem_with_the_field():
    with pytest.raises(raceway.Error) as e:
        raceway.Component(SCENE.replace('"ring"', '"rign"').replace('"6205"', "6205"))
    err = e.value
    assert err.kind == "parse" and "2 problem(s)" in err.message
    assert "model.level" in err.message and "rign" in err.message
    assert "bearing" in err.message
    assert err.field in ("model.level", "bearing")


def test_a_failed_step_leaves_the_component_as_it_was():
    c = raceway.Component(SCENE)
    stepped(c, 2)
    before = c.state_bytes()
    with pytest.raises(raceway.Error) as e:
        c.do_step(1.0, H)  # not the component's time
    assert "t" in e.value.message
    assert c.state_bytes() == before


def test_outputs_are_the_variable_table_outputs():
    c = raceway.Component(SCENE)
    stepped(c, 1)
    table = raceway.variables()
    outs = table[table.role == "output"].name.tolist()
    got = c.outputs()
    assert set(outs) <= set(got)
    assert all(math.isfinite(v) for v in got.values())
    assert got["K.y.y"] == c.get("K.y.y") and got["K.y.y"] > 1e7


def test_misuse_raises_raceway_error_naming_the_argument():
    # Issue #38 item 9: these were AttributeError (set(None, 1.0), set of a list), a JSON
    # syntax error without a field (NaN in a scene dict) and RecursionError (a scene dict
    # nested 2000 deep, or containing itself).
    c = raceway.Component()
    for bad in [(None, 1.0), (5,), ([("shaft.y",)],), ([1, 2],)]:
        with pytest.raises(raceway.Error) as e:
            c.set(*bad)
        assert e.value.field == "name" and "(name, value) pairs" in e.value.message
    # A sequence of pairs is a way to set several inputs, as a dict is.
    c.set([("shaft.y", -1e-5), ("shaft.omega", 100.0)])
    assert c.get("shaft.y") == -1e-5 and c.get("shaft.omega") == 100.0
    with pytest.raises(raceway.Error) as e:
        raceway.Component({"bearing": "6205", "run": {"duration_s": float("nan")}})
    assert e.value.field == "run.duration_s" and "finite" in e.value.message
    deep = {}
    inner = deep
    for _ in range(2000):
        inner["a"] = {}
        inner = inner["a"]
    itself = {}
    itself["r"] = itself
    for scene in (deep, itself):
        with pytest.raises(raceway.Error) as e:
            raceway.Component(scene)
        assert "nests deeper than 16 levels" in e.value.message


def test_unset_inputs_hold_the_scenes_initial_values_as_the_cli_does(tmp_path, cli):
    """One rule for unset inputs: the default scene's component, never given an input,
    holds the scene's initial values, so its force at t = 0 and after one step equals the
    first two rows of `raceway run`."""
    import csv

    cli("run", "-q", "--duration", "0.0002", "--out", str(tmp_path))
    with open(tmp_path / "series.csv") as f:
        rows = list(csv.DictReader(f))[:2]
    want = [(float(r["force.x [N]"]), float(r["force.y [N]"])) for r in rows]
    c = raceway.Component()
    assert c.get("shaft.y") == -10e-6 and c.get("shaft.x") == 0.0
    got = [(c.get("force.x"), c.get("force.y"))]
    c.do_step(0.0, 1e-4)
    got.append((c.get("force.x"), c.get("force.y")))
    for g, w in zip(got, want):
        assert g == pytest.approx(w, abs=1e-9 * abs(want[0][1]))
