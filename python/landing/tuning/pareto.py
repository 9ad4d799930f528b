"""Ranking evaluations: the Pareto front, non-dominated sorting with crowding, and Deb's
feasibility rules as the ranks CMA-ES is told."""

from __future__ import annotations

import numpy as np

__all__ = ["best_and_front", "pareto_front", "ranks"]


def pareto_front(values: np.ndarray) -> np.ndarray:
    """Indices of the non-dominated rows of ``values`` (E, M), every column minimised (rows with
    a NaN are left out).

    A row is dominated when another is no greater in every column and less in one; equal rows
    are all kept.

    Parameters
    ----------
    values : numpy.ndarray
        The objectives, shape (E, M): E evaluations, M objectives, in their own units.

    Returns
    -------
    numpy.ndarray
        The indices (int) of the non-dominated finite rows, increasing.

    Examples
    --------
    >>> pareto_front(np.array([[1.0, 4.0], [2.0, 2.0], [3.0, 3.0], [4.0, 1.0], [np.nan, 0.0]]))
    array([0, 1, 3])
    """
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


def ranks(obj: np.ndarray, violation: np.ndarray, feasible: np.ndarray) -> np.ndarray:
    """Deb's rules as ranks (0 best) within a generation.

    Feasible evaluations come first; among them, for one objective, the least objective; for
    several, non-dominated sorting, then the greater crowding distance. Infeasible ones follow
    by their violation. Ties go to the earlier index.

    Parameters
    ----------
    obj : numpy.ndarray
        The objectives, shape (E, M), every column minimised.
    violation : numpy.ndarray
        The constraint violation of each evaluation, shape (E,), >= 0.
    feasible : numpy.ndarray
        Whether each evaluation meets the constraints, bool, shape (E,).

    Returns
    -------
    numpy.ndarray
        The rank of each evaluation, float, shape (E,): a permutation of 0 .. E - 1.

    Examples
    --------
    >>> obj = np.array([[3.0], [1.0], [0.5], [2.0]])
    >>> ranks(obj, np.array([0.0, 0.0, 2.0, 0.0]), np.array([True, True, False, True]))
    array([2., 0., 3., 1.])
    """
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


def best_and_front(objectives: np.ndarray, violation: np.ndarray,
                   feasible: np.ndarray) -> tuple[int, np.ndarray]:
    """The best evaluation and the Pareto front of the feasible ones (see
    :class:`~landing.tuning.TuneResult`): for one objective the feasible one with the least
    objective (else the least violation), the front that one alone; for several the front's
    member with the least first objective (else the least violation).

    Parameters
    ----------
    objectives : numpy.ndarray
        The objectives, shape (E, M), every column minimised.
    violation : numpy.ndarray
        The constraint violation of each evaluation, shape (E,), >= 0.
    feasible : numpy.ndarray
        Whether each evaluation meets the constraints, bool, shape (E,).

    Returns
    -------
    tuple of (int, numpy.ndarray)
        The index of the best evaluation, and the indices of the feasible Pareto front sorted
        by the first objective (empty when none is feasible).

    Examples
    --------
    >>> obj = np.array([[1.0, 4.0], [2.0, 2.0], [0.5, 0.5], [4.0, 1.0]])
    >>> best_and_front(obj, np.array([0.0, 0.0, 1.0, 0.0]), np.array([True, True, False, True]))
    (0, array([0, 1, 3]))
    >>> best, front = best_and_front(obj[:, :1], np.ones(4), np.zeros(4, dtype=bool))
    >>> best, front.size
    (0, 0)
    """
    n = objectives.shape[0]
    if objectives.shape[1] == 1:
        order = np.lexsort((np.arange(n), np.where(feasible, objectives[:, 0], violation), ~feasible))
        best = int(order[0])
        return best, (np.array([best]) if feasible[best] else np.zeros(0, dtype=int))
    fi = np.flatnonzero(feasible)
    front = fi[pareto_front(objectives[fi])] if fi.size else np.zeros(0, dtype=int)
    if front.size:
        front = front[np.lexsort((front, objectives[front, 0]))]
        return int(front[0]), front
    return int(np.lexsort((np.arange(n), violation))[0]), front
