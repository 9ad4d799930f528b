"""Scenarios: a plant, a law, a reference, dispersions, a horizon and a step, as data.

A scenario prints as what it is and is overridden with :meth:`Scenario.replace`; the presets
reproduce the seeds' experiments. Gains the seeds do not print come from documented studies
(docs/parameters.md).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any, Callable, Optional

import numpy as np

from landing import _core, controllers, disturbances, dispersions, plants
from landing._internal.args import choice, integer, pair, real, real_array, short
from landing._internal.limits import require_memory
from landing.controllers import Controller
from landing.dispersions import Dispersion
from landing.disturbances import DisturbanceLike, compiled
from landing.errors import ParameterError, ParameterTypeError
from landing.plants import Plant
from landing.reference import Reference
from landing.results import SimulationResult
from landing.simulation import simulate, simulate_batch

__all__ = [
    "Scenario",
    "PRESETS",
    "preset",
    "write_preset_files",
    "MARS_FIXED_TIME_GAINS",
    "MARS_NOMINAL_STATE",
    "MARS_SUPER_TWISTING_C",
    "mars_nominal",
    "mars_super_twisting",
    "mars_monte_carlo",
    "mars_thrust_limited",
    "SEED000_OFFSET",
    "seed000_reference",
    "seed000_initial_state",
    "SEED002_OFFSET",
    "seed002_reference",
    "seed002_initial_state",
    "seed002_plant",
    "SEED000_GAINS",
    "SEED002_GAINS",
    "seed000_tracking",
    "seed000_landing",
    "seed002_landing",
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

    def __post_init__(self) -> None:
        """Checks every field as :func:`landing.simulate_batch` would, so that a bad scenario
        is refused when it is made, naming the field."""
        owner = f"Scenario {self.name!r}" if isinstance(self.name, str) else "Scenario"
        if not isinstance(self.name, str):
            raise ParameterTypeError(f"Scenario: name must be a string, got {short(self.name)}")
        for name, cls, what, optional in (
            ("plant", Plant, "a landing.plants plant", False),
            ("controller", Controller, "a landing.controllers law", False),
            ("dispersion", Dispersion, "a landing.dispersions dispersion or None", True),
            ("reference", Reference, "a landing.reference reference or None", True),
        ):
            value = getattr(self, name)
            if not (isinstance(value, cls) or (optional and value is None)):
                raise ParameterTypeError(f"{owner}: {name} must be {what}, got {short(value)}")
        x0 = real_array("x0", self.x0, finite=True, owner=owner)
        if x0.ndim != 1:
            # its length is checked against the plant when it is run: a campaign that replaces
            # the plant draws its states from the dispersion and never uses this one
            raise ParameterError(f"{owner}: x0 has shape {x0.shape}; it takes one state (n_state,)")
        real("t_final", self.t_final, positive=True, owner=owner)
        real("dt", self.dt, positive=True, owner=owner)
        compiled(self.disturbance)
        choice("integrator", self.integrator, tuple(_core.INTEGRATORS), owner=owner)
        integer("substeps", self.substeps, minimum=1, cap="max_substeps", owner=owner)
        integer("record_every", self.record_every, minimum=0, maximum=2**63 - 1, owner=owner)
        for name in ("settle_tolerance", "chatter_cutoff"):
            if getattr(self, name) is not None:
                real(name, getattr(self, name), positive=True, owner=owner)
        if self.theta is not None:
            for i, v in enumerate(pair("theta", self.theta, owner=owner)):
                t = real(f"theta[{i}]", v, owner=owner)
                if not 0 < t < 1:
                    raise ParameterError(f"{owner}: theta[{i}] = {t:g} violates 0 < theta < 1")
        if not isinstance(self.description, str):
            raise ParameterTypeError(f"{owner}: description must be a string, got {short(self.description)}")

    def replace(self, **changes: Any) -> "Scenario":
        """A copy with some fields changed: ``s.replace(dt=1e-2)``. A dict given for a part
        (plant, controller, reference, dispersion) changes some of its parameters and keeps the
        others: ``s.replace(controller={"alpha1": 6.0})`` is
        ``s.replace(controller=s.controller.replace(alpha1=6.0))``."""
        known = {f.name for f in dataclasses.fields(self)}
        unknown = sorted(set(changes) - known)
        if unknown:
            raise ParameterTypeError(
                f"Scenario {self.name!r}: unknown field {unknown[0]!r}; the fields are {sorted(known)}"
            )
        for key, value in changes.items():
            current = getattr(self, key)
            if isinstance(value, dict) and hasattr(current, "replace"):
                changes[key] = current.replace(**value)
        return dataclasses.replace(self, **changes)

    def to_toml(self) -> str:
        """The scenario as a TOML file's text, which :func:`load` reads back (``landing show``
        prints it)."""
        from landing.scenario_files import scenario_to_toml

        return scenario_to_toml(self)

    @staticmethod
    def load(spec: Any) -> "Scenario":
        """A preset by name (:data:`PRESETS`) or a scenario TOML file by path."""
        from landing.scenario_files import load_scenario

        return load_scenario(spec)

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
        owner = f"scenario {self.name!r}"
        n = integer("n", n, minimum=0, cap="max_cases", owner=owner)
        dim = self.plant.state_dim
        # the draws, then the states built from them
        require_memory(f"{owner}: the initial states of {n} cases", 2 * 8 * n * dim)
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


# --- Asteroid landing, seed 000 (433 Eros, two mass points) ------------------------------------

#: Where the probe starts relative to the Table 1 reference, m: the seed tracks from an offset
#: it does not print (docs/parameters.md).
SEED000_OFFSET = np.array([10.0, 10.0, 10.0])


def seed000_reference(t_end: float = 8000.0):
    """The cubic of seed 000 eq. 8-10 through the Table 1 boundary states."""
    from landing.reference import Cubic

    return Cubic.from_boundary([3200.0, 1300.0, 9000.0], [-1.2, 0.2, -1.0], [2837.0, 928.1, 5708.0], [0.0, 0.0, 0.0],
                               t_end)


def seed000_initial_state() -> np.ndarray:
    """Table 1's initial state plus the documented position offset."""
    return np.r_[np.array([3200.0, 1300.0, 9000.0]) + SEED000_OFFSET, -1.2, 0.2, -1.0]


# --- Asteroid landing, seed 002 (433 Eros, second-degree harmonics) ----------------------------

#: Where the probe starts relative to the seed-002 reference, m (the seed does not say).
SEED002_OFFSET = np.array([50.0, 50.0, 50.0])


def seed002_reference(t_end: float = 4000.0):
    """The cubic of seed 002 eq. 5-8 from (550, 500, 8200) m, (-1.7, 0.7, -1.5) m/s to rest at
    (20, 80, 2000) m."""
    from landing.reference import Cubic

    return Cubic.from_boundary([550.0, 500.0, 8200.0], [-1.7, 0.7, -1.5], [20.0, 80.0, 2000.0], [0.0, 0.0, 0.0], t_end)


def seed002_initial_state() -> np.ndarray:
    """Seed 002 Table 2's initial state plus the documented position offset."""
    return np.r_[np.array([550.0, 500.0, 8200.0]) + SEED002_OFFSET, -1.7, 0.7, -1.5]


def seed002_plant():
    """433 Eros with second-degree harmonics (seed 002 Table 2), omega = 1.65e-4 rad/s."""
    from landing.gravity import Harmonic2

    return plants.SmallBody(gravity=Harmonic2(), omega=1.65e-4)


#: Seed-000 gains, from examples/studies/asteroid_gains_seed000.py: PD-SMC calibrated to the
#: seed's 8 s, the terminal and fuzzy terms tuned for the least integrated error.
SEED000_GAINS: dict[str, Any] = dict(
    lam=1.0, k=2.5, beta=0.4, p=1.0, q=5.0, n=10.0, m=10.0, boundary_layer=0.3,
)

#: Seed-002 gains, from examples/studies/asteroid_gains_seed002.py (w = 0.017 rad/s, critically
#: damped sliding dynamics).
SEED002_GAINS: dict[str, Any] = dict(
    c1=0.017**2, c2=2 * 0.017, k=0.1, epsilon=1e-3, ke=3.162e4, kec=10.0, ku=2.813e-4,
)

SEED000_LAWS = ("pd", "ftsmc", "fuzzy_ftsmc")


def _seed000_law(law: str, switch: str) -> Controller:
    g = SEED000_GAINS
    common = dict(k=g["k"], switch=switch, boundary_layer=g["boundary_layer"])
    terminal = dict(alpha=g["lam"], beta=g["beta"], p=g["p"], q=g["q"])
    if law == "pd":
        return controllers.PDSlidingMode(lambda_=g["lam"], **common)
    if law == "ftsmc":
        return controllers.FastTerminalSMC(**terminal, **common)
    if law == "fuzzy_ftsmc":
        return controllers.FuzzyFastTerminalSMC(**terminal, n=g["n"], m=g["m"], **common)
    raise ParameterError(f"law = {law!r} is not one of {SEED000_LAWS}")


def seed000_tracking(law: str = "fuzzy_ftsmc", switch: str = "sign", **overrides: Any) -> Scenario:
    """Seed 000: tracking the Table 1 cubic on 433 Eros (two mass points) for 15 s at
    dt = 0.01 s, from the documented 10 m offset; ``law`` is "pd", "ftsmc" or "fuzzy_ftsmc",
    ``switch`` "sign" or "tanh" (the seed's two variants)."""
    s = Scenario(
        name=f"seed000_{law}_{switch}",
        description=f"seed 000 trajectory tracking, {law} with {switch} switching",
        plant=plants.SmallBody(),
        controller=_seed000_law(law, switch),
        x0=seed000_initial_state(),
        reference=seed000_reference(),
        t_final=15.0,
        dt=0.01,
        settle_tolerance=0.1,
    )
    return s.replace(**overrides)


def seed000_landing(law: str = "fuzzy_ftsmc", switch: str = "tanh", **overrides: Any) -> Scenario:
    """Seed 000's full landing: the same tracking over the whole 8000 s reference."""
    return seed000_tracking(law, switch, name=f"seed000_landing_{law}_{switch}",
                            description=f"seed 000 full 8000 s landing, {law} with {switch} switching",
                            t_final=8000.0, record_every=100).replace(**overrides)


SEED002_LAWS = ("exponential", "fuzzy_variable_rate")


def seed002_landing(law: str = "fuzzy_variable_rate", **overrides: Any) -> Scenario:
    """Seed 002: landing on 433 Eros (C20/C22 gravity) along its cubic over 4000 s at dt = 0.1 s,
    from the documented 50 m offset, under a model uncertainty of up to 1 % of the command;
    ``law`` is "exponential" (law 4) or "fuzzy_variable_rate" (law 5)."""
    g = SEED002_GAINS
    surface = dict(c1=g["c1"], c2=g["c2"], k=g["k"])
    if law == "exponential":
        controller: Controller = controllers.IntegralExponentialReaching(**surface, epsilon=g["epsilon"])
    elif law == "fuzzy_variable_rate":
        controller = controllers.FuzzyVariableRate(**surface, ke=g["ke"], kec=g["kec"], ku=g["ku"])
    else:
        raise ParameterError(f"law = {law!r} is not one of {SEED002_LAWS}")
    s = Scenario(
        name=f"seed002_{law}",
        description=f"seed 002 landing with the {law} reaching law",
        plant=seed002_plant(),
        controller=controller,
        x0=seed002_initial_state(),
        reference=seed002_reference(),
        disturbance=disturbances.CommandNoise(0.01),
        t_final=4000.0,
        dt=0.1,
        record_every=10,
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
    spread_deg = real("spread_deg", spread_deg, positive=True)
    if spread_deg > 180.0:
        raise ParameterError(f"spread_deg = {spread_deg:g} violates spread_deg <= 180")
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


#: Every preset by name: ``landing list`` shows them, ``landing show NAME`` prints their TOML
#: (shipped in ``landing/presets/``), and ``Scenario.load(NAME)`` reads it.
PRESETS: dict[str, Callable[[], Scenario]] = {
    "mars_nominal": mars_nominal,
    "mars_super_twisting_printed": lambda: mars_super_twisting("printed"),
    "mars_super_twisting_standard": lambda: mars_super_twisting("standard"),
    "mars_monte_carlo": mars_monte_carlo,
    "mars_thrust_limited": mars_thrust_limited,
    **{f"seed000_{law}_{switch}": (lambda law=law, switch=switch: seed000_tracking(law, switch))
       for law in SEED000_LAWS for switch in ("sign", "tanh")},
    **{f"seed000_landing_{law}_tanh": (lambda law=law: seed000_landing(law, "tanh")) for law in SEED000_LAWS},
    **{f"seed002_{law}": (lambda law=law: seed002_landing(law)) for law in SEED002_LAWS},
    **{f"tether_{law}_{fidelity}": (lambda law=law, fidelity=fidelity: tether_comparison(law, fidelity))
       for law in ("fntsmc", "ntsmc") for fidelity in ("flexible", "simplified")},
    "tether_monte_carlo_fntsmc_10deg": tether_monte_carlo,
}


def preset(name: str) -> Scenario:
    """The preset ``name`` (see :data:`PRESETS`), built by its Python function."""
    if name not in PRESETS:
        raise ParameterError(f"preset = {name!r} is not one of {sorted(PRESETS)}")
    return PRESETS[name]()


def write_preset_files(directory: Any = None) -> list[Any]:
    """Writes every preset's TOML file (into the package's ``presets/`` by default); the
    shipped files are made this way, and a test checks that they are up to date."""
    from pathlib import Path

    from landing.scenario_files import PRESET_DIR

    out = Path(directory) if directory is not None else PRESET_DIR
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for name in PRESETS:
        path = out / f"{name}.toml"
        path.write_text(preset(name).to_toml(), encoding="utf-8")
        written.append(path)
    return written
