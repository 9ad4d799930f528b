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
  ``t1``, ``t2`` (the Mars fixed-time guidance paper, eq. 18, 26), ``s1_radius``, ``s1_time``,
  ``s2_radius``, ``s2_time``, ``settle_bound`` (the sound total s2_time + s1_time), each the
  largest over the axes, computed with the scenario's disturbance bound and ``theta`` (0.5, 0.5
  when the scenario has none);
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

from landing._internal.expression import BOUND_NAMES, Expression
from landing.tuning.pareto import pareto_front
from landing.tuning.result import GainSpec, TuneResult
from landing.tuning.search import tune

__all__ = ["Expression", "GainSpec", "TuneResult", "tune", "pareto_front", "BOUND_NAMES"]
