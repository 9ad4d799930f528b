"""The ``landing`` command (also ``python -m landing``).

    landing list                         the presets
    landing show SCENARIO                a scenario as TOML (copy it, edit it, run it)
    landing run SCENARIO                 the nominal case: metrics and figures
    landing mc SCENARIO --cases N        a Monte Carlo campaign: report and figures
    landing report DIR                   a stored campaign's report and figures
    landing bounds SCENARIO              the theory's bounds for the scenario's law
    landing tune CONFIG --out DIR        search a law's gains (a scenario file with a [tune] table)

SCENARIO is a preset name or a TOML file. Exit codes: 0 success, 2 bad input (a bad file, key,
value or argument), 1 any other failure. Errors are one line; ``--traceback`` shows the rest.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
import traceback
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import Any, Optional, Union

from landing import controllers, plots, theory
from landing.campaign import MonteCarloResult, load, monte_carlo
from landing.campaign.dask import connect
from landing.errors import LandingError, SimulationError, StoreError
from landing.results import SimulationResult
from landing.scenarios import PRESETS, FileError, Scenario, preset
from landing.scenarios.files import read_toml, scenario_from_dict
from landing.tuning import tune

EXIT_OK = 0
EXIT_FAILURE = 1
EXIT_BAD_INPUT = 2


def _scenario(spec: str) -> Scenario:
    return Scenario.load(spec)


def _figures(result: Union[SimulationResult, MonteCarloResult], scenario: Scenario, out: Optional[str],
             default: str) -> None:
    if out == "":
        return
    folder = Path(out or default)
    if isinstance(result, MonteCarloResult) and "states" not in result.keep:
        print("no figures: the states were not kept (--keep)")
        return
    figs = plots.standard_figures(result, scenario.plant, scenario.reference)
    if not figs:
        print("no figures: nothing was recorded (record_every = 0)")
        return
    written = plots.save_figures(figs, folder)
    print(f"figures written to {folder}/: " + ", ".join(p.name for p in written))


def cmd_list(args: argparse.Namespace) -> int:
    width = max(len(n) for n in PRESETS)
    for name in PRESETS:
        print(f"{name:<{width}}  {preset(name).description}")
    return EXIT_OK


def cmd_show(args: argparse.Namespace) -> int:
    sys.stdout.write(_scenario(args.scenario).to_toml())
    return EXIT_OK


def cmd_run(args: argparse.Namespace) -> int:
    scenario = _scenario(args.scenario)
    print(f"{scenario.name}: {scenario.description}")
    start = time.perf_counter()
    result = scenario.simulate(threads=args.threads)
    print(f"one case, {scenario.t_final:g} s at dt = {scenario.dt:g} s, in {time.perf_counter() - start:.2f} s")
    print(result.metrics)
    _figures(result, scenario, args.out, f"figures/{scenario.name}")
    return EXIT_OK


def cmd_mc(args: argparse.Namespace) -> int:
    scenario = _scenario(args.scenario)
    kwargs: dict[str, Any] = dict(seed=args.seed, threads=args.threads, chunk_size=args.chunk_size)
    if args.store is not None:
        kwargs["store"] = args.store
    if args.no_progress:
        kwargs["progress"] = False
    if args.record_every is not None:
        kwargs["record_every"] = args.record_every
    if args.keep is not None:
        kwargs["keep"] = [k for k in args.keep.split(",") if k] if args.keep != "none" else []
    client = None
    if args.scheduler is not None:
        client = kwargs["client"] = connect(args.scheduler)
    start = time.perf_counter()
    try:
        mc = monte_carlo(scenario, args.cases, **kwargs)
    finally:
        if client is not None:
            client.close()
    print(f"{args.cases} cases in {time.perf_counter() - start:.2f} s")
    print(mc.report())
    _figures(mc, scenario, args.out, f"figures/{scenario.name}")
    return EXIT_OK


def cmd_report(args: argparse.Namespace) -> int:
    mc = load(args.store)
    print(mc.report())
    _figures(mc, mc.scenario, args.out, str(Path(args.store) / "figures"))
    return EXIT_OK


def cmd_verify(args: argparse.Namespace) -> int:
    """A stored campaign against a requirement: exit 0 when it shows the requirement met for at
    least p of cases with the confidence, 1 when it does not."""
    v = load(args.store).verify(args.requirement, args.p, args.confidence)
    print(v)
    return EXIT_OK if v.met else EXIT_FAILURE


def cmd_bounds(args: argparse.Namespace) -> int:
    scenario = _scenario(args.scenario)
    law = scenario.controller
    if isinstance(law, controllers.FixedTimeMSS):
        bounds = scenario.bounds()
        if bounds is None:
            # no splitting constants given: the nominal (disturbance-free) bounds
            bounds = theory.mss_bounds(law)
        print(bounds)
        return EXIT_OK
    if isinstance(law, controllers.FixedTimeNTSMC):
        tol = scenario.settle_tolerance if scenario.settle_tolerance is not None else 1e-6
        print(theory.fntsmc_bounds(law, tol))
        return EXIT_OK
    print(f"{scenario.name}: the theory module has no bounds for {type(law).__name__} "
          "(it has them for FixedTimeMSS and FixedTimeNTSMC)")
    return EXIT_BAD_INPUT


def _tune_config(path: str) -> tuple[Scenario, dict[str, Any]]:
    """A tuning file: a scenario TOML file with a ``[tune]`` table (gains, objective,
    constraints, cases, budget, seed, popsize, sigma0), or a ``[tune]`` table alone whose
    ``scenario`` key names a preset or another scenario file."""
    file = Path(path)
    if not file.exists():
        raise FileError(f"{path}: no such file")
    try:
        text = file.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise FileError(f"{path}: cannot be read ({exc})") from None
    d = read_toml(text, path)
    spec = d.pop("tune", None)
    if not isinstance(spec, dict):
        raise FileError(f"{path}: missing the [tune] table (gains, objective, constraints, cases, budget, seed)")
    allowed = {"scenario", "gains", "objective", "constraints", "cases", "budget", "seed", "popsize", "sigma0"}
    for key in spec:
        if key not in allowed:
            raise FileError(f"{path}: tune.{key}: unknown key (the [tune] table takes {sorted(allowed)})")
    if "scenario" in spec:
        if d:
            raise FileError(f"{path}: tune.scenario = {spec['scenario']!r} and scenario keys "
                            f"({', '.join(sorted(d))}) both given; use one")
        ref = str(spec.pop("scenario"))
        local = file.parent / ref
        scenario = Scenario.load(str(local) if local.exists() else ref)
    else:
        scenario = scenario_from_dict(d, str(file))
    for key in ("gains", "objective"):
        if key not in spec:
            raise FileError(f"{path}: tune.{key} is missing")
    gains = spec["gains"]
    if not isinstance(gains, dict):
        raise FileError(f"{path}: tune.gains = {gains!r} must be a table name = [low, high] or [low, high, \"log\"]")
    kwargs: dict[str, Any] = {
        "gains": {k: tuple(v) if isinstance(v, list) else v for k, v in gains.items()},
        "objective": spec["objective"],
        "constraints": spec.get("constraints", []),
    }
    for key in ("cases", "budget", "seed", "popsize", "sigma0"):
        if key in spec:
            kwargs[key] = spec[key]
    return scenario, kwargs


def cmd_tune(args: argparse.Namespace) -> int:
    scenario, kwargs = _tune_config(args.config)
    if args.budget is not None:
        kwargs["budget"] = args.budget
    if args.seed is not None:
        kwargs["seed"] = args.seed
    print(f"tuning {scenario.name}: {', '.join(kwargs['gains'])} for {kwargs['objective']}")
    result = tune(scenario, **kwargs, threads=args.threads, progress=not args.no_progress)
    print(result)
    folder = Path(args.out or f"tuning/{scenario.name}")
    written = result.write(folder)
    if args.figures:
        written += plots.save_figures(
            {"convergence": plots.tuning_convergence(result), "front": plots.tuning_front(result)}, folder)
    print(f"written to {folder}/: " + ", ".join(p.name for p in written))
    if result.interrupted:
        print("landing: interrupted; the result above is the best so far", file=sys.stderr)
        return 130
    return EXIT_OK


def parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(
        prog="landing",
        description="Simulate spacecraft landing and attitude control under sliding-mode and fuzzy laws.",
        epilog="SCENARIO is a preset name (landing list) or a TOML file (landing show PRESET > mine.toml).",
    )
    ap.add_argument("--traceback", action="store_true", help="show the full traceback of an error")
    sub = ap.add_subparsers(dest="command", required=True, metavar="COMMAND")

    p = sub.add_parser("list", help="list the presets")
    p.set_defaults(run=cmd_list)

    p = sub.add_parser("show", help="print a scenario as TOML")
    p.add_argument("scenario", metavar="SCENARIO")
    p.set_defaults(run=cmd_show)

    figures_help = "folder for the figures (default figures/NAME); '' for none"
    p = sub.add_parser("run", help="simulate the nominal case: metrics and figures")
    p.add_argument("scenario", metavar="SCENARIO")
    p.add_argument("--threads", type=int, default=None)
    p.add_argument("--out", default=None, help=figures_help)
    p.set_defaults(run=cmd_run)

    p = sub.add_parser("mc", help="a Monte Carlo campaign: report and figures")
    p.add_argument("scenario", metavar="SCENARIO")
    p.add_argument("--cases", type=int, required=True)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--store", default=None, help="campaign directory: written as chunks complete, resumed if present")
    p.add_argument("--chunk-size", type=int, default=None)
    p.add_argument("--threads", type=int, default=None)
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="run the chunks on the Dask cluster of this scheduler (tcp://host:8786), "
                        "--threads threads each on a worker; needs landing[dask]")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.add_argument("--record-every", type=int, default=None, metavar="K",
                   help="keep every K-th control instant of the trajectories (default: the scenario's); "
                        "0 keeps final states and metrics only")
    p.add_argument("--keep", default=None, metavar="SIGNALS",
                   help="the recorded signals kept, comma-separated among states, controls, diagnostics "
                        "(default all), or none")
    p.add_argument("--out", default=None, help=figures_help)
    p.set_defaults(run=cmd_mc)

    p = sub.add_parser("report", help="report and figures of a stored campaign")
    p.add_argument("store", metavar="DIR")
    p.add_argument("--out", default=None, help="folder for the figures (default DIR/figures); '' for none")
    p.set_defaults(run=cmd_report)

    p = sub.add_parser("verify", help="a stored campaign against a requirement, with a confidence "
                                      "(exit 1 when not shown)")
    p.add_argument("store", metavar="DIR")
    p.add_argument("requirement", metavar="REQUIREMENT",
                   help='each case\'s pass or fail, e.g. "touchdown_speed <= 1 and max(abs(touchdown_position)) <= 5"')
    p.add_argument("--p", type=float, default=0.9973, help="the fraction of cases to show it for (default 0.9973)")
    p.add_argument("--confidence", type=float, default=0.9, help="the confidence (default 0.9)")
    p.set_defaults(run=cmd_verify)

    p = sub.add_parser("bounds", help="the theory's bounds for a scenario's law")
    p.add_argument("scenario", metavar="SCENARIO")
    p.set_defaults(run=cmd_bounds)

    p = sub.add_parser("tune", help="search a law's gains (a scenario file with a [tune] table)")
    p.add_argument("config", metavar="CONFIG")
    p.add_argument("--out", default=None, help="folder for the result (default tuning/NAME)")
    p.add_argument("--budget", type=int, default=None, help="override tune.budget")
    p.add_argument("--seed", type=int, default=None, help="override tune.seed")
    p.add_argument("--threads", type=int, default=None)
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.add_argument("--figures", action="store_true", help="also write the convergence and front figures")
    p.set_defaults(run=cmd_tune)
    return ap


def _subject(args: argparse.Namespace) -> Optional[str]:
    """The file or directory a command reads (a scenario or tuning file, a store): what its
    error messages name."""
    for name in ("store", "scenario", "config"):
        value = getattr(args, name, None)
        if value is not None:
            return str(value)
    return None


def _one_line(exc: BaseException, subject: Optional[str]) -> str:
    """An error's message on one line, naming ``subject`` when it does not already."""
    text = str(exc)
    if not text.strip():
        text = type(exc).__name__
    text = " ".join(line.strip() for line in text.splitlines() if line.strip())
    if subject and subject not in text:
        text = f"{subject}: {text}"
    return text


def _show_warning(message: Union[Warning, str], category: type[Warning], filename: str, lineno: int,
                  file: Any = None, line: Optional[str] = None) -> None:
    """A warning as one line on stderr (not the source line Python shows by default)."""
    text = " ".join(str(message).split())
    print(f"landing: {category.__name__}: {text}", file=sys.stderr)


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Runs the command line; returns the exit code (the console script exits with it)."""
    args = parser().parse_args(argv)  # exits with 2 on a bad command line
    try:
        with warnings.catch_warnings():
            warnings.showwarning = _show_warning
            return int(args.run(args))
    except KeyboardInterrupt as exc:
        # a campaign says what it kept and how to resume
        print(f"landing: interrupted{': ' + str(exc) if str(exc) else ''}", file=sys.stderr)
        return 130
    except BrokenPipeError:
        # the reader went away (`landing list | head`): not an error of ours
        sys.stdout = open(os.devnull, "w")  # noqa: SIM115 - keeps the exit flush quiet
        return EXIT_OK
    except Exception as exc:  # noqa: BLE001 - the command line reports every failure
        # the library's input errors (a file, key, value or argument that breaks a rule, a
        # store that cannot be used) are LandingErrors; anything else, a failed run or a store's
        # disk failing it included, is a failure
        bad_input = (isinstance(exc, LandingError) and not isinstance(exc, SimulationError)
                     and not (isinstance(exc, StoreError) and isinstance(exc.__cause__, OSError)))
        if args.traceback:
            traceback.print_exc()
        else:
            what = "error" if bad_input else f"failed: {type(exc).__name__}"
            print(f"landing: {what}: {_one_line(exc, _subject(args))}", file=sys.stderr)
        return EXIT_BAD_INPUT if bad_input else EXIT_FAILURE


def console() -> None:
    """Entry point of the ``landing`` console script."""
    sys.exit(main())


if __name__ == "__main__":  # pragma: no cover
    console()
