"""Convergence bounds of the fixed-time laws, and their checks against simulation.

The formulas are computed by the Rust core (``landing_core::theory``) and broadcast over
arrays in :mod:`landing.theory.bounds`; every bound comes with a check in
:mod:`landing.theory.checks` that simulates the system it speaks about and reports each case
that violates it:

- :func:`check_fixed_time_bound`: the scalar reaching law ``s' = -c1 sig^e1(s) - c2 sig^e2(s)``
  (the Mars fixed-time guidance paper's Lemma 2; eq. 18 with the beta gains, eq. 26 with the
  alpha gains) from any s(0).
- :func:`check_practical_bound`: the same law with a bounded disturbance (Theorem 1; eq. 38
  to 40 for s2, eq. 31 and 45 for s1).
- :func:`check_mss`: a recorded run of :class:`~landing.controllers.FixedTimeMSS` against its
  practical neighbourhoods and times (Theorem 4).
- :func:`min_final_time`: the Mars paper's Remark 1.
- :func:`fntsmc_bounds` (the tethered-satellite paper's Theorem 1, made sound) with
  :func:`check_fntsmc_bound` (the law on a double integrator, where its derivation holds exactly) and
  :func:`check_fntsmc_run` (a recorded tethered-satellite run); the printed eq. 42 and 47 are
  :func:`fntsmc_ts_printed` and :func:`fntsmc_td_printed`.
- :func:`terminal_reaching_time` and :func:`fast_terminal_reaching_time` (the fuzzy
  fast-terminal asteroid paper's eq. 5 and 7, with p and q as the surfaces have them; the
  printed forms swap them:
  :func:`terminal_reaching_time_printed`, :func:`fast_terminal_reaching_time_printed`), with
  :func:`check_terminal_reaching_time` (the fast terminal law on a double integrator, started
  on its surface).
"""

from landing.theory._signals import entry_time, settle_time
from landing.theory.bounds import (
    FNTSMCBounds,
    MSSBounds,
    chattering_band,
    disturbance_bound,
    fast_terminal_reaching_time,
    fast_terminal_reaching_time_printed,
    fixed_time_bound,
    fntsmc_bounds,
    fntsmc_td_printed,
    fntsmc_ts_printed,
    min_final_time,
    min_time_to_rest,
    mss_bounds,
    practical_radius,
    practical_time_bound,
    scenario_bounds,
    terminal_reaching_time,
    terminal_reaching_time_printed,
)
from landing.theory.checks import (
    BoundCheck,
    check_fixed_time_bound,
    check_fntsmc_bound,
    check_fntsmc_run,
    check_mss,
    check_practical_bound,
    check_terminal_reaching_time,
)

__all__ = [
    "fixed_time_bound",
    "practical_time_bound",
    "practical_radius",
    "MSSBounds",
    "mss_bounds",
    "disturbance_bound",
    "scenario_bounds",
    "min_final_time",
    "min_time_to_rest",
    "chattering_band",
    "entry_time",
    "settle_time",
    "BoundCheck",
    "check_fixed_time_bound",
    "check_practical_bound",
    "check_mss",
    "FNTSMCBounds",
    "fntsmc_bounds",
    "fntsmc_ts_printed",
    "fntsmc_td_printed",
    "check_fntsmc_bound",
    "check_fntsmc_run",
    "terminal_reaching_time",
    "fast_terminal_reaching_time",
    "terminal_reaching_time_printed",
    "fast_terminal_reaching_time_printed",
    "check_terminal_reaching_time",
]
