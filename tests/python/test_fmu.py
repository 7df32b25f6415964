"""The raceway FMUs in fmpy: validation, archive, symbols, simulation, FMU state, directional
derivatives, the state machine, the GUID check, instantiate/free cycles, error messages.

Everything asserted here must stay true whatever the bearing physics is (round trips,
identical continuation, derivatives against finite differences, refusals)."""

import json
import math
import re
import subprocess
import sys
import zipfile

import numpy as np
import pytest
from fmpy import simulate_fmu
from fmpy.fmi1 import FMICallException
from fmpy.validation import validate_fmu

from conftest import FMU_DIR, ROOT, VERSIONS, Host, copy_fmu_dir, fmu_path

INPUTS = [
    "shaft.x", "shaft.y", "shaft.z", "shaft.rx", "shaft.ry",
    "shaft.vx", "shaft.vy", "shaft.vz", "shaft.wx", "shaft.wy", "shaft.omega",
]
LOADS = ["force.x", "force.y", "force.z", "moment.x", "moment.y", "torque.z"]
MOTION = {"shaft.x": 4e-6, "shaft.y": -20e-6, "shaft.vy": 1e-4, "shaft.omega": 183.26}
H = 1e-4

FMI2_FUNCTIONS = """fmi2GetTypesPlatform fmi2GetVersion fmi2SetDebugLogging fmi2Instantiate
fmi2FreeInstance fmi2SetupExperiment fmi2EnterInitializationMode fmi2ExitInitializationMode
fmi2Terminate fmi2Reset fmi2GetReal fmi2GetInteger fmi2GetBoolean fmi2GetString fmi2SetReal
fmi2SetInteger fmi2SetBoolean fmi2SetString fmi2GetFMUstate fmi2SetFMUstate fmi2FreeFMUstate
fmi2SerializedFMUstateSize fmi2SerializeFMUstate fmi2DeSerializeFMUstate
fmi2GetDirectionalDerivative fmi2SetRealInputDerivatives fmi2GetRealOutputDerivatives
fmi2DoStep fmi2CancelStep fmi2GetStatus fmi2GetRealStatus fmi2GetIntegerStatus
fmi2GetBooleanStatus fmi2GetStringStatus""".split()

FMI3_FUNCTIONS = """fmi3GetVersion fmi3SetDebugLogging fmi3InstantiateModelExchange
fmi3InstantiateCoSimulation fmi3InstantiateScheduledExecution fmi3FreeInstance
fmi3EnterInitializationMode fmi3ExitInitializationMode fmi3EnterEventMode fmi3Terminate
fmi3Reset fmi3GetFloat32 fmi3GetFloat64 fmi3GetInt8 fmi3GetUInt8 fmi3GetInt16 fmi3GetUInt16
fmi3GetInt32 fmi3GetUInt32 fmi3GetInt64 fmi3GetUInt64 fmi3GetBoolean fmi3GetString
fmi3GetBinary fmi3GetClock fmi3SetFloat32 fmi3SetFloat64 fmi3SetInt8 fmi3SetUInt8
fmi3SetInt16 fmi3SetUInt16 fmi3SetInt32 fmi3SetUInt32 fmi3SetInt64 fmi3SetUInt64
fmi3SetBoolean fmi3SetString fmi3SetBinary fmi3SetClock fmi3GetNumberOfVariableDependencies
fmi3GetVariableDependencies fmi3GetFMUState fmi3SetFMUState fmi3FreeFMUState
fmi3SerializedFMUStateSize fmi3SerializeFMUState fmi3DeserializeFMUState
fmi3GetDirectionalDerivative fmi3GetAdjointDerivative fmi3EnterConfigurationMode
fmi3ExitConfigurationMode fmi3GetIntervalDecimal fmi3GetIntervalFraction
fmi3GetShiftDecimal fmi3GetShiftFraction fmi3SetIntervalDecimal fmi3SetIntervalFraction
fmi3SetShiftDecimal fmi3SetShiftFraction fmi3EvaluateDiscreteStates
fmi3UpdateDiscreteStates fmi3EnterContinuousTimeMode fmi3CompletedIntegratorStep
fmi3SetTime fmi3SetContinuousStates fmi3GetContinuousStateDerivatives
fmi3GetEventIndicators fmi3GetContinuousStates fmi3GetNominalsOfContinuousStates
fmi3GetNumberOfEventIndicators fmi3GetNumberOfContinuousStates fmi3EnterStepMode
fmi3GetOutputDerivatives fmi3DoStep fmi3ActivateModelPartition""".split()


def outputs_of(h):
    return [v.name for v in h.md.modelVariables if v.causality == "output"]


def run_steps(h, t, n, names, motion=MOTION, wiggle=True):
    """n steps of H from t with inputs that change every step; outputs after each step."""
    out = []
    for i in range(n):
        inputs = dict(motion)
        if wiggle:
            inputs["shaft.y"] = motion["shaft.y"] * (1.0 + 0.05 * math.sin(0.7 * i))
            inputs["shaft.x"] = motion["shaft.x"] * math.cos(0.3 * i)
        h.set_many(inputs)
        h.step(t, H)
        t += H
        out.append(h.get(names))
    return t, np.array(out)


# ---------------------------------------------------------------------------------------
# archive, model description, binary


@pytest.mark.parametrize("version", VERSIONS)
def test_fmpy_validation_finds_no_problem(version):
    assert validate_fmu(str(fmu_path(version))) == []


@pytest.mark.parametrize("version,platform", [("fmi2", "linux64"), ("fmi3", "x86_64-linux")])
def test_archive_layout(version, platform):
    with zipfile.ZipFile(fmu_path(version)) as z:
        names = sorted(z.namelist())
        assert names == ["binaries/%s/raceway.so" % platform, "documentation/index.html",
                         "documentation/licenses/LICENSE-APACHE",
                         "documentation/licenses/LICENSE-MIT",
                         "documentation/licenses/THIRD-PARTY-NOTICES.md",
                         "documentation/licenses/license.txt", "modelDescription.xml"]
        assert b"Apache License" in z.read("documentation/licenses/LICENSE-APACHE")
        assert b"Permission is hereby granted" in z.read("documentation/licenses/LICENSE-MIT")
        assert b"nalgebra" in z.read("documentation/licenses/THIRD-PARTY-NOTICES.md")
        for info in z.infolist():
            assert info.compress_type == zipfile.ZIP_DEFLATED
            assert "\\" not in info.filename and not info.filename.startswith(("/", "."))
        xml = z.read("modelDescription.xml").decode()
    assert 'modelIdentifier="raceway"' in xml
    for home in (str(ROOT), "/home/", "/root/"):
        assert home not in xml


def test_binary_carries_no_build_paths_and_stays_loaded(unzipped):
    import os

    so = unzipped["fmi2"] / "binaries/linux64/raceway.so"
    data = so.read_bytes()
    for path in (str(ROOT), os.path.expanduser("~/.cargo"), os.environ.get("CARGO_HOME", "")):
        if path:
            assert path.encode() not in data, path
    # -z nodelete: hosts dlclose the library in freeInstance (docs/physics.md §C4 #7)
    dyn = subprocess.run(["readelf", "-d", str(so)], check=True, capture_output=True,
                         text=True).stdout
    assert "NODELETE" in dyn


def test_one_guid_shared_by_both_descriptions_and_the_binary(unzipped):
    guids = []
    for v in VERSIONS:
        xml = (unzipped[v] / "modelDescription.xml").read_text()
        m = re.search(r'(?:guid|instantiationToken)="(\{[0-9a-f-]{36}\})"', xml)
        guids.append(m.group(1))
    assert guids[0] == guids[1]
    so = (unzipped["fmi2"] / "binaries/linux64/raceway.so").read_bytes()
    assert guids[0].encode() in so


@pytest.mark.parametrize("version,platform", [("fmi2", "linux64"), ("fmi3", "x86_64-linux")])
def test_exported_symbols_are_exactly_the_fmi_functions(unzipped, version, platform):
    so = unzipped[version] / "binaries" / platform / "raceway.so"
    out = subprocess.run(
        ["nm", "-D", "--defined-only", str(so)], check=True, capture_output=True, text=True
    ).stdout
    symbols = {line.split()[-1] for line in out.splitlines() if line.strip()}
    assert len(FMI2_FUNCTIONS) == 34 and len(FMI3_FUNCTIONS) == 75
    assert symbols == set(FMI2_FUNCTIONS) | set(FMI3_FUNCTIONS)


def test_variable_table_in_docs_is_up_to_date():
    table = (FMU_DIR / "variables.md").read_text()
    doc = (ROOT / "docs" / "fmi.md").read_text()
    begin = doc.index("<!-- BEGIN generated variable table")
    end = doc.index("<!-- END generated variable table -->")
    section = doc[begin:end]
    assert table.strip() in section, "docs/fmi.md is out of date: run scripts/build-fmu"
    assert section.count("\n| `") == table.count("\n| `")


def test_model_structure_declares_direct_feedthrough(unzipped):
    h = Host("fmi2", unzipped["fmi2"])
    inputs = {v for v in h.md.modelVariables if v.causality == "input"}
    assert {v.name for v in inputs} == set(INPUTS)
    outs = h.md.outputs
    assert {u.variable.name for u in outs} == set(outputs_of(h))
    for u in outs:
        assert set(u.dependencies) == inputs
    cs = h.md.coSimulation
    assert cs.canHandleVariableCommunicationStepSize and cs.canInterpolateInputs
    assert cs.canGetAndSetFMUstate and cs.canSerializeFMUstate
    assert cs.providesDirectionalDerivative and cs.maxOutputDerivativeOrder == 1


# ---------------------------------------------------------------------------------------
# simulation from a table of shaft motion


def motion_table(t_end=0.02, n=21, all_inputs=True):
    t = np.linspace(0.0, t_end, n)
    y = -20e-6 * (1.0 + 0.5 * np.sin(2 * np.pi * 50 * t))
    x = 5e-6 * np.cos(2 * np.pi * 50 * t)
    rows = []
    for i, ti in enumerate(t):
        j = min(i, n - 2)
        vy = (y[j + 1] - y[j]) / (t[j + 1] - t[j])
        vx = (x[j + 1] - x[j]) / (t[j + 1] - t[j])
        rows.append((ti, x[i], y[i], vx, vy, 183.26) + (0.0,) * 6)
    names = ["time", "shaft.x", "shaft.y", "shaft.vx", "shaft.vy", "shaft.omega", "shaft.z",
             "shaft.rx", "shaft.ry", "shaft.vz", "shaft.wx", "shaft.wy"]
    if not all_inputs:
        # fmpy 0.3.32 sets input derivatives through a buffer of exactly 9 values
        # (simulation.py, Input: `derivatives=(value_type * 9)()`, then `derivatives[:] = d`)
        rows, names = [r[:10] for r in rows], names[:10]
    return np.array(rows, dtype=[(nm, float) for nm in names])


@pytest.mark.parametrize("version,event_mode", [("fmi2", False), ("fmi3", False),
                                                ("fmi3", True)])
def test_simulate_a_stand_alone_bearing_from_a_motion_table(version, event_mode):
    table = motion_table()
    extra = {"use_event_mode": True} if event_mode else {}
    res = simulate_fmu(
        str(fmu_path(version)), stop_time=0.02, output_interval=5e-4, input=table,
        output=["shaft.y", "force.x", "force.y", "K.y.y"], **extra,
    )
    assert res["time"][-1] == pytest.approx(0.02)
    for name in ("force.x", "force.y", "K.y.y"):
        assert np.all(np.isfinite(res[name])), name
    # the fmpy input table reaches the component (recorded after the step it was set for)
    expected = np.interp(res["time"][:-1], table["time"], table["shaft.y"])
    assert np.allclose(res["shaft.y"][1:], expected, rtol=1e-12, atol=0)
    # a bearing pushes back: force opposite to a displacement beyond the clearance
    late = res["time"] > 1e-3
    assert np.all(res["force.y"][late] * res["shaft.y"][late] <= 0.0)
    assert np.max(np.abs(res["force.y"][late])) > 0.0


def test_simulate_fmi2_with_input_derivatives_matches_velocity_extrapolation():
    """fmpy's set_input_derivatives feeds fmi2SetRealInputDerivatives (canInterpolateInputs);
    with input_rule = derivatives the inputs move along the table's slope inside each step,
    close to the velocity-rule run (the table's velocities are the same slopes, fmpy takes
    the slope of the interval before a breakpoint) and far from holding the inputs."""
    table = motion_table(all_inputs=False)
    common = dict(stop_time=0.02, output_interval=5e-4, input=table,
                  output=["force.x", "force.y"])
    # input_rule is an Enumeration: 1 hold, 2 velocity, 3 derivatives
    a = simulate_fmu(str(fmu_path("fmi2")), start_values={"input_rule": 2}, **common)
    b = simulate_fmu(str(fmu_path("fmi2")), start_values={"input_rule": 3},
                     set_input_derivatives=True, **common)
    c = simulate_fmu(str(fmu_path("fmi2")), start_values={"input_rule": 1}, **common)
    for name in ("force.x", "force.y"):
        assert np.all(np.isfinite(b[name]))
        d_vel = np.sqrt(np.mean((a[name] - b[name]) ** 2))
        d_hold = np.sqrt(np.mean((a[name] - c[name]) ** 2))
        assert d_vel < 0.5 * d_hold, (name, d_vel, d_hold)


# ---------------------------------------------------------------------------------------
# FMU state


@pytest.mark.parametrize("version", VERSIONS)
def test_get_step_set_step_gives_identical_outputs(host, version):
    h = host(version).init(start_values=MOTION)
    names = outputs_of(h)
    t, _ = run_steps(h, 0.0, 3, names)
    s = h.get_state()
    t1, first = run_steps(h, t, 5, names)
    h.set_state(s)
    assert h.time() == t
    t2, again = run_steps(h, t, 5, names)
    assert t1 == t2
    assert np.array_equal(first, again)
    # the state object is not consumed: a second restore works as well
    h.set_state(s)
    _, third = run_steps(h, t, 5, names)
    assert np.array_equal(first, third)
    h.free_state(s)


RESTORE_SCRIPT = r"""
import json, sys
sys.path.insert(0, sys.argv[1])
from conftest import Host
from test_fmu import run_steps
version, unzipdir, state_file, t, n = sys.argv[2], sys.argv[3], sys.argv[4], float(sys.argv[5]), int(sys.argv[6])
h = Host(version, unzipdir).instantiate().init()
names = [v.name for v in h.md.modelVariables if v.causality == "output"]
s = h.deserialize(open(state_file, "rb").read())
h.set_state(s)
rtol = h.get(["rtol"])[0]
_, out = run_steps(h, t, n, names)
print(json.dumps({"rtol": rtol, "level": h.get_item("input_rule"), "out": out.tolist()}))
"""


@pytest.mark.parametrize("version", VERSIONS)
def test_serialised_state_continues_identically_in_another_process(host, unzipped, version, tmp_path):
    # non-default parameters: the other process must take them from the state
    h = host(version).init(start_values={**MOTION, "rtol": 1e-7, "input_rule": "hold"})
    names = outputs_of(h)
    t, _ = run_steps(h, 0.0, 4, names)
    s = h.get_state()
    blob = h.serialize(s)
    assert blob[:4] == b"RWFU"
    (tmp_path / "state.bin").write_bytes(blob)
    _, here = run_steps(h, t, 6, names)
    script = tmp_path / "restore.py"
    script.write_text(RESTORE_SCRIPT)
    proc = subprocess.run(
        [sys.executable, str(script), str(ROOT / "tests" / "python"), version,
         str(unzipped[version]), str(tmp_path / "state.bin"), repr(t), "6"],
        capture_output=True, text=True, check=True,
    )
    there = json.loads(proc.stdout.strip().splitlines()[-1])
    assert there["rtol"] == 1e-7 and there["level"] == "hold"
    assert np.array_equal(np.array(there["out"]), here)
    # a damaged state is refused with a message, not a crash
    with pytest.raises(FMICallException):
        h.deserialize(b"XXXX" + blob[4:])
    assert "bad magic" in h.log_text()


@pytest.mark.parametrize("version", VERSIONS)
def test_rollback_after_a_refused_step(host, version):
    """A failed DoStep leaves the component as it was; SetFMUstate brings the instance back
    and the run continues exactly as without the failure."""
    h = host(version).init(start_values=MOTION)
    names = outputs_of(h)
    t, _ = run_steps(h, 0.0, 2, names)
    s = h.get_state()
    _, ref = run_steps(h, t, 3, names)
    h.set_state(s)
    with pytest.raises(FMICallException):
        h.step(t + 1.0, H)  # a time jump: refused
    assert "must not jump" in h.log_text()
    h.set_state(s)
    _, after = run_steps(h, t, 3, names)
    assert np.array_equal(ref, after)


# ---------------------------------------------------------------------------------------
# derivatives

DELTA = {"shaft.x": 1e-8, "shaft.y": 1e-8, "shaft.z": 1e-8, "shaft.rx": 1e-7, "shaft.ry": 1e-7,
         "shaft.vx": 1e-4, "shaft.vy": 1e-4, "shaft.vz": 1e-4, "shaft.wx": 1e-3, "shaft.wy": 1e-3,
         "shaft.omega": 1e-2}


RADIAL = (["force.x", "force.y", "torque.z"],
          ["shaft.x", "shaft.y", "shaft.vx", "shaft.vy", "shaft.omega"])
FULL = (LOADS, INPUTS)


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("block", [
    pytest.param(RADIAL, id="radial"),
    pytest.param(FULL, id="full"),
])
def test_directional_derivatives_match_finite_differences_with_rollback(host, version, block):
    """J = d(loads)/d(inputs) from GetDirectionalDerivative against central differences of
    a short step taken from one saved state (inputs held over the step)."""
    LOADS, INPUTS = block
    h = host(version).init(start_values={**MOTION, "input_rule": "hold"})
    t, _ = run_steps(h, 0.0, 2, LOADS, wiggle=False)
    h_fd = 1e-7
    s = h.get_state()
    base = dict(MOTION)
    # the derivative at the inputs `base`, after a step with them
    h.set_many(base)
    h.step(t, h_fd)
    jac = np.array([h.directional_derivative(LOADS, [k], [1.0]) for k in INPUTS]).T
    # the whole matrix in one call equals the columns (linearity in the seed)
    seed = np.linspace(0.5, 1.5, len(INPUTS))
    assert np.allclose(h.directional_derivative(LOADS, INPUTS, seed), jac @ seed, rtol=1e-12,
                       atol=1e-9 * np.abs(jac).max())
    fd = np.zeros_like(jac)
    for j, k in enumerate(INPUTS):
        f = []
        for sign in (+1, -1):
            h.set_state(s)
            h.set_many({**base, k: base.get(k, 0.0) + sign * DELTA[k]})
            h.step(t, h_fd)
            f.append(np.array(h.get(LOADS)))
        fd[:, j] = (f[0] - f[1]) / (2 * DELTA[k])
    h.set_state(s)
    scale = np.abs(fd).max(axis=1, keepdims=True) + 1e-9
    bad = np.argwhere(np.abs(jac - fd) > 2e-3 * scale + 1e-6)
    assert bad.size == 0, [(LOADS[i], INPUTS[j], jac[i, j], fd[i, j]) for i, j in bad]
    assert np.abs(fd).max() > 0.0


@pytest.mark.parametrize("version", VERSIONS)
def test_directional_derivative_is_minus_the_k_and_c_outputs(host, version):
    h = host(version).init(start_values=MOTION)
    run_steps(h, 0.0, 2, LOADS)
    dofs = ["x", "y", "z", "rx", "ry"]
    rows = ["force.x", "force.y", "force.z", "moment.x", "moment.y"]
    disp = ["shaft.x", "shaft.y", "shaft.z", "shaft.rx", "shaft.ry"]
    vel = ["shaft.vx", "shaft.vy", "shaft.vz", "shaft.wx", "shaft.wy"]
    for i, r in enumerate(rows):
        k = h.get([f"K.{dofs[i]}.{d}" for d in dofs])
        c = h.get([f"C.{dofs[i]}.{d}" for d in dofs])
        for j in range(5):
            assert h.directional_derivative([r], [disp[j]], [1.0])[0] == pytest.approx(-k[j])
            assert h.directional_derivative([r], [vel[j]], [1.0])[0] == pytest.approx(-c[j])


@pytest.mark.parametrize("version", VERSIONS)
def test_output_derivatives_of_order_one_only(host, version):
    h = host(version).init(start_values=MOTION)
    run_steps(h, 0.0, 2, LOADS)
    vr = [h.vr[n] for n in LOADS]
    if version == "fmi2":
        d = h.fmu.getRealOutputDerivatives(vr, [1] * len(vr))
    else:
        d = h.fmu.getOutputDerivatives(vr, [1] * len(vr))
    assert np.all(np.isfinite(d))
    with pytest.raises(FMICallException):
        if version == "fmi2":
            h.fmu.getRealOutputDerivatives(vr[:1], [2])
        else:
            h.fmu.getOutputDerivatives(vr[:1], [2])
    assert "maxOutputDerivativeOrder is 1" in h.log_text()


# ---------------------------------------------------------------------------------------
# communication time


@pytest.mark.parametrize("version", VERSIONS)
def test_tiny_time_mismatch_warns_and_lands_on_t_plus_h(host, version):
    h = host(version).init(start_values=MOTION)
    t, _ = run_steps(h, 0.0, 3, LOADS)
    h.step(t + 1e-11, H)  # 1e-7 of the step: accepted with a warning
    assert any(st == 1 and "differs from the FMU's time" in m for st, m in h.logs)
    assert h.time() == pytest.approx(t + 1e-11 + H, rel=0, abs=1e-15)
    with pytest.raises(FMICallException):
        h.step(t + H + 1e-3 + 1e-11, H)  # a real jump


# ---------------------------------------------------------------------------------------
# state machine, GUID, errors


def expect_error(h, call, *words):
    with pytest.raises(FMICallException) as e:
        call()
    assert e.value.status == 3  # Error
    text = h.log_text()
    for w in words:
        assert w in text, (w, text)


ILLEGAL = {
    "step before initialisation": lambda h: h.step(0.0, H),
    "exit initialisation before entering it": lambda h: h.fmu.exitInitializationMode(),
    "terminate before initialisation": lambda h: h.fmu.terminate(),
    "read an output while instantiated (FMI 2) / in Instantiated (FMI 3)":
        lambda h: h.get(["force.x"]),
}


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("case", sorted(ILLEGAL))
def test_illegal_call_sequences_return_error(host, version, case):
    h = host(version)
    expect_error(h, lambda: ILLEGAL[case](h), "Illegal call sequence")
    # the instance can still be reset and used
    h.fmu.reset()
    h.init(start_values=MOTION)
    run_steps(h, 0.0, 2, LOADS)


@pytest.mark.parametrize("version", VERSIONS)
def test_more_refusals_after_initialisation(host, version):
    h = host(version).init(start_values=MOTION)
    run_steps(h, 0.0, 1, LOADS)
    s = h.get_state()
    expect_error(h, lambda: h.set("force.x", 1.0), "force.x", "cannot be set")
    h.set_state(s)
    expect_error(h, lambda: h.set("rtol", 1e-5), "rtol", "fixed")
    h.set_state(s)
    expect_error(h, lambda: h.step(H, 0.0), "h = 0")
    h.set_state(s)
    expect_error(h, lambda: h.directional_derivative(["shaft.x"], ["shaft.y"], [1.0]),
                 "not an output")
    h.set_state(s)
    if version == "fmi2":
        expect_error(h, lambda: h.fmu.fmi2CancelStep(h.fmu.component), "not supported")
        h.set_state(s)
        expect_error(h, lambda: h.fmu.setupExperiment(startTime=0.0), "Illegal call sequence")
    else:
        expect_error(h, lambda: h.fmu.enterEventMode(), "eventModeUsed = false")
        h.set_state(s)
        expect_error(h, lambda: h.fmu.fmi3SetTime(h.fmu.component, 0.0), "Model Exchange only")
    h.set_state(s)
    h.fmu.terminate()
    expect_error(h, lambda: h.step(H, H), "Illegal call sequence")


def test_fmi2_null_and_bad_pointers_are_errors_not_crashes(unzipped):
    import ctypes

    lib = ctypes.CDLL(str(unzipped["fmi2"] / "binaries/linux64/raceway.so"))
    lib.fmi2DoStep.argtypes = [ctypes.c_void_p, ctypes.c_double, ctypes.c_double, ctypes.c_int]
    assert lib.fmi2DoStep(None, 0.0, 1e-3, 1) == 3
    lib.fmi2FreeInstance.argtypes = [ctypes.c_void_p]
    lib.fmi2FreeInstance(None)  # ignored
    h = Host("fmi2", unzipped["fmi2"]).instantiate()
    h.init(start_values=MOTION)
    lib.fmi2GetReal.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_void_p]
    assert lib.fmi2GetReal(h.fmu.component, None, 3, None) == 3
    assert "is NULL" in h.log_text()
    h.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_wrong_guid_is_refused_with_a_log_message(host, version):
    h = host(version, instantiate=False, guid="{00000000-0000-0000-0000-000000000000}")
    with pytest.raises(Exception, match="instantiate"):
        h.instantiate()
    assert "wrong GUID" in h.log_text()
    h.freed = True


def test_fmi3_model_exchange_is_refused_with_a_log_message(unzipped):
    from fmpy.fmi3 import FMU3Model

    logs = []
    md = Host("fmi3", unzipped["fmi3"]).md
    m = FMU3Model(guid=md.guid, unzipDirectory=str(unzipped["fmi3"]), modelIdentifier="raceway")
    with pytest.raises(Exception):
        m.instantiate(logMessage=lambda env, status, cat, msg: logs.append(msg.decode()))
    assert any("co-simulation" in m for m in logs)


@pytest.mark.parametrize("version", VERSIONS)
def test_bad_values_give_an_error_naming_the_cause(host, version):
    cases = [
        # (what is set, words the log must contain)
        ({"shaft.x": float("nan")}, ["shaft.x", "NaN", "finite"]),
        ({"clearance": float("inf")}, ["clearance", "finite"]),
        ({"rtol": 5.0}, ["rtol", "5", "[1e-14, 0.1]"]),
        ({"scene": "this is [not a scene"}, ["parameter `scene`", "TOML"]),
        ({"bearing": "no-such-bearing"}, ["parameter `bearing`", "no-such-bearing", "6205"]),
        ({"level": 9}, ["parameter `level`", "9", "quasi_static"]),
        ({"input_rule": -1}, ["parameter `input_rule`", "-1", "velocity"]),
        ({"override_clearance": True, "clearance": 0.5}, ["clearance", "[-0.001, 0.001]"]),
        ({"scene": 'bearing = "6205"\n[model]\ncausality = "load"\n'}, ["motion-driven"]),
    ]
    for values, words in cases:
        h = host(version)
        with pytest.raises(FMICallException):
            h.init(start_values=values)
        text = h.log_text()
        for w in words:
            assert w in text, (values, w, text)
        h.free()
    # NaN during stepping, too
    h = host(version).init(start_values=MOTION)
    expect_error(h, lambda: h.set("shaft.omega", float("nan")), "shaft.omega", "NaN")


@pytest.mark.parametrize("version", VERSIONS)
def test_parameters_reach_the_component_and_read_back(host, version):
    h = host(version).init(start_values={**MOTION, "input_rule": "hold", "rtol": 1e-8,
                                         "bearing": "6205", "clearance": 12e-6,
                                         "override_clearance": True})
    assert h.get_item("input_rule") == "hold"
    assert h.get_item("level") == "scene"
    assert h.get_boolean("override_clearance")
    assert h.get_string("bearing") == "6205"
    assert h.get(["rtol", "clearance"]) == [1e-8, 12e-6]
    run_steps(h, 0.0, 2, LOADS)
    assert np.all(np.isfinite(h.get(LOADS)))


# ---------------------------------------------------------------------------------------
# resources


@pytest.mark.parametrize("version", VERSIONS)
def test_scene_from_resources_in_a_folder_needing_percent_encoding(unzipped, version, tmp_path):
    d = copy_fmu_dir(unzipped[version], tmp_path / "a folder with spaces %20 and ü" / "fmu")
    (d / "resources").mkdir()
    (d / "resources" / "scene.toml").write_text(
        'bearing = "6205"\n[inputs]\nspeed_rpm = 1000\ninitial = { "shaft.x" = 7e-6 }\n'
    )
    h = Host(version, d).instantiate().init()
    assert h.get(["shaft.x", "shaft.omega", "shaft.y"]) == [7e-6, 1000 * math.pi / 30, 0.0]
    h.free()
    # the scene parameter wins over the resource
    h = Host(version, d).instantiate().init(start_values={"scene": 'bearing = "6205"\n'})
    assert h.get(["shaft.x"]) == [0.0]
    h.free()
    # a broken resource scene is named
    (d / "resources" / "scene.toml").write_text("bearing = \n")
    h = Host(version, d).instantiate()
    with pytest.raises(FMICallException):
        h.init()
    assert "resources/scene.toml" in h.log_text()
    h.free()


# ---------------------------------------------------------------------------------------
# many instances


def rss_kib():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


@pytest.mark.parametrize("version", VERSIONS)
def test_ten_thousand_instantiate_free_cycles_do_not_leak(unzipped, version):
    import ctypes

    plat = "linux64" if version == "fmi2" else "x86_64-linux"
    lib = ctypes.CDLL(str(unzipped[version] / "binaries" / plat / "raceway.so"))
    h = Host(version, unzipped[version])
    guid = h.md.guid.encode()
    res = (unzipped[version] / "resources").as_uri().encode()
    if version == "fmi2":
        from fmpy.fmi2 import fmi2CallbackFunctions

        cb = fmi2CallbackFunctions()  # all NULL: allowed (canNotUseMemoryManagementFunctions)
        lib.fmi2Instantiate.restype = ctypes.c_void_p
        lib.fmi2Instantiate.argtypes = [ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p,
                                        ctypes.c_char_p, ctypes.c_void_p, ctypes.c_int,
                                        ctypes.c_int]
        lib.fmi2FreeInstance.argtypes = [ctypes.c_void_p]

        def make():
            return lib.fmi2Instantiate(b"i", 1, guid, res, ctypes.addressof(cb), 0, 0)

        free = lib.fmi2FreeInstance
    else:
        lib.fmi3InstantiateCoSimulation.restype = ctypes.c_void_p
        lib.fmi3InstantiateCoSimulation.argtypes = [
            ctypes.c_char_p, ctypes.c_char_p, ctypes.c_char_p, ctypes.c_bool, ctypes.c_bool,
            ctypes.c_bool, ctypes.c_bool, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_void_p,
            ctypes.c_void_p, ctypes.c_void_p]
        lib.fmi3FreeInstance.argtypes = [ctypes.c_void_p]

        def make():
            return lib.fmi3InstantiateCoSimulation(b"i", guid, None, False, False, False, False,
                                                   None, 0, None, None, None)

        free = lib.fmi3FreeInstance
    for _ in range(1000):
        free(make())
    before = rss_kib()
    for _ in range(9000):
        p = make()
        assert p
        free(p)
    assert rss_kib() - before < 4096
    # full life cycles (component built, stepped, state taken) with fmpy, too
    before = None
    for i in range(300):
        x = Host(version, unzipped[version]).instantiate().init(start_values=MOTION)
        x.step(0.0, H)
        s = x.get_state()
        x.free_state(s)
        x.free()
        if i == 100:
            before = rss_kib()
    assert rss_kib() - before < 4096


@pytest.mark.parametrize("version", VERSIONS)
def test_percent_signs_reach_the_logger_verbatim(host, version):
    """The FMI 2 logger is printf-like: the FMU must pass its message through "%s"."""
    h = host(version)
    with pytest.raises(FMICallException):
        h.init(start_values={"bearing": "x%s%d%n%%y"})
    assert "`x%s%d%n%%y`" in h.log_text()


@pytest.mark.parametrize("version", VERSIONS)
def test_a_bad_scene_is_logged_with_line_column_and_suggestions(host, version):
    """The log callback carries `raceway scene --check`'s problems: line:column, the field
    and the nearest known name, every problem at once."""
    h = host(version)
    with pytest.raises(FMICallException):
        h.init(start_values={"scene": 'bearing = "6205"\n[model]\nlevl = "ring"\n[solver]\nrtol = 0.5\n'})
    text = h.log_text()
    assert "2 problem(s)" in text, text
    assert "3:1: `model.levl`: unknown key `levl`; did you mean `level`?" in text, text
    assert "5:8: `solver.rtol`" in text, text
