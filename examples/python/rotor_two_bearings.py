"""A rigid rotor on two raceway bearing FMUs, co-simulated from Python with fmpy.

The rotor (mass m, transverse inertia J, unbalance m_u e at its centre, gravity along -y) has
four degrees of freedom q = (x, y, theta_x, theta_y) of its centre; bearing j sits at axial
position z_j, where the journal moves by s_j = S_j q:

    s_j = (x + z_j theta_y,  y - z_j theta_x)

and the bearing's radial force f_j = (Fx, Fy) acts on the rotor as S_j^T f_j (virtual work).
The bearings are point supports: the journal's tilt is not passed to them and their moments
(small for a single-row ball bearing) are left out. Each bearing is one FMU instance
(FMI 2, motion-driven).

Coupling (Jacobi, one communication step h): at t_i both sides start together. The bearings
get the rotor's motion at t_i and step to t_i + h. The rotor steps with the bearing force
linearised about what the bearings last reported,

    f_j(s, sdot) ~= f_j - K_j (s - s_hat_j) - C_j (sdot - v_hat_j),

using the K and C outputs (s_hat_j, v_hat_j: the motion the bearing computed that output
for; the bearings run with input_rule = "hold", so that is the input of their last step).
For a linear bearing this is exact, so the coupling adds no instability (docs/physics.md §C5.3). The rotor
integrates this linear ODE with the Newmark average-acceleration rule (trapezoidal,
unconditionally stable; Hairer & Wanner, Newmark 1959).

    python examples/python/rotor_two_bearings.py [OUT_DIR] [--duration S] [--step H] [--fmu F]

writes OUT_DIR/orbits.png, OUT_DIR/forces.png and OUT_DIR/summary.json (default OUT_DIR: out/).
"""

import argparse
import json
import math
import os
import pathlib

import numpy as np
from fmpy import read_model_description
from fmpy.fmi2 import FMU2Slave
from fmpy import extract

G = 9.81
DOF = ["x", "y", "z", "rx", "ry"]
LOADS = ["force.x", "force.y", "force.z", "moment.x", "moment.y"]
MOTION = ["shaft.x", "shaft.y", "shaft.z", "shaft.rx", "shaft.ry"]
VELOCITY = ["shaft.vx", "shaft.vy", "shaft.vz", "shaft.wx", "shaft.wy"]


class Rotor:
    """Rigid rotor: mass, inertia, unbalance, bearing positions, a light external damper."""

    def __init__(self, mass=10.0, length=0.4, radius=0.05, z_bearings=(-0.15, 0.25),
                 unbalance=5e-4, rpm=1750.0, damping=500.0):
        self.m = mass
        self.J = mass * (3 * radius**2 + length**2) / 12.0
        self.M = np.diag([mass, mass, self.J, self.J])
        self.z = z_bearings
        self.me = unbalance  # kg m
        self.omega = rpm * 2 * math.pi / 60.0
        self.c = damping  # N s/m on x, y (seals, air): keeps the start-up transient short
        self.S = [self.selector(z) for z in z_bearings]

    @staticmethod
    def selector(z):
        return np.array([[1, 0, 0, z], [0, 1, -z, 0]], dtype=float)

    def external(self, t):
        """Gravity and unbalance, generalised forces."""
        f = self.me * self.omega**2
        return np.array([f * math.cos(self.omega * t), -self.m * G + f * math.sin(self.omega * t),
                         0.0, 0.0])


class Bearing:
    """One bearing FMU instance."""

    def __init__(self, unzipdir, md, name):
        self.vr = {v.name: v.valueReference for v in md.modelVariables}
        self.fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzipdir,
                             modelIdentifier=md.coSimulation.modelIdentifier, instanceName=name)
        self.fmu.instantiate()
        self.fmu.setupExperiment(startTime=0.0)
        # inputs held over each step: the output at t + h belongs to the motion set at t
        # (input_rule is an Enumeration: its items by name from the model description)
        hold = next(int(i.value) for v in md.modelVariables if v.name == "input_rule"
                    for i in v.declaredType.items if i.name == "hold")
        self.fmu.setInteger([self.vr["input_rule"]], [hold])
        self.fmu.enterInitializationMode()
        self.fmu.exitInitializationMode()
        self.in_vr = [self.vr[n] for n in MOTION + VELOCITY + ["shaft.omega"]]
        self.out_vr = ([self.vr[n] for n in LOADS]
                       + [self.vr[f"K.{i}.{j}"] for i in DOF for j in DOF]
                       + [self.vr[f"C.{i}.{j}"] for i in DOF for j in DOF])
        self.f = np.zeros(2)
        self.K = np.zeros((2, 2))
        self.C = np.zeros((2, 2))
        self.s_hat = np.zeros(2)
        self.v_hat = np.zeros(2)

    def step(self, t, h, s, v, omega):
        """Journal motion s = (x, y), v = (vx, vy) in; radial force, K, C (x, y block) out."""
        z3 = [0.0, 0.0, 0.0]
        self.fmu.setReal(self.in_vr, [s[0], s[1]] + z3 + [v[0], v[1]] + z3 + [omega])
        self.fmu.doStep(t, h)
        y = np.array(self.fmu.getReal(self.out_vr))
        self.f = y[:2]
        self.K = y[5:30].reshape(5, 5)[:2, :2]
        self.C = y[30:55].reshape(5, 5)[:2, :2]
        # the motion this output belongs to
        self.s_hat, self.v_hat = s.copy(), v.copy()

    def free(self):
        try:
            self.fmu.terminate()
        finally:
            self.fmu.freeInstance()


def linear_model(rotor, bearings, t):
    """M qdd + C qd + K q = b(t): the rotor with the linearised bearings."""
    K = np.zeros((4, 4))
    C = np.diag([rotor.c, rotor.c, 0.0, 0.0])
    b = rotor.external(t)
    for S, br in zip(rotor.S, bearings):
        K += S.T @ br.K @ S
        C += S.T @ br.C @ S
        b = b + S.T @ (br.f + br.K @ br.s_hat + br.C @ br.v_hat)
    return K, C, b


def simulate(fmu, duration=0.1, h=1e-4, rotor=None):
    rotor = rotor or Rotor()
    unzipdir = extract(str(fmu))
    md = read_model_description(unzipdir)
    bearings = [Bearing(unzipdir, md, name) for name in ("A", "B")]
    q, v = np.zeros(4), np.zeros(4)
    n = int(round(duration / h))
    rec = {"t": [], "s": [[], []], "f": [[], []]}
    try:
        for i in range(n):
            t = i * h
            # rotor step with the bearings as they reported at t (Newmark, beta = 1/4)
            K, C, b0 = linear_model(rotor, bearings, t)
            _, _, b1 = linear_model(rotor, bearings, t + h)
            a = np.linalg.solve(rotor.M, b0 - C @ v - K @ q)
            lhs = 4 / h**2 * rotor.M + 2 / h * C + K
            rhs = b1 + rotor.M @ (4 / h**2 * q + 4 / h * v + a) + C @ (2 / h * q + v)
            q1 = np.linalg.solve(lhs, rhs)
            a1 = 4 / h**2 * (q1 - q) - 4 / h * v - a
            v1 = v + h / 2 * (a + a1)
            # bearing steps with the rotor's motion at t (in parallel: Jacobi)
            for S, br in zip(rotor.S, bearings):
                br.step(t, h, S @ q, S @ v, rotor.omega)
            q, v = q1, v1
            rec["t"].append(t + h)
            for j, (S, br) in enumerate(zip(rotor.S, bearings)):
                rec["s"][j].append(S @ q)
                rec["f"][j].append(br.f.copy())
    finally:
        for br in bearings:
            br.free()
    t = np.array(rec["t"])
    return rotor, t, [np.array(s) for s in rec["s"]], [np.array(f) for f in rec["f"]]


def whole_revolutions(t, omega, skip=0.2):
    """Mask of the last whole number of revolutions after the first `skip` of the run."""
    period = 2 * math.pi / omega
    t0, t1 = t[0] + skip * (t[-1] - t[0]), t[-1]
    revs = math.floor((t1 - t0) / period)
    if revs < 1:
        return t >= t0
    return t >= t1 - revs * period


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("out", nargs="?", default="out", help="folder for the plots (default out/)")
    p.add_argument("--duration", type=float, default=0.2, help="simulated time, s")
    p.add_argument("--step", type=float, default=1e-4, help="communication step, s")
    p.add_argument("--fmu", default=os.path.join("target", "fmu", "raceway-fmi2.fmu"))
    args = p.parse_args(argv)

    rotor, t, s, f = simulate(args.fmu, args.duration, args.step)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 2, figsize=(9, 4.2))
    for j, name in enumerate("AB"):
        ax[j].plot(s[j][:, 0] * 1e6, s[j][:, 1] * 1e6, lw=0.8)
        ax[j].set(title=f"bearing {name} (z = {rotor.z[j]} m)", xlabel="x, µm", ylabel="y, µm")
        ax[j].set_aspect("equal", adjustable="datalim")
    fig.suptitle("journal orbits")
    fig.tight_layout()
    fig.savefig(out / "orbits.png", dpi=120)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(8, 4))
    for j, name in enumerate("AB"):
        ax.plot(t * 1e3, f[j][:, 1], lw=0.8, label=f"force.y, bearing {name}")
    ax.plot(t * 1e3, f[0][:, 1] + f[1][:, 1], lw=1.0, label="sum")
    ax.axhline(rotor.m * G, color="k", ls="--", lw=0.8, label="rotor weight m g")
    ax.set(xlabel="t, ms", ylabel="N", title="vertical bearing forces on the rotor")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "forces.png", dpi=120)
    plt.close(fig)

    w = whole_revolutions(t, rotor.omega)
    summary = {
        "duration [s]": float(t[-1]),
        "step [s]": args.step,
        "rotor_weight [N]": rotor.m * G,
        "mean_vertical_bearing_force [N]": float(np.mean(f[0][w, 1] + f[1][w, 1])),
        "mean_horizontal_bearing_force [N]": float(np.mean(f[0][w, 0] + f[1][w, 0])),
        "max_journal_displacement [m]": float(max(np.abs(sj[:, :2]).max() for sj in s)),
        "all_finite": bool(all(np.all(np.isfinite(x)) for x in s + f)),
    }
    (out / "summary.json").write_text(json.dumps(summary, indent=2))
    print(json.dumps(summary, indent=2))


if __name__ == "__main__":
    main()
