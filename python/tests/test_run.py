"""raceway.run against `raceway run`: the same series columns (with SI units) and the same
summary."""

import json
import math

import numpy as np
import pandas as pd

import raceway

MEASUREMENTS = {"cpu [s]", "load_average"}


def test_run_matches_the_command_line(cli, tmp_path):
    series, summary = raceway.run(None, duration=0.02)
    cli("run", "--quiet", "--duration", "0.02", "--out", str(tmp_path))
    csv = pd.read_csv(tmp_path / "series.csv")
    # The CLI prints numbers with {:e} (shortest round trip), so the values are equal.
    assert list(series.columns) == list(csv.columns)
    np.testing.assert_array_equal(series.to_numpy(), csv.to_numpy())
    ref = json.loads((tmp_path / "summary.json").read_text())
    for k in MEASUREMENTS:
        ref.pop(k), summary.pop(k)
    assert summary == ref


def test_columns_carry_the_variable_table_units():
    series, _ = raceway.run(None, duration=0.005, kc=True)
    table = raceway.variables().set_index("name")
    assert series.columns[0] == "t [s]"
    for col in series.columns[1:]:
        name, unit = col[: col.index(" [")], col[col.index("[") + 1 : -1]
        assert table.loc[name, "unit"] == unit, col
    assert "K.y.y [N/m]" in series.columns and "C.y.y [N.s/m]" in series.columns
    assert np.isfinite(series.to_numpy()).all()
    t = series["t [s]"].to_numpy()
    assert math.isclose(t[-1], 0.005, rel_tol=1e-12) and (np.diff(t) > 0).all()


def test_duration_is_checked_like_the_scene_field():
    import pytest

    with pytest.raises(raceway.Error) as e:
        raceway.run(None, duration=-1.0)
    assert "run.duration_s" in e.value.message and "-1" in e.value.message


def test_columns_are_the_outputs_the_level_and_effects_set(cli, root, tmp_path):
    """issue #40 item 4: no cage, guide or wear columns on the linear level; a wear scene
    keeps its wear and film columns; the DataFrame's columns are series.csv's header."""
    linear = str(root / "examples/scenes/6205-linear.toml")
    series, _ = raceway.run(linear, duration=0.002)
    cli("run", linear, "--quiet", "--duration", "0.002", "--out", str(tmp_path / "lin"))
    header = (tmp_path / "lin" / "series.csv").read_text().splitlines()[0].split(",")
    assert list(series.columns) == header
    names = {c[: c.index(" [")] for c in series.columns}
    for gone in ("cage.slip", "cage.x", "cage.speed", "guide.force", "pocket.max_force",
                 "wear.max_depth", "film.min_thickness", "power.loss"):
        assert gone not in names, gone
    wear, _ = raceway.run(str(root / "examples/scenes/6012-wear.toml"), duration=0.002)
    assert "wear.max_depth [m]" in wear.columns and "film.min_thickness [m]" in wear.columns
    assert "guide.force [N]" not in wear.columns
