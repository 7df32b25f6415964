"""The shortest use of the raceway FMU from fmpy (docs/fmi.md, "Shortest use")."""

import numpy as np
from fmpy import read_model_description, simulate_fmu

fmu = "target/fmu/raceway-fmi2.fmu"
inputs = [v.name for v in read_model_description(fmu).modelVariables if v.causality == "input"]

# shaft motion: 20 µm downward, turning at 1750 rpm (every input in the table, others 0)
motion = np.zeros(11, dtype=[("time", float)] + [(name, float) for name in inputs])
motion["time"] = np.linspace(0.0, 0.01, 11)
motion["shaft.y"] = -20e-6
motion["shaft.omega"] = 183.26
result = simulate_fmu(
    fmu,
    stop_time=0.01,
    output_interval=1e-3,
    input=motion,
    output=["force.x", "force.y", "K.y.y"],
)
print(result["force.y"][-1], "N")
