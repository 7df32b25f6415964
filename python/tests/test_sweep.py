"""raceway.Sweep and raceway.sweep against `raceway sweep`: same index space, same table."""

import pickle

import pandas as pd
import pytest

import raceway
from sweeps import SWEEP, assert_same_table


@pytest.fixture(scope="module")
def cli_table(cli, root, tmp_path_factory):
    out = tmp_path_factory.mktemp("cli")
    cli("sweep", SWEEP, "--out", str(out), "--jobs", "1", "--quiet")
    return pd.read_csv(out / "sweep.csv")


def test_threads_and_shards_give_the_cli_table(root, cli_table, tmp_path):
    path = root / SWEEP
    assert_same_table(raceway.sweep(path, jobs=2), cli_table)
    # Two shards into one folder: the whole table again; a third call resumes (runs nothing).
    raceway.sweep(path, tmp_path, jobs=1, shard=(0, 2))
    rows = sorted((tmp_path / "rows").iterdir())
    assert len(rows) == 9
    assert_same_table(raceway.sweep(path, tmp_path, shard=(1, 2)), cli_table)
    stamp = [p.stat().st_mtime_ns for p in sorted((tmp_path / "rows").iterdir())]
    assert_same_table(raceway.sweep(path, tmp_path), cli_table)
    assert [p.stat().st_mtime_ns for p in sorted((tmp_path / "rows").iterdir())] == stamp


def test_points_rows_and_pickling(root, cli_table):
    sw = raceway.Sweep(root / SWEEP)
    assert len(sw) == len(cli_table) == 18
    assert sw.columns == [c for c in cli_table.columns[1:5]]
    p = sw.point(5)
    assert list(p) == sw.columns
    assert p['inputs.speed_rpm'] == cli_table.loc[5, 'inputs.speed_rpm']
    # A pickled sweep carries its base scene: the same points anywhere.
    again = pickle.loads(pickle.dumps(sw))
    assert len(again) == 18 and again.scene_text(7) == sw.scene_text(7)
    rows = again.run_points(range(18))
    assert all(r["error"] is None for r in rows)
    assert_same_table(sw.table(rows[::-1]), cli_table)


def test_a_failed_point_is_a_row():
    sw = raceway.Sweep(
        {"axis": [{"key": "run.step_s", "values": [1e-4, 1.0]}, {"key": "run.duration_s", "values": [0.001]}]}
    )
    ok, bad = sw.run_points([0, 1])
    assert ok["error"] is None and ok["summary"]
    assert "run.step_s" in bad["error"] and bad["summary"] == []


def test_a_bad_sweep_gets_every_problem_with_line_and_column():
    text = 'scene = "nope.toml"\n\n[[axis]]\nkey = "run.duration_s"\nvalue = [1]\n'
    with pytest.raises(raceway.Error) as e:
        raceway.Sweep(text)
    m = e.value.message
    assert "problem(s)" in m and "1:1" in m and "nope.toml" in m and "5:1" in m, m
