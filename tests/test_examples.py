"""The documented commands keep working: every example script runs to completion."""

import re
import subprocess
import sys

import pytest

from _cases import ROOT

SCRIPTS = ["mars_nominal.py", "mars_monte_carlo.py", "mars_reproduction.py", "asteroid_seed000.py",
           "asteroid_seed002.py", "tether_comparison.py", "tether_monte_carlo.py", "mars_optimal.py", "own_law.py",
           "own_plant.py", "mars_realistic.py"]
# scripts that write figures, and how many at least
FIGURES = {"mars_monte_carlo.py": 5, "mars_realistic.py": 5, "asteroid_seed000.py": 5, "asteroid_seed002.py": 5,
           "tether_comparison.py": 3, "tether_monte_carlo.py": 1, "mars_optimal.py": 2}
# arguments that keep a campaign short; the documented command runs it in full
SHORT = {"tether_monte_carlo.py": ["--cases", "2"], "mars_realistic.py": ["--cases", "40"],
         "mars_optimal.py": ["--nodes", "40"], "own_law.py": ["--cases", "4", "--budget", "6"],
         "own_plant.py": ["--cases", "4", "--budget", "6"]}


# more than about 5 s each on two cores; mars_optimal needs CasADi
SLOW = {"mars_monte_carlo.py", "mars_reproduction.py", "asteroid_seed000.py", "asteroid_seed002.py",
        "tether_comparison.py", "tether_monte_carlo.py", "mars_optimal.py"}
MARKS = {"mars_optimal.py": [pytest.mark.optimal]}


@pytest.mark.parametrize("script", [
    pytest.param(s, marks=[*MARKS.get(s, []), *([pytest.mark.slow] if s in SLOW else [])]) for s in SCRIPTS])
def test_example_runs(script, tmp_path):
    args = [sys.executable, str(ROOT / "examples" / script)]
    args += SHORT.get(script, [])
    if script in FIGURES:
        args += ["--out", str(tmp_path / "figures")]
    done = subprocess.run(args, capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.strip()
    if script in FIGURES:
        assert len(list((tmp_path / "figures").glob("*.png"))) >= FIGURES[script]


@pytest.mark.slow
def test_the_guide_prints_what_the_lunar_lander_script_prints(tmp_path):
    """docs/own-law.md quotes examples/own_plant.py's output: its campaign lines must be what
    the script prints now (the tuner's lines depend on its search, and are left out)."""
    page = (ROOT / "docs" / "own-law.md").read_text()
    quoted = re.search(r"`python examples/own_plant.py`.*?```\n(.*?)```", page, re.S).group(1).splitlines()
    done = subprocess.run([sys.executable, str(ROOT / "examples" / "own_plant.py"), "--budget", "2"],
                          capture_output=True, text=True, timeout=300, cwd=tmp_path)
    assert done.returncode == 0, done.stderr[-2000:]
    printed = done.stdout.splitlines()
    assert printed[:2] == quoted[:2]


def test_the_drag_mars_reproduction_prints_is_the_plants(tmp_path):
    # examples/mars_reproduction.py computes the largest drag acceleration from recorded states
    # with the plant's documented formula; the core's own drag reaches a law as its drift
    # (modelled acceleration = gravity + drag), so a Python law that records its drift gives the
    # core's drag at the same instants, against which the example's formula is checked
    import importlib.util

    import numpy as np

    import landing

    spec = importlib.util.spec_from_file_location("mars_reproduction", ROOT / "examples" / "mars_reproduction.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)

    def hover(t, e, de, ref, drift, inertia, params, memory):
        return -drift, None, {"drift": drift.copy()}

    nominal = landing.scenarios.mars_nominal()
    law = landing.controllers.PythonLaw(hover, diagnostics=["drift"])
    run = nominal.replace(controller=law, t_final=2.0, record_every=1).simulate()
    core = np.asarray(run.diagnostics["drift"]) - np.array([0.0, 0.0, -float(nominal.plant.gravity)])
    assert np.abs(core).max() > 0.1  # the drag is not negligible on this run
    ours = [module.largest_drag(nominal.plant, np.asarray(run.states)[i:i + 1]) for i in range(len(run.t))]
    np.testing.assert_allclose(ours, np.linalg.norm(core, axis=-1), rtol=1e-12, atol=0)
