"""Quick start: one landing, then a hundred, then a figure (docs/guide/quickstart.md)."""

import numpy as np

import landing

# A preset: the Mars paper's lander (Table I), its fixed-time guidance, 60 s at 1 ms.
scenario = landing.scenarios.preset("mars_nominal")
print(scenario.description)

# One case: the nominal initial state. Metrics are a per-case table; a single run's are scalars.
res = scenario.simulate()
m = res.metrics
print(f"landed within 1 m after {m['settle_time']:.2f} s, burning {m['fuel_to_settle']:.1f} kg")
print(f"peak |F| {m['peak_command'] / 1e3:.2f} kN, final |r| {m['final_position_error']:.1e} m")

# The same parts from a hundred dispersed initial states (100 m and 10 m/s of spread), in one
# batch on every core; the draws are seeded, so the same seed gives the same cases.
spread = landing.dispersions.Normal(mean=scenario.x0, std=[100, 100, 100, 10, 10, 10, 0])
x0 = spread.sample(100, seed=1)                    # (100, 7)
batch = landing.simulate_batch(scenario.plant, scenario.controller, x0, t_final=60.0, dt=1e-3,
                               reference=scenario.reference, record_every=100, seed=1)
print(f"{batch.n_cases} cases, states {batch.states.shape} (case, instant, state)")
fuel = batch.metrics["fuel_to_settle"]
print(f"fuel to landing: median {np.median(fuel):.1f} kg, 95th percentile {np.percentile(fuel, 95):.1f} kg")
print(f"diverged: {int(batch.metrics['diverged'].sum())} of {batch.n_cases}")

# A figure: each plot function takes a result and returns a matplotlib Figure.
fig = landing.plots.positions(batch, max_cases=20)
fig.savefig("quickstart_positions.png", dpi=80)
print("wrote quickstart_positions.png")
