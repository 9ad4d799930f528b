"""What the law sees: a sensor between the plant and the law, and a filter between the sensor
and the law.

A plant given ``sensor=Noise(...)`` makes its law read measured coordinates and rates in
place of the true ones; with ``filter=KalmanFilter(...)`` as well, the law reads the filter's
estimate. The physics, the events and the tracking metrics keep the true state; the metrics
``navigation_position_rms``, ``navigation_velocity_rms``, ``navigation_position_error`` and
``navigation_velocity_error`` measure what the law read against it, and a run that records
keeps it beside the law's diagnostics as ``estimated_position`` and ``estimated_velocity``.

Every number of both may be given per case, ``(N, K)`` or ``(N, 1)`` rows (a campaign's
chunks take their own rows), and dispersed (``scenario.disperse({"plant.sensor.bias":
Normal(0.0, 0.5)})``: one draw per case for every component, or one per component); whether
there is a filter is the batch's. The noise is drawn from each case's own counter-based stream,
so a case's measurements do not depend on the thread count, the batch or the chunking. The
models (docs/parameters.md, "sensing"):

* measurement at control instant k: ``y_k = [q_k, q'_k] + bias + w_k + std * n_k`` per
  component, with ``w_0 = 0`` and ``w_(k+1) = w_k + random_walk * sqrt(dt) * m_k`` (``n_k``
  and ``m_k`` independent standard normals);
* the filter: per axis, the discrete Kalman filter of ``[q_i, q'_i]`` with the plant's model
  (the applied command over the inertia plus the plant's modelled acceleration at the
  estimate, held over the control period) and an unknown acceleration of standard deviation
  ``process_noise`` held over each period; it measures ``[q_i, q'_i]`` with the white noise's
  variance and starts from the first measurement.

Example
-------
>>> import landing
>>> from landing.sensors import KalmanFilter, Noise
>>> plant = landing.plants.DoubleIntegrator(
...     sensor=Noise(std=[0.5, 0.5, 0.5, 0.05, 0.05, 0.05]), filter=KalmanFilter(process_noise=0.01)
... )
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

from landing import _core
from landing._internal.table import ArrayLike, Table

__all__ = ["Sensor", "Noise", "Filter", "KalmanFilter"]


def _through_plant(key: str, carrier: dict[str, Any]) -> Any:
    """A compiler for a table nested in a plant: the core reads it as the double integrator's
    ``key``, so a bad value is refused when the object is made, by the same reader that reads it
    in a plant."""

    def compile_(owner: str, table: dict[str, Any]) -> Any:
        return _core.Plant(owner, {"kind": "double_integrator", **carrier, key: table})

    return compile_


class Sensor(Table):
    """Base class of the sensors: what a plant's law reads in place of the true ``[q, q']``.

    Parameters
    ----------
    **fields : ArrayLike
        The subclass's fields (see each one); the base class takes none of its own.

    Examples
    --------
    >>> import numpy as np, landing
    >>> from landing.controllers import PDSlidingMode
    >>> plant = landing.plants.DoubleIntegrator(sensor=Noise(std=0.5))
    >>> law = PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1)
    >>> r = landing.simulate(plant, law, np.array([10.0, 0, 5, 0, 0, 0]), t_final=10.0, dt=0.01, seed=1)
    >>> print(f"{r.metrics['navigation_position_rms']:.3f} (units of q)")
    0.881 (units of q)
    """

    family: ClassVar[str] = "sensor"
    _compiler = staticmethod(_through_plant("sensor", {}))


@dataclass(frozen=True, eq=False)
class Noise(Sensor):
    """White noise, a constant bias and a random walk on each component of ``[q, q']``: the D
    coordinates, then their D rates (m and m/s on the landers).

    Parameters
    ----------
    std : ArrayLike
        Standard deviation of the white noise per component of ``[q, q']`` (a scalar serves
        all), units of q then q/s (m, m/s on the landers); std >= 0. Default 0.
    bias : ArrayLike
        Constant bias per component, units of q then q/s. Default 0.
    random_walk : ArrayLike
        Random-walk density per component, units of q/sqrt(s) then q/s/sqrt(s); >= 0: the
        walk's variance at time t is ``random_walk**2 * t``. Default 0.

    Examples
    --------
    A bias of 1 (units of q) on the first coordinate is what the law reads wrong, exactly:

    >>> import numpy as np, landing
    >>> from landing.controllers import PDSlidingMode
    >>> plant = landing.plants.DoubleIntegrator(sensor=Noise(bias=[1.0, 0, 0, 0, 0, 0]))
    >>> law = PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1)
    >>> r = landing.simulate(plant, law, np.array([10.0, 0, 5, 0, 0, 0]), t_final=10.0, dt=0.01)
    >>> print(f"{r.metrics['navigation_position_rms']:.3f}")
    1.000
    """

    std: ArrayLike = 0.0
    bias: ArrayLike = 0.0
    random_walk: ArrayLike = 0.0

    kind: ClassVar[str] = "noise"


class Filter(Table):
    """Base class of the estimators between a sensor and the law.

    Parameters
    ----------
    **fields : ArrayLike
        The subclass's fields (see each one); the base class takes none of its own.

    Examples
    --------
    >>> isinstance(KalmanFilter(process_noise=0.01), Filter)
    True
    """

    family: ClassVar[str] = "filter"
    # a filter is read with a sensor; this one has a positive std, as a filter needs
    _compiler = staticmethod(_through_plant(
        "filter", {"sensor": {"kind": "noise", "std": 1.0, "bias": 0.0, "random_walk": 0.0}}
    ))


@dataclass(frozen=True, eq=False)
class KalmanFilter(Filter):
    """The per-axis position/velocity Kalman filter with the plant's model (module docstring).

    Parameters
    ----------
    process_noise : ArrayLike
        Standard deviation of the unknown acceleration held over each control period, per
        axis (a scalar serves all), units of q/s^2 (m/s^2 on the landers); >= 0: the filter's
        model of the disturbances. The sensor's ``std`` must be positive on every component.
        Default 0.

    Examples
    --------
    The filter's estimate is nearer the truth than the raw measurements:

    >>> import numpy as np, landing
    >>> from landing.controllers import PDSlidingMode
    >>> plant = landing.plants.DoubleIntegrator(
    ...     sensor=Noise(std=[0.5, 0.5, 0.5, 0.05, 0.05, 0.05]), filter=KalmanFilter(process_noise=0.01)
    ... )
    >>> law = PDSlidingMode(lambda_=1.0, k=0.5, switch="sat", boundary_layer=0.1)
    >>> r = landing.simulate(plant, law, np.array([10.0, 0, 5, 0, 0, 0]), t_final=10.0, dt=0.01, seed=1)
    >>> print(f"{r.metrics['navigation_position_rms']:.3f}")
    0.056
    """

    process_noise: ArrayLike = 0.0

    kind: ClassVar[str] = "kalman"
