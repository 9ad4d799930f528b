"""Plants, laws, references, disturbances and sensors, with their units (docs/guide/models.md)."""

import numpy as np

import landing
from landing import controllers, disturbances, gravity, plants, reference, sensors

# Each class declares its parameters as the core reads them: shape, unit, rule.
q1 = controllers.FixedTimeMSS.parameters["q1"]
print(f"FixedTimeMSS q1: {q1.shape}, unit {q1.unit!r}, rule {q1.rule!r}: {q1.doc}")

# An asteroid landing (the small-body plant in 433 Eros's rotating frame, a second-degree
# harmonic field), the fuzzy variable-rate reaching law tracking a cubic to the surface, and a
# command noise of 1 %.
plant = plants.SmallBody(gravity=gravity.Harmonic2(), omega=1.65e-4)
law = controllers.FuzzyVariableRate(c1=0.017**2, c2=0.034, k=0.1, ke=3.162e4, kec=10, ku=2.813e-4)
ref = reference.Cubic.from_boundary([550, 500, 8200], [-1.7, 0.7, -1.5], [20, 80, 2000], [0, 0, 0], 4000)
res = landing.simulate(plant, law, [600, 550, 8250, -1.7, 0.7, -1.5], t_final=4000.0, dt=0.1, reference=ref,
                       disturbance=disturbances.CommandNoise(0.01), seed=3)
print(f"asteroid: tracking within 1 m from {res.metrics['settle_time']:.1f} s, "
      f"final error {np.linalg.norm(res.metrics['final_error']):.2e} m")

# The Mars lander as a real engine: a thrust magnitude limit (N), a minimum throttle, a pointing
# cone about +z (rad), a lag (s) and a delay (control periods), a noisy sensor and a filter; the
# case ends at touchdown.
lander = plants.MarsLander(thrust_magnitude_limit=22e3, min_throttle=0.2, pointing_limit=np.radians(60),
                           engine_time_constant=0.1, control_delay=2,
                           sensor=sensors.Noise(std=[1, 1, 0.5, 0.1, 0.1, 0.05]),
                           filter=sensors.KalmanFilter(process_noise=0.1))
guidance = landing.scenarios.preset("mars_realistic").controller
mars_ref = landing.scenarios.preset("mars_realistic").reference
run = landing.simulate(lander, guidance, [-2000, 1000, 1500, 100, -15, -75, 1905], t_final=60.0, dt=0.01,
                       reference=mars_ref, stop_at="touchdown", seed=1)
m = run.metrics
print(f"Mars, realistic loop: touchdown at {m['touchdown_time']:.2f} s, {m['touchdown_speed']:.3f} m/s, "
      f"{np.linalg.norm(m['touchdown_position'][:2]):.2f} m from the target, "
      f"peak |F| {m['peak_command'] / 1e3:.2f} kN (limit 22 kN)")
print(f"  the law read the position with {m['navigation_position_rms']:.3f} m rms error")

# The tethered satellite (angles in rad, torques in N m): the flexible model's state holds the
# tether's nodes.
tether = plants.TetheredSatellite(fidelity="flexible", nodes=8)
x0 = tether.initial_state(phi=np.radians(1), theta=np.radians(1))
swing = landing.simulate(tether, controllers.FixedTimeNTSMC(), x0, t_final=100.0, dt=0.01,
                         substeps=tether.substeps_for(0.01))
angles, rates = tether.coordinates(swing.states)
print(f"tether: state of {x0.size} components; |phi|, |theta| at 100 s: "
      f"{np.degrees(abs(angles[-1, 0])):.1e}, {np.degrees(abs(angles[-1, 1])):.1e} degrees")
