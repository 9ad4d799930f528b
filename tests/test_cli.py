"""Scenario files and the command line: every preset ships as a TOML file that reads back to
the same scenario (the same bits when run), bad files are refused with the file, the key, the
value and the rule, and the `landing` command's subcommands do what they say."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import landing
from landing import cli
from landing.scenarios import PRESETS, FileError, Scenario, load_scenario, preset, preset_path
from landing.scenarios.files import tomllib


def _short(s: Scenario, steps: int = 40) -> dict:
    return dict(t_final=steps * s.dt, record_every=7)


@pytest.mark.parametrize("name", sorted(PRESETS))
def test_every_preset_ships_as_an_up_to_date_toml_file(name):
    path = preset_path(name)
    assert path.exists(), f"{path} missing: run landing.scenarios.write_preset_files()"
    assert path.read_text(encoding="utf-8") == preset(name).to_toml(), (
        f"{path} is out of date: run landing.scenarios.write_preset_files()")


@pytest.mark.parametrize("name", ["mars_monte_carlo", "mars_super_twisting_standard", "seed000_fuzzy_ftsmc_sign",
                                  "seed002_fuzzy_variable_rate", "tether_fntsmc_flexible"])
def test_a_preset_file_runs_with_the_bits_of_the_python_preset(name):
    py, toml = preset(name), Scenario.load(name)
    assert toml.name == name
    opts = _short(py)
    x0 = py.initial_states(5, seed=3)
    assert np.array_equal(toml.initial_states(5, seed=3), x0)
    a = py.simulate_batch(x0, seed=3, **opts)
    b = toml.simulate_batch(x0, seed=3, **opts)
    for field in ("states", "controls", "final_state"):
        assert np.array_equal(getattr(a, field), getattr(b, field), equal_nan=True), field
    for k in a.metrics:
        assert np.array_equal(a.metrics[k], b.metrics[k], equal_nan=True), k


def _write(tmp_path: Path, text: str) -> Path:
    p = tmp_path / "mine.toml"
    p.write_text(text, encoding="utf-8")
    return p


def _nominal_text() -> str:
    return preset("mars_nominal").to_toml()


@pytest.mark.parametrize("edit, pattern", [
    (("alpha1 = 4.89", "alpah1 = 4.89"), r"mine\.toml: controller\.alpah1: unknown key \(FixedTimeMSS takes"),
    (("alpha1 = 4.89", "alpha1 = -4.89"), r"mine\.toml: controller: FixedTimeMSS: alpha1 = -4\.89 violates alpha1 > 0"),
    (("alpha1 = 4.89", 'alpha1 = "fast"'), r"mine\.toml: controller: .*alpha1.*real number"),
    (("dt = 0.001", "dt = -0.001"), r"mine\.toml: dt = -0\.001 violates dt > 0"),
    (("substeps = 1", "substeps = 1.5"), r"mine\.toml: substeps = 1\.5 violates substeps an integer >= 1"),
    (('kind = "FixedTimeMSS"', 'kind = "FixedTime"'), r"mine\.toml: controller\.kind = 'FixedTime' is not one of"),
    (('integrator = "rk4"', 'integrator = "rk5"'), r"mine\.toml: integrator = 'rk5' is not one of"),
    (("t_final = 60.0", "t_final = 60.0\nhorizon = 3"), r"mine\.toml: horizon: unknown key"),
    (("x0 = [", "x0 = [1.0, "), r"mine\.toml: x0 = .* violates x0 a list of 7 finite numbers"),
    (("dt = 0.001", "dt = 0.001 ="), r"mine\.toml: not valid TOML"),
])
def test_a_bad_file_is_refused_naming_the_file_the_key_the_value_and_the_rule(tmp_path, edit, pattern):
    old, new = edit
    text = _nominal_text()
    assert old in text
    path = _write(tmp_path, text.replace(old, new, 1))
    with pytest.raises(FileError, match=pattern):
        load_scenario(path)
    assert issubclass(FileError, landing.ParameterError)


def test_the_command_line_exits_2_with_one_line_on_a_bad_file(tmp_path, capsys):
    path = _write(tmp_path, _nominal_text().replace("alpha1 = 4.89", "alpha1 = -4.89"))
    assert cli.main(["run", str(path), "--out", ""]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "alpha1 = -4.89 violates alpha1 > 0" in err[0] and str(path) in err[0]
    assert cli.main(["show", "no_such_preset"]) == 2
    assert "not a preset" in capsys.readouterr().err


def test_list_show_run_mc_and_bounds(tmp_path, capsys):
    assert cli.main(["list"]) == 0
    listed = capsys.readouterr().out
    assert all(name in listed for name in PRESETS)

    assert cli.main(["show", "mars_nominal"]) == 0
    shown = capsys.readouterr().out
    assert shown == preset_path("mars_nominal").read_text(encoding="utf-8")
    assert tomllib.loads(shown)["controller"]["kind"] == "FixedTimeMSS"

    # a user's edited copy: a short horizon and another gain
    path = _write(tmp_path, shown.replace("t_final = 60.0", "t_final = 2.0").replace("alpha1 = 4.89", "alpha1 = 5.5"))
    out = tmp_path / "figs"
    assert cli.main(["run", str(path), "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "mars_nominal" in text and "final_position_error" in text
    assert {p.name for p in out.iterdir()} >= {"positions.png", "thrust.png", "landing_sites.png"}
    expected = preset("mars_nominal").replace(t_final=2.0, controller={"alpha1": 5.5}).simulate()
    assert f"{float(expected.metrics['final_position_error']):.6g}" in text

    assert cli.main(["mc", str(path), "--cases", "6", "--seed", "2", "--out", "", "--no-progress"]) == 0
    report = capsys.readouterr().out
    assert "6 cases, seed 2" in report and "diverged: 0 of 6" in report

    assert cli.main(["bounds", "mars_monte_carlo"]) == 0
    assert "T1 (eq. 18)" in capsys.readouterr().out


def test_python_dash_m_landing_and_the_console_script():
    out = subprocess.run([sys.executable, "-m", "landing", "list"], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0 and "mars_monte_carlo" in out.stdout
    bad = subprocess.run([sys.executable, "-m", "landing", "show", "nope"], capture_output=True, text=True,
                         timeout=120)
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1
    exe = shutil.which("landing")
    if exe is None:
        pytest.skip("the console script is not on PATH (package not installed with pip)")
    assert subprocess.run([exe, "list"], capture_output=True, text=True, timeout=120).returncode == 0


def test_replace_changes_one_gain_in_one_call():
    s = preset("mars_nominal")
    a = s.replace(controller={"alpha1": 6.0}, plant={"thrust_limit": 4e4})
    assert float(a.controller.alpha1) == 6.0 and float(a.controller.beta1) == float(s.controller.beta1)
    assert float(a.plant.thrust_limit) == 4e4
    b = s.replace(controller=s.controller.replace(alpha1=6.0), plant=s.plant.replace(thrust_limit=4e4))
    assert a.to_toml() == b.to_toml()
    with pytest.raises(landing.ParameterTypeError, match="unknown field 'controler'"):
        s.replace(controler={"alpha1": 6.0})
    with pytest.raises(landing.ParameterError, match="alpha1"):
        s.replace(controller={"alpha1": -1.0})


@pytest.mark.parametrize("per_case", ["(N,)", "(N, 3)"])
def test_per_case_gains_go_through_monte_carlo_and_its_bounds(per_case):
    n = 8
    alpha = np.linspace(1.0, 5.0, n)
    gains = alpha if per_case == "(N,)" else np.repeat(alpha[:, None], 3, axis=1)
    s = preset("mars_monte_carlo").replace(t_final=2.0, controller={"alpha1": gains})
    mc = landing.monte_carlo(s, n, seed=4)
    assert mc.bounds.t2.shape == (n, 3)
    # case i's bounds are those of the law with its own gain (computed case by case)
    for i in (0, n - 1):
        single = landing.theory.mss_bounds(s.controller.replace(alpha1=float(alpha[i])),
                                           landing.theory.disturbance_bound(s.disturbance), *s.theta)
        assert np.array_equal(mc.bounds.t2[i], single.t2)
    report = mc.report()
    assert f"over {n} cases" in report and len(report.splitlines()) < 40


def test_progress_reaches_logs_as_lines(capsys):
    s = preset("mars_monte_carlo").replace(t_final=0.5)
    landing.monte_carlo(s, 40, seed=1, progress=True, chunk_size=10)
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if "mars_monte_carlo" in line]
    assert lines and "40/40" in lines[-1] and "\r" not in err


def test_mc_writes_a_store_that_report_reads_back(tmp_path, capsys):
    pytest.importorskip("pyarrow")
    pytest.importorskip("zarr")
    text = preset("mars_monte_carlo").to_toml().replace("t_final = 60.0", "t_final = 1.0")
    path = _write(tmp_path, text)
    store = tmp_path / "campaign"
    assert cli.main(["mc", str(path), "--cases", "6", "--seed", "5", "--store", str(store), "--out", ""]) == 0
    first = capsys.readouterr().out
    assert cli.main(["report", str(store), "--out", str(tmp_path / "figs")]) == 0
    again = capsys.readouterr().out
    report = first[first.index("mars_monte_carlo: 6 cases"):]
    assert again.startswith(report.split("\n")[0]) and report.splitlines()[:12] == again.splitlines()[:12]
    assert (tmp_path / "figs" / "landing_sites.png").exists()
