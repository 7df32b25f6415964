"""Numpydoc docstrings of the classes the native module ``raceway._raceway`` defines.

The classes are built in Rust (PyO3); their docstrings are set here, from Python, so that
``help(raceway.Component)`` shows the full reference. The ``.pyi`` stubs carry the same
information for editors.
"""

from __future__ import annotations

COMPONENT = """The bearing as a co-simulation component: set inputs, step, read outputs.

The same component the C ABI and the FMUs wrap: ``do_step(t, h)`` sub-steps the bearing's
own dynamics over ``[t, t + h]`` with the inputs set before it, and a failed step leaves
the component exactly as it was. SI units throughout (m, rad, N, N m, rad/s).

Parameters
----------
scene : str, os.PathLike or dict, optional
    TOML (or JSON) text, the path of a scene file, or a dict of the same tables
    (``{"bearing": "6205", "model": {"level": "ring"}}``). ``None``: the embedded
    default scene (a 6205 at 1750 rpm on the quasi-static level). ``raceway scene
    --explain`` lists every field.

Raises
------
raceway.Error
    For a bad scene, listing every problem at once.

Attributes
----------
time : float
    Current time in s (the end of the last step).
level : str
    The model level: ``linear``, ``quasi_static``, ``ring``, ``skidding`` or ``full``.
causality : str
    ``"motion"`` (the host prescribes the shaft motion, the bearing returns forces) or
    ``"load"`` (the host prescribes loads, the bearing returns the motion).
bearing : str
    The bearing's designation (``"6205"``).

Methods
-------
set(name, value=None)
    Set one input (``set("shaft.y", -1e-5)``) or several from a dict, SI units. Several
    are set all or none. Raises :class:`raceway.Error` naming the variable and its range.
get(name)
    The value of one variable (input or output) by name (``"force.y"``, ``"K.y.y"``).
do_step(t, h)
    Advance from ``t`` (must equal :attr:`time`) to ``t + h`` with the inputs set.
    Raises :class:`raceway.Error` on failure; the component is then unchanged.
outputs()
    Every output at :attr:`time` as a dict by name (forces, K and C, diagnostics).
inputs()
    Every input of this component's causality, by name, as last set.
get_state(), set_state(state)
    Take a :class:`raceway.State` snapshot; restore it (same scene).
state_bytes(), set_state_bytes(data)
    The state as versioned, checked bytes (the C ABI's and FMUs' format); restore it.
    Raises :class:`raceway.Error` and changes nothing for bytes of another scene or version.

See Also
--------
raceway.variables : the names, units and value references of every variable.
raceway.run : a whole stand-alone run as ``raceway run`` does it.

Examples
--------
>>> import raceway
>>> c = raceway.Component({"bearing": "6205", "model": {"level": "quasi_static"}})
>>> c.set({"shaft.x": 0.0, "shaft.y": -10e-6, "shaft.z": 0.0, "shaft.rx": 0.0,
...        "shaft.ry": 0.0, "shaft.vx": 0.0, "shaft.vy": 0.0, "shaft.vz": 0.0,
...        "shaft.wx": 0.0, "shaft.wy": 0.0, "shaft.omega": 183.26})
>>> c.do_step(0.0, 1e-4)
>>> c.get("force.y") > 0
True
"""

STATE = """An opaque snapshot of a :class:`raceway.Component`'s state.

Holds the time, the integrator states and the inputs. Made by
:meth:`Component.get_state`; restored by :meth:`Component.set_state` on the same component
or another one built from the same scene. ``bytes(state)`` is its serialised form (the same
bytes as :meth:`Component.state_bytes`); it pickles.

Attributes
----------
time : float
    The time of the snapshot, s.

Methods
-------
from_bytes(data)
    Static: a snapshot from its bytes. Raises :class:`raceway.Error` for bytes of another
    version or a truncated buffer.

Examples
--------
>>> import raceway
>>> c = raceway.Component()
>>> s = c.get_state()
>>> raceway.State.from_bytes(bytes(s)).time == s.time
True
"""

ERROR = """Any failure of the library: a bad scene or argument, a failed step, an unknown name.

Attributes
----------
message : str
    The project's message (the text the command line prints after ``error:``); for a bad
    input it names the field, the value and the allowed range. ``str(e)`` is the same.
kind : str
    ``"invalid"``, ``"unknown"``, ``"parse"``, ``"not_converged"``, ``"step_failed"``,
    ``"budget"``, ``"call_order"``, ``"io"`` or ``"panic"`` (a bug in the library, caught
    before it reached Python).
field : str or None
    The field or argument at fault when the error names one (``"model.level"``).

Examples
--------
>>> import raceway
>>> try:
...     raceway.Component({"model": {"level": "rng"}})
... except raceway.Error as e:
...     print(e.field)
model.level
"""


def apply(component, state, error) -> None:
    """Set the docstrings of the native classes (their ``__doc__`` is writable)."""
    for cls, text in ((component, COMPONENT), (state, STATE), (error, ERROR)):
        try:
            cls.__doc__ = text
        except (AttributeError, TypeError):  # an immutable type: keep the native text
            pass
