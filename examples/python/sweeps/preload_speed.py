"""A design sweep of a spindle bearing: axial preload × speed → peak contact pressure and stiffness.

A 7008CE angular-contact bearing (docs/physics.md §10: 16 balls, 15° free contact angle) under
a constant 200 N radial load and an axial preload, at speeds up to 30 000 rpm. Each grid
point is the Jones–Harris quasi-static equilibrium (``raceway.quasi_static``: the balls'
centrifugal force and gyroscopic moment included, outer-race control), run on two threads
(the package releases the GIL). Read from each: the highest Hertz pressure over all balls
and both races (``balls["p_i [Pa]"]``, ``balls["p_o [Pa]"]``) and the radial and axial
stiffness ``K_yy``, ``K_zz`` of the 5×5 ``K = -dF/dq``. Written: ``grid.csv`` and a
heat-map figure of the three.

Check (CI): at every speed the axial stiffness rises with the preload (more load on every
ball stiffens its Hertz contacts, like Q^(1/3)), and the heaviest preload gives a higher peak
pressure than the lightest. The peak pressure does not rise with every step of preload: at
speed a light preload first spreads the radial load more evenly over the balls.

    python examples/python/sweeps/preload_speed.py --quick
    python examples/python/sweeps/preload_speed.py --write-docs
"""

from __future__ import annotations

import csv
import itertools
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

import raceway
from common import arguments, check, figure_path, load_average, pyplot, save

BEARING = "7008ce"
RADIAL_N = 200.0


def point(preload_n: float, rpm: float) -> tuple[float, float, float, float, float]:
    """Peak contact pressure (Pa), K_yy and K_zz (N/m) at one grid point, 1.0 when every
    ball carries load on both races (else 0.0), and the thread CPU time it took (s)."""
    cpu0 = time.thread_time()
    r = raceway.quasi_static(BEARING, speed_rpm=float(rpm), fy=-RADIAL_N, fz=float(preload_n))
    peak = float(max(r.balls["p_i [Pa]"].max(), r.balls["p_o [Pa]"].max()))
    loaded = float(min(r.balls["q_i [N]"].min(), r.balls["q_o [N]"].min()) > 0.0)
    return peak, float(r.K[1, 1]), float(r.K[2, 2]), loaded, time.thread_time() - cpu0


def plot(path, preloads, speeds, grids):
    plt = pyplot()
    panels = [
        ("peak contact pressure [GPa]", grids["p"] / 1e9, "magma"),
        ("radial stiffness $K_{yy}$ [N/µm]", grids["kyy"] / 1e6, "viridis"),
        ("axial stiffness $K_{zz}$ [N/µm]", grids["kzz"] / 1e6, "viridis"),
    ]
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.3), constrained_layout=True)
    for ax, (label, z, cmap) in zip(axes, panels):
        m = ax.pcolormesh(speeds / 1000.0, preloads, z, shading="nearest", cmap=cmap)
        fig.colorbar(m, ax=ax, label=label)
        ax.set(xlabel="shaft speed [1000 rpm]", ylabel="axial preload [N]", title=label.split(" [")[0])
    fig.suptitle(f"{BEARING}, {RADIAL_N:g} N radial: quasi-static equilibrium over preload × speed")
    save(fig, path)


def main() -> None:
    args = arguments("preload_speed", __doc__)
    if args.quick:
        preloads, speeds = np.linspace(50.0, 1000.0, 4), np.linspace(0.0, 30000.0, 4)
    else:
        preloads, speeds = np.linspace(50.0, 1000.0, 20), np.linspace(0.0, 30000.0, 16)
    grid = list(itertools.product(preloads, speeds))
    with ThreadPoolExecutor(max_workers=2) as pool:
        values = list(pool.map(lambda g: point(*g), grid))
    cpu = sum(v[4] for v in values)
    print(f"{len(grid)} equilibria: the workers' thread CPU time {cpu:.3f} s, {cpu / len(grid) * 1e3:.2f} ms a point (load average {load_average()})")
    shape = (len(preloads), len(speeds))
    grids = {k: np.array([v[i] for v in values]).reshape(shape) for i, k in enumerate(("p", "kyy", "kzz", "all"))}
    with open(args.out / "grid.csv", "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["preload [N]", "speed [rpm]", "peak_pressure [Pa]", "Kyy [N/m]", "Kzz [N/m]", "all_balls_loaded"])
        for (w, n), v in zip(grid, values):
            out.writerow([w, n, *v[:3], bool(v[3])])
    plot(figure_path(args, "preload-speed"), preloads, speeds, grids)

    p, kzz = grids["p"], grids["kzz"]
    print(f"peak pressure: {p.min() / 1e9:.3f} to {p.max() / 1e9:.3f} GPa; K_zz {kzz.min() / 1e6:.1f} to {kzz.max() / 1e6:.1f} N/µm")
    # Not checked: that the peak pressure rises with every step of preload. Under the
    # radial load, at speed, a light preload first spreads the radial load more evenly
    # over the balls (the peak falls a little), then raises every ball's load
    # (docs/python-examples.md).
    dips = int((np.diff(p, axis=0) <= 0).sum())
    check(bool(np.all(p[-1] > p[0])), "the heaviest preload gives a higher peak pressure than the lightest at every speed")
    check(bool(np.all(np.diff(kzz, axis=0) > 0)), "axial stiffness rises with the preload at every speed")
    print(f"steps of preload where the peak pressure does not rise: {dips} of {p.size - p.shape[1]}")


if __name__ == "__main__":
    main()
