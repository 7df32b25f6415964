"""raceway: rolling-element bearing simulation from Python.

The Rust library behind the ``raceway`` command line, the C ABI and the FMUs, bound with
PyO3. SI units everywhere (m, N, Pa, s, rad, rad/s) except where a name says otherwise
(``speed_rpm``). Every call that computes releases the GIL, so threads run in parallel;
every failure raises :class:`raceway.Error` carrying the library's message.

Functions: :func:`run`, :func:`quasi_static`, :func:`shaft`, :func:`sweep`,
:func:`bearings`, :func:`bearing`, :func:`variables`; classes: :class:`Component`,
:class:`State`, :class:`Sweep`, :class:`Error`; :mod:`raceway.dask` for Dask clusters. ``help()`` of each
shows its parameters, returns, errors and an example.
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
    "RollerQuasiStaticResult",
    "State",
    "Sweep",
    "bearing",
    "bearings",
    "quasi_static",
    "run",
    "shaft",
    "sweep",
    "variables",
]


def variables() -> pd.DataFrame:
    """The variable table of the component, the C ABI and the FMUs.

    Returns
    -------
    pandas.DataFrame
        One row per variable, columns ``name``, ``vr`` (value reference of the C ABI and
        the FMUs), ``unit`` (SI), ``role`` and ``description``.

    Examples
    --------
    >>> import raceway
    >>> v = raceway.variables()
    >>> v.set_index("name").loc["force.y", "unit"]
    'N'
    """
    return pd.DataFrame(
        _raceway.variable_table(), columns=["name", "vr", "unit", "role", "description"]
    )


def run(scene: Any = None, duration: Optional[float] = None, *, kc: bool = False):
    """Run a scene stand-alone, as ``raceway run`` does, without writing files or plots.

    Parameters
    ----------
    scene : str, os.PathLike or dict, optional
        TOML (or JSON) text, the path of a scene file, or a dict of the same tables.
        ``None``: the embedded default scene.
    duration : float, optional
        Run time in s; overrides the scene's ``run.duration_s``.
    kc : bool, default False
        Add the stiffness and damping columns ``K.i.j`` and ``C.i.j``.

    Returns
    -------
    series : pandas.DataFrame
        One row per communication point, the columns of ``series.csv`` (``"t [s]"``,
        ``"force.y [N]"``, ``"shaft.y [m]"``, ...: the inputs and the outputs the scene's
        level and effects set, each with its SI unit; no ``wear.max_depth`` without wear,
        no cage or guide columns on levels that do not integrate the cage).
    summary : dict
        What ``raceway run`` writes to ``summary.json``, keys labelled ``name [unit]``
        (``"peak_pressure [Pa]"``, ``summary["rating"]["L10 [Mrev]"]``; every key in
        docs/columns.md): peak loads and pressures, characteristic frequencies found, ISO ratings, ``cpu [s]`` (thread CPU time),
        ``load_average``; ``scene`` is the file's stem (``"default"`` for the default).

    Raises
    ------
    raceway.Error
        For a bad scene (every problem at once) or a failed step.

    Examples
    --------
    >>> import raceway
    >>> series, summary = raceway.run("examples/scenes/default.toml", duration=0.01)
    >>> bool(series["force.y [N]"].iloc[-1] > 0)
    True
    """
    names, columns, summary = _raceway.run(scene, duration, kc)
    series = pd.DataFrame(dict(zip(names, (np.asarray(c) for c in columns))))
    return series, json.loads(summary)


@dataclass
class QuasiStaticResult:
    """The Jones–Harris quasi-static equilibrium of :func:`quasi_static`.

    Attributes
    ----------
    balls : pandas.DataFrame
        One row per ball: azimuth ``psi [rad]``, contact loads ``q_i [N]``, ``q_o [N]``,
        contact angles, approaches, semi-axes, peak pressures ``p_i [Pa]``, ``p_o [Pa]``,
        centrifugal force, gyroscopic moment, orbital and spin speeds, spin-to-roll ratios.
    K : numpy.ndarray
        Stiffness ``K = -dF/dq``, 5×5, order ``(x, y, z, rx, ry)``; N/m, N/rad, N m/m, N m/rad.
    displacement : numpy.ndarray
        Inner-ring displacement ``(x, y, z, rx, ry)``, m and rad.
    forces : numpy.ndarray
        Forces and moments of the bearing on the shaft ``(Fx, Fy, Fz, Mx, My)`` (= -load).
    data : dict
        Everything, as ``raceway quasi-static --json`` prints it: ``solution``, ``rating``
        (ISO 281/76 C, C0, P, L10, a_ISO, S0, peak pressure), ``warnings``.
    """

    balls: pd.DataFrame
    K: np.ndarray
    displacement: np.ndarray
    forces: np.ndarray
    data: dict


@dataclass
class RollerQuasiStaticResult:
    """The quasi-static equilibrium of a roller bearing (:func:`quasi_static` with a
    cylindrical or tapered roller designation such as ``"NU206"`` or ``"30206"``).

    Attributes
    ----------
    rollers : pandas.DataFrame
        One row per roller: azimuth ``psi [rad]``, inner (cone) and outer (cup) contact
        loads ``q_i [N]``, ``q_o [N]``, their peak pressures ``p_i [Pa]``, ``p_o [Pa]``,
        the flange load ``flange [N]`` (tapered: the cone back flange; zero otherwise) and
        the edge stress ``edge_p [Pa]`` (the larger inner pressure of the two end laminae).
    lamina_load : numpy.ndarray
        Outer-contact load of each lamina, N, one row per roller (small end first).
    lamina_pressure : numpy.ndarray
        Inner-contact peak pressure of each lamina, Pa, one row per roller.
    K : numpy.ndarray
        Stiffness ``K = -dF/dq``, 5×5, order ``(x, y, z, rx, ry)``; N/m, N/rad, N m/m, N m/rad.
    displacement : numpy.ndarray
        Shaft displacement ``(x, y, z, rx, ry)``, m and rad.
    forces : numpy.ndarray
        Forces and moments of the rollers on the shaft ``(Fx, Fy, Fz, Mx, My)`` (= -load).
    data : dict
        Everything, as ``raceway quasi-static --bearing NAME --json`` prints it:
        ``solution`` (``displacement.x [m]`` .. ``displacement.ry [rad]``, ``force.x [N]`` ..
        ``force.ry [N.m]``, ``stiffness [SI]``, ``iterations [1]``, ``rollers``), the ISO
        281/76 ratings ``C [N]``, ``C0 [N]``, ``P [N]``, ``P0 [N]``, ``L10 [Mrev]``, and
        ``max_pressure [Pa]``, ``max_edge_pressure [Pa]``; ISO/TS 16281's reference rating
        life from the lamina loads ``lamina_life`` (``L10r [Mrev]``, ``life_inner [Mrev]``,
        ``life_outer [Mrev]``, ``P_ref [N]``, ``options``, ``ratings``) and
        ``lamina_life_without_edge_factor``, the lamina static safety ``S0_lamina [1]`` =
        (4000 MPa / max_pressure)², and ``notes`` (what is UNSOURCED). Each roller row
        carries ``lamina_load_outer [N]`` and ``lamina_load_inner [N]``. Every key is
        listed in docs/columns.md.
    """

    rollers: pd.DataFrame
    lamina_load: np.ndarray
    lamina_pressure: np.ndarray
    K: np.ndarray
    displacement: np.ndarray
    forces: np.ndarray
    data: dict


_AXES = (("x", "m", "N"), ("y", "m", "N"), ("z", "m", "N"), ("rx", "rad", "N.m"), ("ry", "rad", "N.m"))


def _five(sol: dict, name: str, displacement: bool) -> np.ndarray:
    """The five keys ``name.x [m]`` .. ``name.ry [rad]`` (or N, N.m) of a solution as one
    array (docs/columns.md)."""
    return np.array(
        [sol[f"{name}.{a} [{dm if displacement else fn}]"] for a, dm, fn in _AXES], dtype=float
    )


def _roller_result(data: dict) -> RollerQuasiStaticResult:
    sol = data["solution"]
    rows = sol["rollers"]
    col = lambda f: np.array([f(r) for r in rows], dtype=float)  # noqa: E731
    rollers = pd.DataFrame(
        {
            "psi [rad]": col(lambda r: r["psi [rad]"]),
            "q_i [N]": col(lambda r: r["q_i [N]"]),
            "q_o [N]": col(lambda r: r["q_o [N]"]),
            "p_i [Pa]": col(lambda r: r["p_i [Pa]"]),
            "p_o [Pa]": col(lambda r: r["p_o [Pa]"]),
            "flange [N]": col(lambda r: r["flange_load [N]"]),
            "edge_p [Pa]": col(lambda r: r["edge_pressure [Pa]"]),
        }
    )
    rollers.index.name = "roller"
    return RollerQuasiStaticResult(
        rollers=rollers,
        lamina_load=np.array([r["lamina_load_outer [N]"] for r in rows], dtype=float),
        lamina_pressure=np.array([r["lamina_pressure [Pa]"] for r in rows], dtype=float),
        K=np.array(sol["stiffness [SI]"], dtype=float).reshape(5, 5),
        displacement=_five(sol, "displacement", True),
        forces=_five(sol, "force", False),
        data=data,
    )


def _error(message: str, kind: str, field: Optional[str]) -> Error:
    """A :class:`raceway.Error` raised on the Python side, with the library's attributes."""
    e = Error(message)
    e.message, e.kind, e.field = message, kind, field
    return e


def _duty_text(duty: Any) -> Optional[str]:
    """The load spectrum's text: a file's (path), the text itself (a ``str`` with a line
    break), or the rows of a sequence of ``(fr_n, fa_n, speed_rpm, time_share)``."""
    if duty is None:
        return None
    if isinstance(duty, os.PathLike) or (isinstance(duty, str) and "\n" not in duty):
        path = os.fspath(duty)
        try:
            with open(path, encoding="utf-8") as f:
                return f.read()
        except OSError as e:
            raise _error(f"cannot read duty `{path}`: {e}", "io", "duty") from None
    if isinstance(duty, str):
        return duty
    try:
        return "\n".join(", ".join(repr(float(v)) for v in row) for row in duty) + "\n"
    except (TypeError, ValueError) as e:
        raise _error(
            f"duty: expected a path, the spectrum's text or rows of 4 numbers "
            f"(fr_n, fa_n, speed_rpm, time_share): {e}",
            "invalid",
            "duty",
        ) from None


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
    hold: Optional[dict[str, float]] = None,
    ambient_temp_c: Optional[float] = None,
    duty: Any = None,
    skf_lubrication: Optional[str] = None,
    skf_seal: Optional[Sequence[float]] = None,
    skf_drag: Optional[Sequence[float]] = None,
    skf_constants: Optional[Sequence[float]] = None,
) -> Union[QuasiStaticResult, RollerQuasiStaticResult]:
    """The Jones–Harris quasi-static equilibrium under a load on the inner ring.

    The outer ring is fixed; solved as ``raceway quasi-static`` solves it. A cylindrical or
    tapered roller designation (``"NU206"``, ``"30206"``) is solved by the roller
    equilibrium with its laminae and gives a :class:`RollerQuasiStaticResult`, the content
    of ``raceway quasi-static --bearing NU206 --json``; the options after ``my`` are for
    ball bearings and refused (by name) for a roller bearing.

    Parameters
    ----------
    bearing : str, optional
        A preset or catalogue designation (``"6205"``, ``"7008ce"``, see :func:`bearings`)
        or the path of a TOML bearing file. ``None``: the default scene's bearing (6205).
    speed_rpm : float, default 0
        Shaft speed in rpm, >= 0.
    fx, fy, fz : float, default 0
        Loads on the inner ring, N.
    mx, my : float, default 0
        Moments on the inner ring, N m.
    race_control : {"outer", "none"}, optional
        Ball race control (``None``: the default scene's, outer).
    kappa : float, optional
        Viscosity ratio for a_ISO.
    contamination : float, optional
        ISO 281 contamination factor eC, 0..1, for a_ISO.
    oil : str, optional
        An ISO VG grade (``"VG68"``): its viscosity at ``oil_temp_c`` gives kappa when
        ``kappa`` is absent (docs/calculator.md).
    oil_vi : float, optional
        The oil's viscosity index (default 95).
    oil_temp_c : float, optional
        Operating oil temperature, °C (default 70).
    f0 : float, optional
        Palmgren's lubrication factor for the viscous friction moment (default 2).
    shaft_interference_um, housing_interference_um : float, optional
        Diametral interference of the inner ring on the shaft and of the outer ring in the
        housing, µm: the operating clearance.
    inner_ring_temp_c, outer_ring_temp_c : float, optional
        Ring temperatures, °C, for the operating clearance.
    ambient_temp_c : float, optional
        Ambient temperature, °C, of the thermally safe speed (default 20); with ``oil`` the
        design check carries ISO 15312's thermal reference speed and the thermally safe
        speed at ``oil_temp_c`` (``data["calculator"]["thermal_speed"]``).
    hold : dict, optional
        Ring coordinates held at a value while the others are solved, e.g.
        ``{"rx_mrad": 0, "ry_mrad": 0}`` (keys ``x_um``, ``y_um``, ``z_um``, ``rx_mrad``,
        ``ry_mrad``); the reaction on each is ``result.data["solution"]["reaction.rx [N.m]"]`` etc.
        and ``result.data["solution"]["held"]`` says which were held.
    duty : str, os.PathLike or sequence, optional
        A load spectrum, as ``raceway quasi-static --duty FILE``: the path of a file (one
        row per line ``fr_n, fa_n, speed_rpm, time_share``; ``#`` comments; a first line of
        names is skipped), that text itself (a ``str`` with a line break), or a sequence of
        ``(fr_n, fa_n, speed_rpm, time_share)`` rows. The ISO 281 life under the duty cycle
        is ``result.data["calculator"]["duty"]`` (with ``oil`` and ``contamination``, each
        row's a_ISO).
    skf_lubrication, skf_seal, skf_drag, skf_constants : optional
        The SKF four-term friction model (``data["calculator"]["skf_friction"]``, beside
        Palmgren's, with ``oil``), as ``raceway quasi-static --skf-*``: the lubrication
        method (``"oil-bath"`` default, ``"oil-jet"``, ``"oil-air"``, ``"grease"``); seal
        constants ``(KS1, BETA, KS2, DS_MM)``; oil-bath drag ``(VM, H_MM)``; geometry
        constants ``(R1, R2, R3, S1, S2, S3)`` for a series not built in (60, 62, 63).

    Returns
    -------
    QuasiStaticResult or RollerQuasiStaticResult
        Per-ball table, 5×5 stiffness, displacement, forces and the ratings; the design
        check (oil viscosity and kappa, Palmgren friction, subsurface stresses, operating
        clearance) is ``result.data["calculator"]``. For a roller bearing: per-roller
        table, lamina loads and pressures, 5×5 stiffness and the ISO 281/76 ratings.

    Raises
    ------
    raceway.Error
        For an unknown bearing, a bad argument (named in ``field``) or no equilibrium.

    Examples
    --------
    >>> import raceway
    >>> qs = raceway.quasi_static("7008ce", speed_rpm=20000, fy=100, fz=300)
    >>> qs.K.shape
    (5, 5)
    >>> nu = raceway.quasi_static("NU206", fy=-8000)
    >>> nu.lamina_load.shape  # 14 rollers, 30 laminae each
    (14, 30)
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
        None if hold is None else {str(k): float(v) for k, v in hold.items()},
        ambient_temp_c,
        _duty_text(duty),
        skf_lubrication,
        None if skf_seal is None else [float(v) for v in skf_seal],
        None if skf_drag is None else [float(v) for v in skf_drag],
        None if skf_constants is None else [float(v) for v in skf_constants],
    )
    data = json.loads(text)
    if data.get("element") == "roller":
        return _roller_result(data)
    sol = data["solution"]
    balls = pd.DataFrame(dict(zip(names, (np.asarray(c) for c in columns))))
    balls.index.name = "ball"
    return QuasiStaticResult(
        balls=balls,
        K=np.array(sol["stiffness [SI]"], dtype=float).reshape(5, 5),
        displacement=_five(sol, "displacement", True),
        forces=_five(sol, "force", False),
        data=data,
    )


def shaft(shaft: Any) -> dict[str, Any]:
    """A rigid shaft on bearing locations, solved as ``raceway shaft FILE --json`` solves it.

    Loads at axial positions, bearing locations (single bearings or sets: ball, tapered or
    flanged cylindrical rows) along the shaft; the 5-DOF equilibrium of the shaft, each
    location's reaction and each row's loads, stiffness and life (docs/sets.md for the
    file format).

    Parameters
    ----------
    shaft : str or os.PathLike
        The path of a shaft file (TOML; ``examples/shafts/spindle.toml``) or its text.

    Returns
    -------
    dict
        What ``raceway shaft FILE --json`` prints, keys ``name [unit]`` in SI
        (docs/columns.md): ``omega [rad/s]``, ``load.x [N]`` .. ``load.ry [N.m]`` at the
        origin, the shaft's ``displacement.x [m]`` .. ``displacement.ry [rad]``, the
        system ``stiffness [SI]`` (5×5), ``locations`` (each with its ``position [m]`` and
        its set's ``force.*``, ``rows`` and ``system_life [Mrev]``), the system
        ``system_life [Mrev]`` and ``warnings``.

    Raises
    ------
    raceway.Error
        For an unreadable or bad file (the field at fault in ``field``) or no equilibrium.

    Examples
    --------
    >>> import raceway
    >>> s = raceway.shaft("examples/shafts/spindle.toml")
    >>> [loc["name"] for loc in s["locations"]]
    ['front DB pair', 'rear']
    >>> s["system_life [Mrev]"] > 0
    True
    """
    if isinstance(shaft, os.PathLike):
        shaft = os.fspath(shaft)
    if not isinstance(shaft, str):
        raise _error(
            f"shaft: expected the path of a shaft file or its TOML text, found "
            f"{type(shaft).__name__}",
            "invalid",
            "shaft",
        )
    return json.loads(_raceway.shaft_json(shaft))


def bearings() -> pd.DataFrame:
    """The bearing presets, as ``raceway bearings --json`` lists them.

    Returns
    -------
    pandas.DataFrame
        One row per preset (``name [unit]`` columns in mm, µm, degrees, kg;
        ``C [N]`` and ``C0 [N]`` the ISO 281/76 ratings; docs/columns.md). Catalogue designations
        (60/62/63, 70/72/73 C/AC/B) are reached one at a time with :func:`bearing`.

    Examples
    --------
    >>> import raceway
    >>> "name" in raceway.bearings().columns
    True
    """
    return pd.DataFrame(json.loads(_raceway.bearings_json()))


def bearing(name: str) -> dict:
    """One preset or catalogue designation, as ``raceway bearings NAME --json`` prints it.

    Parameters
    ----------
    name : str
        ``"6206"``, ``"7205b"``, ...

    Returns
    -------
    dict
        Its data, ISO ratings and where each number comes from.

    Raises
    ------
    raceway.Error
        For an unknown designation, with the nearest names.

    Examples
    --------
    >>> import raceway
    >>> isinstance(raceway.bearing("6206"), dict)
    True
    """
    return json.loads(_raceway.bearing_json(name))


def _table(csv_text: str) -> pd.DataFrame:
    """sweep.csv text as ``pd.read_csv`` loads the file."""
    return pd.read_csv(io.StringIO(csv_text))


class Sweep:
    """A parsed and checked sweep: a base scene and axes.

    Every point is a pure function index → scene → summary row, the same as
    ``raceway sweep`` computes. A ``Sweep`` pickles (it carries its base scene), so it can
    be shipped to Dask workers on other machines.

    Parameters
    ----------
    sweep : str, os.PathLike or dict
        The sweep file's path, its TOML text, or a dict of the same tables
        (``{"scene": {...}, "axis": [{"key": ..., "values": [...]}]}``).

    Raises
    ------
    raceway.Error
        With every problem of the sweep at once, each with its line:column.

    Attributes
    ----------
    columns : list of str
        The axes' column names (units in the names).

    Methods
    -------
    point(index)
        The axes' values at point ``index``, by column name.
    scene_text(index)
        The scene (TOML) of point ``index``.
    run_point(index), run_points(indices)
        Run points (GIL released); each row has ``index``, ``axes``, ``summary`` and
        ``error`` (a failed run is a row, never an exception).
    table(rows)
        The rows as the DataFrame ``pd.read_csv("DIR/sweep.csv")`` gives for them.

    Examples
    --------
    >>> import raceway
    >>> sw = raceway.Sweep("examples/sweeps/6205-speed-displacement.toml")
    >>> len(sw) > 0
    True
    """

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
    """Run a sweep on this machine's threads, exactly as ``raceway sweep`` does.

    Parameters
    ----------
    sweep : str, os.PathLike, dict or Sweep
        The sweep file's path, its TOML text, a dict of the same tables, or a :class:`Sweep`.
    out : str or os.PathLike, optional
        The output folder (``rows/``, ``series/``, ``sweep.csv``; resumable: finished rows
        are skipped). ``None``: a temporary folder, removed afterwards.
    jobs : int, optional
        Threads (``None``: every core).
    shard : tuple of (int, int), optional
        ``(k, n)``: only the indices ``i % n == k``.

    Returns
    -------
    pandas.DataFrame
        ``sweep.csv`` loaded with pandas: the axis values and the run summary per point.

    Raises
    ------
    raceway.Error
        For a bad sweep file; a failed point is a row with its error, not an exception.

    Examples
    --------
    >>> import raceway
    >>> table = raceway.sweep("examples/sweeps/6205-speed-displacement.toml")  # doctest: +SKIP
    """
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


from . import _docs  # noqa: E402

_docs.apply(Component, State, Error)

from . import dask  # noqa: E402  (the submodule needs the names above)
