"""Sweeps over a Dask ``distributed`` cluster: the same index space as ``raceway sweep``.

Dask schedules; raceway computes each point (a pure function index → row) on a worker.
Any ``distributed.Client`` works: a ``LocalCluster`` on one machine, or
``dask_jobqueue.SLURMCluster`` (PBS, SGE, ...) on a cluster.
"""

from __future__ import annotations

import os
from typing import Any, Optional, Union

import pandas as pd

from . import Sweep, SweepLike

def sweep(
    sweep: Union[SweepLike, Sweep],
    client: Any,
    *,
    out: Optional[Union[str, "os.PathLike[str]"]] = None,
    batch: Optional[int] = None,
) -> pd.DataFrame:
    """Map the sweep's points over ``client`` (a ``distributed.Client``) and return the
    table: the same DataFrame as ``pd.read_csv`` of the serial ``raceway sweep``'s
    ``sweep.csv``, bit for bit in every column but the machine measurements ``cpu [s]`` and
    ``load_average``.

    ``out``: also write the rows into this folder as ``raceway sweep --out`` does
    (``rows/<index>.json`` and ``sweep.csv``; finished rows there are skipped, so a sweep
    resumes, and the folder merges with ``raceway sweep --merge``). ``batch``: points per
    Dask task (``None``: about four tasks per worker thread, so the scheduler's overhead stays
    small against the runs).
    """
