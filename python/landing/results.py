"""What a batch produced: :class:`SimulationResult`, its per-case :class:`Metrics`, and their
xarray and pandas views.

A result is one set of arrays with a case axis first; :meth:`SimulationResult.cases` takes some
cases (a view for a range), :meth:`SimulationResult.concat` joins batches, and
:meth:`SimulationResult.empty` with :meth:`SimulationResult.put` fills a preallocated output
chunk by chunk (what a campaign does). The conversions to xarray and pandas need the optional
extra ``landing[io]``; nothing here imports it until one is asked for.
"""

from __future__ import annotations

import dataclasses
import importlib
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, Callable, Optional, Union

import numpy as np

from landing import _core
from landing._internal.args import integer
from landing.errors import ParameterError, ParameterTypeError

if TYPE_CHECKING:  # pragma: no cover
    import pandas
    import xarray

__all__ = [
    "DIVERGENCE_REASONS",
    "IO_PACKAGES",
    "METRICS",
    "SIGNALS",
    "UNITS",
    "Metrics",
    "SimulationResult",
    "axis_names",
    "describe_diverged",
    "diverged_cases",
    "flat_columns",
    "flat_metric_units",
    "metric_units",
    "require_io",
]


DIVERGENCE_REASONS: tuple[str, ...] = tuple(_core.DIVERGENCE_REASONS)
"""Names of the codes in ``metrics["diverged_reason"]`` (index 0: not diverged)."""


def diverged_cases(metrics: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
    """The indices of the diverged cases, by reason name (only the reasons that occur).

    Parameters
    ----------
    metrics : mapping of str to numpy.ndarray
        Per-case metrics with ``diverged_reason`` (codes indexing :data:`DIVERGENCE_REASONS`).

    Returns
    -------
    dict of str to numpy.ndarray
        ``{reason: case indices}``.

    Examples
    --------
    >>> import numpy as np
    >>> metrics = {"diverged": np.array([False, True, True]), "diverged_reason": np.array([0, 3, 3])}
    >>> from landing.results import diverged_cases
    >>> diverged_cases(metrics)
    {'non_finite_state': array([1, 2])}
    """
    codes = np.atleast_1d(metrics["diverged_reason"])
    return {DIVERGENCE_REASONS[c]: np.flatnonzero(codes == c) for c in np.unique(codes) if c != 0}


def describe_diverged(metrics: Mapping[str, np.ndarray], shown: int = 10) -> str:
    """"k of n cases diverged (reason: cases ...; ...)", or "0 of n".

    Parameters
    ----------
    metrics : mapping of str to numpy.ndarray
        Per-case metrics with ``diverged`` and ``diverged_reason``.
    shown : int, default 10
        The most cases listed per reason.

    Returns
    -------
    str
        The description.

    Examples
    --------
    >>> import numpy as np
    >>> metrics = {"diverged": np.array([False, True, True]), "diverged_reason": np.array([0, 3, 3])}
    >>> from landing.results import describe_diverged
    >>> describe_diverged(metrics)
    '2 of 3 cases diverged (non_finite_state: 2 (cases 1, 2))'
    """
    n = np.atleast_1d(metrics["diverged"]).size
    groups = diverged_cases(metrics)
    k = sum(v.size for v in groups.values())
    if k == 0:
        return f"0 of {n}"
    parts = []
    for name, idx in groups.items():
        listed = ", ".join(str(i) for i in idx[:shown]) + (", ..." if idx.size > shown else "")
        parts.append(f"{name}: {idx.size} (cases {listed})")
    return f"{k} of {n} cases diverged ({'; '.join(parts)})"



#: The optional packages of ``landing[io]``.
IO_PACKAGES: tuple[str, ...] = ("pyarrow", "zarr", "xarray", "pandas")

#: The recorded signals a result may hold besides its final states and metrics (what a
#: campaign may keep: ``monte_carlo(..., keep=...)``).
SIGNALS: tuple[str, ...] = ("states", "controls", "diagnostics")

#: Units of the state and control components, by name (where known).
UNITS: dict[str, str] = {
    # Mars lander
    "rx": "m", "ry": "m", "rz": "m", "vx": "m/s", "vy": "m/s", "vz": "m/s", "m": "kg",
    "Fx": "N", "Fy": "N", "Fz": "N",
    # small body
    "x": "m", "y": "m", "z": "m", "ux": "m/s^2", "uy": "m/s^2", "uz": "m/s^2",
    # tethered satellite
    "phi": "rad", "theta": "rad", "phi_dot": "rad/s", "theta_dot": "rad/s", "thrust": "N", "torque": "N m",
}

#: The per-case metric columns as the core declares them, in output order: each a mapping with
#: ``name``, ``unit`` (SI; "units of q" for the plant's generalized coordinate's, "command
#: units" for the applied command's), ``per_axis`` and ``doc``.
METRICS: tuple[Mapping[str, Any], ...] = tuple(MappingProxyType(dict(m)) for m in _core.METRICS)


def _common_unit(names: Sequence[str]) -> str:
    units = {UNITS.get(n, "") for n in names}
    return units.pop() if len(units) == 1 else ""


def metric_units(state_names: Sequence[str], control_names: Sequence[str], axes: int) -> dict[str, str]:
    """The unit of each metric for a plant with these components: the core's declaration with the
    generalized coordinate's unit (the first ``axes`` states') and the command's put in. A metric
    whose unit is mixed on this plant (the tethered satellite's thrust and torque) or none (a
    flag, a code) has none.

    Parameters
    ----------
    state_names : sequence of str
        The plant's state components (``"rx"``... for the Mars lander).
    control_names : sequence of str
        Its command components (``"Fx"``...).
    axes : int
        Its number of axes.

    Returns
    -------
    dict of str to str
        ``{metric: unit}`` (m, m/s, s, kg, N...), the metrics with a unit only.

    Examples
    --------
    >>> from landing.results import metric_units
    >>> units = metric_units(("rx", "ry", "rz", "vx", "vy", "vz", "m"), ("Fx", "Fy", "Fz"), 3)
    >>> units["final_error"], units["fuel_used"], units["peak_command"], units["settle_time"]
    ('m', 'kg', 'N', 's')
    """
    q = _common_unit(state_names[:axes])
    u = _common_unit(control_names)
    out: dict[str, str] = {}
    for m in METRICS:
        unit = str(m["unit"])
        for placeholder, value in (("units of q", q), ("command units", u)):
            if placeholder in unit:
                unit = unit.replace(placeholder, value) if value else ""
        if unit:
            out[str(m["name"])] = unit
    return out


def flat_metric_units(state_names: Sequence[str], control_names: Sequence[str],
                      axes: Sequence[str]) -> dict[str, str]:
    """:func:`metric_units` by the column names of :func:`flat_columns` (``name_<axis>`` for the
    per-axis metrics).

    Parameters
    ----------
    state_names : sequence of str
        The plant's state components.
    control_names : sequence of str
        Its command components.
    axes : sequence of str
        The axes' names (``("x", "y", "z")``).

    Returns
    -------
    dict of str to str
        ``{column: unit}``.

    Examples
    --------
    >>> from landing.results import flat_metric_units
    >>> units = flat_metric_units(("rx", "ry", "rz", "vx", "vy", "vz", "m"), ("Fx", "Fy", "Fz"), ("x", "y", "z"))
    >>> units["final_error_z"], units["touchdown_speed"]
    ('m', 'm/s')
    """
    units = metric_units(state_names, control_names, len(axes))
    per_axis = {str(m["name"]) for m in METRICS if m["per_axis"]}
    out: dict[str, str] = {}
    for name, unit in units.items():
        if name in per_axis:
            out.update({f"{name}_{a}": unit for a in axes})
        else:
            out[name] = unit
    return out


# --- optional imports ----------------------------------------------------------------------------



def require_io(*names: str, what: str = "this") -> Any:
    """Import the named optional packages (one module, or a tuple of them), or raise an ImportError
    saying how to install them.

    Parameters
    ----------
    *names : str
        The modules (``"pandas"``, ``"pyarrow.parquet"``...).
    what : str, default "this"
        What needs them, for the error's message.

    Returns
    -------
    module or tuple of modules
        The module for one name, else a tuple of them in order.

    Examples
    --------
    >>> from landing.results import require_io
    >>> require_io("pandas", what="to_pandas").__name__
    'pandas'
    """
    modules = []
    for name in names:
        try:
            modules.append(importlib.import_module(name))
        except ImportError as e:
            raise ImportError(
                f"{what} needs {name.split('.')[0]}, part of the optional extra landing[io] "
                f"({', '.join(IO_PACKAGES)}): pip install \"landing[io]\""
            ) from e
    return modules[0] if len(modules) == 1 else tuple(modules)


# --- names, columns, units --------------------------------------------------------------------------


def axis_names(metrics: Mapping[str, np.ndarray], state_names: Sequence[str]) -> tuple[str, ...]:
    """x, y, z for three axes; the first state names (the generalized coordinates, e.g. phi and
    theta) otherwise.

    Parameters
    ----------
    metrics : mapping of str to numpy.ndarray
        Per-case metrics (their ``final_error`` gives the number of axes).
    state_names : sequence of str
        The plant's state components.

    Returns
    -------
    tuple of str
        The axes' names (empty without ``final_error``).

    Examples
    --------
    >>> import numpy as np
    >>> from landing.results import axis_names
    >>> axis_names({"final_error": np.zeros((4, 2))}, ("phi", "theta", "phi_dot", "theta_dot"))
    ('phi', 'theta')
    """
    if "final_error" not in metrics:
        return ()
    d = int(np.shape(metrics["final_error"])[-1]) if np.ndim(metrics["final_error"]) else 0
    if d == 3:
        return ("x", "y", "z")
    if len(state_names) >= d:
        return tuple(state_names[:d])
    return tuple(str(j) for j in range(d))


def _single_case(columns: Mapping[str, np.ndarray]) -> bool:
    return np.ndim(columns["diverged"]) == 0 if "diverged" in columns else False


def flat_columns(columns: Mapping[str, np.ndarray], axes: Sequence[str] = ()) -> dict[str, np.ndarray]:
    """Per-case columns, the per-axis ones split into ``name_<axis>`` (one row for a single case's
    scalar metrics).

    Parameters
    ----------
    columns : mapping of str to numpy.ndarray
        Per-case columns, (N,) or (N, D), in their units.
    axes : sequence of str, default ()
        The axes' names (``_0``, ``_1``... without them).

    Returns
    -------
    dict of str to numpy.ndarray
        The columns, each (N,), units unchanged.

    Examples
    --------
    >>> import numpy as np
    >>> from landing.results import flat_columns
    >>> sorted(flat_columns({"final_error": np.zeros((2, 3)), "diverged": np.zeros(2, bool)}, ("x", "y", "z")))
    ['diverged', 'final_error_x', 'final_error_y', 'final_error_z']
    """
    single = _single_case(columns)
    flat: dict[str, np.ndarray] = {}
    for k, v in columns.items():
        v = np.asarray(v)
        if single:
            v = v[None, ...]
        if v.ndim == 1:
            flat[k] = v
            continue
        names = axes if len(axes) == v.shape[1] else tuple(str(j) for j in range(v.shape[1]))
        for j, a in enumerate(names):
            flat[f"{k}_{a}"] = v[:, j]
    return flat



def component_units(names: Sequence[str]) -> list[str]:
    """The unit of each state or control component (empty where unknown)."""
    return [UNITS.get(n, "") for n in names]


def dataset_coords(t: np.ndarray, state_names: Sequence[str], control_names: Sequence[str],
                   axes: Sequence[str]) -> dict[str, Any]:
    """The coordinates of a result's xarray Dataset, and of a campaign store's trajectories:
    the recorded times (s), the component names with their units and the axis names."""
    coords: dict[str, Any] = {
        "time": ("time", t, {"units": "s", "long_name": "control instant"}),
        "state": ("state", list(state_names)),
        "control": ("control", list(control_names)),
        "state_units": ("state", component_units(state_names)),
        "control_units": ("control", component_units(control_names)),
    }
    if axes:
        coords["axis"] = ("axis", list(axes))
    return coords


def result_dataset(
    result: SimulationResult,
    *,
    x0: Optional[np.ndarray] = None,
    seed: Optional[int] = None,
    attrs: Optional[dict[str, Any]] = None,
) -> xarray.Dataset:
    """The xarray Dataset of a result (see :meth:`SimulationResult.to_xarray`)."""
    xr = require_io("xarray", what="to_xarray")
    single = result.final_state.ndim == 1
    case: tuple[str, ...] = () if single else ("case",)
    axes = result.axis_names
    coords = dataset_coords(result.t, result.state_names, result.control_names, axes)
    if not single:
        coords["case"] = ("case", np.arange(result.n_cases))
    data: dict[str, Any] = {}
    if result.states is not None:
        data["states"] = (case + ("time", "state"), result.states,
                          {"long_name": "state at the recorded instants", "units_by": "state_units"})
    if result.controls is not None:
        data["controls"] = (case + ("time", "control"), result.controls,
                            {"long_name": "command applied after saturation", "units_by": "control_units"})
    for name, v in result.diagnostics.items():
        dims = case + ("time",) + (("axis",) if v.ndim == len(case) + 2 else ())
        data[name] = (dims, v, {"long_name": f"law diagnostic {name}"})
    data["final_state"] = (case + ("state",), result.final_state,
                           {"long_name": "state at t_final", "units_by": "state_units"})
    if x0 is not None:
        data["x0"] = (case + ("state",), x0, {"long_name": "initial state", "units_by": "state_units"})
    units = metric_units(result.state_names, result.control_names, len(axes))
    for name, v in result.metrics.items():
        v = np.asarray(v)
        dims = case + (("axis",) if v.ndim == len(case) + 1 else ())
        meta = {"long_name": f"metric {name}"}
        if name in units:
            meta["units"] = units[name]
        data[name if name not in data else f"metric_{name}"] = (dims, v, meta)
    ds_attrs: dict[str, Any] = {"kernel": result.kernel}
    if seed is not None:
        ds_attrs["seed"] = int(seed)
    ds_attrs.update(attrs or {})
    return xr.Dataset(data, coords=coords, attrs=ds_attrs)


# --- the result types ------------------------------------------------------------------------------


class Metrics(Mapping[str, np.ndarray]):
    # The docstring is made below from the core's declaration of the columns (METRICS).

    def __init__(self, columns: Mapping[str, np.ndarray]):
        self._columns = dict(columns)

    def __getitem__(self, name: str) -> np.ndarray:
        return self._columns[name]

    def __getattr__(self, name: str) -> np.ndarray:
        try:
            return self.__dict__["_columns"][name]
        except KeyError:
            raise AttributeError(name) from None

    def __iter__(self) -> Iterator[str]:
        return iter(self._columns)

    def __len__(self) -> int:
        return len(self._columns)

    def __dir__(self) -> list[str]:
        return sorted(set(super().__dir__()) | set(self._columns))

    def diverged_cases(self) -> dict[str, np.ndarray]:
        """The indices of the diverged cases, by reason name (only the reasons that occur).

        Returns
        -------
        dict of str to numpy.ndarray
            ``{reason: case indices}``.
        """
        return diverged_cases(self._columns)

    def row(self, case: int) -> dict[str, Any]:
        """The metrics of one case.

        Parameters
        ----------
        case : int
            The case.

        Returns
        -------
        dict
            ``{column: value}``, in each metric's unit.
        """
        return {k: v[case] for k, v in self._columns.items()}

    def cases(self, start: Any, stop: Optional[int] = None) -> Metrics:
        """Some of the cases: ``m.cases(a, b)`` is cases a .. b - 1 (views of these columns),
        ``m.cases(index)`` those of an integer index array or a boolean mask (copies).

        Parameters
        ----------
        start : int or array_like
            The first case, or an index array or mask.
        stop : int, optional
            One past the last case.

        Returns
        -------
        Metrics
            Those cases' columns.
        """
        key = _case_key(start, stop)
        return self._map(lambda a: a[key])

    def _map(self, fn: Callable[[np.ndarray], np.ndarray]) -> Metrics:
        """The columns with ``fn`` applied to each (without the context of :meth:`to_pandas`)."""
        return Metrics({k: fn(np.asarray(v)) for k, v in self._columns.items()})

    def to_pandas(
        self,
        *,
        axis_names: Optional[Sequence[str]] = None,
        x0: Optional[np.ndarray] = None,
        state_names: Optional[Sequence[str]] = None,
        seed: Optional[int] = None,
        first_case: int = 0,
    ) -> pandas.DataFrame:
        """A pandas DataFrame, one row per case (index ``case``; a single case gives one row).

        Per-axis columns are split with the axis names, ``final_error_x`` ... (``_0``, ``_1`` ... when
        the axes have no names). The arguments default to what the result that made these metrics
        knows (a :class:`SimulationResult` or a Monte Carlo campaign fills them). Needs pandas
        (``pip install "landing[io]"``).

        Parameters
        ----------
        axis_names : sequence of str, optional
            The axes' names.
        x0 : numpy.ndarray, optional
            The initial states, (N, n_state), added as ``x0_<state name>`` columns (m, m/s, kg...).
        state_names : sequence of str, optional
            The states' names.
        seed : int, optional
            Adds a ``seed`` column.
        first_case : int, default 0
            The index of the first row.

        Returns
        -------
        pandas.DataFrame
            One row per case, in the metrics' units.

        Examples
        --------
        >>> import numpy as np, landing
        >>> from landing.controllers import PDSlidingMode
        >>> law = PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1)
        >>> x0 = np.zeros((4, 6))
        >>> x0[:, 0] = [1.0, 2.0, 5.0, 10.0]
        >>> res = landing.simulate_batch(landing.plants.DoubleIntegrator(), law, x0, t_final=10.0, dt=0.01,
        ...                              record_every=10)
        >>> df = res.metrics.to_pandas()
        >>> df.shape[0], list(df.columns[:2]), df.index.name
        (4, ['x0_x', 'x0_y'], 'case')
        """
        pd = require_io("pandas", what="Metrics.to_pandas")
        ctx = self.__dict__.get("_context", {})
        axis_names = tuple(axis_names if axis_names is not None else ctx.get("axis_names", ()))
        x0 = x0 if x0 is not None else ctx.get("x0")
        state_names = tuple(state_names if state_names is not None else ctx.get("state_names", ()))
        seed = seed if seed is not None else ctx.get("seed")
        first_case = first_case or int(ctx.get("first_case", 0))
        flat = flat_columns(self._columns, axis_names)
        n = len(next(iter(flat.values()))) if flat else 0
        front: dict[str, np.ndarray] = {}
        if seed is not None:
            front["seed"] = np.full(n, int(seed), dtype=np.uint64)
        if x0 is not None:
            x = np.atleast_2d(np.asarray(x0))
            names = state_names if len(state_names) == x.shape[1] else tuple(str(j) for j in range(x.shape[1]))
            for j, name in enumerate(names):
                front[f"x0_{name}"] = x[:, j]
        index = pd.RangeIndex(first_case, first_case + n, name="case")
        return pd.DataFrame({**front, **flat}, index=index)

    def _with_context(self, **context: Any) -> Metrics:
        """The same columns, knowing what :meth:`to_pandas` adds (axis names, seed, x0)."""
        out = Metrics(self._columns)
        out.__dict__["_context"] = {**self.__dict__.get("_context", {}), **context}
        return out

    def __repr__(self) -> str:
        cols = {k: np.atleast_1d(v) for k, v in self._columns.items()}
        n = len(cols["diverged"])
        lines = [f"Metrics({n} case{'s' if n != 1 else ''})"]
        for k, v in cols.items():
            if v.ndim == 1 and v.dtype != bool and (n > 1 or np.ndim(self._columns[k]) == 0):
                finite = v[np.isfinite(v)]
                if finite.size:
                    lines.append(f"  {k:<22} mean {finite.mean():.6g}  min {finite.min():.6g}  max {finite.max():.6g}")
                else:
                    lines.append(f"  {k:<22} (none)")
        lines.append(f"  {'diverged':<22} {describe_diverged(self._columns)}")
        return "\n".join(lines)


def _metrics_doc() -> str:
    """The Metrics docstring: the column list is the core's declaration (METRICS)."""
    lines = ["Per-case figures of merit: a table of columns, one row per case.", "",
             "Columns (N cases, D axes; units as the core declares them, \"units of q\" being the",
             "plant's generalized coordinate's and \"command units\" the applied command's):", ""]
    for m in METRICS:
        shape = "(N, D)" if m["per_axis"] else "(N,)"
        unit = f" [{m['unit']}]" if m["unit"] else ""
        lines.append(f"- ``{m['name']}`` {shape}{unit}: {m['doc']}.")
    lines += [
        "",
        "The divergence codes index :data:`landing.DIVERGENCE_REASONS` (0 ``none``;",
        "``non_finite_command``: the law returned NaN or infinity; ``command_out_of_range``: a",
        "command component beyond ``landing.MAX_COMMAND`` = 1e100; ``non_finite_state``;",
        "``out_of_domain``: the state left the plant's domain, listed in docs/parameters.md, or a",
        "component exceeded 1e100; ``non_finite_metric``: a statistic or the final error's norm",
        "overflowed). No metric is infinite without the flag;",
        ":meth:`Metrics.diverged_cases` groups the diverged cases by reason.",
        "",
        "Columns are also attributes: ``res.metrics.fuel_used``.",
        "",
        "Parameters",
        "----------",
        "columns : mapping of str to numpy.ndarray",
        "    The columns by name, one row per case (a single case's: scalars and (D,) rows).",
        "",
        "Examples",
        "--------",
        ">>> import numpy as np, landing",
        ">>> from landing.controllers import PDSlidingMode",
        ">>> law = PDSlidingMode(lambda_=1.0, k=0.5, switch=\"sat\", boundary_layer=0.1)",
        ">>> x0 = np.zeros((4, 6))",
        ">>> x0[:, 0] = [1.0, 2.0, 5.0, 10.0]",
        ">>> m = landing.simulate_batch(landing.plants.DoubleIntegrator(), law, x0, t_final=10.0, dt=0.01).metrics",
        ">>> m[\"final_error\"].shape, m.final_position_error.shape",
        "((4, 3), (4,))",
        ">>> print(f\"{m.row(3)['final_position_error']:.3f} m\")",
        "5.497 m",
        ">>> m.diverged_cases()",
        "{}",
    ]
    return "\n".join(lines)


Metrics.__doc__ = _metrics_doc()


@dataclass(frozen=True, eq=False)
class SimulationResult:
    """What a batch produced. Made by :func:`landing.simulate` and :func:`landing.simulate_batch`.

    ``result[i]`` is case i alone, with the case axis dropped. A Monte Carlo campaign run with
    ``keep=`` leaves out what it did not keep: ``states`` or ``controls`` are then None and
    ``diagnostics`` is empty.

    Parameters
    ----------
    t : numpy.ndarray
        (T,) recorded control instants, s (empty with ``record_every=0``).
    states : numpy.ndarray or None
        (N, T, n_state) states at the recorded instants (m, m/s, kg for the Mars lander; rad and
        rad/s for the tethered satellite).
    controls : numpy.ndarray or None
        (N, T, n_control) the command applied over ``[t_k, t_k + dt)``, after saturation (thrust
        in N for the Mars lander). The last entry is the command computed at t_final, which would
        be held next.
    final_state : numpy.ndarray
        (N, n_state) state at t_final.
    diagnostics : dict of str to numpy.ndarray
        Name -> (N, T, D) internal signals of the law (sliding variables, ...), or (N, T) for
        scalar ones (blending coefficients); for a plant with a sensor, also
        ``estimated_position`` and ``estimated_velocity`` (N, T, D), what the law read.
    metrics : Metrics
        Per-case table, see :class:`Metrics`.
    state_names, control_names : tuple of str
        The components' names.
    kernel : str, default ""
        The instruction-set level the batch ran at (the same bits at every level).

    Examples
    --------
    >>> import numpy as np, landing
    >>> from landing.controllers import PDSlidingMode
    >>> law = PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1)
    >>> x0 = np.zeros((4, 6))
    >>> x0[:, 0] = [1.0, 2.0, 5.0, 10.0]
    >>> res = landing.simulate_batch(landing.plants.DoubleIntegrator(), law, x0, t_final=10.0, dt=0.01,
    ...                              record_every=10)
    >>> res.t.shape, res.states.shape, res.state_names
    ((101,), (4, 101, 6), ('x', 'y', 'z', 'vx', 'vy', 'vz'))
    >>> res[3].final_state.shape, res.axis_names
    ((6,), ('x', 'y', 'z'))
    >>> print(" ".join(f"{e:.3f}" for e in res.metrics["final_position_error"]), "m")
    0.000 0.001 0.500 5.497 m
    """

    t: np.ndarray
    states: Optional[np.ndarray]
    controls: Optional[np.ndarray]
    final_state: np.ndarray
    diagnostics: dict[str, np.ndarray]
    metrics: Metrics
    state_names: tuple[str, ...]
    control_names: tuple[str, ...]
    #: The instruction-set level the batch ran at (the same bits at every level).
    kernel: str = ""

    def __post_init__(self) -> None:
        # the metrics know their axis names (and the initial states, when recorded) for to_pandas
        context: dict[str, Any] = {"axis_names": self.axis_names, "state_names": self.state_names}
        if self.states is not None and self.t.size and self.t[0] == 0.0:
            context["x0"] = self.states[..., 0, :]
        object.__setattr__(self, "metrics", self.metrics._with_context(**context))

    @property
    def n_cases(self) -> int:
        """The number of cases (1 for a single case)."""
        return int(self.final_state.shape[0]) if self.final_state.ndim == 2 else 1

    def __repr__(self) -> str:
        """A short description (sizes, names, the recorded instants, the metric table), not the
        arrays: ``print(res)``, ``res`` in a notebook."""
        single = self.final_state.ndim == 1
        head = "one case" if single else f"{self.n_cases} case{'s' if self.n_cases != 1 else ''}"
        if self.t.size:
            step = f", every {self.t[1] - self.t[0]:.6g} s" if self.t.size > 1 else ""
            when = f"{self.t.size} instants recorded, {self.t[0]:.6g} .. {self.t[-1]:.6g} s{step}"
        else:
            when = "final states and metrics only (nothing recorded)"
        lines = [f"<landing.SimulationResult: {head}, {when}{', kernel ' + self.kernel if self.kernel else ''}>"]

        def shape(a: Any) -> str:
            return "x".join(str(d) for d in np.shape(a))

        if self.states is not None:
            lines.append(f"  states       ({shape(self.states)}) {' '.join(self.state_names)}")
        if self.controls is not None:
            lines.append(f"  controls     ({shape(self.controls)}) {' '.join(self.control_names)}")
        if self.diagnostics:
            lines.append("  diagnostics  " + ", ".join(f"{k} ({shape(v)})" for k, v in self.diagnostics.items()))
        lines.append(f"  final_state  ({shape(self.final_state)})")
        lines += ["  " + line for line in repr(self.metrics).splitlines()]
        return "\n".join(lines)

    @property
    def axis_names(self) -> tuple[str, ...]:
        """Names of the axes of the per-axis metrics and diagnostics (x, y, z for the
        three-axis plants, the generalized coordinates' names otherwise)."""
        return axis_names(self.metrics, self.state_names)

    def to_xarray(self) -> xarray.Dataset:
        """An xarray Dataset: ``states`` (case, time, state), ``controls`` (case, time, control), each
        diagnostic (case, time[, axis]), ``final_state`` (case, state) and every metric (case[,
        axis]), with the time (s), component and axis names as coordinates and units where known (a
        single case has no ``case`` dimension). Needs xarray (``pip install "landing[io]"``).

        Returns
        -------
        xarray.Dataset
            The result's data, units in each variable's attributes.

        Examples
        --------
        >>> import numpy as np, landing
        >>> from landing.controllers import PDSlidingMode
        >>> law = PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1)
        >>> x0 = np.zeros((4, 6))
        >>> x0[:, 0] = [1.0, 2.0, 5.0, 10.0]
        >>> res = landing.simulate_batch(landing.plants.DoubleIntegrator(), law, x0, t_final=10.0, dt=0.01,
        ...                              record_every=10)
        >>> ds = res.to_xarray()
        >>> ds.sizes["case"], ds.sizes["time"], ds["time"].attrs["units"], ds["settle_time"].attrs["units"]
        (4, 101, 's', 's')
        """
        return result_dataset(self)

    @property
    def diverged(self) -> np.ndarray:
        """Per case, whether it diverged (``metrics["diverged"]``)."""
        return self.metrics["diverged"]

    def __len__(self) -> int:
        return self.n_cases

    def __getitem__(self, case: int) -> SimulationResult:
        self._require_batch()
        return self._map(lambda a: a[case])

    def cases(self, start: Any, stop: Optional[int] = None) -> SimulationResult:
        """Some of the cases, the case axis kept: ``res.cases(a, b)`` is cases a .. b - 1 (views of this
        result's arrays, as a slice is), ``res.cases(index)`` those of an integer index array or a
        boolean mask (copies).

        Parameters
        ----------
        start : int or array_like
            The first case, or an index array or mask.
        stop : int, optional
            One past the last case.

        Returns
        -------
        SimulationResult
            Those cases.

        Examples
        --------
        >>> import numpy as np, landing
        >>> from landing.controllers import PDSlidingMode
        >>> law = PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1)
        >>> x0 = np.zeros((4, 6))
        >>> x0[:, 0] = [1.0, 2.0, 5.0, 10.0]
        >>> res = landing.simulate_batch(landing.plants.DoubleIntegrator(), law, x0, t_final=10.0, dt=0.01,
        ...                              record_every=10)
        >>> res.cases(1, 3).n_cases, res.cases(np.array([0, 3])).states.shape
        (2, (2, 101, 6))
        """
        self._require_batch()
        key = _case_key(start, stop)
        return self._map(lambda a: a[key])

    def with_metrics(self, columns: Mapping[str, np.ndarray]) -> SimulationResult:
        """This result with more per-case metric columns (one row per case each): a campaign's draws of
        its dispersed parameters, ``param.<path>``.

        Parameters
        ----------
        columns : mapping of str to numpy.ndarray
            The columns, each with one row per case.

        Returns
        -------
        SimulationResult
            The result with them.
        """
        for name, v in columns.items():
            if np.shape(v)[:1] != (self.n_cases,):
                raise ParameterError(f"metric column {name!r} has shape {np.shape(v)}; it takes one row per case "
                                     f"({self.n_cases})")
        return dataclasses.replace(self, metrics=Metrics({**self.metrics, **columns}))

    def keeping(self, signals: Sequence[str]) -> SimulationResult:
        """This result with only the recorded signals named in ``signals`` (of :data:`SIGNALS`); the final
        states and the metrics are always kept.

        Parameters
        ----------
        signals : sequence of str
            Among ``"states"``, ``"controls"``, ``"diagnostics"``.

        Returns
        -------
        SimulationResult
            The result without the others.
        """
        return dataclasses.replace(
            self,
            states=self.states if "states" in signals else None,
            controls=self.controls if "controls" in signals else None,
            diagnostics=self.diagnostics if "diagnostics" in signals else {},
        )

    @classmethod
    def empty(cls, n: int, like: SimulationResult) -> SimulationResult:
        """``n`` cases of uninitialised arrays shaped and typed like those of the batch ``like``, with its
        times, names, kernel and signals (what ``like`` lacks is absent here too): an output allocated
        once, which :meth:`put` fills.

        Parameters
        ----------
        n : int
            The number of cases.
        like : SimulationResult
            A batch to take shapes, types, times and names from.

        Returns
        -------
        SimulationResult
            The output, its values uninitialised.
        """
        like._require_batch()
        n = integer("n", n, minimum=0)
        return like._map(lambda a: np.empty((n,) + a.shape[1:], dtype=a.dtype))

    def put(self, start: int, part: SimulationResult) -> None:
        """Copies the cases of the batch ``part`` into cases ``start .. start + len(part)`` of this one,
        every signal this result holds (``part`` may hold more).

        Parameters
        ----------
        start : int
            The first case written.
        part : SimulationResult
            The batch copied in.

        Examples
        --------
        >>> import numpy as np, landing
        >>> from landing.controllers import PDSlidingMode
        >>> law = PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1)
        >>> x0 = np.zeros((4, 6))
        >>> x0[:, 0] = [1.0, 2.0, 5.0, 10.0]
        >>> res = landing.simulate_batch(landing.plants.DoubleIntegrator(), law, x0, t_final=10.0, dt=0.01,
        ...                              record_every=10)
        >>> out = landing.SimulationResult.empty(8, like=res)
        >>> out.put(0, res)
        >>> out.put(4, res)
        >>> bool(np.array_equal(out.states[4:], res.states))
        True
        """
        part._require_batch()
        start = integer("start", start, minimum=0)
        into = self.cases(start, start + part.n_cases)
        if into.n_cases != part.n_cases:
            raise ParameterError(
                f"put: cases {start} .. {start + part.n_cases - 1} are beyond this result's {self.n_cases}"
            )
        for name in ("states", "controls"):
            dest = getattr(into, name)
            if dest is not None:
                _copy(dest, _signal(part, name))
        into.final_state[...] = part.final_state
        for k, v in into.diagnostics.items():
            _copy(v, _signal(part, "diagnostics", k))
        for k, v in into.metrics.items():
            v[...] = part.metrics[k]

    @classmethod
    def concat(cls, parts: Sequence[SimulationResult]) -> SimulationResult:
        """The cases of the batches ``parts`` one after the other (say, the chunks of one campaign). They
        must share their recorded times, component names and signals; the kernel named is the first
        part's (every level gives the same bits).

        Parameters
        ----------
        parts : sequence of SimulationResult
            The batches.

        Returns
        -------
        SimulationResult
            Their cases, in order.

        Examples
        --------
        >>> import numpy as np, landing
        >>> from landing.controllers import PDSlidingMode
        >>> law = PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1)
        >>> x0 = np.zeros((4, 6))
        >>> x0[:, 0] = [1.0, 2.0, 5.0, 10.0]
        >>> res = landing.simulate_batch(landing.plants.DoubleIntegrator(), law, x0, t_final=10.0, dt=0.01,
        ...                              record_every=10)
        >>> landing.SimulationResult.concat([res, res.cases(0, 2)]).n_cases
        6
        """
        parts = list(parts)
        if not parts or not all(isinstance(p, SimulationResult) for p in parts):
            raise ParameterTypeError("concat takes a non-empty sequence of SimulationResult batches")
        first = parts[0]
        for i, p in enumerate(parts):
            p._require_batch()
            same = (np.array_equal(p.t, first.t) and p.state_names == first.state_names
                    and p.control_names == first.control_names
                    and (p.states is None) == (first.states is None)
                    and (p.controls is None) == (first.controls is None)
                    and list(p.diagnostics) == list(first.diagnostics) and list(p.metrics) == list(first.metrics))
            if not same:
                raise ParameterError(f"concat: part {i} differs from part 0 in its times, names or signals")
        out = cls.empty(sum(p.n_cases for p in parts), like=first)
        start = 0
        for p in parts:
            out.put(start, p)
            start += p.n_cases
        return out

    def _require_batch(self) -> None:
        if self.final_state.ndim != 2:
            raise TypeError("this result holds a single case")

    def _map(self, fn: Callable[[np.ndarray], np.ndarray]) -> SimulationResult:
        """This result with ``fn`` applied to each per-case array (states, controls, final
        state, diagnostics, metrics); the times, names and kernel are kept. Every slice,
        allocation and selection of cases goes through here."""
        return dataclasses.replace(
            self,
            states=None if self.states is None else fn(self.states),
            controls=None if self.controls is None else fn(self.controls),
            final_state=fn(self.final_state),
            diagnostics={k: fn(v) for k, v in self.diagnostics.items()},
            metrics=self.metrics._map(fn),
        )

    def state(self, name: str) -> np.ndarray:
        """One state component by name, e.g. ``res.state("rz")``.

        Parameters
        ----------
        name : str
            The component's name (one of :attr:`state_names`).

        Returns
        -------
        numpy.ndarray
            (N, T), or (T,) for a single case, in the component's unit (m, m/s, kg, rad...).

        Examples
        --------
        >>> import numpy as np, landing
        >>> from landing.controllers import PDSlidingMode
        >>> law = PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1)
        >>> x0 = np.zeros((4, 6))
        >>> x0[:, 0] = [1.0, 2.0, 5.0, 10.0]
        >>> res = landing.simulate_batch(landing.plants.DoubleIntegrator(), law, x0, t_final=10.0, dt=0.01,
        ...                              record_every=10)
        >>> res.state("x").shape, float(res.state("x")[3, 0])
        ((4, 101), 10.0)
        """
        if self.states is None:
            raise ParameterError(f"state {name!r}: the states were not kept (keep=...)")
        return self.states[..., self.state_names.index(name)]


def _case_key(start: Any, stop: Optional[int]) -> Union[slice, np.ndarray]:
    """The index of :meth:`SimulationResult.cases`: a slice from ``(start, stop)``, else the
    integer index array or boolean mask ``start``."""
    if stop is not None:
        return slice(integer("start", start, minimum=0), integer("stop", stop, minimum=0))
    key = np.asarray(start)
    if key.ndim == 1 and key.size == 0:
        return key.astype(np.intp)
    if key.ndim != 1 or key.dtype.kind not in "iub":
        raise ParameterTypeError(
            f"cases takes (start, stop) or a 1-d integer index array or boolean mask, got {start!r}"
        )
    return key


def _copy(dest: np.ndarray, values: np.ndarray) -> None:
    """``dest[...] = values``, skipped when ``values`` is ``dest`` itself (a chunk a campaign
    ran into its own output: the copy would only touch every page again)."""
    same = (dest.dtype == values.dtype and dest.shape == values.shape and dest.strides == values.strides
            and dest.__array_interface__["data"][0] == values.__array_interface__["data"][0])
    if not same:
        dest[...] = values


def _signal(part: SimulationResult, name: str, key: Optional[str] = None) -> np.ndarray:
    """A recorded signal of ``part`` that an output holds, or a ParameterError if ``part`` lacks it."""
    value = getattr(part, name) if key is None else part.diagnostics.get(key)
    if value is None:
        raise ParameterError(f"put: the part lacks {name if key is None else f'the diagnostic {key!r}'}")
    return value
