"""What a tuning found: the searched gains' specifications and :class:`TuneResult`, every
evaluation with its objectives, constraint margins and feasibility."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional, Union

import numpy as np

from landing.scenarios import Scenario

__all__ = ["GainSpec", "TuneResult"]


@dataclass(frozen=True)
class GainSpec:
    """One searched gain: its law parameter name, bounds and scale (``"linear"`` or ``"log"``).

    :func:`~landing.tuning.tune` makes them from its ``gains`` argument; the search runs in the
    unit coordinate u in [0, 1], mapped linearly, or linearly in log10, onto the bounds.

    Parameters
    ----------
    name : str
        The law parameter's name (``"lambda_"``, ``"alpha1"``).
    low, high : float
        The bounds, in the gain's units; ``low > 0`` on a log scale.
    scale : {"linear", "log"}
        How u maps onto the bounds (default ``"linear"``).

    Examples
    --------
    >>> k = GainSpec("k", 0.1, 2.0, "log")
    >>> print(" ".join(f"{g:.3f}" for g in k.decode(np.array([0.0, 0.5, 1.0]))))
    0.100 0.447 2.000
    >>> print(f"{k.encode(1.0):.3f}")
    0.769
    """

    name: str
    low: float
    high: float
    scale: str = "linear"

    def decode(self, u: np.ndarray) -> np.ndarray:
        """From the search's unit coordinate to the gain.

        Parameters
        ----------
        u : numpy.ndarray
            Unit coordinates (clipped to [0, 1]).

        Returns
        -------
        numpy.ndarray
            The gains, same shape as ``u``, in the gain's units.
        """
        u = np.clip(u, 0.0, 1.0)
        if self.scale == "log":
            return 10 ** (math.log10(self.low) + u * (math.log10(self.high) - math.log10(self.low)))
        return self.low + u * (self.high - self.low)

    def encode(self, g: float) -> float:
        """From a gain to the search's unit coordinate (the inverse of :meth:`decode`).

        Parameters
        ----------
        g : float
            The gain, in its units.

        Returns
        -------
        float
            Its unit coordinate (outside [0, 1] for a gain outside the bounds).
        """
        if self.scale == "log":
            return (math.log10(g) - math.log10(self.low)) / (math.log10(self.high) - math.log10(self.low))
        return (g - self.low) / (self.high - self.low)


@dataclass(eq=False)
class TuneResult:
    """What :func:`tune` found, with every evaluation.

    Made by :func:`~landing.tuning.tune`; its fields:

    Parameters
    ----------
    base : Scenario
        The scenario tuned (with its original gains); the first set-up for several.
    gains : tuple of GainSpec
        The searched gains' specifications.
    objectives, constraints : tuple of str
        Their texts (or callables' names).
    seed, cases, budget, popsize : int
        The run's settings.
    x : numpy.ndarray
        Shape (E, G): the evaluated gain sets, in the order of ``gains``, in the gains' units.
    generation : numpy.ndarray
        Shape (E,): the generation of each evaluation (0 first).
    objective_values : numpy.ndarray
        Shape (E, M), in the units of the objectives' metrics.
    constraint_values : numpy.ndarray
        Shape (E, C): margins, satisfied when <= 0.
    diverged : numpy.ndarray
        Shape (E,): the fraction of each candidate's cases that diverged.
    violation : numpy.ndarray
        Shape (E,): the total violation by which infeasible candidates are ranked (0:
        feasible).
    feasible : numpy.ndarray
        Shape (E,), bool.
    best : int
        Index of the best evaluation (single objective: the feasible one with the least
        objective, else the least violation; several: the front's member with the least first
        objective).
    front : numpy.ndarray
        Indices of the Pareto front of the feasible evaluations (the best alone for one
        objective).
    interrupted : bool
        True when Ctrl-C stopped the search; the rest is what was done so far.
    stop : str
        Why the search ended.
    elapsed : float
        Wall time of the search, s.
    setups : dict of str to Scenario
        The other set-ups by label, when several were tuned together.

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
    >>> r.n_evaluations, r.gain_names, r.best_feasible, r.unmet()
    (12, ('lambda_', 'k'), True, [])
    >>> print(", ".join(f"{k} = {v:.3f}" for k, v in r.best_gains.items()))
    lambda_ = 0.949, k = 1.426
    >>> print(f"{r.best_objectives['mean(iae)']:.3f}")
    57.433
    >>> print(f"{r.scenario().controller.k:.3f}")
    1.426
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
        """Evaluation ``index``'s gains by name.

        Parameters
        ----------
        index : int
            Row of ``x``.

        Returns
        -------
        dict of str to float
            The gains, in their units.
        """
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
        "diverged cases" when some of its cases diverged.

        Parameters
        ----------
        index : int or None
            The evaluation (default the best).

        Returns
        -------
        list of str
            The texts of the unmet constraints (empty when it is feasible).
        """
        i = self.best if index is None else index
        out = [c for j, c in enumerate(self.constraints)
               if not (self.constraint_values[i, j] <= 0)]
        if self.diverged[i] > 0:
            out.append(f"diverged cases ({self.diverged[i]:.0%})")
        return out

    def scenario(self, index: Optional[int] = None, setup: Optional[str] = None) -> Scenario:
        """The tuned scenario: the base (or set-up ``setup``) with the best gains (or evaluation
        ``index``'s).

        Parameters
        ----------
        index : int or None
            The evaluation whose gains to take (default the best).
        setup : str or None
            The label of the set-up, when several were tuned (default ``base``).

        Returns
        -------
        Scenario
            The scenario with those gains in its law.
        """
        g = self.best_gains if index is None else self.gains_of(index)
        s = self.base if setup is None else self.setups[setup]
        return s.replace(controller=g)

    def best_so_far(self) -> np.ndarray:
        """(generations,) the best objective (the first) among the feasible evaluations up to
        each generation (NaN before the first feasible one).

        Returns
        -------
        numpy.ndarray
            Shape (generations,), in the units of the first objective.
        """
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
        each constraint's margin ("constraint_j"), diverged, violation, feasible.

        Returns
        -------
        dict of str to numpy.ndarray
            The columns, each of shape (E,).
        """
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
        scenario ``tuned.toml`` and ``summary.txt`` (with the column legend) into ``folder``.

        Parameters
        ----------
        folder : str or Path
            Made if missing.

        Returns
        -------
        list of Path
            The files written.
        """
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
