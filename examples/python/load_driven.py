"""The load-driven raceway FMU from fmpy (docs/fmi.md, "Load-driven FMU"): 1 kN hung on the
inner ring of a 6205 with 10 µm clearance, released from rest; the FMU moves the ring (its
mass plus 1 kg) on its balls and returns where it comes to rest."""

import sys

from fmpy import simulate_fmu

fmu = sys.argv[1] if len(sys.argv) > 1 else "target/fmu/raceway-load-fmi2.fmu"
scene = """
bearing = { preset = "6205", clearance_um = 10.0 }
[model]
level = "quasi_static"
start = "rest"            # released at the centre ("equilibrium": starts at rest on its balls)
attached_mass_kg = 1.0
contact_damping = 3000.0  # N s/m per loaded ball
"""
result = simulate_fmu(
    fmu,
    stop_time=0.03,
    output_interval=1e-3,
    start_values={"scene": scene, "load.y": -1000.0, "shaft.omega": 0.0},
    output=["shaft.y", "force.y", "K.y.y", "balls.loaded"],
)
last = result[-1]
print(f"sag {last['shaft.y'] * 1e6:.4f} µm, bearing force {last['force.y']:.3f} N, "
      f"K.y.y {last['K.y.y'] * 1e-6:.1f} N/µm, {last['balls.loaded']} balls loaded")
