"""Sweeps over a Dask ``distributed`` cluster (documented in ``dask.pyi``).

Dask only schedules: each task is a batch of point indices, and a worker computes each
point with the same library function as ``raceway sweep`` (``raceway::sweep::Sweep::
run_point``), so the rows are the same bit for bit. The rows come back as the library's
JSON and the table is made by the library's CSV writer, then read by pandas as the CLI's
sweep.csv is.
"""

from __future__ import annotations

import math
import os
from typing import Any, List, Optional, Sequence, Union

import pandas as pd

from . import Sweep, _raceway, _table


def _run_batch(sweep: Any, indices: Sequence[int], series_dir: Optional[str]) -> List[str]:
    """On a worker: the rows (JSON) of a batch of points."""
    return sweep.run_points_json(list(indices), series_dir)


def sweep(
    sweep: Any,
    client: Any,
    *,
    out: Optional[Union[str, "os.PathLike[str]"]] = None,
    batch: Optional[int] = None,
) -> pd.DataFrame:
    """Map the sweep's points over a Dask ``distributed.Client``.

    Parameters
    ----------
    sweep : str, os.PathLike, dict or raceway.Sweep
        The sweep file's path, its TOML text, a dict of the same tables, or a Sweep.
    client : distributed.Client
        Any client: a ``LocalCluster``, or ``dask_jobqueue.SLURMCluster`` on a cluster.
    out : str or os.PathLike, optional
        Also write the rows into this folder as ``raceway sweep --out`` does; finished rows
        there are skipped (resume), and it merges with ``raceway sweep --merge``.
    batch : int, optional
        Points per Dask task (``None``: about four tasks per worker thread).

    Returns
    -------
    pandas.DataFrame
        The DataFrame ``pd.read_csv`` gives for the serial ``raceway sweep``'s
        ``sweep.csv``, bit for bit in every column but ``cpu [s]`` and ``load_average``.

    Raises
    ------
    raceway.Error
        For a bad sweep file.

    Examples
    --------
    >>> from distributed import Client, LocalCluster  # doctest: +SKIP
    >>> import raceway.dask  # doctest: +SKIP
    >>> with Client(LocalCluster(n_workers=2)) as client:  # doctest: +SKIP
    ...     table = raceway.dask.sweep("examples/sweeps/6205-speed-displacement.toml", client)
    """
    from distributed import as_completed  # optional dependency: only here

    native = Sweep(sweep)._native
    folder = None if out is None else os.fspath(out)
    todo = list(range(len(native)))
    if folder is not None:
        finished = set(_raceway.sweep_finished(native, folder))
        todo = [i for i in todo if i not in finished]
    if batch is None:
        threads = max(1, sum(client.nthreads().values()))
        batch = max(1, math.ceil(len(todo) / (4 * threads)))
    if batch < 1:
        raise _raceway.Error(f"batch = {batch}: must be >= 1")
    series_dir = None if folder is None else os.path.join(os.path.abspath(folder), "series")
    rows: List[str] = []
    if todo:
        shared = client.scatter(native, broadcast=True, hash=False)
        batches = [todo[k : k + batch] for k in range(0, len(todo), batch)]
        futures = client.map(
            _run_batch,
            [shared] * len(batches),
            batches,
            [series_dir] * len(batches),
            pure=False,
        )
        for future in as_completed(futures):
            done = future.result()
            rows.extend(done)
            if folder is not None:
                # Each batch on disk as it arrives: a killed sweep resumes from there.
                _raceway.sweep_store(folder, done)
    if folder is not None:
        return _table(_raceway.sweep_store(folder, []))
    return _table(_raceway.sweep_csv(rows))
