"""A second, independent FMI 2 host: libcosim (OSP, C++, FMI Library) through libcosimpy.
Two instances of the bearing FMU with different shaft displacements are stepped by
libcosim's fixed-step algorithm; each force equals what fmpy gets for the same motion."""

import numpy as np
import pytest

from conftest import Host, fmu_path

libcosim = pytest.importorskip("libcosimpy")

from libcosimpy.CosimEnums import CosimErrorCode, CosimExecutionState  # noqa: E402
from libcosimpy.CosimExecution import CosimExecution  # noqa: E402
from libcosimpy.CosimLogging import CosimLogLevel, log_output_level  # noqa: E402
from libcosimpy.CosimObserver import CosimObserver  # noqa: E402
from libcosimpy.CosimSlave import CosimLocalSlave  # noqa: E402

H = 1e-4
N = 100
CASES = {"A": {"shaft.y": -20e-6, "shaft.omega": 183.26},
         "B": {"shaft.y": -10e-6, "shaft.x": 3e-6, "shaft.omega": 100.0}}
OUT = ["force.x", "force.y", "K.y.y", "torque.z"]


def fmpy_reference(unzipped, inputs):
    h = Host("fmi2", unzipped["fmi2"]).instantiate().init(start_values=inputs)
    t = 0.0
    for _ in range(N):
        h.step(t, H)
        t += H
    values = h.get(OUT)
    h.free()
    return np.array(values)


def test_libcosim_steps_two_instances_like_fmpy(unzipped):
    log_output_level(CosimLogLevel.ERROR)
    ex = CosimExecution.from_step_size(step_size=int(round(H * 1e9)))  # ns
    obs = CosimObserver.create_last_value()
    ex.add_observer(obs)
    idx = {}
    for name in CASES:
        idx[name] = ex.add_local_slave(CosimLocalSlave(fmu_path=str(fmu_path("fmi2")),
                                                       instance_name=name))
        assert idx[name] >= 0
    refs = {v.name.decode(): v.reference for v in ex.slave_variables(idx["A"])}
    for name, inputs in CASES.items():
        for var, value in inputs.items():
            assert ex.real_initial_value(idx[name], refs[var], value)
    assert ex.simulate_until(target_time=int(round(N * H * 1e9)))
    st = ex.status()
    assert st.error_code == CosimErrorCode.SUCCESS.value
    assert st.current_time == int(round(N * H * 1e9))
    assert st.state != CosimExecutionState.ERROR.value
    got = {n: np.array(obs.last_real_values(idx[n], [refs[o] for o in OUT])) for n in CASES}
    for name, inputs in CASES.items():
        ref = fmpy_reference(unzipped, inputs)
        assert np.all(np.isfinite(got[name]))
        assert np.allclose(got[name], ref, rtol=1e-9, atol=1e-12), (name, got[name], ref)
    # the two instances are independent
    assert not np.allclose(got["A"], got["B"])
