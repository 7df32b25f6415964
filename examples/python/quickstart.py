"""The shortest use of the raceway FMU from fmpy (docs/fmi.md, "Shortest use")."""

import numpy as np
from fmpy import simulate_fmu

# shaft motion: 20 µm downward, turning at 1750 rpm
t = np.linspace(0.0, 0.01, 11)
motion = np.array(
    [(ti, -20e-6, 0.0, 183.26) for ti in t],
    dtype=[("time", float), ("shaft.y", float), ("shaft.vy", float), ("shaft.omega", float)],
)
result = simulate_fmu(
    "target/fmu/raceway-fmi2.fmu",
    stop_time=0.01,
    output_interval=1e-3,
    input=motion,
    output=["force.x", "force.y", "K.y.y"],
)
print(result["force.y"][-1], "N")
