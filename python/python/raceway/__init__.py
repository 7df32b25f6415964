"""raceway: rolling-element (ball) bearing simulation from Python.

The API with its documentation is in ``__init__.pyi`` (what editors show); this module adds
pandas and numpy around the native module ``raceway._raceway`` (PyO3), which does all the
work with the GIL released.
"""

from __future__ import annotations

import io
import json
import os
import shutil
import tempfile
from dataclasses import dataclass
from typing import Any, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import pandas as pd

from . import _raceway
from ._raceway import Component, Error, State

__version__: str = _raceway.__version__

__all__ = [
    "Component",
    "Error",
    "QuasiStaticResult",
    "State",
    "Sweep",
    "bearing",
    "bearings",
    "quasi_static",
    "run",
    "sweep",
    "variables",
]


def variables() -> pd.DataFrame:
    """The variable table (name, vr, unit, role, description)."""
    return pd.DataFrame(
        _raceway.variable_table(), columns=["name", "vr", "unit", "role", "description"]
    )


def run(scene: Any = None, duration: Optional[float] = None, *, kc: bool = False):
    """Run a scene as ``raceway run`` does: (series DataFrame, summary dict)."""
    names, columns, summary = _raceway.run(scene, duration, kc)
    series = pd.DataFrame(dict(zip(names, (np.asarray(c) for c in columns))))
    return series, json.loads(summary)


@dataclass
class QuasiStaticResult:
    """The Jones–Harris quasi-static equilibrium of :func:`quasi_static`."""

    balls: pd.DataFrame
    K: np.ndarray
    displacement: np.ndarray
    forces: np.ndarray
    data: dict


def quasi_static(
    bearing: Optional[str] = None,
    speed_rpm: float = 0.0,
    fx: float = 0.0,
    fy: float = 0.0,
    fz: float = 0.0,
    mx: float = 0.0,
    my: float = 0.0,
    *,
    race_control: Optional[str] = None,
    kappa: Optional[float] = None,
    contamination: Optional[float] = None,
    oil: Optional[str] = None,
    oil_vi: Optional[float] = None,
    oil_temp_c: Optional[float] = None,
    f0: Optional[float] = None,
    shaft_interference_um: Optional[float] = None,
    housing_interference_um: Optional[float] = None,
    inner_ring_temp_c: Optional[float] = None,
    outer_ring_temp_c: Optional[float] = None,
) -> QuasiStaticResult:
    """The Jones–Harris quasi-static equilibrium, as ``raceway quasi-static`` solves it.

    The design check (oil viscosity and kappa, Palmgren friction, subsurface stresses,
    operating clearance; docs/calculator.md) is ``result.data["calculator"]``.
    """
    text, names, columns = _raceway.quasi_static(
        None if bearing is None else os.fspath(bearing),
        float(speed_rpm),
        [float(v) for v in (fx, fy, fz, mx, my)],
        race_control,
        kappa,
        contamination,
        oil,
        oil_vi,
        oil_temp_c,
        f0,
        shaft_interference_um,
        housing_interference_um,
        inner_ring_temp_c,
        outer_ring_temp_c,
    )
    data = json.loads(text)
    sol = data["solution"]
    balls = pd.DataFrame(dict(zip(names, (np.asarray(c) for c in columns))))
    balls.index.name = "ball"
    return QuasiStaticResult(
        balls=balls,
        K=np.array(sol["stiffness"], dtype=float).reshape(5, 5),
        displacement=np.array(sol["q"], dtype=float),
        forces=np.array(sol["forces"], dtype=float),
        data=data,
    )


def bearings() -> pd.DataFrame:
    """The bearing presets as ``raceway bearings --json`` lists them."""
    return pd.DataFrame(json.loads(_raceway.bearings_json()))


def bearing(name: str) -> dict:
    """One preset or catalogue designation, as ``raceway bearings NAME --json``."""
    return json.loads(_raceway.bearing_json(name))


def _table(csv_text: str) -> pd.DataFrame:
    """sweep.csv text as ``pd.read_csv`` loads the file."""
    return pd.read_csv(io.StringIO(csv_text))


class Sweep:
    """A parsed and checked sweep (see ``__init__.pyi``)."""

    def __init__(self, sweep: Any) -> None:
        if isinstance(sweep, Sweep):
            self._native = sweep._native
        elif isinstance(sweep, _raceway.Sweep):
            self._native = sweep
        else:
            self._native = _raceway.Sweep(sweep)

    def __len__(self) -> int:
        return len(self._native)

    def __repr__(self) -> str:
        return repr(self._native)

    @property
    def columns(self) -> list:
        return self._native.columns

    def point(self, index: int) -> dict:
        return dict(json.loads(self._native.point_json(index)))

    def scene_text(self, index: int) -> str:
        return self._native.scene_text(index)

    def run_point(self, index: int) -> dict:
        return self.run_points([index])[0]

    def run_points(self, indices: Sequence[int]) -> list:
        return [json.loads(r) for r in self._native.run_points_json(list(indices))]

    def table(self, rows: Sequence[Mapping[str, Any]]) -> pd.DataFrame:
        return _table(_raceway.sweep_csv([_row_json(r) for r in rows]))


def _row_json(row: Mapping[str, Any]) -> str:
    # Python writes a float as the shortest text that reads back to the same bits, and the
    # library reads it back exactly, so a row survives the trip bit for bit.
    return json.dumps(dict(row), allow_nan=False)


def sweep(
    sweep: Any,
    out: Optional[Union[str, "os.PathLike[str]"]] = None,
    *,
    jobs: Optional[int] = None,
    shard: Optional[Tuple[int, int]] = None,
) -> pd.DataFrame:
    """Run a sweep as ``raceway sweep`` does and return its sweep.csv as a DataFrame."""
    sw = Sweep(sweep)
    folder = tempfile.mkdtemp(prefix="raceway-sweep-") if out is None else os.fspath(out)
    try:
        _raceway.sweep_execute(
            sw._native, folder, jobs, None if shard is None else tuple(shard)
        )
        with open(os.path.join(folder, "sweep.csv"), encoding="utf-8") as f:
            return _table(f.read())
    finally:
        if out is None:
            shutil.rmtree(folder, ignore_errors=True)


from . import dask  # noqa: E402  (the submodule needs the names above)
