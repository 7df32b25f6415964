"""Stiffness and damping of a 6205 against speed and load, fed to a ROSS rotor: Campbell diagram.

K: the Jones–Harris quasi-static equilibrium (``raceway.quasi_static``: centrifugal and
gyroscopic ball loads included, dry Hertz contacts), the 2×2 radial block of its 5×5
``K = -dF/dq`` at the load. C: the component's damping output ``C = -dF/dv`` at the ring
level with the Hamrock–Dowson EHL film (Reynolds squeeze damping of the inlet, in parallel
with Hertz and the film in series), load-driven under the same load at the same speed,
averaged over whole ball passes (the coefficients vary as balls pass; a rotor code wants
their mean). Both are tabulated against speed and handed to ROSS
(``ross-rotordynamics``) as speed-dependent ``BearingElement`` coefficients of a small
rotor, whose Campbell diagram is drawn for a light and a heavy bearing load.

Check (CI): the heavier load stiffens the Hertz contacts (K grows like W^(1/3)), so the
rotor's first forward mode lies higher at every speed.

    python examples/python/sweeps/rotor_campbell.py --quick
    python examples/python/sweeps/rotor_campbell.py --write-docs
"""

from __future__ import annotations

import csv
import math
import warnings

import numpy as np

import raceway
from common import Clock, arguments, check, figure_path, pyplot, save

BEARING = "6205"
RPM_PER_RAD_S = 30.0 / math.pi


def damping(load_n: float, rpm: float) -> np.ndarray:
    """Mean 2×2 damping (x, y) of the bearing under ``load_n`` downward at ``rpm``, N s/m:
    the component's ``C.*.*`` outputs at the ring level with the EHL film, averaged over
    the last whole ball passes of a two-revolution run (the bearing starts in its static
    equilibrium under the load, so there is no start transient to skip)."""
    duration = 120.0 / rpm if rpm > 0 else 0.01
    scene = {
        "bearing": BEARING,
        "model": {"level": "ring", "causality": "load", "ring_dof": 2},
        "inputs": {
            "rule": "hold",
            "speed_rpm": rpm,
            "initial": {"load.y": -load_n},
        },
        "effects": {"lubrication": {"film": "ehl", "lubricant": "study2"}},
        "run": {"duration_s": duration, "step_s": duration / 400},
    }
    series, summary = raceway.run(scene, kc=True)
    bpfo = next(f["expected [Hz]"] for f in summary["frequencies"] if f["label"] == "1xBPFO")
    t = series["t [s]"].to_numpy()
    if bpfo > 0:
        passes = math.floor((t[-1] - t[0]) * bpfo)
        keep = t > t[-1] - passes / bpfo
    else:
        keep = np.ones_like(t, dtype=bool)
    names = [["C.x.x", "C.x.y"], ["C.y.x", "C.y.y"]]
    return np.array([[series[f"{n} [N.s/m]"][keep].mean() for n in row] for row in names])


def coefficients(loads: list[float], speeds_rpm: np.ndarray) -> dict[float, dict[str, np.ndarray]]:
    """K (2×2, N/m) and C (2×2, N s/m) per load, one entry per speed."""
    table = {}
    for w in loads:
        k = np.array([raceway.quasi_static(BEARING, speed_rpm=float(n), fy=-w).K[:2, :2] for n in speeds_rpm])
        c = np.array([damping(w, float(n)) for n in speeds_rpm])
        table[w] = {"K": k, "C": c}
    return table


def rotor(k: np.ndarray, c: np.ndarray, speeds_rad_s: np.ndarray):
    """A steel rotor on two 6205s: 25 mm journals, a 30 mm body 0.4 m long, a 200 mm ×
    30 mm disk at mid-span (its first bending mode crosses the shaft speed within the
    range); each bearing gets the speed-dependent K and C."""
    import ross as rs

    steel = rs.Material(name="Steel", rho=7810.0, E=211e9, G_s=81.2e9)
    lengths = [0.025] + [0.1] * 4 + [0.025]
    diameters = [0.025] + [0.030] * 4 + [0.025]
    shaft = [
        rs.ShaftElement(L=l, idl=0.0, odl=d, material=steel, n=i, shear_effects=True, rotary_inertia=True, gyroscopic=True)
        for i, (l, d) in enumerate(zip(lengths, diameters))
    ]
    disk = [rs.DiskElement.from_geometry(n=3, material=steel, width=0.030, i_d=0.030, o_d=0.200)]
    bearings = [
        rs.BearingElement(
            n=node,
            kxx=k[:, 0, 0], kxy=k[:, 0, 1], kyx=k[:, 1, 0], kyy=k[:, 1, 1],
            cxx=c[:, 0, 0], cxy=c[:, 0, 1], cyx=c[:, 1, 0], cyy=c[:, 1, 1],
            frequency=speeds_rad_s,
        )
        for node in (0, len(shaft))
    ]
    return rs.Rotor(shaft_elements=shaft, disk_elements=disk, bearing_elements=bearings)


def first_forward(wd: np.ndarray, whirl: np.ndarray) -> np.ndarray:
    """Lowest forward-whirling damped frequency at each speed (ROSS: whirl 0 = forward)."""
    fwd = np.where(whirl == 0.0, wd, np.inf)
    return fwd.min(axis=1)


def plot_kc(path, speeds_rpm, table):
    plt = pyplot()
    fig, (ak, ac) = plt.subplots(1, 2, figsize=(11, 4.2), constrained_layout=True)
    for w, d in table.items():
        (line,) = ak.plot(speeds_rpm, d["K"][:, 1, 1] / 1e6, marker="o", ms=3, label=f"{w:g} N: $K_{{yy}}$")
        ak.plot(speeds_rpm, d["K"][:, 0, 0] / 1e6, ls="--", color=line.get_color(), label=f"{w:g} N: $K_{{xx}}$")
        ac.plot(speeds_rpm, d["C"][:, 1, 1], marker="o", ms=3, color=line.get_color(), label=f"{w:g} N: $C_{{yy}}$")
        ac.plot(speeds_rpm, d["C"][:, 0, 0], ls="--", color=line.get_color(), label=f"{w:g} N: $C_{{xx}}$")
    ak.set(xlabel="shaft speed [rpm]", ylabel="stiffness [MN/m]", title="K: quasi-static (Jones–Harris), load along y")
    ac.set(xlabel="shaft speed [rpm]", ylabel="damping [N s/m]", title="C: ring level, EHL squeeze film")
    ak.set_ylim(bottom=0)
    ac.set_ylim(bottom=0)
    for a in (ak, ac):
        a.grid(alpha=0.3)
        a.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, title="radial load")
    fig.suptitle(f"{BEARING}: stiffness and damping against speed and radial load")
    save(fig, path)


def plot_campbell(path, speeds_rpm, campbells):
    plt = pyplot()
    fig, axes = plt.subplots(1, len(campbells), figsize=(11, 4.4), sharey=True, constrained_layout=True)
    for ax, (w, (wd, whirl)) in zip(np.atleast_1d(axes), campbells.items()):
        f = wd / (2 * math.pi)
        for j in range(f.shape[1]):
            for kind, colour, name in ((0.0, "tab:blue", "forward"), (1.0, "tab:red", "backward"), (0.5, "tab:gray", "mixed")):
                sel = whirl[:, j] == kind
                ax.plot(speeds_rpm[sel], f[sel, j], "o", ms=3, color=colour, label=name)
        ax.plot(speeds_rpm, speeds_rpm / 60.0, "k--", lw=1, label="1× shaft speed")
        ax.set(xlabel="shaft speed [rpm]", title=f"bearing load {w:g} N each")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("damped natural frequency [Hz]")
    handles, labels = axes[-1].get_legend_handles_labels()
    unique = dict(zip(labels, handles))
    axes[-1].legend(unique.values(), unique.keys(), loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)
    fig.suptitle("Campbell diagram: rotor on two 6205s (K, C from raceway, modes from ROSS)")
    save(fig, path)


def main() -> None:
    args = arguments("rotor_campbell", __doc__)
    clock = Clock()
    if args.quick:
        loads, speeds_rpm, campbell_rpm = [50.0, 1000.0], np.linspace(0, 15000, 4), np.linspace(0, 15000, 6)
    else:
        loads, speeds_rpm, campbell_rpm = [50.0, 200.0, 1000.0], np.linspace(0, 15000, 16), np.linspace(0, 15000, 31)
    table = coefficients(loads, speeds_rpm)
    print(clock.report(f"K and C at {len(loads) * len(speeds_rpm)} points"))
    with open(args.out / "kc.csv", "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["load [N]", "speed [rpm]", "Kxx [N/m]", "Kxy [N/m]", "Kyx [N/m]", "Kyy [N/m]", "Cxx [N.s/m]", "Cxy [N.s/m]", "Cyx [N.s/m]", "Cyy [N.s/m]"])
        for w, d in table.items():
            for n, k, c in zip(speeds_rpm, d["K"], d["C"]):
                out.writerow([w, n, *k.ravel(), *c.ravel()])
    plot_kc(figure_path(args, "kc"), speeds_rpm, table)

    clock = Clock()
    campbells = {}
    for w in (loads[0], loads[-1]):
        r = rotor(table[w]["K"], table[w]["C"], speeds_rpm / RPM_PER_RAD_S)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            camp = r.run_campbell(campbell_rpm / RPM_PER_RAD_S, frequencies=4)
        campbells[w] = (np.asarray(camp.wd), np.asarray(camp.whirl_values))
    print(clock.report(f"ROSS (import, JIT, rotors) and its Campbell diagrams, {len(campbell_rpm)} speeds each"))
    plot_campbell(figure_path(args, "campbell"), campbell_rpm, campbells)

    light, heavy = (first_forward(*campbells[w]) / (2 * math.pi) for w in (loads[0], loads[-1]))
    step = max(1, len(campbell_rpm) // 6)
    for n, a, b in list(zip(campbell_rpm, light, heavy))[::step]:
        print(f"  {n:7.0f} rpm: first forward mode {a:7.2f} Hz at {loads[0]:g} N, {b:7.2f} Hz at {loads[-1]:g} N")
    kyy = [table[w]["K"][:, 1, 1] for w in (loads[0], loads[-1])]
    check(bool(np.all(kyy[1] > kyy[0])), f"K_yy at {loads[-1]:g} N above K_yy at {loads[0]:g} N at every speed")
    check(
        bool(np.all(np.isfinite(light)) and np.all(heavy > light)),
        f"first forward mode higher with the stiffer bearings ({loads[-1]:g} N) at every speed: "
        f"{heavy[0]:.1f} Hz vs {light[0]:.1f} Hz at rest",
    )


if __name__ == "__main__":
    main()
