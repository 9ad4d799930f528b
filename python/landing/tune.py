"""Gain tuning with the batch engine: :func:`tune` searches a law's gains with CMA-ES.

Each generation's population of candidate gain sets runs as one batch (per-case gains): every
candidate on the same K dispersed cases (common random numbers: the same initial states and the
same random-stream case indices for every candidate; with a random disturbance, whose streams
the engine keys by the case's index in its batch, each candidate runs as its own batch of the K
cases instead). Several set-ups may share the gains (``{"nominal": s1, "storm": s2}``: one batch
per set-up and generation; expressions name ``nominal.fuel_used``). Objectives and constraints
are written as small expressions over the per-case metrics (:class:`landing.Metrics` columns),
their aggregates and the theory's bounds, or as Python callables.

The search runs in the unit cube, one coordinate per gain mapped linearly or log10-linearly onto
its (low, high), kept inside by CMA-ES's boundary transformation; the seed drives CMA-ES's
normal draws through a ``numpy.random.Generator`` of its own (no global state).

The expression grammar (parsed with :mod:`ast`, then walked node by node; nothing is ``eval``-ed):

- numbers; the names of metric columns (``fuel_used``, ``peak_command``, ``final_error``...,
  one value per case, or per case and axis); the bound names (FixedTimeMSS laws only):
  ``t1``, ``t2`` (seed 001 eq. 18, 26), ``s1_radius``, ``s1_time``, ``s2_radius``, ``s2_time``,
  ``settle_bound`` (the sound total s2_time + s1_time), each the largest over the axes, computed
  with the scenario's disturbance bound and ``theta`` (0.5, 0.5 when the scenario has none);
- ``+ - * / **``, unary ``-``, the comparisons ``< <= > >=`` (true/false per case inside an
  aggregate, e.g. ``mean(touchdown_speed < 1)``);
- element-wise ``abs``, ``sqrt``, ``log``, ``log10``, ``exp``;
- aggregates over the cases (and axes): ``mean``, ``max``, ``min``, ``std``, ``median``,
  ``sum``, ``all``, ``any``, ``percentile(x, q)`` with q a number in [0, 100]. A NaN (a case that
  never settles...) makes the aggregate NaN.

An objective must reduce to one number per candidate (``"mean(fuel_used)"``); every objective is
minimised (write ``-mean(x)`` to maximise). A constraint is one comparison whose sides reduce
to one number each (``"max(peak_command) <= 40e3"``, ``"abs(t1 - 74.578) <= 1e-3"``).

Constraint handling: Deb's feasibility rules. A candidate is feasible when every constraint
holds, no case diverged and its objectives are numbers. Within a generation feasible candidates
rank before infeasible ones, feasible ones by objective (by Pareto layer, then crowding, for
several objectives), infeasible ones by their total violation: the sum over the broken constraints of the margin
(``lhs - rhs`` for ``<``, ``<=``; ``rhs - lhs`` for ``>``, ``>=``) over ``|rhs|`` (1 where rhs
is 0), plus the fraction of diverged cases, plus 1e6 per NaN constraint or objective. CMA-ES
only uses the ranks, which are what it is told.

Several objectives: CMA-ES ranks by non-dominated sorting; the result's front is the Pareto
front of all feasible evaluations, not the output of a dedicated multi-objective algorithm.
"""

from __future__ import annotations

import ast
import math
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Mapping, Optional, Sequence, Union

import numpy as np

from landing import controllers, disturbances
from landing.errors import DivergenceWarning, ParameterError
from landing.scenarios import Scenario
from landing._internal.args import integer, real
from landing.results import Metrics, SimulationResult
from landing.simulation import RunOptions, simulate_batch

__all__ = ["Expression", "TuneResult", "tune", "pareto_front", "BOUND_NAMES"]

#: Bound names an expression may use (FixedTimeMSS laws).
BOUND_NAMES = ("t1", "t2", "s1_radius", "s1_time", "s2_radius", "s2_time", "settle_bound")

_ELEMENTWISE: dict[str, Callable[[Any], Any]] = {
    "abs": np.abs, "sqrt": np.sqrt, "log": np.log, "log10": np.log10, "exp": np.exp,
}
_AGGREGATES: dict[str, Callable[[Any], Any]] = {
    "mean": np.mean, "max": np.max, "min": np.min, "std": np.std, "median": np.median,
    "sum": np.sum, "all": np.all, "any": np.any,
}
_BINOPS: dict[type, Callable[[Any, Any], Any]] = {
    ast.Add: np.add, ast.Sub: np.subtract, ast.Mult: np.multiply, ast.Div: np.divide, ast.Pow: np.power,
}
_CMPOPS: dict[type, tuple[str, Callable[[Any, Any], Any]]] = {
    ast.Lt: ("<", np.less), ast.LtE: ("<=", np.less_equal), ast.Gt: (">", np.greater),
    ast.GtE: (">=", np.greater_equal),
}

ObjectiveLike = Union[str, Callable[[Metrics, Optional[Mapping[str, float]]], float]]


class Expression:
    """An objective or constraint parsed from the grammar of this module.

    ``Expression(text, metric_names, bound_names, kind)`` refuses (ParameterError naming the
    expression) unknown names, anything outside the grammar, an objective that does not reduce
    to one number, and a constraint that is not one comparison."""

    def __init__(self, text: str, metric_names: Sequence[str], bound_names: Sequence[str] = (),
                 kind: str = "objective"):
        if not isinstance(text, str):
            raise ParameterError(f"{kind} = {text!r} must be an expression string or a callable")
        self.text = text
        self.kind = kind
        self._metrics = set(metric_names)
        self._bounds = set(bound_names)
        try:
            tree = ast.parse(text.strip(), mode="eval")
        except SyntaxError as exc:
            raise ParameterError(f"{kind} = {text!r} is not a valid expression ({exc.msg})") from None
        self.names: set[str] = set()
        body = tree.body
        if kind == "constraint":
            if not (isinstance(body, ast.Compare) and len(body.ops) == 1 and type(body.ops[0]) in _CMPOPS):
                raise ParameterError(
                    f"constraint = {text!r} violates the rule: one comparison with <, <=, > or >= "
                    "(for an equality write abs(lhs - rhs) <= tol)"
                )
            self.op = _CMPOPS[type(body.ops[0])][0]
            for side in (body.left, body.comparators[0]):
                if self._check(side):
                    raise ParameterError(
                        f"constraint = {text!r}: each side must reduce to one number per candidate "
                        f"(aggregate the per-case metrics with mean, max, min, percentile...)"
                    )
            self.lhs, self.rhs = body.left, body.comparators[0]
        else:
            if self._check(body):
                raise ParameterError(
                    f"objective = {text!r} must reduce to one number per candidate (aggregate the "
                    f"per-case metrics with mean, max, min, percentile...)"
                )
            self.body = body

    def _refuse(self, node: ast.AST, why: str) -> ParameterError:
        return ParameterError(f"{self.kind} = {self.text!r}: {why} (at {ast.unparse(node)!r})")

    def _check(self, node: ast.AST) -> bool:
        """Validates ``node``; returns whether it is per case (True) or one number (False)."""
        if isinstance(node, ast.Constant):
            if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
                raise self._refuse(node, "only numbers are allowed as constants")
            return False
        if isinstance(node, (ast.Name, ast.Attribute)):
            key = _qualified(node)
            if key is None:
                raise self._refuse(node, "only NAME or SETUP.NAME may be named")
            if key in self._metrics:
                self.names.add(key)
                return True
            if key in self._bounds:
                self.names.add(key)
                return False
            if key.rpartition(".")[2] in BOUND_NAMES:
                raise self._refuse(node, f"the bound {key!r} is defined for FixedTimeMSS laws only")
            raise self._refuse(
                node, f"unknown name {key!r} (metrics: {', '.join(sorted(self._metrics))}; "
                f"bounds: {', '.join(sorted(self._bounds)) or 'none for this law'})"
            )
        if isinstance(node, ast.BinOp):
            if type(node.op) not in _BINOPS:
                raise self._refuse(node, "only + - * / ** are allowed")
            return self._check(node.left) | self._check(node.right)
        if isinstance(node, ast.UnaryOp):
            if not isinstance(node.op, (ast.USub, ast.UAdd)):
                raise self._refuse(node, "only unary - and + are allowed")
            return self._check(node.operand)
        if isinstance(node, ast.Compare):
            if len(node.ops) != 1 or type(node.ops[0]) not in _CMPOPS:
                raise self._refuse(node, "one comparison with <, <=, > or >= at a time")
            return self._check(node.left) | self._check(node.comparators[0])
        if isinstance(node, ast.Call):
            if not isinstance(node.func, ast.Name) or node.keywords:
                raise self._refuse(node, "only calls of the grammar's functions, with positional arguments")
            f = node.func.id
            if f in _ELEMENTWISE:
                if len(node.args) != 1:
                    raise self._refuse(node, f"{f} takes one argument")
                return self._check(node.args[0])
            if f in _AGGREGATES:
                if len(node.args) != 1:
                    raise self._refuse(node, f"{f} takes one argument")
                self._check(node.args[0])
                return False
            if f == "percentile":
                if len(node.args) != 2:
                    raise self._refuse(node, "percentile takes (x, q)")
                q = node.args[1]
                if not (isinstance(q, ast.Constant) and isinstance(q.value, (int, float))
                        and not isinstance(q.value, bool) and 0 <= q.value <= 100):
                    raise self._refuse(node, "percentile's q must be a number in [0, 100]")
                self._check(node.args[0])
                return False
            raise self._refuse(
                node, f"unknown function {f!r} (functions: "
                f"{', '.join(sorted([*_ELEMENTWISE, *_AGGREGATES, 'percentile']))})"
            )
        raise self._refuse(node, f"{type(node).__name__} is outside the grammar")

    def _eval(self, node: ast.AST, env: Mapping[str, Any]) -> Any:
        if isinstance(node, ast.Constant):
            return float(node.value)
        if isinstance(node, (ast.Name, ast.Attribute)):
            return env[_qualified(node)]
        if isinstance(node, ast.BinOp):
            return _BINOPS[type(node.op)](self._eval(node.left, env), self._eval(node.right, env))
        if isinstance(node, ast.UnaryOp):
            v = self._eval(node.operand, env)
            return np.negative(v) if isinstance(node.op, ast.USub) else v
        if isinstance(node, ast.Compare):
            return _CMPOPS[type(node.ops[0])][1](self._eval(node.left, env), self._eval(node.comparators[0], env))
        assert isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
        f = node.func.id
        x = np.asarray(self._eval(node.args[0], env), dtype=float)
        if f in _ELEMENTWISE:
            return _ELEMENTWISE[f](x)
        if f == "percentile":
            return float(np.percentile(x, float(node.args[1].value)))  # type: ignore[attr-defined]
        return float(_AGGREGATES[f](x))

    def value(self, env: Mapping[str, Any]) -> float:
        """The objective's value, or for a constraint its margin ``lhs - rhs`` (``<``, ``<=``)
        or ``rhs - lhs`` (``>``, ``>=``): satisfied when <= 0 (< 0 for strict ones)."""
        with np.errstate(all="ignore"):
            if self.kind != "constraint":
                return float(np.asarray(self._eval(self.body, env), dtype=float).reshape(-1)[0])
            lhs = float(np.asarray(self._eval(self.lhs, env), dtype=float).reshape(-1)[0])
            rhs = float(np.asarray(self._eval(self.rhs, env), dtype=float).reshape(-1)[0])
        self.last_scale = abs(rhs) if rhs != 0 and math.isfinite(rhs) else 1.0
        return lhs - rhs if self.op in ("<", "<=") else rhs - lhs

    def __repr__(self) -> str:
        return f"Expression({self.text!r})"


def _qualified(node: ast.AST) -> Optional[str]:
    """``name`` or ``setup.name``; None for anything else."""
    if isinstance(node, ast.Name):
        return node.id
    if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name):
        return f"{node.value.id}.{node.attr}"
    return None


class _Callable:
    """A user's callable objective or constraint: ``f(metrics, bounds) -> float``; a constraint
    callable returns its margin, satisfied when <= 0."""

    def __init__(self, f: Callable[..., float], kind: str):
        self.f = f
        self.kind = kind
        self.text = getattr(f, "__name__", repr(f))
        self.op = "<="
        self.last_scale = 1.0

    def value(self, env: Mapping[str, Any]) -> float:
        return float(self.f(env["__metrics__"], env["__bounds__"]))


@dataclass(frozen=True)
class GainSpec:
    """One searched gain: its law parameter name, bounds and scale (``"linear"`` or ``"log"``)."""

    name: str
    low: float
    high: float
    scale: str = "linear"

    def decode(self, u: np.ndarray) -> np.ndarray:
        """From the search's unit coordinate to the gain."""
        u = np.clip(u, 0.0, 1.0)
        if self.scale == "log":
            return 10 ** (math.log10(self.low) + u * (math.log10(self.high) - math.log10(self.low)))
        return self.low + u * (self.high - self.low)

    def encode(self, g: float) -> float:
        if self.scale == "log":
            return (math.log10(g) - math.log10(self.low)) / (math.log10(self.high) - math.log10(self.low))
        return (g - self.low) / (self.high - self.low)


@dataclass(eq=False)
class TuneResult:
    """What :func:`tune` found, with every evaluation.

    Attributes
    ----------
    base : the scenario tuned (with its original gains); the first set-up for several.
    gains : the searched gains' specifications.
    objectives, constraints : their texts (or callables' names).
    seed, cases, budget, popsize : the run's settings.
    x : (E, G) the evaluated gain sets, in the order of ``gains``.
    generation : (E,) the generation of each evaluation (0 first).
    objective_values : (E, M).
    constraint_values : (E, C) margins, satisfied when <= 0 (see :meth:`Expression.value`).
    diverged : (E,) the fraction of each candidate's cases that diverged.
    violation : (E,) the total violation by which infeasible candidates are ranked (0: feasible).
    feasible : (E,) bool.
    best : index of the best evaluation (single objective: the feasible one with the least
        objective, else the least violation; several: the front's member with the least first
        objective).
    front : indices of the Pareto front of the feasible evaluations (the best alone for one
        objective).
    interrupted : True when Ctrl-C stopped the search; the rest is what was done so far.
    stop : why the search ended.
    elapsed : seconds.
    """

    base: Scenario
    gains: tuple[GainSpec, ...]
    objectives: tuple[str, ...]
    constraints: tuple[str, ...]
    seed: int
    cases: int
    budget: int
    popsize: int
    x: np.ndarray
    generation: np.ndarray
    objective_values: np.ndarray
    constraint_values: np.ndarray
    diverged: np.ndarray
    violation: np.ndarray
    feasible: np.ndarray
    best: int
    front: np.ndarray
    interrupted: bool = False
    stop: str = ""
    elapsed: float = 0.0
    #: the other set-ups by label, when several were tuned together (``base`` is the first)
    setups: dict[str, Scenario] = field(default_factory=dict)

    @property
    def n_evaluations(self) -> int:
        return int(self.x.shape[0])

    @property
    def gain_names(self) -> tuple[str, ...]:
        return tuple(g.name for g in self.gains)

    def gains_of(self, index: int) -> dict[str, float]:
        """Evaluation ``index``'s gains by name."""
        return {g.name: float(self.x[index, j]) for j, g in enumerate(self.gains)}

    @property
    def best_gains(self) -> dict[str, float]:
        return self.gains_of(self.best)

    @property
    def best_feasible(self) -> bool:
        return bool(self.feasible[self.best])

    @property
    def best_objectives(self) -> dict[str, float]:
        return {o: float(self.objective_values[self.best, j]) for j, o in enumerate(self.objectives)}

    @property
    def best_constraints(self) -> dict[str, float]:
        return {c: float(self.constraint_values[self.best, j]) for j, c in enumerate(self.constraints)}

    def unmet(self, index: Optional[int] = None) -> list[str]:
        """The constraints evaluation ``index`` (default: the best) does not meet, plus
        "diverged cases" when some of its cases diverged."""
        i = self.best if index is None else index
        out = [c for j, c in enumerate(self.constraints)
               if not (self.constraint_values[i, j] <= 0)]
        if self.diverged[i] > 0:
            out.append(f"diverged cases ({self.diverged[i]:.0%})")
        return out

    def scenario(self, index: Optional[int] = None, setup: Optional[str] = None) -> Scenario:
        """The tuned scenario: the base (or set-up ``setup``) with the best gains (or evaluation
        ``index``'s)."""
        g = self.best_gains if index is None else self.gains_of(index)
        s = self.base if setup is None else self.setups[setup]
        return s.replace(controller=g)

    def best_so_far(self) -> np.ndarray:
        """(generations,) the best objective (the first) among the feasible evaluations up to
        each generation (NaN before the first feasible one)."""
        n = int(self.generation.max()) + 1 if self.generation.size else 0
        out = np.full(n, np.nan)
        cur = np.inf
        for g in range(n):
            sel = (self.generation == g) & self.feasible
            if sel.any():
                cur = min(cur, float(np.min(self.objective_values[sel, 0])))
            out[g] = cur if math.isfinite(cur) else np.nan
        return out

    def table(self) -> dict[str, np.ndarray]:
        """Every evaluation as columns: generation, each gain, each objective ("objective_j"),
        each constraint's margin ("constraint_j"), diverged, violation, feasible."""
        cols: dict[str, np.ndarray] = {"generation": self.generation}
        for j, g in enumerate(self.gains):
            cols[g.name] = self.x[:, j]
        for j in range(len(self.objectives)):
            cols[f"objective_{j}"] = self.objective_values[:, j]
        for j in range(len(self.constraints)):
            cols[f"constraint_{j}"] = self.constraint_values[:, j]
        cols["diverged"] = self.diverged
        cols["violation"] = self.violation
        cols["feasible"] = self.feasible
        return cols

    def write(self, folder: Union[str, Path]) -> list[Path]:
        """Writes ``evaluations.parquet`` (pyarrow present) or ``evaluations.csv``, the tuned
        scenario ``tuned.toml`` and ``summary.txt`` (with the column legend) into ``folder``."""
        out = Path(folder)
        out.mkdir(parents=True, exist_ok=True)
        cols = self.table()
        written = []
        try:
            import pyarrow as pa
            import pyarrow.parquet as pq

            path = out / "evaluations.parquet"
            pq.write_table(pa.table({k: np.asarray(v) for k, v in cols.items()}), path)
        except ImportError:
            path = out / "evaluations.csv"
            names = list(cols)
            rows = np.column_stack([np.asarray(cols[k], dtype=float) for k in names])
            np.savetxt(path, rows, delimiter=",", header=",".join(names), comments="", fmt="%.17g")
        written.append(path)
        toml = out / "tuned.toml"
        toml.write_text(self.scenario().to_toml(), encoding="utf-8")
        written.append(toml)
        summary = out / "summary.txt"
        legend = [f"objective_{j}: {o}" for j, o in enumerate(self.objectives)]
        legend += [f"constraint_{j}: {c} (margin, met when <= 0)" for j, c in enumerate(self.constraints)]
        summary.write_text(str(self) + "\n\ncolumns:\n  " + "\n  ".join(legend) + "\n", encoding="utf-8")
        written.append(summary)
        return written

    def __str__(self) -> str:
        b = self.best
        lines = [
            f"tuning {self.base.name}: {self.n_evaluations} evaluations of {self.cases} case"
            f"{'s' if self.cases != 1 else ''} each, seed {self.seed}, {int(self.feasible.sum())} feasible"
            + (", interrupted" if self.interrupted else "") + f" ({self.stop}, {self.elapsed:.1f} s)",
            "best gains: " + ", ".join(f"{k}={v:.6g}" for k, v in self.best_gains.items()),
        ]
        for o, v in self.best_objectives.items():
            lines.append(f"  {o} = {v:.6g}")
        for j, c in enumerate(self.constraints):
            m = self.constraint_values[b, j]
            lines.append(f"  {c}: {'met' if m <= 0 else 'NOT met'} (margin {m:.4g})")
        lines.append(f"  feasible: {self.best_feasible}" + ("" if self.best_feasible else
                                                              f"; unmet: {'; '.join(self.unmet())}"))
        if len(self.objectives) > 1:
            lines.append(f"  Pareto front of the feasible evaluations: {self.front.size} points")
        return "\n".join(lines)


def _parse_gains(gains: Mapping[str, Any], law: controllers.Controller) -> tuple[GainSpec, ...]:
    if not isinstance(gains, Mapping) or not gains:
        raise ParameterError(f"gains = {gains!r} must be a non-empty dict {{name: (low, high)}}")
    import dataclasses

    names = {f.name for f in dataclasses.fields(law)}
    out = []
    for name, spec in gains.items():
        if name not in names:
            raise ParameterError(
                f"gains: {name!r} is not a parameter of {type(law).__name__} (its parameters: {sorted(names)})"
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
    if disturbance is None:
        return False
    parts = disturbance.components() if hasattr(disturbance, "components") else list(disturbance)
    return any(isinstance(p, (disturbances.UniformNoise, disturbances.CommandNoise)) for p in parts)


def _column_shape(law: controllers.Controller, name: str) -> bool:
    """Whether the law reads ``name`` per axis, so that a per-case gain must be given as
    (N, 1) (a 1-D array of length D would be read per axis); scalar parameters take (N,)."""
    from landing.errors import LandingError

    try:
        law.replace(**{name: np.ones((2, 1))})
        return True
    except LandingError:
        return False


def _per_case(value: np.ndarray, column: bool) -> np.ndarray:
    return np.ascontiguousarray(value.reshape(-1, 1) if column else value.reshape(-1))


def _bounds_for(scenario: Scenario, law: controllers.Controller) -> Optional[dict[str, np.ndarray]]:
    """The bound names per candidate ((P,) arrays, the largest over the axes), or None."""
    if not isinstance(law, controllers.FixedTimeMSS):
        return None
    from landing import theory

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


def pareto_front(values: np.ndarray) -> np.ndarray:
    """Indices of the non-dominated rows of ``values`` (E, M), every column minimised (rows with
    a NaN are left out)."""
    v = np.asarray(values, dtype=float)
    ok = np.flatnonzero(np.all(np.isfinite(v), axis=1))
    keep = []
    for i in ok:
        dominated = np.any(np.all(v[ok] <= v[i], axis=1) & np.any(v[ok] < v[i], axis=1))
        if not dominated:
            keep.append(i)
    return np.asarray(keep, dtype=int)


def _layers(values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Non-dominated sorting: layer (0 best) and crowding distance of each row."""
    n = values.shape[0]
    layer = np.full(n, -1)
    crowd = np.zeros(n)
    remaining = np.arange(n)
    k = 0
    while remaining.size:
        f = remaining[pareto_front(values[remaining])]
        if f.size == 0:
            f = remaining
        layer[f] = k
        for m in range(values.shape[1]):
            order = f[np.argsort(values[f, m], kind="stable")]
            span = values[order[-1], m] - values[order[0], m]
            crowd[order[0]] = crowd[order[-1]] = np.inf
            if span > 0:
                crowd[order[1:-1]] += (values[order[2:], m] - values[order[:-2], m]) / span
        remaining = np.setdiff1d(remaining, f)
        k += 1
    return layer, crowd


def _ranks(obj: np.ndarray, violation: np.ndarray, feasible: np.ndarray) -> np.ndarray:
    """Deb's rules as ranks (0 best) within a generation."""
    n = obj.shape[0]
    if obj.shape[1] == 1:
        primary = np.where(feasible, 0, 1)
        key2 = np.where(feasible, obj[:, 0], violation)
        order = np.lexsort((np.arange(n), key2, primary))
    else:
        key1 = np.full(n, np.inf)
        key2 = np.where(feasible, 0.0, violation)
        fi = np.flatnonzero(feasible)
        if fi.size:
            layer, crowd = _layers(obj[fi])
            key1[fi] = layer
            key2[fi] = -crowd
        primary = np.where(feasible, 0, 1)
        order = np.lexsort((np.arange(n), key2, key1, primary))
    ranks = np.empty(n)
    ranks[order] = np.arange(n, dtype=float)
    return ranks


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
    scenario : the set-up; its dispersion (if any) draws the K cases with ``seed``. Or several
        set-ups by label, ``{"nominal": s1, "storm": s2}``, whose laws share the searched gains:
        every candidate runs on each, and the expressions name their metrics and bounds
        ``nominal.fuel_used``, ``storm.s1_radius`` (``t1``, ``t2``... alone: the first set-up's).
    gains : ``{name: (low, high)}`` or ``{name: (low, high, "log")}``, law parameters shared by
        every axis; the search runs in [0, 1] per gain (log10-mapped on a log scale), bounded
        by CMA-ES's boundary transformation.
    objective : an expression (module docstring) or a callable ``f(metrics, bounds) -> float``
        (metrics: the candidate's K cases, a dict of them by label for several set-ups; bounds:
        a dict of the bound names, or None), or a list of them (several objectives, every one
        minimised).
    constraints : expressions (one comparison each) or callables returning a margin that is
        met when <= 0. A candidate with a diverged case is infeasible.
    cases : K, the dispersed cases every candidate runs on (the same for all: common random
        numbers).
    budget : the most candidate evaluations (each runs K cases on every set-up).
    seed : seeds the cases (dispersion and random streams) and the search: the same seed gives
        the same evaluations and result, whatever ``threads``.
    optimizer : ``"cma"`` (the only one).
    popsize : candidates per generation (default: CMA-ES's 4 + 3 ln(number of gains)).
    sigma0 : initial step in the unit coordinates.
    start : the initial mean's gains (default: the middle of the box); the start itself is
        one of the first generation's candidates.
    threads : worker threads of the batches (default: all cores).
    progress : show progress on stderr (default: when the run is long).

    Each generation runs as one batch of popsize x K cases per set-up, with per-case gains.
    When a set-up's disturbance draws random numbers, the engine keys them by the case's index
    in the batch, so one batch cannot give every candidate the same streams: then each
    candidate runs as its own batch of K cases (same seed, same case indices).

    Ctrl-C between or during generations stops the search and returns what was done so far,
    with ``interrupted=True``.
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
    try:
        import cma
    except ImportError:  # pragma: no cover - depends on the installation
        raise ImportError("landing.tune needs the cma package: pip install cma (or landing[tune])") from None
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
    objs = [o if isinstance(o, Expression) else
            (_Callable(o, "objective") if callable(o) else Expression(o, metric_names, bound_names, "objective"))
            for o in objs_in]
    if isinstance(constraints, (str, bytes)) or callable(constraints):
        constraints = [constraints]  # type: ignore[list-item]
    cons = [(_Callable(c, "constraint") if callable(c) else Expression(c, metric_names, bound_names, "constraint"))
            for c in constraints]
    need_bounds = mss and any(isinstance(e, _Callable) or any(n.rpartition(".")[2] in BOUND_NAMES for n in e.names)
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

    xs: list[np.ndarray] = []
    gens: list[np.ndarray] = []
    ov: list[np.ndarray] = []
    cv: list[np.ndarray] = []
    dv: list[np.ndarray] = []
    vv: list[np.ndarray] = []
    fv: list[np.ndarray] = []
    interrupted = False
    stop = "budget"
    t0 = time.perf_counter()
    if progress is None:
        progress = budget * K * sum(s.t_final / s.dt for s in setups.values()) > 2e8
    bar = None
    if progress:
        from landing._internal.progress import ProgressBar

        bar = ProgressBar(int(budget), label=f"tuning {first.name}")
        bar._bar.unit = "candidate"
        bar._bar.refresh()
    done = 0
    g = 0
    try:
        while done < budget:
            if es.stop():
                stop = "converged (" + ", ".join(sorted(es.stop())) + ")"
                break
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                us = es.ask()
            p = len(us)
            # the last generation is cut to the budget; CMA-ES is not told about it
            U = np.asarray(us[: budget - done], dtype=float)[:, :dim]
            G = np.column_stack([specs[j].decode(U[:, j]) for j in range(dim)])
            P = G.shape[0]
            per_setup = {label: _evaluate(s, specs, G, x0s[label], K, int(seed), run[label])
                         for label, s in setups.items()}
            bounds: dict[str, np.ndarray] = {}
            if need_bounds:
                for label, s in setups.items():
                    law_p = s.controller.replace(**{sp.name: G[:, j] for j, sp in enumerate(specs)})
                    b = _bounds_for(s, law_p) or {}
                    if label:
                        bounds.update({f"{label}.{k}": v for k, v in b.items()})
                    if not bounds.keys() & set(BOUND_NAMES):
                        bounds.update(b)
            o = np.full((P, len(objs)), np.nan)
            c = np.full((P, len(cons)), np.nan)
            div = np.zeros(P)
            viol = np.zeros(P)
            for i in range(P):
                env: dict[str, Any] = {}
                for label, ms in per_setup.items():
                    env.update({(f"{label}.{k}" if label else k): v for k, v in ms[i].items()})
                b_i = {k: float(v[i]) for k, v in bounds.items()} if need_bounds else None
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
            feas = viol == 0
            xs.append(G)
            gens.append(np.full(P, g))
            ov.append(o)
            cv.append(c)
            dv.append(div)
            vv.append(viol)
            fv.append(feas)
            done += P
            if bar:
                bar.update(P)
            if P == p:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    es.tell(us, list(_ranks(o, viol, feas)))
            g += 1
    except KeyboardInterrupt:
        interrupted = True
        stop = "interrupted"
    finally:
        if bar:
            bar.close()
    if not xs:
        if interrupted:
            raise KeyboardInterrupt("tuning interrupted before its first generation completed")
        raise ParameterError(f"budget = {budget} gave no evaluation")  # pragma: no cover
    X = np.vstack(xs)
    O = np.vstack(ov)
    C = np.vstack(cv) if cons else np.zeros((X.shape[0], 0))
    V = np.concatenate(vv)
    F = np.concatenate(fv)
    if len(objs) == 1:
        order = np.lexsort((np.arange(X.shape[0]), np.where(F, O[:, 0], V), ~F))
        best = int(order[0])
        front = np.array([best]) if F[best] else np.zeros(0, dtype=int)
    else:
        fi = np.flatnonzero(F)
        front = fi[pareto_front(O[fi])] if fi.size else np.zeros(0, dtype=int)
        if front.size:
            front = front[np.lexsort((front, O[front, 0]))]
            best = int(front[0])
        else:
            best = int(np.lexsort((np.arange(X.shape[0]), V))[0])
    return TuneResult(
        base=first, gains=specs, objectives=tuple(e.text for e in objs),
        constraints=tuple(e.text for e in cons), seed=int(seed), cases=K, budget=int(budget), popsize=lam,
        x=X, generation=np.concatenate(gens), objective_values=O, constraint_values=C,
        diverged=np.concatenate(dv), violation=V, feasible=F, best=best, front=front,
        interrupted=interrupted, stop=stop, elapsed=time.perf_counter() - t0,
        setups={k: v for k, v in setups.items() if k},
    )


def _evaluate(scenario: Scenario, specs: tuple[GainSpec, ...], G: np.ndarray, x0_cases: np.ndarray, K: int,
              seed: int, options: RunOptions) -> list[Metrics]:
    """Every candidate (row of G) on the K cases of one set-up: one Metrics per candidate."""
    P = G.shape[0]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DivergenceWarning)
        if _is_random(scenario.disturbance):
            out = []
            for i in range(P):
                law = scenario.controller.replace(**{s.name: float(G[i, j]) for j, s in enumerate(specs)})
                out.append(_run(scenario, law, x0_cases, seed, options).metrics)
            return out
        law = scenario.controller.replace(
            **{s.name: _per_case(np.repeat(G[:, j], K), _column_shape(scenario.controller, s.name))
               for j, s in enumerate(specs)})
        res = _run(scenario, law, np.tile(x0_cases, (P, 1)), seed, options)
    return [res.metrics.cases(i * K, (i + 1) * K) for i in range(P)]


def _run(scenario: Scenario, law: controllers.Controller, x0: np.ndarray, seed: int,
         options: RunOptions) -> SimulationResult:
    """One batch of a set-up's cases under another law."""
    return simulate_batch(scenario.plant, law, x0, seed=seed, **scenario.run_options(**options.keywords()))
