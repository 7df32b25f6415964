"""Exudyn peer of the speed page (issue #36): a deep-groove ball bearing built like Exudyn's
ball-bearing test model, with Exudyn's own bearing builders (`exudyn.machines`), and run
at Exudyn's fixed step and at a refined step.

The model (the test model's data, set up here in our own code):
- a 6010-size bearing: outside diameter 80 mm, bore 50 mm, width 16 mm, 14 balls of
  8.73 mm on a 65 mm pitch diameter, groove radii 1.25 x the ball radius (f = 0.625);
- 6-DOF rigid steel balls (7800 kg/m3), each on the rings through Exudyn's sphere-torus
  contact (linear stiffness 5e6 N/m, damping 50 N s/m, friction 0.2, proportional zone
  0.01 m/s), the balls made 1 % larger than the grooves' zero-clearance size (preload);
- the cage a rigid body tied to each ball by a Cartesian spring-damper (1e5 N/m, 100 N s/m);
- the outer ring fixed, the inner ring a rigid shaft (50 mm x 120 mm steel cylinder)
  turning at a held speed, loaded by 200 N along the axis and its weight (gravity on
  every body);
- generalized-alpha with modified Newton (tolerances 1e-8 absolute, 1e-6 relative), a
  sparse linear solver, one thread, a fixed step (Exudyn's: 1e-4 s).

Two changes from the test model, both to give Exudyn its best case: the axial load is
constant (the test model's user function ramps it through Python each step) and its
small ramped tilting torque is left out (Python callbacks cost Exudyn time raceway does
not pay); the balls and cage start at their kinematic speeds (the test model starts
them at rest with the shaft turning, which is a start-up transient, not the steady run).

Output: one CSV line per run on stdout after a header,
`rpm,step_s,t_end_s,cpu_s,steps,err_l2`, where `cpu_s` is the process CPU time of
`SolveDynamic` (time.process_time) and `err_l2` the relative L2 error of the inner ring's
bearing force (sum of the 14 inner contacts' forces, x, y, z) at every 0.1 ms point against
the run at step/`--refine` (its own refined run); the reference line has an empty error.
Run through `scripts/peer-exudyn` (which installs exudyn into target/venv).
Usage: exudyn_bearing.py [--rpm 3000,30000] [--t-end 0.05] [--refine 10] [--repeats 3]
"""

import argparse
import math
import sys
import time

import numpy as np

import exudyn as exu
from exudyn.utilities import (
    InertiaCylinder,
    MarkerBodyRigid,
    SensorObject,
)
from exudyn.machines import CreateBallBearing, GetBallBearingData

OUTSIDE_D = 0.080
BORE_D = 0.050
WIDTH = 0.016
N_BALLS = 14
BALL_R = 0.00873 / 2
PITCH_R = 0.0325
GROOVE_R = 1.25 * BALL_R
DENSITY = 7800.0
SHAFT_LENGTH = 0.120
AXIAL_LOAD = 200.0
G = 9.81
OUTPUT_STEP = 1e-4


def kinematic_speeds(omega):
    """Cage and ball angular speeds (about the axis) of rolling without slip, contact angle 0,
    outer ring fixed: cage = omega/2 (1 - D/dm); ball spin relative to the cage
    -(dm/D) (1 - (D/dm)^2) omega/2, added to the cage's rotation for the absolute speed."""
    d, dm = 2 * BALL_R, 2 * PITCH_R
    cage = 0.5 * omega * (1 - d / dm)
    spin = -0.5 * omega * (dm / d) * (1 - (d / dm) ** 2)
    return cage, cage + spin


def build(rpm):
    """The model at shaft speed `rpm`; returns (SystemContainer, mbs, force sensors)."""
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    axis = [0, 0, 1]
    data = GetBallBearingData(
        axis,
        OUTSIDE_D,
        BORE_D,
        WIDTH,
        N_BALLS,
        radiusBalls=BALL_R,
        ballsAngleOffset=0,
        radiusCage=PITCH_R,
        innerGrooveRadius=GROOVE_R,
        outerGrooveRadius=GROOVE_R,
        innerEdgeChamfer=0.001,
        outerEdgeChamfer=0.001,
        innerRingShoulderRadius=0.029875,
        outerRingShoulderRadius=0.035125,
    )
    omega = rpm * math.pi / 30
    gravity = [0, -G, 0]
    ground = mbs.CreateGround()
    m_outer = mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localPosition=[0, 0, 0]))
    shaft = mbs.CreateRigidBody(
        referencePosition=[0, 0, 0],
        nodeType=exu.NodeType.RotationRxyz,
        inertia=InertiaCylinder(DENSITY, SHAFT_LENGTH, 0.5 * BORE_D, axis=2),
        initialAngularVelocity=[0, 0, omega],
        gravity=gravity,
    )
    # The shaft's speed held (a velocity-level constraint on its rotation about z).
    mbs.CreateCoordinateConstraint(
        bodyNumbers=[shaft, None],
        coordinates=[5, None],
        velocityLevel=True,
        offset=omega,
        show=False,
    )
    m_inner = mbs.AddMarker(MarkerBodyRigid(bodyNumber=shaft, localPosition=[0, 0, 0]))
    data["radiusBalls"] *= 1.01
    cage_w, ball_w = kinematic_speeds(omega)
    items = CreateBallBearing(
        mbs,
        data,
        m_inner,
        m_outer,
        DENSITY,
        DENSITY,
        cageInitialAngularVelocity=[0, 0, cage_w],
        ballsInitialAngularVelocity=[0, 0, ball_w],
        gravity=gravity,
        springStiffnessCage=1e5,
        springDampingCage=1e2,
        contactParametersRingBalls={
            "contactStiffness": 5e6,
            "contactDamping": 50,
            "dynamicFriction": 0.2,
            "contactStiffnessExponent": 1,
            "frictionProportionalZone": 1e-2,
        },
    )
    mbs.CreateForce(bodyNumber=shaft, localPosition=[0, 0, 0], loadVector=[0, 0, -AXIAL_LOAD])
    sensors = [
        mbs.AddSensor(
            SensorObject(
                objectNumber=o,
                storeInternal=True,
                outputVariableType=exu.OutputVariableType.Force,
            )
        )
        for o in items["innerRingBallContacts"]
    ]
    mbs.Assemble()
    return sc, mbs, sensors


def settings(step, t_end):
    s = exu.SimulationSettings()
    s.solutionSettings.writeSolutionToFile = False
    s.solutionSettings.sensorsWritePeriod = OUTPUT_STEP
    s.timeIntegration.numberOfSteps = int(round(t_end / step))
    s.timeIntegration.endTime = t_end
    s.timeIntegration.newton.absoluteTolerance = 1e-8
    s.timeIntegration.newton.relativeTolerance = 1e-6
    s.timeIntegration.newton.useModifiedNewton = True
    s.timeIntegration.verboseMode = 0
    s.displayStatistics = False
    s.displayComputationTime = False
    s.linearSolverType = exu.LinearSolverType.EigenSparse
    s.parallel.numberOfThreads = 1
    return s


def run(rpm, step, t_end):
    """One run: (process CPU s of the solve, force samples [n, 4] as t, Fx, Fy, Fz)."""
    sc, mbs, sensors = build(rpm)
    s = settings(step, t_end)
    c0 = time.process_time()
    ok = mbs.SolveDynamic(s)
    cpu = time.process_time() - c0
    if ok is False:
        raise RuntimeError(f"SolveDynamic failed at {rpm} rpm, step {step}")
    total = None
    for k in sensors:
        v = np.asarray(mbs.GetSensorStoredData(k))
        total = v.copy() if total is None else total + np.c_[np.zeros(len(v)), v[:, 1:]]
    return cpu, total


def force_error(run_f, ref_f):
    """Relative L2 error of (Fx, Fy, Fz) over the common output times (t > 0)."""
    ti = np.rint(run_f[:, 0] / OUTPUT_STEP).astype(int)
    tr = np.rint(ref_f[:, 0] / OUTPUT_STEP).astype(int)
    common, ia, ib = np.intersect1d(ti, tr, return_indices=True)
    keep = common > 0
    a, b = run_f[ia[keep], 1:], ref_f[ib[keep], 1:]
    return float(np.sqrt(((a - b) ** 2).sum() / (b**2).sum()))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--rpm", default="3000,30000")
    p.add_argument("--t-end", type=float, default=0.05)
    p.add_argument("--step", type=float, default=1e-4)
    p.add_argument("--refine", type=int, default=10)
    p.add_argument("--repeats", type=int, default=3)
    a = p.parse_args()
    print("rpm,step_s,t_end_s,cpu_s,steps,err_l2")
    for rpm in [float(x) for x in a.rpm.split(",")]:
        h_ref = a.step / a.refine
        cpu_ref, ref = run(rpm, h_ref, a.t_end)
        print(f"{rpm},{h_ref},{a.t_end},{cpu_ref},{round(a.t_end / h_ref)},", flush=True)
        cpus = []
        for _ in range(a.repeats):
            cpu, f = run(rpm, a.step, a.t_end)
            cpus.append(cpu)
        err = force_error(f, ref)
        cpu = sorted(cpus)[len(cpus) // 2]
        print(f"{rpm},{a.step},{a.t_end},{cpu},{round(a.t_end / a.step)},{err}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
