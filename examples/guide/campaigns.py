"""Monte Carlo campaigns: dispersions, a store, verification, sensitivity (docs/guide/campaigns.md)."""

import landing
from landing.dispersions import Normal, TruncatedNormal

# The realistic-loop preset: engine limits, lag, delay, a noisy sensor and a Kalman filter, each
# case ending at touchdown; its initial states are dispersed (Table II of the Mars paper) and so
# are some of its parameters (Isp, thrust, lag, drag).
scenario = landing.scenarios.preset("mars_realistic")
print(f"dispersed already: {', '.join(scenario.dispersions)}")

# Disperse more: any numeric parameter by its path, each case drawing its own value from a
# stream keyed by (seed, case, path). Here a sensor bias per case, one draw per component.
dispersed = scenario.disperse({"plant.sensor.bias": Normal(0.0, [0.5, 0.5, 0.5, 0.05, 0.05, 0.05]),
                               "plant.isp": TruncatedNormal(225.0, 3.0, 215.0, 235.0)})

# 200 cases in chunks of 50, written to a store as each chunk completes (re-running the same
# call resumes an interrupted campaign; landing.load reads it back, bit for bit).
mc = landing.monte_carlo(dispersed, 200, seed=7, chunk_size=50, store="runs/realistic", progress=False)
print(f"{mc.n_cases} cases, draws recorded as {[c for c in mc.metrics if c.startswith('param.')]}")
speed = mc.metrics["touchdown_speed"]
print(f"touchdown speed: max {speed.max():.3f} m/s, mean {speed.mean():.3f} m/s")

# The requirement a review asks for, with a confidence: Clopper-Pearson on the pass/fail of each
# case, and how many cases it would take to show it. (At touchdown rz = 0, so the largest
# |touchdown_position| over the axes is the larger horizontal miss.)
print(mc.verify("touchdown_speed <= 1.0 and max(abs(touchdown_position)) <= 5", p=0.99, confidence=0.9))
print(f"cases needed to show 99.73 % at 90 % with no failure: {landing.campaign.samples_needed(0.9973, 0.9)}")
bound = mc.tolerance_bound("touchdown_speed", p=0.95, confidence=0.9)
print(f"95 % of cases touch down below {bound:.3f} m/s, with 90 % confidence (Wilks)")

# Which dispersions drive the touchdown speed: Spearman's and the partial rank correlation,
# strongest first (bias_5 is the bias of the vertical velocity the law reads).
for name, spearman, partial in mc.sensitivity().drivers("touchdown_speed")[:3]:
    print(f"  {name:<36} {spearman:+.3f} {partial:+.3f}")

# Read back: the same campaign, and its data as tables and labelled arrays.
same = landing.load("runs/realistic")
print(f"loaded: {same.n_cases} cases, the same touchdown speeds: {bool((same.metrics['touchdown_speed'] == speed).all())}")
df = same.metrics.to_pandas()
print(f"metrics as pandas: {df.shape[0]} rows, {df.shape[1]} columns")

fig = landing.plots.landing_sites(mc, requirement_radius=5.0)
fig.savefig("campaigns_landing_sites.png", dpi=80)
