"""The documented commands keep working: every example script runs to completion."""

import subprocess
import sys

import pytest

from _cases import ROOT

SCRIPTS = ["mars_nominal.py", "mars_monte_carlo.py", "mars_reproduction.py", "asteroid_seed000.py",
           "asteroid_seed002.py", "tether_comparison.py", "tether_monte_carlo.py", "mars_optimal.py"]
# scripts that write figures, and how many at least
FIGURES = {"mars_monte_carlo.py": 5, "asteroid_seed000.py": 5, "asteroid_seed002.py": 5, "tether_comparison.py": 3,
           "tether_monte_carlo.py": 1, "mars_optimal.py": 2}
# arguments that keep a campaign short; the documented command runs it in full
SHORT = {"tether_monte_carlo.py": ["--cases", "2"], "mars_optimal.py": ["--nodes", "40"]}


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
