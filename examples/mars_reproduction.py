"""Every number of docs/reproduction-mars.md: the Mars fixed-time guidance paper's printed figures
beside ours.

    python examples/mars_reproduction.py
"""

from __future__ import annotations

import warnings

import numpy as np

import landing
from landing import scenarios, theory

NOMINAL_KEYS = ("settle_time", "fuel_to_settle", "peak_command", "final_position_error", "final_velocity_error")


def line(label: str, ours: str, paper: str) -> None:
    print(f"  {label:<52} {ours:<28} paper: {paper}" if paper else f"  {label:<52} {ours}")


def largest_drag(plant: landing.plants.MarsLander, states: np.ndarray) -> float:
    """The largest |a_drag| over recorded states ``(..., 7)``: eq. 12 with the sign fixed, as the
    plant's docstring writes it, ``a_drag_i = -k_d v_i |v_i| exp(-h_d rz) / (A_i m)``, with the
    plant's own parameters."""
    if not plant.drag:
        return 0.0
    r, v, m = states[..., :3], states[..., 3:6], states[..., 6:7]
    a = (-float(np.asarray(plant.drag_coefficient)) * v * np.abs(v) * np.exp(-float(np.asarray(plant.density_decay)) * r[..., 2:3])
         / (np.asarray(plant.area, dtype=float) * m))
    return float(np.nanmax(np.linalg.norm(a, axis=-1)))


def nominal() -> None:
    print("Part 1: nominal landing (Table I), fixed-time MSS, preset gains")
    r = scenarios.mars_nominal().simulate()
    m = r.metrics
    line("peak thrust per axis / of |F|", f"{np.max(m['peak_command_axis']) / 1e3:.2f} / {m['peak_command'] / 1e3:.2f} kN",
         "below 40 kN (Fig. 2(c))")
    line("fuel to landing (|r| within 1 m)", f"{m['fuel_to_settle']:.2f} kg", "238.2907 kg (Fig. 4)")
    line("landing time (|r| within 1 m from then on)", f"{m['settle_time']:.2f} s", "about 10-15 s (Fig. 2(a))")
    line("final |r|, |v| at 60 s", f"{m['final_position_error']:.2e} m, {m['final_velocity_error']:.2e} m/s", "precise soft landing")
    a_max = 40e3 / 1905.0
    tf1, tf2 = theory.min_final_time(scenarios.MARS_NOMINAL_STATE[:3], scenarios.MARS_NOMINAL_STATE[3:6], a_max, [0, 0, -3.7114])
    line("Remark 1 lower bound at 40 kN, max over axes", f"{max(tf1.max(), tf2.max()):.2f} s", "(not printed)")
    rest = theory.min_time_to_rest(scenarios.MARS_NOMINAL_STATE[:3], scenarios.MARS_NOMINAL_STATE[3:6], a_max,
                                   [0, 0, -3.7114])
    line("fastest possible landing at 40 kN per axis (bang-bang)", f"{rest.max():.2f} s", "")
    # the same bound with the lightest mass a landing of T seconds can reach (|F| <= 40 kN sqrt 3,
    # m' = -|F| / (Isp g0)): a landing in T needs T >= rest(T); rest falls as T grows, so the
    # least such T is where they meet (bisection). Drag is neglected in both bounds.
    lander = scenarios.mars_nominal().plant
    burn = np.sqrt(3) * 40e3 / (lander.isp * lander.g0)

    def rest_at(T: float) -> float:
        return float(np.max(theory.min_time_to_rest(scenarios.MARS_NOMINAL_STATE[:3], scenarios.MARS_NOMINAL_STATE[3:6],
                                                    40e3 / (1905.0 - burn * T), [0, 0, -3.7114])))
    lo, hi = 0.0, float(rest.max())
    for _ in range(60):
        lo, hi = (lo, (lo + hi) / 2) if rest_at((lo + hi) / 2) <= (lo + hi) / 2 else ((lo + hi) / 2, hi)
    line("  the same with the mass a landing that fast can burn", f"{hi:.2f} s", "")
    line("  40 kN per axis at 1905 kg / at that landing's mass", f"{40e3 / 1905.0:.1f} / {40e3 / (1905.0 - burn * hi):.1f} m/s^2", "")
    # after landing the sampled law chatters: every control period recorded, 50 to 60 s
    fine = scenarios.mars_nominal().replace(record_every=1).simulate()
    late = fine.t >= 50.0
    u = fine.controls[late]
    swing = (u.max(axis=0) - u.min(axis=0)) / 1e3
    line("after landing (50-60 s): thrust peak to peak per axis",
         f"{swing.min():.2f} to {swing.max():.2f} kN", "(continuous time: none)")
    line("after landing (50-60 s): largest |r_i|", f"{np.abs(fine.states[late, :3]).max():.1e} m", "")
    line("largest drag acceleration |a_drag| (eq. 12), 0-60 s", f"{largest_drag(lander, fine.states):.2f} m/s^2", "")

    print("\nSuper-twisting baseline (eq. 46, B1, B2 as printed), nominal landing, 200 s")
    for variant in ("printed", "standard"):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", landing.DivergenceWarning)
            scenario = scenarios.mars_super_twisting(variant)
            run = scenario.simulate()
            m = run.metrics
        line(f"{variant}: landing time / fuel to landing", f"{m['settle_time']:.2f} s / {m['fuel_to_settle']:.1f} kg",
             "30 s / 277.1288 kg (Fig. 5)")
        line(f"{variant}: peak thrust, first ground crossing", f"{m['peak_command'] / 1e3:.1f} kN, {m['touchdown_time']:.2f} s", "")
        line(f"{variant}: largest drag acceleration |a_drag| (eq. 12)",
             f"{largest_drag(scenario.plant, np.asarray(run.states)):.2f} m/s^2", "")


def bounds() -> None:
    print("\nFixed-time bounds (eq. 18, 26)")
    line("T1, T2 with the reconstruction from the printed bounds",
         f"{theory.fixed_time_bound(0.8, 0.95, 0.4, 1.05):.4f} s, {theory.fixed_time_bound(0.9, 0.9, 0.5, 1.1):.4f} s",
         "74.5780 s, 30.8217 s")
    b = scenarios.mars_monte_carlo().bounds()
    line("T1, T2 with the preset gains", f"{b.t1[0]:.2f} s, {b.t2[0]:.2f} s", "")
    line("s2 neighbourhood, time (eq. 39, 40; theta1 = 0.2)", f"{b.s2_radius[0]:.2f} m/s, {b.s2_time[0]:.1f} s", "26.5257 m, 131.5173 s")
    line("s1 neighbourhood, time (eq. 31, 45; theta2 = 0.1)", f"{b.s1_radius[0]:.2f} m, {b.s1_time[0]:.1f} s", "23.8472 m, 85.8610 s")
    line("s1 settles by (s2 time + s1 time; eq. 32 prints max)", f"{b.settle_time[0]:.1f} s", "")


def monte_carlo() -> None:
    print("\nPart 2: 300-case Monte Carlo (Table II, a_p = 20 sin t), seed 1")
    mc = landing.monte_carlo(scenarios.mars_monte_carlo(), 300, seed=1)
    m = mc.metrics
    err = np.abs(m["final_error"])
    tail = mc.t >= 40.0
    amp = np.abs(mc.states[:, tail, :3]).max(axis=1)
    line("cases diverged", f"{int(m['diverged'].sum())} of 300", "")
    line("final |r_i| at 60 s, max over cases and axes", f"{err.max():.2f} m", "at most 23.8472 m per axis")
    line("max |r_i| over t >= 40 s (steady oscillation)", f"{amp.max():.2f} m", "")
    b = scenarios.mars_monte_carlo().bounds()
    settle, radius = float(np.max(b.settle_time)), float(np.max(b.s1_radius))
    inside = (f"not informative ({settle:.0f} s)" if settle > 60.0 else
              f"not informative ({radius:.0f} m)" if radius >= 100 * err.max() else
              f"{int(mc.within_radius_at_end().sum())} of 300")
    line("cases within the s1 neighbourhood at 60 s", inside, "all 300")
    line("first ground crossing speed, median / max", f"{np.nanmedian(m['touchdown_speed']):.1f} / {np.nanmax(m['touchdown_speed']):.1f} m/s", "at most 1.5 m/s")
    line("peak thrust, max over cases", f"{m['peak_command'].max() / 1e3:.1f} kN", "(no limit in part 2)")

    print("\nPart 3: 50-case uniform sweep (Table III), 50 kN per axis, seed 1")
    mc = landing.monte_carlo(scenarios.mars_thrust_limited(), 50, seed=1)
    m = mc.metrics
    line("cases landed precisely (|r| < 0.1 m at 60 s)", f"{int(np.sum(m['final_position_error'] < 0.1))} of 50", "all 50")
    line("landing time (1 m), min / median / max", f"{np.nanmin(m['settle_time']):.1f} / {np.nanmedian(m['settle_time']):.1f} / {np.nanmax(m['settle_time']):.1f} s", "within 10 s")
    a_max = 50e3 / 1905.0
    tf1, tf2 = theory.min_final_time(mc.x0[:, :3], mc.x0[:, 3:6], a_max, [0, 0, -3.7114])
    lower = np.maximum(tf1, tf2).max(axis=1)
    line("Remark 1 lower bound per case, median / max", f"{np.median(lower):.1f} / {lower.max():.1f} s", "")
    rest = theory.min_time_to_rest(mc.x0[:, :3], mc.x0[:, 3:6], a_max, [0, 0, -3.7114]).max(axis=1)
    line("fastest possible landing per case (bang-bang), median / max", f"{np.median(rest):.1f} / {rest.max():.1f} s", "")
    # a rigorous version: as if the lander weighed 1500 kg from the start (more than 400 kg of
    # propellant gone, twice what any case here burns)
    light = theory.min_time_to_rest(mc.x0[:, :3], mc.x0[:, 3:6], 50e3 / 1500.0, [0, 0, -3.7114]).max(axis=1)
    line("cases that cannot land within 10 s even at 1500 kg", f"{int(np.sum(light > 10))} of 50 (min {light.min():.1f} s)", "")
    line("peak thrust per axis, max over cases", f"{np.max(m['peak_command_axis']) / 1e3:.1f} kN", "limit 50 kN")


def main() -> None:
    nominal()
    bounds()
    monte_carlo()


if __name__ == "__main__":
    main()
