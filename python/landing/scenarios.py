"""Scenarios: a plant, a law, a reference, dispersions, a horizon and a step, as data.

A scenario prints as what it is and is overridden with :meth:`Scenario.replace`; the presets
reproduce the seeds' experiments. Gains the seeds do not print come from documented studies
(docs/parameters.md).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any, Optional

import numpy as np

from landing import controllers, disturbances, dispersions, plants
from landing.controllers import Controller
from landing.dispersions import Dispersion
from landing.disturbances import DisturbanceLike
from landing.errors import ParameterError
from landing.plants import Plant
from landing.reference import Reference
from landing.simulation import SimulationResult, simulate, simulate_batch

__all__ = [
    "Scenario",
    "MARS_FIXED_TIME_GAINS",
    "MARS_NOMINAL_STATE",
    "MARS_SUPER_TWISTING_C",
    "mars_nominal",
    "mars_super_twisting",
    "mars_monte_carlo",
    "mars_thrust_limited",
    "TETHER_INITIAL_ANGLES",
    "TETHER_NODES",
    "TETHER_SETTLE_TOLERANCE",
    "TETHER_RATE_SPREAD",
    "tether_plant",
    "tether_law",
    "tether_comparison",
    "tether_monte_carlo",
]


@dataclass(eq=False)
class Scenario:
    """Everything a run needs but the number of cases and the seed.

    ``x0`` is the nominal initial state; ``dispersion`` (if any) draws the initial states of
    a Monte Carlo campaign. ``theta`` holds the splitting constants (theta1, theta2) of seed
    001's practical fixed-time analysis, for the bounds a campaign is checked against.
    """

    name: str
    plant: Plant
    controller: Controller
    x0: Any
    t_final: float
    dt: float
    dispersion: Optional[Dispersion] = None
    reference: Optional[Reference] = None
    disturbance: DisturbanceLike = None
    integrator: str = "rk4"
    substeps: int = 1
    record_every: int = 1
    settle_tolerance: Optional[float] = None
    chatter_cutoff: Optional[float] = None
    theta: Optional[tuple[float, float]] = None
    description: str = ""

    def replace(self, **changes: Any) -> "Scenario":
        """A copy with some fields changed, e.g. ``s.replace(dt=1e-2)``."""
        return dataclasses.replace(self, **changes)

    def run_options(self, **overrides: Any) -> dict[str, Any]:
        """The keyword arguments of :func:`landing.simulate_batch` this scenario stands for."""
        opts = dict(
            t_final=self.t_final, dt=self.dt, integrator=self.integrator, substeps=self.substeps,
            reference=self.reference, disturbance=self.disturbance, record_every=self.record_every,
            settle_tolerance=self.settle_tolerance, chatter_cutoff=self.chatter_cutoff,
        )
        opts.update(overrides)
        return opts

    def simulate(self, **overrides: Any) -> SimulationResult:
        """The nominal case (``x0``) alone."""
        return simulate(self.plant, self.controller, np.asarray(self.x0, dtype=float), **self.run_options(**overrides))

    def simulate_batch(self, x0: Any, **overrides: Any) -> SimulationResult:
        """Given initial states under this scenario."""
        return simulate_batch(self.plant, self.controller, x0, **self.run_options(**overrides))

    def initial_states(self, n: int, seed: int = 0, first_case: int = 0) -> np.ndarray:
        """Cases ``first_case .. first_case + n`` of the dispersion (the nominal state repeated
        if there is none)."""
        if self.dispersion is None:
            return np.tile(np.asarray(self.x0, dtype=float), (n, 1))
        x = self.plant.states_from_draws(self.dispersion.sample(n, seed=seed, first_case=first_case))
        if x.shape[1] != self.plant.state_dim:
            raise ParameterError(
                f"scenario {self.name!r}: the dispersion has {x.shape[1]} components, the plant's "
                f"state has {self.plant.state_dim}"
            )
        return x

    def bounds(self):
        """Seed 001's practical fixed-time bounds for this scenario's law and disturbance (None
        unless the law is FixedTimeMSS and ``theta`` is set)."""
        from landing import theory

        if self.theta is None or not isinstance(self.controller, controllers.FixedTimeMSS):
            return None
        ap_max = theory.disturbance_bound(self.disturbance, self.plant.axes)
        return theory.mss_bounds(self.controller, ap_max, *self.theta)

    def __str__(self) -> str:
        lines = [f"Scenario {self.name!r}" + (f": {self.description}" if self.description else "")]
        for f in dataclasses.fields(self):
            if f.name in ("name", "description"):
                continue
            value = getattr(self, f.name)
            text = np.array2string(np.asarray(value), precision=6) if f.name == "x0" else repr(value)
            lines.append(f"  {f.name:<16} {text}")
        return "\n".join(lines)


#: Seed 001 Table I initial state [r (m), v (m/s), m (kg)].
MARS_NOMINAL_STATE = np.array([-2000.0, 1000.0, 1500.0, 100.0, -15.0, -75.0, 1905.0])

#: Fixed-time MSS gains for the Mars lander, from the tuning study in docs/parameters.md
#: (the seed does not print its gains).
MARS_FIXED_TIME_GAINS: dict[str, Any] = dict(
    beta1=1.3, q1=0.589, beta2=0.0242, q2=1.18, alpha1=4.89, gamma1=0.319, alpha2=0.0129, gamma2=1.42,
)


def _mars_law(**overrides: Any) -> controllers.FixedTimeMSS:
    return controllers.FixedTimeMSS(**{**MARS_FIXED_TIME_GAINS, **overrides})


def mars_nominal(**overrides: Any) -> Scenario:
    """Seed 001 part 1: the nominal landing from Table I, no disturbance, no thrust limit."""
    s = Scenario(
        name="mars_nominal",
        description="seed 001 part 1, nominal landing (Table I)",
        plant=plants.MarsLander(),
        controller=_mars_law(),
        x0=MARS_NOMINAL_STATE.copy(),
        t_final=60.0,
        dt=1e-3,
        record_every=10,
        settle_tolerance=1.0,
    )
    return s.replace(**overrides)


#: Slope of the standard super-twisting variant's sliding variable on the Mars lander, from
#: examples/studies/mars_super_twisting.py (the seed's law has none).
MARS_SUPER_TWISTING_C = 0.1


def mars_super_twisting(variant: str = "printed", **overrides: Any) -> Scenario:
    """The seed's super-twisting baseline (eq. 46, B1, B2 as printed) on the nominal landing,
    over 200 s: with these gains neither variant lands within the fixed-time preset's 60 s."""
    law = controllers.SuperTwisting(variant=variant, c=MARS_SUPER_TWISTING_C)
    return mars_nominal(
        name=f"mars_super_twisting_{variant}",
        description=f"seed 001 super-twisting baseline ({variant} variant), nominal landing",
        controller=law,
        t_final=200.0,
    ).replace(**overrides)


def mars_monte_carlo(**overrides: Any) -> Scenario:
    """Seed 001 part 2: Table II normal dispersions, a_p = 20 sin t on every axis,
    theta1 = 0.2, theta2 = 0.1; run it with ``landing.monte_carlo(scenario, 300)``."""
    sd = np.array([100.0, 100.0, 100.0, 10.0, 10.0, 10.0, 20.0])
    s = Scenario(
        name="mars_monte_carlo",
        description="seed 001 part 2, 300-case Monte Carlo under a_p = 20 sin t (Table II)",
        plant=plants.MarsLander(),
        controller=_mars_law(),
        x0=MARS_NOMINAL_STATE.copy(),
        dispersion=dispersions.Normal(mean=MARS_NOMINAL_STATE, std=sd),
        disturbance=disturbances.Sinusoid(amplitude=20.0, omega=1.0),
        t_final=60.0,
        dt=1e-3,
        record_every=50,
        settle_tolerance=1.0,
        theta=(0.2, 0.1),
    )
    return s.replace(**overrides)


def mars_thrust_limited(**overrides: Any) -> Scenario:
    """Seed 001 part 3: Table III uniform initial positions and velocities (mass 1905 kg),
    50 kN per axis; run it with ``landing.monte_carlo(scenario, 50)``."""
    low = np.array([-1000.0, 0.0, 1000.0, -15.0, -100.0, -75.0, 1905.0])
    high = np.array([200.0, 2000.0, 1500.0, 45.0, 0.0, 0.0, 1905.0])
    s = Scenario(
        name="mars_thrust_limited",
        description="seed 001 part 3, 50-case uniform sweep (Table III), 50 kN per axis",
        plant=plants.MarsLander(thrust_limit=50_000.0),
        controller=_mars_law(),
        x0=0.5 * (low + high),
        dispersion=dispersions.Uniform(low=low, high=high),
        t_final=60.0,
        dt=1e-3,
        record_every=50,
        settle_tolerance=1.0,
    )
    return s.replace(**overrides)


#: Seed 003 section 4: the in-plane and attitude angles start at 1 degree, at rest (rad).
TETHER_INITIAL_ANGLES = (math.radians(1.0), math.radians(1.0))

#: Tether nodes of the flexible plant in the presets (examples/studies/tether_plant.py: N = 8
#: is within 0.01 s of N = 16 on every settle time and 1.3 % on the chattering).
TETHER_NODES = 8

#: "Settled": each angle within 2 % of the initial 1 degree from then on (the seed gives no
#: tolerance; 2 % is the classical settling band).
TETHER_SETTLE_TOLERANCE = math.radians(0.02)

#: Rate spread per degree of angle spread in the tether Monte Carlo, rad/s (phi_dot, theta_dot):
#: a fifth and a tenth of the peak rates of the FNTSMC's seed manoeuvre (1.1e-3 and 1.9e-2 rad/s
#: from 1 degree), so that the rates matter without dominating the angles.
TETHER_RATE_SPREAD = (2e-4, 2e-3)


def tether_plant(fidelity: str = "flexible", **overrides: Any) -> plants.TetheredSatellite:
    """The seed-003 tethered satellite: Table 1 (1000 kg, 10 kg, 100 m, a = 1 m), a 500 km
    orbit, 0.1 N thrust (0.05 N m torque), a YES2-class tether with TETHER_NODES nodes."""
    kw: dict[str, Any] = dict(fidelity=fidelity, nodes=TETHER_NODES)
    kw.update(overrides)
    return plants.TetheredSatellite(**kw)


def tether_law(law: str = "fntsmc") -> Controller:
    """The seed's laws with its gains: ``"fntsmc"`` (eq. 19-24, Table 2, the network of
    examples/studies/tether_rbf.py) or ``"ntsmc"`` (the baseline of its eq. 47/48)."""
    if law == "fntsmc":
        return controllers.FixedTimeNTSMC()
    if law == "ntsmc":
        return controllers.NTSMC()
    raise ParameterError(f'law = {law!r} is not one of ("fntsmc", "ntsmc")')


def tether_comparison(law: str = "fntsmc", fidelity: str = "flexible", **overrides: Any) -> Scenario:
    """Seed 003 section 4: 1 degree on both angles, at rest, to 0 under the 0.1 N limit, on the
    flexible plant; 100 s at dt = 0.01 s (the seed prints no step), every instant recorded."""
    plant = tether_plant(fidelity)
    dt = 0.01
    s = Scenario(
        name=f"tether_{law}_{fidelity}",
        description=f"seed 003 comparison, {law.upper()} on the {fidelity} tethered satellite",
        plant=plant,
        controller=tether_law(law),
        x0=plant.initial_state(*TETHER_INITIAL_ANGLES),
        t_final=100.0,
        dt=dt,
        substeps=plant.substeps_for(dt),
        record_every=1,
        settle_tolerance=TETHER_SETTLE_TOLERANCE,
    )
    return s.replace(**overrides)


def tether_monte_carlo(spread_deg: float = 10.0, law: str = "fntsmc", fidelity: str = "flexible",
                       **overrides: Any) -> Scenario:
    """Initial angles uniform within +-``spread_deg`` degrees and rates within
    +-``spread_deg`` times TETHER_RATE_SPREAD, the seed comparison otherwise; run it with
    ``landing.monte_carlo(scenario, n)`` and check it with ``landing.theory.check_fntsmc_run``.
    The horizon grows with the spread, 40 s per degree rounded up to whole minutes (at least
    100 s): the thrust limit makes large in-plane swings slow."""
    if not (isinstance(spread_deg, (int, float)) and spread_deg > 0):
        raise ParameterError(f"spread_deg = {spread_deg!r} violates spread_deg > 0")
    hi = np.array([math.radians(spread_deg), math.radians(spread_deg),
                   spread_deg * TETHER_RATE_SPREAD[0], spread_deg * TETHER_RATE_SPREAD[1]])
    base = tether_comparison(law, fidelity)
    s = base.replace(
        name=f"tether_monte_carlo_{law}_{spread_deg:g}deg",
        description=f"seed 003 set-up, {law.upper()}, initial angles within {spread_deg:g} degrees",
        dispersion=dispersions.Uniform(low=-hi, high=hi),
        t_final=float(max(100.0, 60.0 * math.ceil(spread_deg * 40.0 / 60.0))),
        record_every=10,
    )
    return s.replace(**overrides)
