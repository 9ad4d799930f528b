"""The search itself: :func:`tune` runs CMA-ES over a law's gains, one batch per generation
and set-up (see :mod:`landing.tune` for the method and the grammar)."""

from __future__ import annotations

import dataclasses
import math
import time
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Optional, Union

import numpy as np

from landing import controllers, theory
from landing._internal.args import integer, real
from landing._internal.expression import BOUND_NAMES, Expression, UserFunction
from landing._internal.extras import import_extra
from landing._internal.progress import ProgressBar
from landing._internal.table import Parameter
from landing.errors import DivergenceWarning, ParameterError
from landing.results import Metrics, SimulationResult
from landing.scenarios import Scenario
from landing.simulation import RunOptions, simulate_batch
from landing.tuning.pareto import best_and_front, ranks
from landing.tuning.result import GainSpec, TuneResult

#: An objective or constraint: an expression of the grammar (``landing._internal.expression``),
#: or a callable ``f(metrics, bounds) -> float``.
ObjectiveLike = Union[str, Callable[[Metrics, Optional[Mapping[str, float]]], float]]

__all__ = ["tune"]


def _parse_gains(gains: Mapping[str, Any], law: controllers.Controller) -> tuple[GainSpec, ...]:
    if not isinstance(gains, Mapping) or not gains:
        raise ParameterError(f"gains = {gains!r} must be a non-empty dict {{name: (low, high)}}")
    # a law written in Python has its parameters in `params`; a built-in law's are its fields
    names = set(law.params) if isinstance(law, controllers.PythonLaw) else {f.name for f in dataclasses.fields(law)}
    out = []
    for name, spec in gains.items():
        if name not in names:
            raise ParameterError(
                f"gains: {name!r} is not a parameter of {type(law).__name__} (its parameters: {sorted(names)})"
            )
        declared = _declared(law, name)
        if declared is None or not declared.numeric:
            numeric = sorted(n for n in names if (d := _declared(law, n)) is not None and d.numeric)
            raise ParameterError(
                f"gains: {name!r} of {type(law).__name__} is not a number to tune (its numeric parameters: {numeric})"
            )
        if not isinstance(spec, (tuple, list)) or len(spec) not in (2, 3):
            raise ParameterError(f"gains[{name!r}] = {spec!r} must be (low, high) or (low, high, 'log')")
        try:
            low, high = float(spec[0]), float(spec[1])
        except (TypeError, ValueError):
            raise ParameterError(f"gains[{name!r}] = {spec!r}: low and high must be numbers") from None
        scale = spec[2] if len(spec) == 3 else "linear"
        if scale not in ("linear", "log"):
            raise ParameterError(f"gains[{name!r}] = {spec!r}: the scale {scale!r} is not 'linear' or 'log'")
        if not (math.isfinite(low) and math.isfinite(high) and low < high):
            raise ParameterError(f"gains[{name!r}] = {spec!r} violates low < high, both finite")
        if scale == "log" and low <= 0:
            raise ParameterError(f"gains[{name!r}] = {spec!r} violates low > 0 on a log scale")
        out.append(GainSpec(name, low, high, scale))
    return tuple(out)


def _is_random(disturbance: Any) -> bool:
    """Whether a component of the disturbance draws random numbers (the core declares which)."""
    if disturbance is None:
        return False
    parts = disturbance.components() if hasattr(disturbance, "components") else list(disturbance)
    return any(p.random for p in parts)


def _declared(law: controllers.Controller, name: str) -> Optional[Parameter]:
    """What the core declares for the law's field ``name`` (None if the field is not a table key)."""
    return law.parameters.get(name)


def _column_shape(law: controllers.Controller, name: str) -> bool:
    """Whether the law reads ``name`` per axis, so that a per-case gain must be given as
    (N, 1) (a 1-D array of length D would be read per axis); scalar parameters take (N,)."""
    declared = _declared(law, name)
    return declared is not None and declared.shape == "per_axis"


def _per_case(value: np.ndarray, column: bool) -> np.ndarray:
    return np.ascontiguousarray(value.reshape(-1, 1) if column else value.reshape(-1))


def _bounds_for(scenario: Scenario, law: controllers.Controller) -> Optional[dict[str, np.ndarray]]:
    """The bound names per candidate ((P,) arrays, the largest over the axes), or None."""
    if not isinstance(law, controllers.FixedTimeMSS):
        return None
    ap = theory.disturbance_bound(scenario.disturbance, scenario.plant.axes)
    th = scenario.theta if scenario.theta is not None else (0.5, 0.5)
    b = theory.mss_bounds(law, ap, *th)

    def worst(a: np.ndarray) -> np.ndarray:
        a = np.asarray(a, dtype=float)
        return a.max(axis=-1) if a.ndim == 2 else np.atleast_1d(a.max())

    return {
        "t1": worst(b.t1), "t2": worst(b.t2), "s1_radius": worst(b.s1_radius), "s1_time": worst(b.s1_time),
        "s2_radius": worst(b.s2_radius), "s2_time": worst(b.s2_time), "settle_bound": worst(b.settle_time),
    }


def _term(spec: Any, kind: str, metric_names: Sequence[str],
          bound_names: Sequence[str]) -> Union[Expression, UserFunction]:
    """An objective or constraint given as a callable or as an expression's text (which
    :class:`Expression` checks, refusing anything else)."""
    if callable(spec):
        return UserFunction(spec, kind)
    return Expression(spec, metric_names, bound_names, kind)


def _probe_metric_names(scenario: Scenario) -> list[str]:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DivergenceWarning)
        res = scenario.simulate_batch(scenario.initial_states(1, seed=0), **{
            "t_final": scenario.dt, "record_every": 0, "threads": 1})
    return list(res.metrics)


def tune(
    scenario: Union[Scenario, Mapping[str, Scenario]],
    gains: Mapping[str, Any],
    objective: Union[ObjectiveLike, Sequence[ObjectiveLike]],
    constraints: Sequence[ObjectiveLike] = (),
    *,
    cases: int = 1,
    budget: int = 200,
    seed: int = 0,
    optimizer: str = "cma",
    popsize: Optional[int] = None,
    sigma0: float = 0.3,
    start: Optional[Mapping[str, float]] = None,
    threads: Optional[int] = None,
    progress: Optional[bool] = None,
) -> TuneResult:
    """Searches ``scenario``'s law gains with CMA-ES (the ``cma`` package).

    Parameters
    ----------
    scenario : Scenario or Mapping[str, Scenario]
        The set-up; its dispersion (if any) draws the K cases with ``seed``. Or several
        set-ups by label, ``{"nominal": s1, "storm": s2}``, whose laws share the searched gains:
        every candidate runs on each, and the expressions name their metrics and bounds
        ``nominal.fuel_used``, ``storm.s1_radius`` (``t1``, ``t2``... alone: the first set-up's).
    gains : Mapping[str, tuple]
        ``{name: (low, high)}`` or ``{name: (low, high, "log")}``, law parameters (by their
        Python field names, ``lambda_``) shared by every axis, bounds in the gains' units; the
        search runs in [0, 1] per gain (log10-mapped on a log scale), bounded by CMA-ES's
        boundary transformation.
    objective : str, callable, or a list of them
        An expression (module docstring) reducing the K cases to one number, such as
        ``"mean(iae)"``, or a callable ``f(metrics, bounds) -> float`` (metrics: the
        candidate's K cases, a dict of them by label for several set-ups; bounds: a dict of the
        bound names, or None), or a list of them (several objectives, every one minimised).
    constraints : sequence of str or callable
        Expressions (one comparison each, ``"max(peak_command) <= 5"``) or callables returning
        a margin that is met when <= 0. A candidate with a diverged case is infeasible.
    cases : int
        K, the dispersed cases every candidate runs on (the same for all: common random
        numbers).
    budget : int
        The most candidate evaluations (each runs K cases on every set-up).
    seed : int
        Seeds the cases (dispersion and random streams) and the search: the same seed gives
        the same evaluations and result, whatever ``threads``.
    optimizer : str
        ``"cma"`` (the only one).
    popsize : int or None
        Candidates per generation (default: CMA-ES's 4 + 3 ln(number of gains)).
    sigma0 : float
        Initial step in the unit coordinates.
    start : Mapping[str, float] or None
        The initial mean's gains (default: the middle of the box); the start itself is one of
        the first generation's candidates.
    threads : int or None
        Worker threads of the batches (default: all cores).
    progress : bool or None
        Show progress on stderr (default: when the run is long).

    Returns
    -------
    TuneResult
        Every evaluation, the best and the Pareto front.

    Raises
    ------
    ParameterError
        If a gain is not a parameter of the law, its bounds are not ``low < high`` (``low > 0``
        on a log scale), or an expression names an unknown metric or does not reduce the cases
        to one number.
    ImportError
        If the ``cma`` package is not installed.

    Notes
    -----
    Each generation runs as one batch of popsize x K cases per set-up, with per-case gains.
    When a set-up's disturbance draws random numbers, the engine keys them by the case's index
    in the batch, so one batch cannot give every candidate the same streams: then each
    candidate runs as its own batch of K cases (same seed, same case indices).

    Ctrl-C between or during generations stops the search and returns what was done so far,
    with ``interrupted=True``.

    Examples
    --------
    >>> import landing
    >>> from landing.controllers import PDSlidingMode
    >>> from landing.scenarios import Scenario
    >>> from landing.tuning import tune
    >>> s = Scenario("pd", landing.plants.DoubleIntegrator(),
    ...              PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1),
    ...              x0=[10.0, 0, 5, 0, 0, 0], t_final=10.0, dt=0.05)
    >>> r = tune(s, {"lambda_": (0.2, 2.0), "k": (0.1, 2.0, "log")}, "mean(iae)",
    ...          ["max(peak_command) <= 5"], budget=12, seed=1, progress=False)
    >>> print(r.stop, r.n_evaluations, int(r.feasible.sum()))
    budget 12 12
    >>> print(", ".join(f"{k} = {v:.3f}" for k, v in r.best_gains.items()))
    lambda_ = 0.949, k = 1.426
    """
    if isinstance(scenario, Scenario):
        setups: dict[str, Scenario] = {"": scenario}
    elif isinstance(scenario, Mapping) and scenario and all(isinstance(v, Scenario) for v in scenario.values()):
        setups = {}
        for label, s in scenario.items():
            if not (isinstance(label, str) and label.isidentifier()):
                raise ParameterError(f"scenario: the label {label!r} violates the rule: a Python identifier")
            if type(s.controller) is not type(next(iter(scenario.values())).controller):
                raise ParameterError(f"scenario[{label!r}]: every set-up must use the same law type")
            setups[label] = s
    else:
        raise ParameterError(
            f"scenario must be a landing.scenarios.Scenario or a dict of them by label, got {type(scenario).__name__}")
    first = next(iter(setups.values()))
    if optimizer != "cma":
        raise ParameterError(f"optimizer = {optimizer!r} is not one of ('cma',)")
    # before any long work, and so that an interrupt during the import leaves the process able to tune
    cma = import_extra("cma", 'landing.tune needs the cma package: pip install "landing[tune]"')
    cases = integer("cases", cases, minimum=1, cap="max_cases")
    budget = integer("budget", budget, minimum=1)
    seed = integer("seed", seed, minimum=0, maximum=2**32 - 1)  # CMA-ES's own seed is seed + 1
    if popsize is not None:
        popsize = integer("popsize", popsize, minimum=2)
    sigma0 = real("sigma0", sigma0, positive=True)
    if sigma0 > 1:
        raise ParameterError(f"sigma0 = {sigma0:g} violates sigma0 <= 1")
    # every set-up's run options, with nothing recorded but the metrics, checked once
    run = {label: s.options.replace(record_every=0, threads=threads) for label, s in setups.items()}
    specs = _parse_gains(gains, first.controller)
    for label, s in setups.items():
        both = [g.name for g in specs if f"controller.{g.name}" in s.dispersions]
        if both:
            where = f"scenario[{label!r}]" if label else "the scenario"
            raise ParameterError(f"gains: {both[0]!r} is tuned and {where} disperses it (controller.{both[0]}): "
                                 "tune it or disperse it")
    mss = isinstance(first.controller, controllers.FixedTimeMSS)

    metric_names: list[str] = []
    bound_names: list[str] = list(BOUND_NAMES) if mss else []
    for label, s in setups.items():
        prefix = f"{label}." if label else ""
        metric_names += [prefix + m for m in _probe_metric_names(s)]
        if mss and label:
            bound_names += [prefix + b for b in BOUND_NAMES]
    objs_in = list(objective) if isinstance(objective, (list, tuple)) else [objective]
    if not objs_in:
        raise ParameterError("objective = [] must name at least one objective")
    objs = [o if isinstance(o, Expression) else _term(o, "objective", metric_names, bound_names) for o in objs_in]
    one = isinstance(constraints, (str, bytes)) or callable(constraints)
    cons = [_term(c, "constraint", metric_names, bound_names) for c in ([constraints] if one else constraints)]
    need_bounds = mss and any(isinstance(e, UserFunction) or any(n.rpartition(".")[2] in BOUND_NAMES for n in e.names)
                              for e in [*objs, *cons])

    K = int(cases)
    x0s = {label: s.initial_states(K, seed=int(seed)) for label, s in setups.items()}
    dim = len(specs)
    rng = np.random.default_rng(int(seed))
    copts: dict[str, Any] = {
        "bounds": [0.0, 1.0], "verbose": -9, "randn": lambda *shape: rng.standard_normal(shape),
        "seed": int(seed) + 1, "tolfun": 0.0, "tolfunhist": 0.0, "tolflatfitness": 10**9,
        "maxfevals": int(budget),
    }
    if popsize is not None:
        copts["popsize"] = int(popsize)
    if start is not None:
        u0 = [specs[j].encode(float(start[g.name])) if g.name in start else 0.5 for j, g in enumerate(specs)]
        u0 = [float(u) for u in np.clip(u0, 0.0, 1.0)]
    else:
        u0 = [0.5] * dim
    if dim == 1:
        # cma's bounded search needs two coordinates: a second one is searched and ignored
        u0 = u0 + [0.5]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        es = cma.CMAEvolutionStrategy(u0, float(sigma0), copts)
    lam = int(es.popsize)
    if start is not None:
        # the start itself is evaluated in the first generation (CMA-ES's injection)
        es.inject([np.asarray(u0, dtype=float)], force=True)

    generations: list[_Generation] = []
    interrupted = False
    stop = "budget"
    t0 = time.perf_counter()
    if progress is None:
        progress = budget * K * sum(s.t_final / s.dt for s in setups.values()) > 2e8
    bar = ProgressBar(int(budget), label=f"tuning {first.name}", unit="candidate") if progress else None
    done = 0
    try:
        while done < budget:
            if es.stop():
                stop = "converged (" + ", ".join(sorted(es.stop())) + ")"
                break
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                us = es.ask()
            # the last generation is cut to the budget; CMA-ES is not told about it
            U = np.asarray(us[: budget - done], dtype=float)[:, :dim]
            G = np.column_stack([specs[j].decode(U[:, j]) for j in range(dim)])
            per_setup = {label: _evaluate(s, specs, G, x0s[label], K, int(seed), run[label])
                         for label, s in setups.items()}
            bounds = _generation_bounds(setups, specs, G) if need_bounds else None
            gen = _Generation(len(generations), G, *_score(per_setup, bounds, objs, cons))
            generations.append(gen)
            done += gen.size
            if bar:
                bar.update(gen.size)
            if gen.size == len(us):
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    es.tell(us, list(ranks(gen.objectives, gen.violation, gen.feasible)))
    except KeyboardInterrupt:
        interrupted = True
        stop = "interrupted"
    finally:
        if bar:
            bar.close()
    if not generations:
        if interrupted:
            raise KeyboardInterrupt("tuning interrupted before its first generation completed")
        raise ParameterError(f"budget = {budget} gave no evaluation")  # pragma: no cover
    X = np.vstack([gen.gains for gen in generations])
    obj = np.vstack([gen.objectives for gen in generations])
    C = np.vstack([gen.constraints for gen in generations]) if cons else np.zeros((X.shape[0], 0))
    V = np.concatenate([gen.violation for gen in generations])
    F = np.concatenate([gen.feasible for gen in generations])
    best, front = best_and_front(obj, V, F)
    return TuneResult(
        base=first, gains=specs, objectives=tuple(e.text for e in objs),
        constraints=tuple(e.text for e in cons), seed=int(seed), cases=K, budget=int(budget), popsize=lam,
        x=X, generation=np.concatenate([np.full(gen.size, gen.index) for gen in generations]),
        objective_values=obj, constraint_values=C, diverged=np.concatenate([gen.diverged for gen in generations]),
        violation=V, feasible=F, best=best, front=front,
        interrupted=interrupted, stop=stop, elapsed=time.perf_counter() - t0,
        setups={k: v for k, v in setups.items() if k},
    )


@dataclass(frozen=True)
class _Generation:
    """One generation's evaluations, in the order CMA-ES asked for them."""

    index: int
    #: (P, G) the candidates' gain sets
    gains: np.ndarray
    #: (P, M) the objectives
    objectives: np.ndarray
    #: (P, C) the constraints' margins, met when <= 0
    constraints: np.ndarray
    #: (P,) the share of each candidate's cases that diverged
    diverged: np.ndarray
    #: (P,) the total violation Deb's rules rank infeasible candidates by (0: feasible)
    violation: np.ndarray

    @property
    def size(self) -> int:
        return int(self.gains.shape[0])

    @property
    def feasible(self) -> np.ndarray:
        return self.violation == 0


def _generation_bounds(setups: Mapping[str, Scenario], specs: tuple[GainSpec, ...],
                       G: np.ndarray) -> dict[str, np.ndarray]:
    """Every candidate's bounds by name ((P,) each): a set-up's under ``label.name``, the
    first set-up's also under the bare names."""
    bounds: dict[str, np.ndarray] = {}
    for label, s in setups.items():
        law_p = s.controller.replace(**{sp.name: G[:, j] for j, sp in enumerate(specs)})
        b = _bounds_for(s, law_p) or {}
        if label:
            bounds.update({f"{label}.{k}": v for k, v in b.items()})
        if not bounds.keys() & set(BOUND_NAMES):
            bounds.update(b)
    return bounds


def _score(per_setup: Mapping[str, list[Metrics]], bounds: Optional[Mapping[str, np.ndarray]],
           objs: Sequence[Union[Expression, UserFunction]],
           cons: Sequence[Union[Expression, UserFunction]]) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The objectives (P, M), constraint margins (P, C), diverged shares (P,) and total
    violations (P,) of a generation's candidates (module docstring: Deb's rules)."""
    P = len(next(iter(per_setup.values())))
    o = np.full((P, len(objs)), np.nan)
    c = np.full((P, len(cons)), np.nan)
    div = np.zeros(P)
    viol = np.zeros(P)
    for i in range(P):
        env: dict[str, Any] = {}
        for label, ms in per_setup.items():
            env.update({(f"{label}.{k}" if label else k): v for k, v in ms[i].items()})
        b_i = {k: float(v[i]) for k, v in bounds.items()} if bounds is not None else None
        if b_i:
            env.update(b_i)
        env["__metrics__"] = per_setup[""][i] if "" in per_setup else {k: v[i] for k, v in per_setup.items()}
        env["__bounds__"] = b_i
        div[i] = float(np.mean(np.concatenate([ms[i]["diverged"] for ms in per_setup.values()])))
        for j, e in enumerate(objs):
            o[i, j] = e.value(env)
            if not math.isfinite(o[i, j]):
                viol[i] += 1e6
        for j, e in enumerate(cons):
            c[i, j] = e.value(env)
            if not math.isfinite(c[i, j]):
                viol[i] += 1e6
            elif c[i, j] > 0 or (c[i, j] == 0 and e.op in ("<", ">")):
                viol[i] += max(c[i, j], 1e-300) / e.last_scale
        viol[i] += div[i]
    return o, c, div, viol


def _evaluate(scenario: Scenario, specs: tuple[GainSpec, ...], G: np.ndarray, x0_cases: np.ndarray, K: int,
              seed: int, options: RunOptions) -> list[Metrics]:
    """Every candidate (row of G) on the K cases of one set-up: one Metrics per candidate."""
    P = G.shape[0]
    # the dispersed parameters' draws for the K cases, the same for every candidate
    draws = scenario.parameter_draws(0, K, seed)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DivergenceWarning)
        if _is_random(scenario.disturbance):
            scenario = scenario.with_draws(draws)
            out = []
            for i in range(P):
                law = scenario.controller.replace(**{s.name: float(G[i, j]) for j, s in enumerate(specs)})
                out.append(_run(scenario, law, x0_cases, seed, options).metrics)
            return out
        # one batch of P x K cases: candidate i's are rows i K .. (i + 1) K, each with the K draws
        scenario = scenario.with_draws({k: np.tile(v, (P, 1)) for k, v in draws.items()})
        law = scenario.controller.replace(
            **{s.name: _per_case(np.repeat(G[:, j], K), _column_shape(scenario.controller, s.name))
               for j, s in enumerate(specs)})
        res = _run(scenario, law, np.tile(x0_cases, (P, 1)), seed, options)
    return [res.metrics.cases(i * K, (i + 1) * K) for i in range(P)]


def _run(scenario: Scenario, law: controllers.Controller, x0: np.ndarray, seed: int,
         options: RunOptions) -> SimulationResult:
    """One batch of a set-up's cases under another law."""
    return simulate_batch(scenario.plant, law, x0, seed=seed, **scenario.run_options(**options.keywords()))
