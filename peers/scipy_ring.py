#!/usr/bin/env python3
"""SciPy peer of raceway's work-precision study: the 2-DOF ring on massless balls
(docs/physics.md §5.1, docs/physics.md §N4.1) of case `6205-2dof`, load-driven, integrated with
scipy.integrate.solve_ivp (Radau, LSODA and DOP853) with a NumPy right-hand side vectorised over
the balls and the analytic Jacobian, scored with raceway's metric against raceway's
reference.

Same equations as src/models/ring.rs + the component's load-driven ring body:
  y = (theta_c, x, y, vx, vy);  theta_c' = omega_c
  psi_j = theta_c + 2 pi j / Z,  delta_j = x cos psi_j + y sin psi_j - Pd/2
  Q_j = Kn delta^1.5 + c min(delta/ramp, 1) d(delta)/dt   (delta > 0)
  F = -sum_j Q_j (cos psi_j, sin psi_j),   (x, y)'' = (F + load) / m
Parameters come from raceway (<dir>/6205-2dof-parameters.json), so both integrate the
same bearing. Output: <dir>/6205-2dof-scipy.csv
(method,rtol,median_s,nfev,njev,nlu,err_l2,err_peak): solve_ivp straight through the window,
sampled at the communication points by t_eval. Also <dir>/6205-2dof-scipy-loop.csv, same
columns: the co-simulation job raceway does, solve_ivp restarted at every communication
point from the state it reached (as a host coupling it at each macro step runs it; the loads
are held, so both jobs integrate the same equations). Times are the process's CPU
time (time.process_time; scripts/peer-scipy limits BLAS to one thread), median of repeats
after a warm-up.

Usage: peers/scipy_ring.py <dir> [--smoke | --quick]
"""
import json
import math
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

CASE = "6205-2dof"


def load(dirname):
    with open(f"{dirname}/{CASE}-parameters.json") as f:
        p = json.load(f)
    ref = np.loadtxt(f"{dirname}/{CASE}-reference.csv", delimiter=",", skiprows=1, ndmin=2)
    return p, ref


class Ring:
    def __init__(self, p):
        self.z = int(p["z"])
        self.kn = p["kn"]
        self.half_pd = 0.5 * p["pd"]
        self.m = p["mass"]
        self.c = p["damping"]
        self.ramp = p["damping_ramp"]
        self.wc = p["cage_omega"]
        self.load = np.array([p["load_x"], p["load_y"]])
        self.offsets = 2.0 * math.pi * np.arange(self.z) / self.z

    def contacts(self, y):
        th, x, yy, vx, vy = y
        psi = th + self.offsets
        c, s = np.cos(psi), np.sin(psi)
        delta = x * c + yy * s - self.half_pd
        rate = vx * c + vy * s + self.wc * (-x * s + yy * c)
        return psi, c, s, delta, rate

    def wrench(self, y):
        _, c, s, delta, rate = self.contacts(y)
        on = delta > 0.0
        d = np.where(on, delta, 0.0)
        q = np.where(on, self.kn * d * np.sqrt(d) + self.c * np.minimum(d / self.ramp, 1.0) * rate, 0.0)
        return -np.dot(q, c), -np.dot(q, s)

    def rhs(self, t, y):
        fx, fy = self.wrench(y)
        return np.array([self.wc, y[3], y[4], (fx + self.load[0]) / self.m, (fy + self.load[1]) / self.m])

    def jac(self, t, y):
        th, x, yy, vx, vy = y
        _, c, s, delta, rate = self.contacts(y)
        on = delta > 0.0
        d = np.where(on, delta, 0.0)
        sq = np.sqrt(d)
        blend = np.minimum(d / self.ramp, 1.0)
        dblend = np.where(on & (d < self.ramp), 1.0 / self.ramp, 0.0)
        q = np.where(on, self.kn * d * sq + self.c * blend * rate, 0.0)
        dq_ddelta = np.where(on, 1.5 * self.kn * sq + self.c * dblend * rate, 0.0)
        cb = np.where(on, self.c * blend, 0.0)
        # d(delta)/d(th, x, y), d(rate)/d(th, x, y, vx, vy)
        dd = [(-x * s + yy * c), c, s]
        dr = [(-vx * s + vy * c + self.wc * (-x * c - yy * s)), -self.wc * s, self.wc * c, c, s]
        J = np.zeros((5, 5))
        J[1, 3] = 1.0
        J[2, 4] = 1.0
        for k in range(5):
            dqk = cb * dr[k] + (dq_ddelta * dd[k] if k < 3 else 0.0)
            # F = -sum q g; g depends on theta: dg/dth = (-s, c)
            dfx = -np.dot(dqk, c)
            dfy = -np.dot(dqk, s)
            if k == 0:
                dfx += np.dot(q, s)
                dfy -= np.dot(q, c)
            J[3, k] = dfx / self.m
            J[4, k] = dfy / self.m
        return J


def error(fx, fy, ref):
    e2 = (fx - ref[:, 1]) ** 2 + (fy - ref[:, 2]) ** 2 + ref[:, 3] ** 2
    r2 = ref[:, 1] ** 2 + ref[:, 2] ** 2 + ref[:, 3] ** 2
    return math.sqrt(e2.sum() / r2.sum()), math.sqrt(e2.max()) / math.sqrt(r2.max())


def run(ring, p, ref, method, rtol):
    atol_m = p["atol_per_rtol"] * rtol
    atol = np.array([atol_m / (0.5 * p["ball_d"]), atol_m, atol_m,
                     atol_m * 2e3 * math.pi, atol_m * 2e3 * math.pi])
    t_eval = ref[:, 0]
    t0 = time.process_time()
    # The explicit DOP853 takes no Jacobian.
    extra = {} if method == "DOP853" else {"jac": ring.jac}
    sol = solve_ivp(ring.rhs, (0.0, p["t_end"]), np.zeros(5), method=method, t_eval=t_eval,
                    rtol=rtol, atol=atol, **extra)
    dt = time.process_time() - t0
    if not sol.success:
        raise RuntimeError(f"{method} rtol {rtol}: {sol.message}")
    f = np.array([ring.wrench(sol.y[:, k]) for k in range(sol.y.shape[1])])
    return dt, sol, error(f[:, 0], f[:, 1], ref)


def run_loop(ring, p, ref, method, rtol):
    """The coupling loop: one solve_ivp per communication step, restarted from the last state."""
    atol_m = p["atol_per_rtol"] * rtol
    atol = np.array([atol_m / (0.5 * p["ball_d"]), atol_m, atol_m,
                     atol_m * 2e3 * math.pi, atol_m * 2e3 * math.pi])
    extra = {} if method == "DOP853" else {"jac": ring.jac}
    ts = ref[:, 0]
    y = np.zeros(5)
    ys = np.empty((5, len(ts)))
    nfev = njev = nlu = 0
    t_prev = 0.0
    t0 = time.process_time()
    for k, t in enumerate(ts):
        sol = solve_ivp(ring.rhs, (t_prev, t), y, method=method, rtol=rtol, atol=atol, **extra)
        if not sol.success:
            raise RuntimeError(f"{method} rtol {rtol} loop at t = {t}: {sol.message}")
        y = sol.y[:, -1]
        ys[:, k] = y
        nfev, njev, nlu = nfev + sol.nfev, njev + (sol.njev or 0), nlu + (sol.nlu or 0)
        t_prev = t
    dt = time.process_time() - t0
    f = np.array([ring.wrench(ys[:, k]) for k in range(len(ts))])
    return dt, (nfev, njev, nlu), error(f[:, 0], f[:, 1], ref)


def check_jacobian(ring):
    """The analytic Jacobian against central differences at a loaded state."""
    y = np.array([0.3, 2e-6, -9e-6, 1e-3, -2e-3])
    J = ring.jac(0.0, y)
    steps = np.array([1e-6, 1e-10, 1e-10, 1e-6, 1e-6])
    for k in range(5):
        yp, ym = y.copy(), y.copy()
        yp[k] += steps[k]
        ym[k] -= steps[k]
        fd = (ring.rhs(0, yp) - ring.rhs(0, ym)) / (2 * steps[k])
        scale = max(np.abs(J[:, k]).max(), 1.0)
        assert np.abs(fd - J[:, k]).max() < 1e-4 * scale, (k, fd, J[:, k])


def main():
    dirname = sys.argv[1] if len(sys.argv) > 1 else "target/raceway-bench"
    smoke = "--smoke" in sys.argv
    quick = "--quick" in sys.argv
    p, ref = load(dirname)
    ring = Ring(p)
    check_jacobian(ring)
    if smoke:
        rtols, reps = [1e-4], 1
    elif quick:
        rtols, reps = [1e-4, 1e-6, 1e-8], 1
    else:
        rtols, reps = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8], 5
    rows = []
    for method in ["Radau", "LSODA", "DOP853"]:
        for rtol in rtols:
            run(ring, p, ref, method, rtol)  # warm-up
            times, sol, (l2, pk) = [], None, (0, 0)
            for _ in range(reps):
                dt, sol, (l2, pk) = run(ring, p, ref, method, rtol)
                times.append(dt)
            med = float(np.median(times))
            rows.append((f"scipy-{method}", rtol, med, sol.nfev, sol.njev or 0, sol.nlu or 0, l2, pk))
            print(f"  scipy {method:<6} rtol {rtol:.0e}: {med * 1e3:9.2f} ms  err L2 {l2:.2e} peak {pk:.2e}"
                  f"  nfev {sol.nfev} njev {sol.njev} nlu {sol.nlu}", flush=True)
    write(f"{dirname}/{CASE}-scipy.csv", rows)
    # The coupling loop: one repeat (each run restarts SciPy hundreds of times; its
    # spread is small against the ratios it is compared by).
    loop_rtols = [1e-4] if (smoke or quick) else [1e-3, 1e-5, 1e-7]
    rows = []
    for method in ["Radau", "LSODA", "DOP853"]:
        for rtol in loop_rtols:
            dt, (nfev, njev, nlu), (l2, pk) = run_loop(ring, p, ref, method, rtol)
            rows.append((f"scipy-{method}-loop", rtol, dt, nfev, njev, nlu, l2, pk))
            print(f"  scipy {method:<6} rtol {rtol:.0e} coupling loop: {dt * 1e3:9.2f} ms  err L2 {l2:.2e}"
                  f"  nfev {nfev}", flush=True)
    write(f"{dirname}/{CASE}-scipy-loop.csv", rows)


def write(path, rows):
    with open(path, "w") as f:
        f.write("method,rtol,median_s,nfev,njev,nlu,err_l2,err_peak\n")
        for r in rows:
            f.write("%s,%g,%.6e,%d,%d,%d,%.4e,%.4e\n" % r)


if __name__ == "__main__":
    main()
