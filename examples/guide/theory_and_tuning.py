"""The theory's bounds against simulation, and gains tuned by the engine (docs/guide/theory.md)."""

import landing
from landing import theory

# The fixed-time bound of a reaching law s' = -c1 sig^e1(s) - c2 sig^e2(s) (e1 < 1 < e2): the
# Mars paper's eq. 18 with its printed gains, and the same law simulated from three starts.
print(f"T <= {theory.fixed_time_bound(0.8, 0.95, 0.4, 1.05):.4f} s (the Mars paper prints 74.5780 s)")
check = theory.check_fixed_time_bound(0.9, 0.9, 0.5, 1.1, s0=[1.0, 1e3, 1e6])
print(check)

# A guidance law's bounds under a bounded disturbance (the paper's Theorem 4: the neighbourhoods
# its sliding variables reach, and when), for the Mars preset's gains and a_p up to 20 m/s^2.
law = landing.scenarios.preset("mars_nominal").controller
b = theory.mss_bounds(law, ap_max=20.0, theta1=0.2, theta2=0.1)
print(f"s2 within {b.s2_radius.max():.1f} m/s by {b.s2_time.max():.1f} s; "
      f"s1 within {b.s1_radius.max():.1f} m by {b.settle_time.max():.1f} s (the sound sum of the two)")

# Gains searched by the engine: CMA-ES over three gains of the same law, each generation one batch
# with per-case gains; land as soon as possible with |F| under 40 kN and the fixed-time bound T1
# under 300 s. A small budget here (a real search: examples/studies/tune_mars.py).
scenario = landing.scenarios.preset("mars_nominal").replace(dt=5e-3, record_every=0)
result = landing.tune(
    scenario,
    gains={"beta1": (0.3, 3.0, "log"), "alpha1": (1.0, 10.0, "log"), "alpha2": (0.005, 0.05, "log")},
    objective="mean(settle_time)",
    constraints=["max(peak_command) < 40e3", "t1 <= 300"],
    budget=60, seed=1, progress=False,
)
print(result)
