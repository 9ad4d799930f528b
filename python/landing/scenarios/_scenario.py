"""The :class:`Scenario`: a plant, a law, a reference, dispersions, a horizon and a step, as data."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, ClassVar, Optional

import numpy as np

from landing._internal.args import integer, pair, real, real_array, short
from landing._internal.limits import require_memory
from landing._internal.table import nested_tables, nested_taking_cases
from landing.controllers import Controller
from landing.dispersions import Dispersion
from landing.disturbances import DisturbanceLike, compiled
from landing.errors import LandingError, ParameterError, ParameterTypeError
from landing.plants import Plant
from landing.reference import Reference
from landing.results import SimulationResult
from landing.scenarios._dispersed import apply_draws, checked_dispersions
from landing.simulation import RunOptions, simulate, simulate_batch, simulate_batch_into

if TYPE_CHECKING:  # pragma: no cover
    from landing.theory.bounds import MSSBounds

__all__ = ["Scenario"]


@dataclass(frozen=True, eq=False)
class Scenario:
    """Everything a run needs but the number of cases and the seed.

    ``x0`` is the nominal initial state; ``dispersion`` (if any) draws the initial states of
    a Monte Carlo campaign, and ``dispersions`` (parameter path -> dispersion, see
    :meth:`disperse`) draws its dispersed parameters. ``theta`` holds the splitting constants
    (theta1, theta2) of the Mars fixed-time guidance paper's practical fixed-time analysis, for
    the bounds a campaign is checked against.
    ``options`` is the :class:`~landing.simulation.RunOptions` of ``t_final``, ``dt``,
    ``integrator``, ``substeps``, ``record_every``, ``settle_tolerance``, ``chatter_cutoff``
    and ``stop_at`` (None, the default: every case runs to ``t_final``; ``"touchdown"`` ends
    each lander case at its touchdown, see :func:`~landing.simulate_batch`), checked once when
    the scenario is made. A scenario is changed by making a new one, :meth:`replace`.

    Parameters
    ----------
    name : str
        The scenario's name (in printouts, stores and messages).
    plant : Plant
        A :mod:`landing.plants` plant.
    controller : Controller
        A :mod:`landing.controllers` law.
    x0 : ArrayLike
        The nominal initial state, shape (n_state,), in the plant's units.
    t_final : float
        Horizon, s; a whole number of control periods.
    dt : float
        Control period, s.
    dispersion : Dispersion or None
        Draws a campaign's initial states (one component per state component).
    reference : Reference or None
        The target the law tracks (default: the origin at rest).
    disturbance : Disturbance, list of Disturbance or None
        Unknown disturbance, q/s^2.
    integrator : str
        ``"rk4"`` (default) or ``"euler"``.
    substeps : int
        Integrator steps per control period, >= 1.
    record_every : int
        Keep every k-th control instant (0: only the final states and the metrics).
    settle_tolerance : float or None
        Tolerance on the tracking-error norm behind ``settle_time``, units of q.
    chatter_cutoff : float or None
        Cut-off of the chattering metric's high-pass filter, Hz.
    stop_at : str or None
        ``"touchdown"`` to end each lander case at its touchdown, or None.
    theta : tuple of float or None
        (theta1, theta2), each in (0, 1).
    description : str
        Free text (``landing list`` shows it).
    dispersions : Mapping[str, Dispersion]
        Parameter path -> dispersion (see :meth:`disperse`).

    Raises
    ------
    ParameterError
        If a field breaks its rule (the message names the scenario and the field).
    ParameterTypeError
        If a field has the wrong type.

    Examples
    --------
    >>> import landing
    >>> from landing.controllers import PDSlidingMode
    >>> from landing.scenarios import Scenario
    >>> s = Scenario("pd", landing.plants.DoubleIntegrator(),
    ...              PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1),
    ...              x0=[10.0, 0, 5, 0, 0, 0], t_final=10.0, dt=0.05)
    >>> r = s.simulate()
    >>> print(f"{r.metrics['final_position_error']:.3f}")
    5.509
    >>> s.replace(dt=0.01).dt, s.replace(controller={"k": 1.0}).controller.k
    (0.01, 1.0)
    """

    #: The fields that are run options (the threads and the kernel level are the machine's,
    #: given per run).
    RUN_OPTIONS: ClassVar[tuple[str, ...]] = (
        "t_final", "dt", "integrator", "substeps", "record_every", "settle_tolerance", "chatter_cutoff",
        "stop_at",
    )

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
    stop_at: Optional[str] = None
    theta: Optional[tuple[float, float]] = None
    description: str = ""
    dispersions: Mapping[str, Dispersion] = field(default_factory=dict)
    options: RunOptions = field(init=False, repr=False)

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
        try:
            options = RunOptions(**{name: getattr(self, name) for name in self.RUN_OPTIONS})
        except LandingError as exc:
            # the scenario's name in front, as in every other refusal here
            raise type(exc)(f"{owner}: {exc}") from None
        object.__setattr__(self, "options", options)
        compiled(self.disturbance)
        if self.theta is not None:
            for i, v in enumerate(pair("theta", self.theta, owner=owner)):
                t = real(f"theta[{i}]", v, owner=owner)
                if not 0 < t < 1:
                    raise ParameterError(f"{owner}: theta[{i}] = {t:g} violates 0 < theta < 1")
        if not isinstance(self.description, str):
            raise ParameterTypeError(f"{owner}: description must be a string, got {short(self.description)}")
        try:
            object.__setattr__(self, "dispersions", checked_dispersions(self, self.dispersions))
        except LandingError as exc:
            raise type(exc)(f"{owner}: {exc}") from None

    def disperse(self, dispersions: Mapping[str, Dispersion]) -> Scenario:
        """A copy whose campaigns draw the parameters ``dispersions`` names, case by case:
        ``s.disperse({"plant.isp": Normal(225, 5), "controller.alpha1": Uniform(4, 6)})``.

        A key is a parameter's path, as :meth:`case_rows` prints them: the scenario's part
        (``plant``, ``controller``, ``reference``, ``disturbance``), a nested configuration's
        field (``plant.sensor``, ``disturbance.parts[1]``), then the parameter. Any numeric
        parameter (a scalar, or per axis: one component draws one value for every axis, one
        per axis draws each axis) of a built-in part, or any ``params`` entry of a law or plant
        written in Python. Case i's draw of a parameter depends only on (seed, i, the path): not
        on the chunking, the threads or the other parameters dispersed. The draws replace the
        parameter's value in each case; :func:`~landing.monte_carlo` records them as the metric
        columns ``param.<path>``. These dispersions add to (or replace, key by key) the
        scenario's own."""
        return self.replace(dispersions={**self.dispersions, **dict(dispersions)})

    def parameter_draws(self, start: int, stop: int, seed: int) -> dict[str, np.ndarray]:
        """The draws of the dispersed parameters for cases ``start .. stop``, each ``(cases,
        components)``, by path."""
        return {name: d.sample(stop - start, seed=seed, first_case=start, key=name)
                for name, d in self.dispersions.items()}

    def with_draws(self, draws: Mapping[str, np.ndarray]) -> Scenario:
        """This scenario with each dispersed parameter given values per case: ``draws[path]``,
        ``(cases, components)`` (as :meth:`parameter_draws` gives them)."""
        return apply_draws(self, draws) if draws else self

    def simulate_cases(self, x0: Any, start: int, n: int, *, seed: int,
                       into: Optional[tuple[np.ndarray, np.ndarray, np.ndarray]] = None,
                       **overrides: Any) -> SimulationResult:
        """Cases ``start .. start + len(x0)`` of an ``n``-case campaign from their initial
        states ``x0``: the parameters given per case keep these cases' rows (:meth:`cases`), the
        dispersed ones take these cases' draws (their metric columns ``param.<path>``), and
        ``seed`` and ``first_case = start`` key the random disturbances, as in the campaign.
        ``into``: arrays the recording is written into (the campaign's rows of its output,
        ``landing.simulation.simulate_batch_into``)."""
        x0 = np.asarray(x0, dtype=float)
        stop = start + x0.shape[0]
        scenario = self.cases(start, stop, n)
        draws = self.parameter_draws(start, stop, seed)
        scenario = scenario.with_draws(draws)
        options = scenario.run_options(seed=seed, first_case=start, **overrides)
        part = simulate_batch_into(into, scenario.plant, scenario.controller, x0, **options)
        if draws:
            part = part.with_metrics({f"param.{k}": (v[:, 0] if v.shape[1] == 1 else v) for k, v in draws.items()})
        return part

    def replace(self, **changes: Any) -> Scenario:
        """A copy with some fields changed: ``s.replace(dt=1e-2)``. A dict given for a part
        (plant, controller, reference, dispersion) changes some of its parameters and keeps the
        others: ``s.replace(controller={"alpha1": 6.0})`` is
        ``s.replace(controller=s.controller.replace(alpha1=6.0))``."""
        known = {f.name for f in dataclasses.fields(self) if f.init}
        unknown = sorted(set(changes) - known)
        if unknown:
            raise ParameterTypeError(
                f"Scenario {self.name!r}: unknown field {unknown[0]!r}; the fields are {sorted(known)}"
            )
        for key, value in changes.items():
            current = getattr(self, key)
            if isinstance(value, dict) and hasattr(current, "replace") and key != "dispersions":
                changes[key] = current.replace(**value)
        return dataclasses.replace(self, **changes)

    def to_toml(self) -> str:
        """The scenario as a TOML file's text, which :meth:`load` reads back (``landing show``
        prints it)."""
        from landing.scenarios.files import scenario_to_toml  # noqa: PLC0415 - one-line delegation up

        return scenario_to_toml(self)

    @staticmethod
    def load(spec: Any) -> Scenario:
        """A preset by name (:data:`landing.scenarios.PRESETS`) or a scenario TOML file by path."""
        from landing.scenarios._presets import load_scenario  # noqa: PLC0415 - one-line delegation up

        return load_scenario(spec)

    def run_options(self, **overrides: Any) -> dict[str, Any]:
        """The keyword arguments of :func:`landing.simulate_batch` this scenario stands for (its
        run options, reference and disturbance), with ``overrides``."""
        opts: dict[str, Any] = {name: getattr(self.options, name) for name in self.RUN_OPTIONS}
        opts.update(reference=self.reference, disturbance=self.disturbance)
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

    #: The fields whose parameters may be given per case (a dispersion draws per case instead).
    PER_CASE: ClassVar[tuple[str, ...]] = ("plant", "controller", "reference", "disturbance")

    def case_rows(self, n: int) -> dict[str, int]:
        """The parameters given one row per case (``"controller.kp"``, ``"plant.isp"``), and
        their rows, for a campaign of ``n`` cases (see :meth:`cases`)."""
        axes = self.plant.axes
        return {f"{name}{suffix}.{k}": rows
                for name in self.PER_CASE for suffix, part in nested_tables(getattr(self, name))
                for k, rows in part.case_rows(n, axes).items()}

    def cases(self, start: int, stop: int, n: int) -> Scenario:
        """This scenario for cases ``start .. stop`` of a campaign of ``n``: each parameter given
        per case (of the plant, law, reference or disturbance: ``n`` rows) keeps its rows
        ``start .. stop``, so that a chunk of a campaign runs its own cases' values. A
        parameter with another number of rows than ``n`` is refused, naming it."""
        owner = f"scenario {self.name!r}"
        n = integer("n", n, minimum=1, cap="max_cases", owner=owner)
        stop = integer("stop", stop, minimum=0, maximum=n, owner=owner)
        start = integer("start", start, minimum=0, maximum=stop, owner=owner)
        wrong = {k: r for k, r in self.case_rows(n).items() if r != n}
        if wrong:
            name, rows = next(iter(wrong.items()))
            raise ParameterError(f"{owner}: {name} has {rows} values per case but the campaign has {n} cases")
        if (start, stop) == (0, n):
            return self
        axes = self.plant.axes
        changes = {}
        for name in self.PER_CASE:
            value = getattr(self, name)
            taken = nested_taking_cases(value, start, stop, n, axes)
            if taken is not value:
                changes[name] = taken
        return self.replace(**changes) if changes else self

    def bounds(self) -> Optional[MSSBounds]:
        """The practical fixed-time bounds of the Mars fixed-time guidance paper for this scenario's law
        and disturbance (None unless the law is FixedTimeMSS and ``theta`` is set)."""
        from landing.theory.bounds import scenario_bounds  # noqa: PLC0415 - one-line delegation up

        return scenario_bounds(self)

    def __str__(self) -> str:
        lines = [f"Scenario {self.name!r}" + (f": {self.description}" if self.description else "")]
        for f in dataclasses.fields(self):
            if f.name in ("name", "description") or not f.init:
                continue
            value = getattr(self, f.name)
            text = np.array2string(np.asarray(value), precision=6) if f.name == "x0" else repr(value)
            lines.append(f"  {f.name:<16} {text}")
        return "\n".join(lines)
