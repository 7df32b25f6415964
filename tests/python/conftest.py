"""Fixtures for the FMU tests: the built archives, extracted once, and small host helpers
that capture the FMU's log messages (fmpy's own slaves, with our logger callbacks)."""

import os
import pathlib
import shutil
import zipfile
from ctypes import byref

import pytest
from fmpy import read_model_description
from fmpy.fmi2 import FMU2Slave, fmi2CallbackFunctions, fmi2CallbackLoggerTYPE
from fmpy.fmi3 import FMU3Slave
from fmpy.logging import addLoggerProxy

ROOT = pathlib.Path(__file__).resolve().parents[2]
FMU_DIR = pathlib.Path(
    os.environ.get("RACEWAY_FMU_DIR", ROOT / os.environ.get("CARGO_TARGET_DIR", "target") / "fmu")
)
VERSIONS = ("fmi2", "fmi3")
# the load-driven FMUs (loads in, ring motion out): same binary, own model descriptions
LOAD_VERSIONS = ("load-fmi2", "load-fmi3")


def fmu_path(version):
    """The archive of `version`: fmi2, fmi3 (motion-driven), load-fmi2, load-fmi3."""
    p = FMU_DIR / f"raceway-{version}.fmu"
    if not p.exists():
        pytest.fail(f"{p} is missing: run scripts/build-fmu first")
    return p


@pytest.fixture(scope="session")
def unzipped(tmp_path_factory):
    """{version: directory} of the extracted archives."""
    out = {}
    for v in VERSIONS + LOAD_VERSIONS:
        d = tmp_path_factory.mktemp(f"raceway-{v}")
        with zipfile.ZipFile(fmu_path(v)) as z:
            z.extractall(d)
        out[v] = d
    return out


class Host:
    """One FMU instance driven through fmpy's FMU2Slave / FMU3Slave, logging captured.

    Calls that fail raise fmpy's FMICallException (status > Warning); `self.logs` holds
    (status, message) of every message the FMU sent."""

    def __init__(self, version, unzipdir, guid=None, name="bearing", logging_on=False):
        # "fmi2" / "fmi3" for the FMI calls, whatever the variant
        self.version = version[-4:]
        self.variant = version
        self.md = read_model_description(str(unzipdir))
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.types = {v.name: v.type for v in self.md.modelVariables}
        self.items = {v.name: {i.name: int(i.value) for i in v.declaredType.items}
                      for v in self.md.modelVariables if v.type == "Enumeration"}
        self.logs = []
        token = guid if guid is not None else self.md.guid
        cls = FMU2Slave if self.version == "fmi2" else FMU3Slave
        self.fmu = cls(
            guid=token,
            unzipDirectory=str(unzipdir),
            modelIdentifier=self.md.coSimulation.modelIdentifier,
            instanceName=name,
        )
        self.logging_on = logging_on
        self.freed = False

    # logging ---------------------------------------------------------------------------
    def _log2(self, env, name, status, category, message):
        self.logs.append((status, message.decode("utf-8")))

    def _log3(self, env, status, category, message):
        self.logs.append((status, message.decode("utf-8")))

    def log_text(self):
        return "\n".join(m for _, m in self.logs)

    # life cycle ------------------------------------------------------------------------
    def instantiate(self, event_mode=False):
        if self.version == "fmi2":
            cb = fmi2CallbackFunctions()
            cb.logger = fmi2CallbackLoggerTYPE(self._log2)
            addLoggerProxy(byref(cb))
            self._callbacks = cb
            self.fmu.instantiate(callbacks=cb, loggingOn=self.logging_on)
        else:
            self.fmu.instantiate(
                loggingOn=self.logging_on, eventModeUsed=event_mode, logMessage=self._log3
            )
        return self

    def init(self, start_values=None, start_time=0.0, stop_time=None, tolerance=None):
        """Instantiate-state parameters/inputs, then initialise."""
        for name, value in (start_values or {}).items():
            self.set(name, value)
        if self.version == "fmi2":
            self.fmu.setupExperiment(tolerance=tolerance, startTime=start_time, stopTime=stop_time)
            self.fmu.enterInitializationMode()
            self.fmu.exitInitializationMode()
        else:
            self.fmu.enterInitializationMode(
                tolerance=tolerance, startTime=start_time, stopTime=stop_time
            )
            self.fmu.exitInitializationMode()
        return self

    def free(self):
        self.freed = True
        self.fmu.freeInstance()

    # values ----------------------------------------------------------------------------
    def set(self, name, value):
        """Set by the variable's type; an Enumeration takes its item's name or number."""
        vr = [self.vr[name]]
        ty = self.types[name]
        fmi2 = self.version == "fmi2"
        if ty == "String":
            self.fmu.setString(vr, [value])
        elif ty == "Enumeration":
            k = self.items[name][value] if isinstance(value, str) else int(value)
            self.fmu.setInteger(vr, [k]) if fmi2 else self.fmu.setInt64(vr, [k])
        elif ty == "Boolean":
            self.fmu.setBoolean(vr, [bool(value)])
        elif ty in ("Integer", "Int32"):
            self.fmu.setInteger(vr, [int(value)]) if fmi2 else self.fmu.setInt32(vr, [int(value)])
        elif fmi2:
            self.fmu.setReal(vr, [value])
        else:
            self.fmu.setFloat64(vr, [value])

    def set_many(self, values):
        for k, v in values.items():
            self.set(k, v)

    def get(self, names):
        """Values of `names` (Real/Float64 and Integer/Int32 variables), in their order."""
        fmi2 = self.version == "fmi2"
        ints = [n for n in names if self.types[n] in ("Integer", "Int32")]
        reals = [n for n in names if n not in ints]
        got = {}
        if reals:
            vrs = [self.vr[n] for n in reals]
            got.update(zip(reals, self.fmu.getReal(vrs) if fmi2 else self.fmu.getFloat64(vrs)))
        if ints:
            vrs = [self.vr[n] for n in ints]
            got.update(zip(ints, self.fmu.getInteger(vrs) if fmi2 else self.fmu.getInt32(vrs)))
        return [got[n] for n in names]

    def get_item(self, name):
        """The item name an Enumeration parameter holds."""
        vr = [self.vr[name]]
        k = (self.fmu.getInteger(vr) if self.version == "fmi2" else self.fmu.getInt64(vr))[0]
        return next(n for n, v in self.items[name].items() if v == k)

    def get_boolean(self, name):
        return bool(self.fmu.getBoolean([self.vr[name]])[0])

    def time(self):
        if self.version == "fmi2":
            return self.fmu.getRealStatus(2)  # fmi2LastSuccessfulTime
        return self.fmu.getFloat64([0])[0]

    def get_string(self, name):
        v = self.fmu.getString([self.vr[name]])[0]
        return v.decode("utf-8") if isinstance(v, bytes) else v

    def step(self, t, h):
        r = self.fmu.doStep(t, h)
        return r

    def get_state(self):
        return self.fmu.getFMUState()

    def set_state(self, s):
        self.fmu.setFMUState(s)

    def free_state(self, s):
        self.fmu.freeFMUState(s)

    def serialize(self, s):
        return self.fmu.serializeFMUState(s)

    def deserialize(self, b):
        return self.fmu.deserializeFMUState(b)

    def directional_derivative(self, unknowns, knowns, seed):
        return self.fmu.getDirectionalDerivative(
            [self.vr[u] for u in unknowns], [self.vr[k] for k in knowns], list(seed)
        )


@pytest.fixture
def host(unzipped):
    """Factory: host(version, **kw) -> an instantiated Host; all are freed at teardown."""
    made = []

    def make(version, instantiate=True, **kw):
        h = Host(version, unzipped[version], **kw)
        if instantiate:
            h.instantiate()
        made.append(h)
        return h

    yield make
    for h in made:
        if h.fmu.component and not h.freed:
            try:
                h.free()
            except Exception:
                pass


def copy_fmu_dir(src, dst):
    shutil.copytree(src, dst)
    return dst


@pytest.fixture(scope="session")
def cli_first_rows(tmp_path_factory):
    """(force.x, force.y) of the default scene's first two rows of `raceway run` (t = 0 and
    t = 1e-4 s); the program is RACEWAY_BIN, else target/debug or target/release."""
    import csv
    import subprocess

    target = ROOT / os.environ.get("CARGO_TARGET_DIR", "target")
    candidates = [os.environ.get("RACEWAY_BIN")] + [
        str(target / p / "raceway") for p in ("debug", "release")
    ]
    exe = next((c for c in candidates if c and os.path.exists(c)), None)
    if exe is None:
        pytest.fail("no raceway binary: run `cargo build` or set RACEWAY_BIN")
    out = tmp_path_factory.mktemp("first-rows")
    subprocess.run([exe, "run", "-q", "--duration", "0.0002", "--out", str(out)], check=True)
    with open(out / "series.csv") as f:
        rows = list(csv.DictReader(f))
    assert [float(r["t [s]"]) for r in rows[:2]] == [0.0, 1e-4]
    return [(float(r["force.x [N]"]), float(r["force.y [N]"])) for r in rows[:2]]
