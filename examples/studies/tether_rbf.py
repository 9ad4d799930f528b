"""Study behind the FNTSMC's RBF network (docs/parameters.md, "Tethered satellite").

The tethered-satellite paper prints every gain of its law (Table 2) but nothing of the network: no centres,
widths, node count or adaptation gain Gamma. This study picks them with the batch engine.

What the network is for: W^T Phi estimates the unknown terms f of eq. 17 that the switching
term eps_max sign(s) (1e-4 N, 1e-4 N m) cannot cover. On the flexible plant alone those terms
are small, so the study adds an unknown disturbance well above eps_max: a thrust bias of 2 mN
(2 % of the limit) and a torque bias of 2 mN m (4 %), each with a 1 mN (m) oscillation at
0.2 rad/s. The law does not see it.

What was required (of each axis, on the paper's nominal case: flexible plant, N = 8, 1 degree on
both angles, 0.1 N, dt = 0.01 s, 100 s), against the same law without the network (gamma = 0):
- R1: settle time (|angle| within 2 % of 1 degree) at most 2 % longer;
- R2: chattering (total variation of the command per second) at most 10 % larger;
- R3: the network's output at 100 s within 10 % of the actuator limit (no weight drift), and
  the same under the disturbance;
- R4: robustness, checked on the best sets of each axis only (stage 2): a dispersed campaign
  of 12 cases (angles uniform within 10 and 15 degrees, rates within 2e-4 and 2e-3 rad/s per
  degree, 400 s, the flexible plant with N = 2 to keep it cheap) settles, worst case per
  axis, at most 10 % later than without the network, with the network's output at the end
  within 10 % of the limit. Without R4 the best disturbance rejection comes with adaptation
  gains that wind up when the tether's tension torque saturates the attitude actuator during
  a large in-plane swing (the paper's adaptation law has no leakage or projection).
What was optimised: the RMS angle over the last 50 s under the disturbance, relative to the
network-free law (the accuracy the network buys).
What was searched: per axis, gamma log-uniform (phi: 1 to 1e4; theta: 1e-5 to 1), the
width b (0.3 to 10), the grid's reach in e1 (0.1 to 4 degrees) and in e2 (phi: 1e-5 to
1e-2 rad/s; theta: 1e-4 to 0.1 rad/s), all log-uniform; the node count per input in
{1, 3, 5, 7}. 300 random sets per node count, each set one case of a batch (per-case gains),
nominal and disturbed; the 8 best feasible sets of each axis then go through R4. The axes
barely couple, so each axis keeps its own best set; the node count is the one whose worse axis
gains most; the chosen pair, rounded to two digits, is run again.

    python examples/studies/tether_rbf.py        (under 1 min on 2 cores)
"""

from __future__ import annotations

import time

import numpy as np

import landing
from landing import disturbances, scenarios, theory
from landing.controllers import FixedTimeNTSMC
from landing.plants import TetheredSatellite

DEG = np.pi / 180.0
DT = 0.01
T_FINAL = 100.0
SETS = 300
NODES = (1, 3, 5, 7)
STAGE2 = 8
CAMPAIGN = 6  # cases per scale
SCALES_DEG = (10.0, 15.0)


def test_disturbance(plant: TetheredSatellite):
    """2 mN (m) bias and a 1 mN (m) oscillation at 0.2 rad/s, as generalized accelerations."""
    m = plant.inertia
    return (disturbances.Constant(value=2e-3 / m)
            + disturbances.Sinusoid(amplitude=1e-3 / m, omega=0.2))


def evaluate(plant, law, n, disturbance=None):
    x0 = np.tile(plant.initial_state(DEG, DEG), (n, 1))
    res = landing.simulate_batch(plant, law, x0, t_final=T_FINAL, dt=DT, substeps=plant.substeps_for(DT),
                                 disturbance=disturbance, record_every=1)
    q, _ = plant.coordinates(res.states)
    tail = res.t >= T_FINAL - 50.0
    limit = np.array([plant.thrust_limit, 0.5 * plant.side * plant.thrust_limit])
    return {
        "settle": theory.settle_time(res.t, q, 0.02 * DEG),
        "variation": res.metrics["chattering_variation_axis"],
        "rms": np.sqrt(np.mean(q[:, tail] ** 2, axis=1)),
        "drift": np.abs(res.diagnostics["rbf"][:, -1, :]) / limit,
        "diverged": res.metrics["diverged"],
    }


def campaign_draws(seed: int = 7) -> np.ndarray:
    """(phi, theta, phi_dot, theta_dot) of the R4 campaign, uniform within each scale."""
    rng = np.random.default_rng(seed)
    rows = []
    for scale in SCALES_DEG:
        hi = np.array([scale * DEG, scale * DEG, scale * 2e-4, scale * 2e-3])
        rows.append(rng.uniform(-hi, hi, (CAMPAIGN, 4)))
    return np.concatenate(rows)


def robustness(law_kw: list[dict], nodes: int, draws: np.ndarray, limit: np.ndarray):
    """Worst settle time per axis and largest end output / limit over the campaign, per set."""
    plant = TetheredSatellite(nodes=2)
    n, m = len(law_kw), draws.shape[0]
    x0 = np.tile(plant.initial_state(draws[:, 0], draws[:, 1], draws[:, 2], draws[:, 3]), (n, 1))
    g = {k: np.repeat(np.array([kw[k] for kw in law_kw]), m, axis=0) for k in law_kw[0]}
    law = FixedTimeNTSMC(rbf_nodes=nodes, **g)
    res = landing.simulate_batch(plant, law, x0, t_final=400.0, dt=DT, substeps=plant.substeps_for(DT),
                                 record_every=10)
    q, _ = plant.coordinates(res.states)
    settle = theory.settle_time(res.t, q, 0.02 * DEG).reshape(n, m, 2)
    worst = np.where(np.isnan(settle), np.inf, settle).max(axis=1)
    drift = (np.abs(res.diagnostics["rbf"][:, -1, :]) / limit).reshape(n, m, 2).max(axis=1)
    return worst, drift


def draw(rng: np.random.Generator, n: int) -> dict[str, np.ndarray]:
    def logu(lo, hi):
        return np.exp(rng.uniform(np.log(lo), np.log(hi), n))

    return dict(
        gamma=np.stack([logu(1.0, 1e4), logu(1e-5, 1.0)], axis=1),
        rbf_width=np.stack([logu(0.3, 10.0), logu(0.3, 10.0)], axis=1),
        rbf_scale_e1=np.stack([logu(0.1, 4.0), logu(0.1, 4.0)], axis=1) * DEG,
        rbf_scale_e2=np.stack([logu(1e-5, 1e-2), logu(1e-4, 1e-1)], axis=1),
    )


def feasible(m, m_dist, base):
    ok = (m["settle"] <= 1.02 * base["settle"]) & (m["variation"] <= 1.1 * base["variation"])
    ok &= (m["drift"] <= 0.1) & (m_dist["drift"] <= 0.1)
    ok &= ~m["diverged"][:, None] & ~m_dist["diverged"][:, None]
    return ok


def main() -> None:
    t0 = time.time()
    plant = TetheredSatellite(nodes=8)
    dist = test_disturbance(plant)
    base_law = FixedTimeNTSMC(gamma=0.0)
    base = evaluate(plant, base_law, 1)
    base_d = evaluate(plant, base_law, 1, dist)
    base = {k: v[0] for k, v in base.items()}
    base_d = {k: v[0] for k, v in base_d.items()}
    print("without the network (gamma = 0):")
    print(f"  nominal   settle {base['settle']} s, variation {base['variation']}")
    print(f"  disturbed settle {base_d['settle']} s, tail RMS {base_d['rms'] / DEG} deg")

    limit = np.array([plant.thrust_limit, 0.5 * plant.side * plant.thrust_limit])
    draws = campaign_draws()
    base_worst, _ = robustness([{"gamma": np.zeros(2)}], 1, draws, limit)
    base_worst = base_worst[0]
    print(f"  R4 campaign ({draws.shape[0]} cases, N = 2): worst settle {base_worst} s")

    rng = np.random.default_rng(2025)
    best = {}
    for nodes in NODES:
        g = draw(rng, SETS)
        law = FixedTimeNTSMC(rbf_nodes=nodes, **g)
        m = evaluate(plant, law, SETS)
        md = evaluate(plant, law, SETS, dist)
        ok = feasible(m, md, base)
        score = md["rms"] / base_d["rms"]
        # stage 2: the best feasible sets of each axis through the robustness campaign
        top = set()
        for axis in range(2):
            idx = np.flatnonzero(ok[:, axis])
            top.update(idx[np.argsort(score[idx, axis])[:STAGE2]].tolist())
        top = sorted(top)
        if top:
            worst, drift = robustness([{k: v[i] for k, v in g.items()} for i in top], nodes, draws, limit)
            robust = (worst <= 1.1 * base_worst) & (drift <= 0.1)
        picks = []
        for axis in range(2):
            idx = np.flatnonzero(ok[:, axis])
            good = [i for j, i in enumerate(top) if robust[j, axis] and ok[i, axis]] if top else []
            print(f"nodes {nodes}, axis {axis}: {idx.size} of {SETS} sets meet R1-R3, "
                  f"{len(good)} of the {len(top)} sent to R4 pass it on this axis", end="")
            if not good:
                print()
                break
            i = min(good, key=lambda k: score[k, axis])
            print(f"; best RMS ratio {score[i, axis]:.3g} (gamma {g['gamma'][i, axis]:.3g}, width "
                  f"{g['rbf_width'][i, axis]:.3g}, e1 {g['rbf_scale_e1'][i, axis] / DEG:.3g} deg, "
                  f"e2 {g['rbf_scale_e2'][i, axis]:.3g} rad/s)")
            picks.append((score[i, axis], {k: v[i, axis] for k, v in g.items()}))
        if len(picks) == 2:
            best[nodes] = (max(p[0] for p in picks), [p[1] for p in picks])

    # the node count is shared by the axes: the one whose worse axis gains most
    nodes = min(best, key=lambda k: best[k][0])
    two = best[nodes][1]
    chosen = {}
    for k in two[0]:
        unit = DEG if k == "rbf_scale_e1" else 1.0
        chosen[k] = [float(f"{two[a][k] / unit:.2g}") * unit for a in range(2)]
    print(f"\nchosen (rounded to two digits), rbf_nodes = {nodes}:")
    for k, v in chosen.items():
        shown = [round(x / DEG, 6) for x in v] if k == "rbf_scale_e1" else v
        print(f"  {k:<13} {shown}" + (" deg" if k == "rbf_scale_e1" else ""))
    law = FixedTimeNTSMC(rbf_nodes=nodes, **chosen)
    m = {k: v[0] for k, v in evaluate(plant, law, 1).items()}
    md = {k: v[0] for k, v in evaluate(plant, law, 1, dist).items()}
    print(f"  nominal   settle {m['settle']} s (without: {base['settle']}), variation {m['variation']} "
          f"(without: {base['variation']})")
    print(f"  disturbed tail RMS {md['rms'] / DEG} deg (without: {base_d['rms'] / DEG}), "
          f"ratio {md['rms'] / base_d['rms']}")
    print(f"  network output at 100 s / limit: nominal {m['drift']}, disturbed {md['drift']}")
    ok = feasible({k: v[None] for k, v in m.items()}, {k: v[None] for k, v in md.items()}, base)
    worst, drift = robustness([{k: np.asarray(v) for k, v in chosen.items()}], nodes, draws, limit)
    print(f"  R4 campaign: worst settle {worst[0]} s (without: {base_worst}), end output / limit {drift[0]}")
    ok &= (worst <= 1.1 * base_worst) & (drift <= 0.1)
    print(f"  meets R1-R4: {bool(ok.all())}")
    # the network the presets ship (an earlier run's choice), under the same disturbance
    shipped = scenarios.tether_law("fntsmc")
    ms = {k: v[0] for k, v in evaluate(plant, shipped, 1, dist).items()}
    g = np.asarray(shipped.gamma, dtype=float)
    print(f"\nshipped (scenarios.tether_law('fntsmc'), gamma ({g[0]:g}, {g[1]:g})):")
    print(f"  disturbed tail RMS {ms['rms'] / DEG} deg, ratio {ms['rms'] / base_d['rms']}")
    print(f"({time.time() - t0:.0f} s)")


if __name__ == "__main__":
    main()
