"""Fuzzy inference: a general Mamdani engine evaluated by the Rust core.

Min for AND and implication, max for aggregation, centroid defuzzification on a sampled output
universe: scikit-fuzzy's conventions (the tests compare with it). Inputs outside a universe are
clipped to it.

>>> from landing.fuzzy import Mamdani, Variable
>>> s = Variable((-5, 5), {"N": ("triangle", -5, -5, 0), "Z": ("triangle", -5, 0, 5), "P": ("triangle", 0, 5, 5)})
>>> out = Variable((-1, 1), {"N": ("triangle", -1, -1, 0), "Z": ("triangle", -1, 0, 1), "P": ("triangle", 0, 1, 1)})
>>> m = Mamdani([s], out, [(("N",), "P"), (("Z",), "Z"), (("P",), "N")])
>>> float(m.evaluate([[0.0]])[0])
0.0
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from landing import _core
from landing._internal.args import choice, integer, pair, real, real_array, short
from landing._internal.table import ArrayLike, Table
from landing.errors import ParameterError, ParameterTypeError

__all__ = ["Variable", "Mamdani", "variable_rate_system", "SET_NAMES_5", "SET_NAMES_7"]

SET_NAMES_5 = ("NB", "NS", "ZR", "PS", "PB")
SET_NAMES_7 = ("NB", "NM", "NS", "ZR", "PS", "PM", "PB")


@dataclass(frozen=True)
class Variable:
    """A linguistic variable: its universe (lo, hi) and named fuzzy sets, each
    ``("triangle", a, b, c)`` or ``("trapezoid", a, b, c, d)``.

    Parameters
    ----------
    universe : tuple of float
        ``(lo, hi)``, lo < hi, in the units of the quantity (inputs outside are clipped).
    sets : Mapping[str, tuple]
        Set name -> ``("triangle", a, b, c)`` (feet a, c and peak b) or
        ``("trapezoid", a, b, c, d)`` (feet a, d and shoulders b, c), in the universe's units;
        ``a == b`` makes a left shoulder.

    Raises
    ------
    ParameterError
        If lo >= hi or a set has the wrong number of parameters.
    ParameterTypeError
        If ``sets`` is not a non-empty mapping of names to shapes.

    Examples
    --------
    >>> v = Variable((-1, 1), {"N": ("triangle", -1, -1, 0), "Z": ("triangle", -1, 0, 1),
    ...                        "P": ("trapezoid", 0, 1, 1, 1)})
    >>> v.index("Z")
    1
    """

    universe: tuple[float, float]
    sets: Mapping[str, tuple]

    def __post_init__(self) -> None:
        u = pair("universe", self.universe, owner="Variable")
        lo = real("universe[0]", u[0], owner="Variable")
        hi = real("universe[1]", u[1], owner="Variable")
        if not hi > lo:
            raise ParameterError(f"Variable: universe = ({lo:g}, {hi:g}) violates lo < hi")
        if not isinstance(self.sets, Mapping) or not self.sets:
            raise ParameterTypeError(
                f"Variable: sets must be a non-empty mapping name -> (shape, parameters...), got {short(self.sets)}"
            )
        for name, spec in self.sets.items():
            if not isinstance(name, str):
                raise ParameterTypeError(f"Variable: set names must be strings, got {short(name)}")
            if isinstance(spec, (str, bytes)) or not isinstance(spec, (tuple, list)) or not spec:
                raise ParameterTypeError(
                    f"Variable: sets[{name!r}] must be ('triangle', a, b, c) or ('trapezoid', a, b, c, d), "
                    f"got {short(spec)}"
                )
            shape = choice(f"sets[{name!r}][0]", spec[0], ("triangle", "trapezoid"), owner="Variable")
            count = 3 if shape == "triangle" else 4
            if len(spec) != count + 1:
                raise ParameterError(
                    f"Variable: sets[{name!r}] = {short(spec)} violates a {shape} has {count} parameters"
                )
            for k, v in enumerate(spec[1:]):
                real(f"sets[{name!r}][{k + 1}]", v, owner="Variable")

    def _table(self) -> dict[str, Any]:
        return {
            "lo": float(self.universe[0]),
            "hi": float(self.universe[1]),
            "sets": [(str(s[0]), [float(v) for v in s[1:]]) for s in self.sets.values()],
        }

    def index(self, name: str) -> int:
        """Position of the set ``name`` among the variable's sets.

        Parameters
        ----------
        name : str
            A set's name.

        Returns
        -------
        int
            Its index, in the order of ``sets``.

        Raises
        ------
        ParameterError
            If the variable has no set of that name.
        """
        try:
            return list(self.sets).index(name)
        except ValueError:
            raise ParameterError(f"no fuzzy set {name!r}; the sets are {list(self.sets)}") from None


class Mamdani(Table):
    """A Mamdani system: input variables, an output variable and rules
    ``((input set names...), output set name)``; ``resolution`` points sample the output
    universe for the centroid.

    Parameters
    ----------
    inputs : Sequence[Variable]
        The input variables, in the order of the columns of ``evaluate``'s argument.
    output : Variable
        The output variable.
    rules : Sequence[tuple[Sequence[str], str]]
        ``((one set name per input...), output set name)``: AND (min) of the inputs' grades
        clips the output set.
    resolution : int
        Number of points sampling the output universe for the centroid, >= 2 (default 401).

    Raises
    ------
    ParameterError
        If a rule names a set that does not exist or the wrong number of input sets.
    ParameterTypeError
        If an argument has the wrong type.

    Examples
    --------
    >>> s = Variable((-5, 5), {"N": ("triangle", -5, -5, 0), "Z": ("triangle", -5, 0, 5),
    ...                        "P": ("triangle", 0, 5, 5)})
    >>> out = Variable((-1, 1), {"N": ("triangle", -1, -1, 0), "Z": ("triangle", -1, 0, 1),
    ...                          "P": ("triangle", 0, 1, 1)})
    >>> m = Mamdani([s], out, [(("N",), "P"), (("Z",), "Z"), (("P",), "N")])
    >>> print(" ".join(f"{y:.3f}" for y in m.evaluate([-5.0, -2.5, 2.5, 7.0])))
    0.667 0.119 -0.119 -0.667
    """

    kind: ClassVar[str] = "mamdani"
    family: ClassVar[str] = "fuzzy"

    def __init__(self, inputs: Sequence[Variable], output: Variable,
                 rules: Sequence[tuple[Sequence[str], str]], resolution: int = 401):
        if isinstance(inputs, (str, bytes, Variable)) or not hasattr(inputs, "__iter__"):
            raise ParameterTypeError(f"Mamdani: inputs must be a list of Variable, got {short(inputs)}")
        self.inputs = list(inputs)
        for i, v in enumerate(self.inputs):
            if not isinstance(v, Variable):
                raise ParameterTypeError(f"Mamdani: inputs[{i}] must be a Variable, got {short(v)}")
        if not isinstance(output, Variable):
            raise ParameterTypeError(f"Mamdani: output must be a Variable, got {short(output)}")
        self.output = output
        if isinstance(rules, (str, bytes)) or not hasattr(rules, "__iter__"):
            raise ParameterTypeError(
                f"Mamdani: rules must be a list of ((input sets...), output set), got {short(rules)}")
        self.rules = []
        for k, rule in enumerate(rules):
            if isinstance(rule, (str, bytes)) or not isinstance(rule, (tuple, list)) or len(rule) != 2:
                raise ParameterTypeError(
                    f"Mamdani: rules[{k}] must be ((input sets...), output set), got {short(rule)}"
                )
            antecedent, consequent = rule
            if isinstance(antecedent, str) or not isinstance(antecedent, (tuple, list)):
                raise ParameterTypeError(
                    f"Mamdani: rules[{k}][0] must be a tuple of set names, got {short(antecedent)}")
            for name in (*antecedent, consequent):
                if not isinstance(name, str):
                    raise ParameterTypeError(f"Mamdani: rules[{k}] names sets by strings, got {short(name)}")
            self.rules.append((tuple(antecedent), consequent))
        self.resolution = integer("resolution", resolution, minimum=2, cap="max_fuzzy_resolution", owner="Mamdani")
        for antecedent, _ in self.rules:
            if len(antecedent) != len(self.inputs):
                raise ParameterError(
                    f"Mamdani: a rule names {len(antecedent)} input sets for {len(self.inputs)} inputs"
                )
        self._compile()

    def _compile(self) -> None:
        self._core = _core.FuzzySystem(self._table())

    def _nested(self) -> _core.FuzzySystem:
        """Inside a law's table the system is its compiled handle."""
        return self._core

    def _table(self) -> dict[str, Any]:
        rules = [[v.index(a) for v, a in zip(self.inputs, antecedent)] + [self.output.index(c)]
                 for antecedent, c in self.rules]
        return {
            "inputs": [v._table() for v in self.inputs],
            "output": self.output._table(),
            "rules": rules,
            "resolution": self.resolution,
        }

    def evaluate(self, inputs: ArrayLike) -> np.ndarray:
        """Crisp outputs (centroids) for a batch of inputs.

        Parameters
        ----------
        inputs : ArrayLike
            Shape (N, number of inputs), in each input's units; (N,) for a one-input system.

        Returns
        -------
        numpy.ndarray
            The outputs, shape (N,), in the output's units.

        Raises
        ------
        ParameterError
            If ``inputs`` is not finite or has the wrong shape.

        Examples
        --------
        >>> y = variable_rate_system().evaluate([[5.0, 5.0], [-2.5, 1.0]])
        >>> print(" ".join(f"{v:.3f}" for v in y))
        3.556 -0.774
        """
        x = real_array("inputs", inputs, finite=True, owner="Mamdani")
        if x.ndim == 1 and len(self.inputs) == 1:
            x = x[:, None]
        if x.ndim != 2 or x.shape[1] != len(self.inputs):
            raise ParameterError(f"Mamdani: inputs has shape {x.shape}; it takes (N, {len(self.inputs)})")
        return self._core.evaluate(np.ascontiguousarray(x))

    def __repr__(self) -> str:
        return (f"Mamdani({len(self.inputs)} inputs, {len(self.output.sets)} output sets, "
                f"{len(self.rules)} rules, resolution {self.resolution})")

    @classmethod
    def _from_table(cls, table: dict[str, Any], input_names: Sequence[Sequence[str]],
                    output_names: Sequence[str]) -> Mamdani:
        def variable(t: dict[str, Any], names: Sequence[str]) -> Variable:
            return Variable((t["lo"], t["hi"]), {n: (k, *p) for n, (k, p) in zip(names, t["sets"])})

        inputs = [variable(t, n) for t, n in zip(table["inputs"], input_names)]
        output = variable(table["output"], output_names)
        rules = [(tuple(input_names[i][a] for i, a in enumerate(r[:-1])), output_names[r[-1]])
                 for r in table["rules"]]
        return cls(inputs, output, rules, table["resolution"])


def variable_rate_system(resolution: int = 401) -> Mamdani:
    """The variable-rate system of the fuzzy variable-rate asteroid paper (sec. 2.3, Table 1),
    as the core defines it: inputs s and s' with NB NS ZR PS PB on [-5, 5], output with NB NM
    NS ZR PS PM PB on [-4, 4], evenly spaced triangles (shoulders at the ends), the 5x5 rule
    table.

    Parameters
    ----------
    resolution : int
        Number of points sampling the output universe, >= 2 (default 401).

    Returns
    -------
    Mamdani
        The system: two inputs, seven output sets, 25 rules.

    Raises
    ------
    ParameterError
        If ``resolution`` is below 2 or above the configured cap.

    Examples
    --------
    >>> variable_rate_system()
    Mamdani(2 inputs, 7 output sets, 25 rules, resolution 401)
    """
    resolution = integer("resolution", resolution, minimum=2, cap="max_fuzzy_resolution",
                         owner="variable_rate_system")
    return Mamdani._from_table(_core.variable_rate_system_table(resolution),
                               [SET_NAMES_5, SET_NAMES_5], SET_NAMES_7)
