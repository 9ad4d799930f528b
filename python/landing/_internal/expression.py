"""One expression grammar on a campaign's metrics: the objectives and constraints of
:func:`landing.tune` (see :mod:`landing.tune`) and the requirements a campaign is verified
against (:meth:`MonteCarloResult.verify <landing.MonteCarloResult.verify>`). Parsed with
:mod:`ast`, checked node by node, then evaluated on the metrics (and the theory's bounds);
nothing is ``eval``-ed.

An objective reduces the metrics of all the cases to one number (``mean(fuel_used)``); a
constraint compares two such numbers. A requirement is one case's pass or fail: comparisons
joined by ``and``, ``or`` and ``not``, where an aggregate reduces over the case's own values
(its axes), so ``max(abs(touchdown_position)) <= 10`` asks every coordinate of each case's
touchdown to be within 10 m. A case whose metric is NaN (diverged, or no touchdown) fails."""

from __future__ import annotations

import ast
import math
from collections.abc import Mapping, Sequence
from typing import Any, Callable, Optional

import numpy as np

from landing.errors import ParameterError

__all__ = ["BOUND_NAMES", "Expression", "UserFunction"]

#: Bound names an expression may use (FixedTimeMSS laws).
BOUND_NAMES = ("t1", "t2", "s1_radius", "s1_time", "s2_radius", "s2_time", "settle_bound")

_ELEMENTWISE: dict[str, Callable[[Any], Any]] = {
    "abs": np.abs, "sqrt": np.sqrt, "log": np.log, "log10": np.log10, "exp": np.exp,
}
_AGGREGATES: dict[str, Callable[..., Any]] = {
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


class Expression:
    """An objective, constraint or requirement parsed from the grammar of this module.

    ``Expression(text, metric_names, bound_names, kind)`` refuses (ParameterError naming the
    expression) unknown names, anything outside the grammar, an objective that does not reduce
    to one number, a constraint that is not one comparison, and a requirement that is not
    comparisons joined by ``and``, ``or`` and ``not``."""

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
        if kind == "requirement":
            self._check_requirement(body)
            self.body = body
            return
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

    def _check_requirement(self, node: ast.AST) -> None:
        """A requirement: comparisons joined by and, or and not (each side per case)."""
        if isinstance(node, ast.BoolOp):
            for v in node.values:
                self._check_requirement(v)
        elif isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not):
            self._check_requirement(node.operand)
        elif isinstance(node, ast.Compare):
            self._check(node)
        else:
            raise ParameterError(
                f"requirement = {self.text!r} violates the rule: comparisons (<, <=, > or >=) joined by and, or "
                f"and not, each case's pass or fail (at {ast.unparse(node)!r})")

    def holds(self, columns: Mapping[str, Any]) -> np.ndarray:
        """A requirement's pass (True) or fail per case, on the metric columns ``columns``
        (each (N,) or (N, D)); NaN fails."""
        if self.kind != "requirement":
            raise ParameterError(f"{self.kind} = {self.text!r} is not a requirement")
        n = len(np.asarray(columns["diverged"]))
        with np.errstate(all="ignore"):
            out = np.asarray(self._per_case(self.body, columns), dtype=bool)
        return np.broadcast_to(out, (n,)).copy()

    def _per_case(self, node: ast.AST, env: Mapping[str, Any]) -> Any:
        """A requirement's node for every case at once: an aggregate reduces each case's own
        values (its row), not the cases."""
        if isinstance(node, ast.BoolOp):
            parts = [self._per_case(v, env) for v in node.values]
            join = np.logical_and if isinstance(node.op, ast.And) else np.logical_or
            out = parts[0]
            for p in parts[1:]:
                out = join(out, p)
            return out
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not):
            return np.logical_not(self._per_case(node.operand, env))
        if isinstance(node, ast.Compare):
            left, right = self._per_case(node.left, env), self._per_case(node.comparators[0], env)
            return _CMPOPS[type(node.ops[0])][1](left, right)
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and (
                node.func.id in _AGGREGATES or node.func.id == "percentile"):
            x = np.asarray(self._per_case(node.args[0], env), dtype=float)
            rows = x.reshape(x.shape[0], -1) if x.ndim >= 1 else x.reshape(1, 1)
            f = node.func.id
            if f == "percentile":
                q = node.args[1]
                assert isinstance(q, ast.Constant) and isinstance(q.value, (int, float))  # (_check)
                out = np.percentile(rows, float(q.value), axis=1)
            else:
                out = _AGGREGATES[f](rows, axis=1)
            return out if x.ndim >= 1 else out[0]
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
            return _ELEMENTWISE[node.func.id](np.asarray(self._per_case(node.args[0], env), dtype=float))
        if isinstance(node, ast.BinOp):
            return _BINOPS[type(node.op)](self._per_case(node.left, env), self._per_case(node.right, env))
        if isinstance(node, ast.UnaryOp):
            v = self._per_case(node.operand, env)
            return np.negative(v) if isinstance(node.op, ast.USub) else v
        return self._eval(node, env)

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
        # the tree was checked when parsed (_check): only the grammar's nodes reach here
        if isinstance(node, ast.Constant):
            assert isinstance(node.value, (int, float))  # a number (_check)
            return float(node.value)
        if isinstance(node, (ast.Name, ast.Attribute)):
            return env[str(_qualified(node))]
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
            q = node.args[1]
            assert isinstance(q, ast.Constant) and isinstance(q.value, (int, float))  # in [0, 100] (_check)
            return float(np.percentile(x, float(q.value)))
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


class UserFunction:
    """A user's callable objective or constraint: ``f(metrics, bounds) -> float``; a constraint
    callable returns its margin, satisfied when <= 0. It stands where an :class:`Expression`
    would."""

    def __init__(self, f: Callable[..., float], kind: str):
        self.f = f
        self.kind = kind
        self.text = getattr(f, "__name__", repr(f))
        self.op = "<="
        self.last_scale = 1.0

    def value(self, env: Mapping[str, Any]) -> float:
        return float(self.f(env["__metrics__"], env["__bounds__"]))
