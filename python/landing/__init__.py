"""landing: spacecraft landing and attitude control under sliding-mode and fuzzy laws.

A Rust core simulates one case or a million in parallel; this package configures plants,
laws, references and disturbances, runs batches and reads the results.

>>> import landing
>>> plant = landing.plants.MarsLander()
>>> law = landing.controllers.SuperTwisting()
>>> x0 = plant.initial_state([-2000, 1000, 1500], [100, -15, -75], 1905)
>>> res = landing.simulate(plant, law, x0, t_final=10.0, dt=0.01)
>>> res.states.shape, f"{res.metrics['fuel_used']:.3f} kg"
((1001, 7), '31.694 kg')
"""

import importlib
from types import ModuleType

from landing import (
    campaign,
    controllers,
    dispersions,
    disturbances,
    errors,
    fuzzy,
    gravity,
    plants,
    reference,
    scenarios,
    sensors,
    theory,
)
from landing._core import __version__
from landing.campaign import MonteCarloResult, load, monte_carlo
from landing.errors import (
    DivergenceWarning,
    LandingError,
    ParameterError,
    ParameterTypeError,
    SimulationError,
    StoreError,
    StoreWarning,
)
from landing.results import DIVERGENCE_REASONS, Metrics, SimulationResult
from landing.simulation import MAX_COMMAND, RunOptions, kernel_levels, simulate, simulate_batch
from landing.tuning import TuneResult, tune

__all__ = [
    "__version__",
    "controllers",
    "dispersions",
    "disturbances",
    "errors",
    "fuzzy",
    "gravity",
    "plants",
    "plots",
    "optimal",
    "reference",
    "scenarios",
    "sensors",
    "theory",
    "monte_carlo",
    "load",
    "MonteCarloResult",
    "campaign",
    "tune",
    "TuneResult",
    "simulate",
    "simulate_batch",
    "RunOptions",
    "kernel_levels",
    "Metrics",
    "DIVERGENCE_REASONS",
    "MAX_COMMAND",
    "SimulationResult",
    "LandingError",
    "ParameterError",
    "ParameterTypeError",
    "SimulationError",
    "StoreError",
    "StoreWarning",
    "DivergenceWarning",
]

#: Modules loaded on first use, so that ``import landing`` leaves matplotlib (the figures) and
#: CasADi (the fuel-optimal baseline) out.
_LAZY = ("plots", "optimal")


def __getattr__(name: str) -> ModuleType:
    if name in _LAZY:
        return importlib.import_module(f"landing.{name}")
    raise AttributeError(f"module 'landing' has no attribute {name!r}")
