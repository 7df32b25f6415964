"""raceway.dask.sweep on a real LocalCluster of two worker processes: the serial CLI's
table, bit for bit."""

import pandas as pd
import pytest

import raceway
import raceway.dask
from sweeps import SWEEP, assert_same_table

distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    )
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


def test_dask_gives_the_serial_cli_table(cli, root, client, tmp_path):
    cli("sweep", SWEEP, "--out", str(tmp_path / "cli"), "--jobs", "1", "--quiet")
    ref = pd.read_csv(tmp_path / "cli" / "sweep.csv")
    # Small batches so both workers get several tasks.
    got = raceway.dask.sweep(root / SWEEP, client, batch=2)
    assert_same_table(got, ref)
    # The workers are separate processes: each ran points.
    assert len(client.scheduler_info()["workers"]) == 2


def test_dask_into_a_folder_resumes_and_merges_with_the_cli(cli, root, client, tmp_path):
    out = tmp_path / "dask"
    # Half the points by the CLI (a shard), the rest by Dask into the same folder.
    cli("sweep", SWEEP, "--out", str(out), "--shard", "0/2", "--quiet")
    got = raceway.dask.sweep(str(root / SWEEP), client, out=out)
    ref_dir = tmp_path / "cli"
    cli("sweep", SWEEP, "--out", str(ref_dir), "--jobs", "1", "--quiet")
    ref = pd.read_csv(ref_dir / "sweep.csv")
    assert_same_table(got, ref)
    assert_same_table(pd.read_csv(out / "sweep.csv"), ref)
    # Nothing left: the CLI resumes with zero runs.
    assert "ran 0, skipped 18" in cli("sweep", SWEEP, "--out", str(out), "--quiet")
    # Another sweep's folder is refused.
    other = {"axis": [{"key": "run.duration_s", "values": [0.001]}]}
    with pytest.raises(raceway.Error) as e:
        raceway.dask.sweep(other, client, out=out)
    assert "another sweep" in e.value.message
