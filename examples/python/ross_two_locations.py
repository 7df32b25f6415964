"""A flexible ROSS rotor on two raceway bearing locations, coupled in the time domain.

The rotor is a ROSS model (``ross-rotordynamics``): a steel shaft of Timoshenko beam elements
with a disk, its mass, stiffness and gyroscopic matrices from ROSS. The bearings are raceway
components (``raceway.Component``, quasi-static level, motion-driven), not ROSS bearing
elements: at the front a 7008CE pair back to back (DB) with a rigid preload, at the rear a
single 6008 deep-groove bearing. Gravity acts along -y.

**The DB pair is one component**: a set scene (`[set] arrangement = "db"`, physics §S1) whose
rows sit at their own axial positions and whose wrench and 5x5 stiffness come out at the
pair's reference point, the node. ``front_location(..., as_set=False)`` builds the same pair
from two single-row components instead, the row facing -z mirrored by hand (its axial and tilt
inputs and outputs change sign); the check below holds for both. Every location answers the
same ``step(q, v)`` with its wrench and 5x5 stiffness at its node.

Coupling per macro step h (Jacobi, as examples/python/rotor_two_bearings.py): each location
gets the shaft's 5 nodal displacements (x, y, z, rx, ry) at its node from the rotor's state and
steps; the rotor steps with the bearing wrench linearised about what the bearings last
reported, ``f(q) ~ f_hat - K (q - q_hat)``, by Newmark's average acceleration rule. A light
Rayleigh damping ``alpha M`` on the rotor lets the start-up transient die within the run.

Check at the end (exit 1 on failure), over the second half of the run (the balls passing
under the load keep a small vibration at the ball-pass frequency): the shaft's mean position
is where the rotor's static solution with the bearings' linearised stiffness puts it (the
disk's deflection within 2 %: the bearings are linearised at the last, vibrating state, whose
amplitude is ~2 % of the deflection), and the bearings' mean vertical force carries the rotor's
weight (within 0.5 %).

    python examples/python/ross_two_locations.py [--quick] [--out DIR]
"""

from __future__ import annotations

import argparse
import math
import pathlib
import sys
import tempfile
import time

import numpy as np

import raceway

G = 9.81
IN = ["shaft.x", "shaft.y", "shaft.z", "shaft.rx", "shaft.ry"]
VEL = ["shaft.vx", "shaft.vy", "shaft.vz", "shaft.wx", "shaft.wy"]
OUT = ["force.x", "force.y", "force.z", "moment.x", "moment.y"]
DOF = ["x", "y", "z", "rx", "ry"]

SCENE = """title = "{title}"
bearing = "{bearing}"

[model]
level = "quasi_static"
causality = "motion"

[inputs]
rule = "hold"
"""


def scene(folder: pathlib.Path, bearing: str) -> str:
    """A motion-driven quasi-static scene for `bearing` (written into `folder`)."""
    p = folder / f"{bearing}.toml"
    p.write_text(SCENE.format(title=f"{bearing}, quasi-static, motion-driven (ROSS example)",
                              bearing=bearing))
    return str(p)


def offset_map(z: float, o: float) -> np.ndarray:
    """The row's own displacement from the node's: T A (physics §S1), row at z from the node,
    facing o = +1 or -1."""
    return np.array([[1, 0, 0, 0, z], [0, 1, 0, -z, 0], [0, 0, o, 0, 0],
                     [0, 0, 0, o, 0], [0, 0, 0, 0, o]], dtype=float)


class Single:
    """One component (a single-row bearing, or a whole set scene) at a node."""

    def __init__(self, path: str, omega: float, z: float = 0.0, o: float = 1.0,
                 offset: float = 0.0):
        self.c = raceway.Component(path)
        self.omega = omega
        self.T = offset_map(z, o)
        self.offset = offset
        self.f = np.zeros(5)
        self.K = np.zeros((5, 5))
        self.q_hat = np.zeros(5)

    def step(self, t, h, q, v):
        ql = self.T @ q
        ql[2] += self.offset
        vl = self.T @ v
        self.c.set({**dict(zip(IN, ql)), **dict(zip(VEL, vl)), "shaft.omega": self.omega})
        self.c.do_step(t, h)
        out = self.c.outputs()
        fl = np.array([out[n] for n in OUT])
        kl = np.array([[out[f"K.{i}.{j}"] for j in DOF] for i in DOF])
        self.f = self.T.T @ fl
        self.K = self.T.T @ kl @ self.T
        self.q_hat = q.copy()


class Rows:
    """Several components at one node, their wrenches and stiffnesses added."""

    def __init__(self, parts):
        self.parts = parts

    def step(self, t, h, q, v):
        for p in self.parts:
            p.step(t, h, q, v)
        self.f = sum(p.f for p in self.parts)
        self.K = sum(p.K for p in self.parts)
        self.q_hat = q.copy()


SET_SCENE = """title = "7008CE DB pair, rigid preload {preload} N, quasi-static (ROSS example)"
bearing = "7008CE"

[set]
arrangement = "db"
spacer_mm = 0
preload_n = {preload}

[model]
level = "quasi_static"
causality = "motion"

[inputs]
rule = "hold"
"""


def front_location(folder: pathlib.Path, omega: float, preload_n: float,
                   as_set: bool = True) -> Rows | Single:
    """The front DB pair of 7008CE (width 15 mm, rows abutting), rigid preload `preload_n`:
    one set component (`as_set`), or two single-row components at the rows' positions."""
    if as_set:
        p = folder / "7008ce-db.toml"
        p.write_text(SET_SCENE.format(preload=preload_n))
        return Single(str(p), omega)
    width = 0.015
    # The rigid offset: each row's own axial displacement carrying the preload at standstill.
    offset = float(raceway.quasi_static("7008ce", fz=preload_n).displacement[2])
    path = scene(folder, "7008ce")
    return Rows([Single(path, omega, -width / 2, +1.0, offset),
                 Single(path, omega, +width / 2, -1.0, offset)])


def rotor_model():
    """ROSS: a 40 mm steel shaft, 300 mm long in 6 elements, a disk 100 mm from the front."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        import ross as rs

    steel = rs.Material(name="Steel", rho=7810.0, E=211e9, G_s=81.2e9)
    shaft = [rs.ShaftElement(L=0.05, idl=0.0, odl=0.040, material=steel, n=i,
                             shear_effects=True, rotary_inertia=True, gyroscopic=True)
             for i in range(6)]
    disk = [rs.DiskElement.from_geometry(n=2, material=steel, width=0.03, i_d=0.04, o_d=0.16)]
    # ROSS needs bearing elements: placeholders of 1 N/m (raceway's bearings act as forces).
    bearings = [rs.BearingElement(n=n, kxx=1.0, cxx=0.0, scale_factor=0.5) for n in (0, 4)]
    return rs.Rotor(shaft_elements=shaft, disk_elements=disk, bearing_elements=bearings)


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--quick", action="store_true", help="a short run (CI): 20 ms")
    p.add_argument("--out", default="out/ross_two_locations")
    p.add_argument("--rpm", type=float, default=6000.0)
    args = p.parse_args(argv)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    t_wall = time.time()

    rotor = rotor_model()
    omega = args.rpm * math.pi / 30.0
    n_nodes = len(rotor.nodes_pos)
    # ROSS orders 6 DOF per node (x, y, z, alpha, beta, theta); keep the first 5 (torsion,
    # unloaded and unsupported here, left out).
    keep = np.array([6 * n + k for n in range(n_nodes) for k in range(5)])
    M = rotor.M(0)[np.ix_(keep, keep)]
    K_r = rotor.K(0)[np.ix_(keep, keep)]
    Gy = rotor.G()[np.ix_(keep, keep)]
    # Remove ROSS's placeholder bearings (1 N/m on x and y at their nodes).
    for n in (0, 4):
        for k in (0, 1):
            K_r[5 * n + k, 5 * n + k] -= 1.0
    ndof = M.shape[0]
    ey = np.zeros(ndof)
    ey[1::5] = 1.0
    f_grav = -G * (M @ ey)  # consistent nodal gravity loads
    weight = -f_grav.sum()
    alpha = 2000.0  # Rayleigh alpha M, 1/s: the start-up transient gone in ~10 ms
    C = alpha * M + omega * Gy

    with tempfile.TemporaryDirectory() as tmp:
        folder = pathlib.Path(tmp)
        locations = {0: front_location(folder, omega, 300.0),
                     4: Single(scene(folder, "6008"), omega)}
        sel = {n: np.arange(5 * n, 5 * n + 5) for n in locations}

        def linear(t):
            K = K_r.copy()
            b = f_grav.copy()
            for n, loc in locations.items():
                i = sel[n]
                K[np.ix_(i, i)] += loc.K
                b[i] += loc.f + loc.K @ loc.q_hat
            return K, b

        h = 1e-4
        duration = 0.02 if args.quick else 0.1
        q, v = np.zeros(ndof), np.zeros(ndof)
        for n, loc in locations.items():
            loc.step(0.0, h, q[sel[n]], v[sel[n]])
        K, b = linear(0.0)
        a = np.linalg.solve(M, b - C @ v - K @ q)
        disk_y, force_y = [], []
        steps = int(round(duration / h))
        for i in range(steps):
            t = i * h
            K, b = linear(t)
            lhs = 4 / h**2 * M + 2 / h * C + K
            rhs = b + M @ (4 / h**2 * q + 4 / h * v + a) + C @ (2 / h * q + v)
            q1 = np.linalg.solve(lhs, rhs)
            a1 = 4 / h**2 * (q1 - q) - 4 / h * v - a
            v = v + h / 2 * (a + a1)
            q, a = q1, a1
            for n, loc in locations.items():
                loc.step(t + h, h, q[sel[n]], v[sel[n]])
            disk_y.append(q[5 * 2 + 1])
            force_y.append(sum(loc.f[1] for loc in locations.values()))

        # The rotor's static solution with the bearings' stiffness linearised at the end.
        K, b = linear(duration)
        q_static = np.linalg.solve(K, b)

    # The balls passing under the load make the bearings' stiffness vary (at the 6008's
    # ball-pass frequency, ~480 Hz here): the shaft keeps a small vibration about its static
    # position, so the time domain is averaged over the second half of the run.
    half = len(disk_y) // 2
    y_dyn, y_sta = float(np.mean(disk_y[half:])), q_static[5 * 2 + 1]
    err = abs(y_dyn / y_sta - 1.0)
    share = float(np.mean(force_y[half:])) / weight
    print(f"rotor (ROSS): {n_nodes} nodes, mass {weight / G:.3f} kg; {args.rpm:.0f} rpm; "
          f"{steps} macro steps of {h * 1e3:.1f} ms")
    for n, loc in locations.items():
        print(f"  node {n} (z {rotor.nodes_pos[n] * 1e3:.0f} mm): Fy {loc.f[1]:.2f} N  "
              f"Fz {loc.f[2]:.3f} N  K_yy {loc.K[1, 1] * 1e-6:.1f} N/um")
    print(f"disk deflection: time domain (mean of the second half) {y_dyn * 1e6:.4f} um, linearised static "
          f"{y_sta * 1e6:.4f} um (error {err * 100:.3f} %)")
    print(f"bearings' vertical force / rotor weight: {share:.5f}")
    print(f"wall time {time.time() - t_wall:.1f} s")

    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(8, 4))
        tt = np.arange(1, len(disk_y) + 1) * h * 1e3
        ax.plot(tt, np.array(disk_y) * 1e6, lw=1.0, label="ROSS rotor on raceway bearings")
        ax.axhline(y_sta * 1e6, color="k", ls="--", lw=0.8,
                   label="static, bearings linearised at the end")
        ax.set(xlabel="time (ms)", ylabel="disk vertical displacement (µm)",
               title=f"ROSS rotor, 7008CE DB pair + 6008, {args.rpm:.0f} rpm: settling under gravity")
        ax.legend(loc="upper right", fontsize=8)
        fig.tight_layout()
        fig.savefig(out / "disk-deflection.png", dpi=100)
        plt.close(fig)
    except ImportError:
        pass

    ok = err < 0.02 and abs(share - 1.0) < 0.005
    print("check ok" if ok else "check FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
