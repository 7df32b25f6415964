"""raceway: rolling-element bearing simulation from Python.

The Rust library behind the `raceway` command line, the C ABI and the FMUs, bound with PyO3.
SI units everywhere (m, N, Pa, s, rad, rad/s) except where a name says otherwise
(``speed_rpm``). Every call that computes releases the GIL, so threads run in parallel.
Every failure raises :class:`raceway.Error` carrying the project's message.

Install from the repository root: ``pip install ./python``.
"""

from __future__ import annotations

import os
from typing import Any, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt
import pandas as pd

from . import dask as dask

__version__: str

SceneLike = Union[str, "os.PathLike[str]", Mapping[str, Any]]
"""A scene: TOML (or JSON) text, the path of a scene file, or a dict of the same tables
(``{"bearing": "6205", "model": {"level": "ring"}, ...}``). A ``str`` that names an existing
file, or ends in ``.toml``/``.json`` and has no newline, is a path; any other ``str`` is text.
See ``raceway scene --explain`` for every field."""

SweepLike = Union[str, "os.PathLike[str]", Mapping[str, Any]]
"""A sweep file: its path, its TOML text, or a dict of the same tables
(``{"scene": {...}, "axis": [{"key": ..., "values": [...]}]}``); see docs/sweep.md. A
relative ``scene`` path is taken from the sweep file's folder (from the working directory
for text and dicts)."""

class Error(Exception):
    """Any failure of the library: a bad scene or argument, a failed step, an unknown name.

    ``str(e)`` and ``e.message`` are the project's message (the same text the command line
    prints after ``error:``), which names the field, the value and the allowed range for a
    bad input.
    """

    message: str
    """The project's message."""
    kind: str
    """``"invalid"``, ``"unknown"``, ``"parse"``, ``"not_converged"``, ``"step_failed"``,
    ``"budget"``, ``"call_order"``, ``"io"``, or ``"panic"`` (a bug in the library, caught
    before it reached Python)."""
    field: Optional[str]
    """The field or argument at fault when the error names one (``"model.level"``,
    ``"shaft.omega"``), else ``None``."""

class State:
    """An opaque snapshot of a :class:`Component`'s state (time, integrator states, inputs).

    Made by :meth:`Component.get_state`; restored by :meth:`Component.set_state` on the
    same component or another one built from the same scene. ``bytes(state)`` is its
    serialised form (the same bytes as :meth:`Component.state_bytes`); it pickles.
    """

    @property
    def time(self) -> float:
        """The time of the snapshot, s."""
    def __bytes__(self) -> bytes: ...
    @staticmethod
    def from_bytes(data: bytes) -> State:
        """A snapshot from its bytes (``bytes(state)`` or :meth:`Component.state_bytes`).
        Raises :class:`Error` for bytes of another version or a truncated buffer."""

class Component:
    """The bearing as a co-simulation component: set inputs, step, read outputs.

    The same component the C ABI and the FMUs wrap: ``do_step(t, h)`` sub-steps the
    bearing's own dynamics over ``[t, t + h]`` with the inputs set before it, and a failed
    step leaves the component exactly as it was.

    >>> c = raceway.Component({"bearing": "6205", "model": {"level": "quasi_static"}})
    >>> c.set("shaft.y", -10e-6); c.set("shaft.omega", 183.26)
    >>> c.do_step(0.0, 1e-4)
    >>> c.get("force.y")
    """

    def __init__(self, scene: Optional[SceneLike] = None) -> None:
        """Build the component of ``scene`` (``None``: the embedded default scene).

        Raises :class:`Error` listing every problem of the scene at once.
        """
    @property
    def time(self) -> float:
        """Current time, s (the end of the last step)."""
    @property
    def level(self) -> str:
        """The model level: ``linear``, ``quasi_static``, ``ring``, ``skidding`` or ``full``."""
    @property
    def causality(self) -> str:
        """``"motion"`` (the host prescribes the shaft motion, the bearing returns forces)
        or ``"load"`` (the host prescribes loads, the bearing returns the motion)."""
    @property
    def bearing(self) -> str:
        """The bearing's designation (``"6205"``)."""
    def set(self, name: Union[str, Mapping[str, float]], value: Optional[float] = None) -> None:
        """Set one input (``set("shaft.y", -1e-5)``) or several (``set({"shaft.y": -1e-5,
        "shaft.omega": 100.0})``), SI units. Several are set all or none: a bad value leaves
        every input as it was. Raises :class:`Error` naming the variable and its allowed
        range."""
    def get(self, name: str) -> float:
        """The value of one variable (input or output) by name (``"force.y"``, ``"K.y.y"``),
        SI units; outputs are those at :attr:`time`."""
    def do_step(self, t: float, h: float) -> None:
        """Advance from ``t`` (must equal :attr:`time`) to ``t + h`` with the inputs set.
        Raises :class:`Error` on failure; the component is then unchanged."""
    def outputs(self) -> dict[str, float]:
        """Every output at :attr:`time`, by name (forces, K and C entries, diagnostics)."""
    def inputs(self) -> dict[str, float]:
        """Every input of this component's causality, by name, as last set."""
    def get_state(self) -> State:
        """A snapshot of the whole state (to go back to it with :meth:`set_state`)."""
    def set_state(self, state: State) -> None:
        """Restore a snapshot taken from a component of the same scene."""
    def state_bytes(self) -> bytes:
        """The state serialised (versioned, checked bytes; the C ABI's and FMUs' format)."""
    def set_state_bytes(self, data: bytes) -> None:
        """Restore a state from :meth:`state_bytes`. Raises :class:`Error` (and changes
        nothing) for bytes of another scene, version or a truncated buffer."""

def variables() -> pd.DataFrame:
    """The variable table: one row per variable, columns ``name``, ``vr`` (value reference
    of the C ABI and the FMUs), ``unit`` (SI), ``role`` and ``description``."""

def run(
    scene: Optional[SceneLike] = None,
    duration: Optional[float] = None,
    *,
    kc: bool = False,
) -> Tuple[pd.DataFrame, dict[str, Any]]:
    """Run a scene stand-alone, as ``raceway run`` does, without writing files or plots.

    ``duration`` (s) overrides the scene's ``run.duration_s``; ``kc=True`` adds the
    stiffness and damping columns ``K.i.j`` and ``C.i.j``.

    Returns ``(series, summary)``: ``series`` has one row per communication point and the
    columns of ``series.csv`` (``"t [s]"``, ``"force.y [N]"``, ``"shaft.y [m]"``, ... every
    variable with its SI unit in the name); ``summary`` is the dict ``raceway run`` writes to
    ``summary.json`` (peak loads and pressures, characteristic frequencies found, ISO
    ratings, ``cpu [s]`` thread CPU time, ``load_average``; ``scene`` is the file's stem,
    ``"default"`` for the default scene, else ``"scene"``).
    """

class QuasiStaticResult:
    """The Jones–Harris quasi-static equilibrium of :func:`quasi_static`."""

    balls: pd.DataFrame
    """One row per ball: azimuth ``psi [rad]``, contact loads ``q_i [N]``, ``q_o [N]``,
    contact angles ``alpha_i [rad]``, ``alpha_o [rad]``, approaches ``delta_i [m]``,
    ``delta_o [m]``, semi-axes ``a_i [m]``, ``b_i [m]``, ``a_o [m]``, ``b_o [m]``, peak
    pressures ``p_i [Pa]``, ``p_o [Pa]``, centrifugal force ``fc [N]``, gyroscopic moment
    ``mg [N.m]``, orbital speed ``omega_m [rad/s]``, spin ``omega_r [rad/s]``, attitude
    ``beta [rad]``, spin-to-roll ratios ``spin_roll_i [-]``, ``spin_roll_o [-]``."""
    K: npt.NDArray[np.float64]
    """Stiffness ``K = -dF/dq``, 5×5, order ``(x, y, z, rx, ry)``; N/m, N/rad, N m/m, N m/rad."""
    displacement: npt.NDArray[np.float64]
    """Inner-ring displacement ``(x, y, z, rx, ry)``, m and rad."""
    forces: npt.NDArray[np.float64]
    """Forces and moments of the bearing on the shaft ``(Fx, Fy, Fz, Mx, My)`` (= −load)."""
    data: dict[str, Any]
    """Everything, as ``raceway quasi-static --json`` prints it: ``solution``, ``rating``
    (ISO 281/76 C, C0, P, L10, a_ISO, S0, peak pressure; ``None`` outside the standards'
    range, then ``rating_error``), ``warnings``."""

class RollerQuasiStaticResult:
    """The quasi-static equilibrium of a roller bearing (:func:`quasi_static` with a
    cylindrical or tapered roller designation such as ``"NU206"`` or ``"30206"``)."""

    rollers: pd.DataFrame
    """One row per roller: azimuth ``psi [rad]``, inner (cone) and outer (cup) contact loads
    ``q_i [N]``, ``q_o [N]``, peak pressures ``p_i [Pa]``, ``p_o [Pa]``, the flange load
    ``flange [N]`` (tapered: the cone back flange; zero otherwise) and the edge stress
    ``edge_p [Pa]`` (the larger inner pressure of the two end laminae)."""
    lamina_load: npt.NDArray[np.float64]
    """Outer-contact load of each lamina, N, rollers × laminae (small end first)."""
    lamina_pressure: npt.NDArray[np.float64]
    """Inner-contact peak pressure of each lamina, Pa, rollers × laminae."""
    K: npt.NDArray[np.float64]
    """Stiffness ``K = -dF/dq``, 5×5, order ``(x, y, z, rx, ry)``; N/m, N/rad, N m/m, N m/rad."""
    displacement: npt.NDArray[np.float64]
    """Shaft displacement ``(x, y, z, rx, ry)``, m and rad."""
    forces: npt.NDArray[np.float64]
    """Forces and moments of the rollers on the shaft ``(Fx, Fy, Fz, Mx, My)`` (= −load)."""
    data: dict[str, Any]
    """Everything, as ``raceway quasi-static --bearing NAME --json`` prints it: ``solution``
    (``displacement.x [m]`` .. ``displacement.ry [rad]``, ``force.x [N]`` .. ``force.ry
    [N.m]``, ``stiffness [SI]``, ``iterations [1]``, ``rollers``), the ISO 281/76 ratings
    ``C [N]``, ``C0 [N]``, ``P [N]``, ``P0 [N]``, ``L10 [Mrev]`` and ``max_pressure [Pa]``,
    ``max_edge_pressure [Pa]``; ISO/TS 16281's lamina life ``lamina_life`` (``L10r [Mrev]``,
    ``life_inner [Mrev]``, ``life_outer [Mrev]``, ``P_ref [N]``, ``options``, ``ratings``)
    and ``lamina_life_without_edge_factor``, ``S0_lamina [1]`` = (4000 MPa / max_pressure)²
    and ``notes`` (what is UNSOURCED); each roller row ``lamina_load_outer [N]`` and
    ``lamina_load_inner [N]``. Every key is listed in docs/columns.md."""

DutyLike = Union[str, "os.PathLike[str]", Sequence[Sequence[float]]]
"""A load spectrum: the path of a file (one row per line ``fr_n, fa_n, speed_rpm,
time_share``), that text (a ``str`` with a line break), or a sequence of such rows."""

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
    duty: Optional[DutyLike] = None,
    skf_lubrication: Optional[str] = None,
    skf_seal: Optional[Sequence[float]] = None,
    skf_drag: Optional[Sequence[float]] = None,
    skf_constants: Optional[Sequence[float]] = None,
) -> Union[QuasiStaticResult, RollerQuasiStaticResult]:
    """The Jones–Harris quasi-static equilibrium under an external load on the inner ring
    (the outer ring fixed), as ``raceway quasi-static`` solves it.

    ``bearing``: a preset or catalogue designation (``"6205"``, ``"7008ce"``, see
    :func:`bearings`) or a TOML bearing file; ``None``: the default scene's bearing (6205).
    ``speed_rpm`` >= 0; loads ``fx, fy, fz`` in N and moments ``mx, my`` in N m;
    ``race_control``: ``"outer"`` or ``"none"`` (``None``: the default scene's, outer);
    ``kappa`` (viscosity ratio) and ``contamination`` (ISO 281 eC, 0..1) for a_ISO.
    The design check (docs/calculator.md) is ``result.data["calculator"]`` (SI): ``oil`` an ISO
    VG grade (``"VG68"``) with ``oil_vi`` (default 95) at ``oil_temp_c`` (default 70) gives the
    viscosity, kappa (used for a_ISO when ``kappa`` is not given) and Palmgren's friction
    moment and power loss (``f0`` default 2); the subsurface stresses below the most loaded
    ball are always there; ``shaft_interference_um``, ``housing_interference_um``,
    ``inner_ring_temp_c``, ``outer_ring_temp_c`` give the operating clearance.
    ``ambient_temp_c`` (default 20 °C): the ambient of the thermally safe speed
    (``data["calculator"]["thermal_speed"]``, with ISO 15312's reference speed).
    ``hold``: ring coordinates held at a value while the others are solved
    (``{"rx_mrad": 0, "ry_mrad": 0}``; keys ``x_um``, ``y_um``, ``z_um``, ``rx_mrad``,
    ``ry_mrad``), the reaction on each in ``result.data["solution"]["reaction.rx [N.m]"]`` etc.
    ``duty``: a load spectrum (``raceway quasi-static --duty FILE``), its ISO 281 life in
    ``result.data["calculator"]["duty"]``.
    The SKF four-term friction model is ``data["calculator"]["skf_friction"]`` (N m, W:
    ``rolling_moment``, ``sliding_moment``, ``seal_moment``, ``drag_moment``, ``moment``,
    ``power``, each ``name [unit]``, the factors, and
    what is ``unconfirmed``; ``skf_note`` says why it is missing): ``skf_lubrication``
    (``"oil-bath"`` default, ``"oil-jet"``, ``"oil-air"``, ``"grease"``), ``skf_seal``
    ``(KS1, BETA, KS2, DS_MM)``, ``skf_drag`` ``(VM, H_MM)``, ``skf_constants``
    ``(R1, R2, R3, S1, S2, S3)`` for a series not built in (deep-groove 60, 62, 63).
    With held tilts, ``data["calculator"]["held_moment"]`` is the moment the bearing carries
    (ISO 281's ``L10`` ignores it; the per-ball ``L10r`` includes it).
    A roller designation (``"NU206"``, ``"30206"``) gives a :class:`RollerQuasiStaticResult`
    (``raceway quasi-static --bearing NU206 --json``); the ball-only options are refused.
    """

def shaft(shaft: Union[str, "os.PathLike[str]"]) -> dict[str, Any]:
    """A rigid shaft on bearing locations, solved as ``raceway shaft FILE --json`` solves
    it: ``shaft`` is the path of a shaft file (TOML) or its text; the result is the JSON as
    a dict, keys ``name [unit]`` in SI (docs/columns.md): ``omega [rad/s]``, ``load.x [N]``
    .. ``load.ry [N.m]``, ``displacement.x [m]`` .. ``displacement.ry [rad]``,
    ``stiffness [SI]``, ``locations``, ``system_life [Mrev]``, ``warnings``."""

def bearings() -> pd.DataFrame:
    """The bearing presets, one row each, as ``raceway bearings --json`` lists them (``name [unit]``
    columns in mm, µm, degrees, kg; ``C [N]`` and ``C0 [N]`` the ISO 281/76 ratings; docs/columns.md). Catalogue
    designations (60/62/63, 70/72/73 C/AC/B) are reached one at a time with :func:`bearing`."""

def bearing(name: str) -> dict[str, Any]:
    """One preset or catalogue designation (``"6206"``, ``"7205b"``, a roller ``"NU206"``):
    its data, ISO ratings and where each number comes from, as ``raceway bearings NAME
    --json`` prints it (``name [unit]`` keys, docs/columns.md)."""

class Sweep:
    """A parsed and checked sweep: a base scene and axes (docs/sweep.md).

    Every point is a pure function index → scene → summary row, the same as
    ``raceway sweep`` computes. A ``Sweep`` pickles (it carries its base scene), so it can be
    shipped to Dask workers on other machines.
    """

    def __init__(self, sweep: SweepLike) -> None:
        """Parse and check a sweep. Raises :class:`Error` with every problem at once, each
        with its line:column."""
    def __len__(self) -> int:
        """Number of points."""
    @property
    def columns(self) -> list[str]:
        """The axes' column names (units in the names: ``inputs.initial.shaft.y_m``)."""
    def point(self, index: int) -> dict[str, Any]:
        """The axes' values at point ``index``, by column name."""
    def scene_text(self, index: int) -> str:
        """The scene (TOML) of point ``index``: the base scene with the point's values."""
    def run_point(self, index: int) -> dict[str, Any]:
        """Run point ``index`` (GIL released) and return its row: ``index``, ``axes`` and
        ``summary`` (lists of ``[column, value]``), ``error`` (``None``, or the message of a
        failed run: a failure is a row, never an exception)."""
    def run_points(self, indices: Sequence[int]) -> list[dict[str, Any]]:
        """:meth:`run_point` for each index, in order (one call, GIL released throughout)."""
    def table(self, rows: Sequence[Mapping[str, Any]]) -> pd.DataFrame:
        """The rows as the DataFrame ``pd.read_csv("DIR/sweep.csv")`` gives for the same rows
        written by ``raceway sweep`` (sorted by index; same columns, same values bit for
        bit)."""

def sweep(
    sweep: SweepLike,
    out: Optional[Union[str, "os.PathLike[str]"]] = None,
    *,
    jobs: Optional[int] = None,
    shard: Optional[Tuple[int, int]] = None,
) -> pd.DataFrame:
    """Run a sweep on this machine's threads, exactly as ``raceway sweep`` does, and return
    ``DIR/sweep.csv`` loaded with pandas.

    ``out``: the output folder (rows/, series/, sweep.csv; resumable: finished rows are
    skipped); ``None``: a temporary folder, removed afterwards. ``jobs``: threads (``None``:
    every core). ``shard=(k, n)``: only the indices ``i % n == k``.
    """
