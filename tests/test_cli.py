"""The `landing` command: its subcommands do what they say, a bad file exits 2 with one line,
``python -m landing`` and the console script run."""

from __future__ import annotations

import shutil
import subprocess
import sys

import pytest

from _cases import write_file
from landing import cli
from landing.scenarios import PRESETS, preset, preset_path
from landing.scenarios.files import tomllib


def _nominal_text() -> str:
    return preset("mars_nominal").to_toml()


def test_the_command_line_exits_2_with_one_line_on_a_bad_file(tmp_path, capsys):
    path = write_file(tmp_path, _nominal_text().replace("alpha1 = 4.89", "alpha1 = -4.89"))
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
    edited = shown.replace("t_final = 60.0", "t_final = 2.0").replace("alpha1 = 4.89", "alpha1 = 5.5")
    path = write_file(tmp_path, edited)
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


@pytest.mark.io
@pytest.mark.slow
def test_mc_writes_a_store_that_report_reads_back(tmp_path, capsys):
    pytest.importorskip("pyarrow")
    pytest.importorskip("zarr")
    text = preset("mars_monte_carlo").to_toml().replace("t_final = 60.0", "t_final = 1.0")
    path = write_file(tmp_path, text)
    store = tmp_path / "campaign"
    assert cli.main(["mc", str(path), "--cases", "6", "--seed", "5", "--store", str(store), "--out", ""]) == 0
    first = capsys.readouterr().out
    assert cli.main(["report", str(store), "--out", str(tmp_path / "figs")]) == 0
    again = capsys.readouterr().out
    report = first[first.index("mars_monte_carlo: 6 cases"):]
    assert again.startswith(report.split("\n")[0]) and report.splitlines()[:12] == again.splitlines()[:12]
    assert (tmp_path / "figs" / "landing_sites.png").exists()


@pytest.mark.io
def test_mc_takes_record_every_and_keep_as_monte_carlo_does(tmp_path, capsys):
    pytest.importorskip("pyarrow")
    import numpy as np

    import landing

    text = preset("mars_monte_carlo").to_toml().replace("t_final = 60.0", "t_final = 1.0")
    path = write_file(tmp_path, text)
    store = tmp_path / "c"
    args = ["mc", str(path), "--cases", "4", "--seed", "2", "--store", str(store), "--record-every", "100",
            "--keep", "states,controls", "--out", ""]
    assert cli.main(args) == 0
    mc = landing.load(store)
    assert mc.keep == ("states", "controls") and mc.diagnostics == {}
    same = landing.monte_carlo(landing.scenarios.Scenario.load(str(path)), 4, seed=2, record_every=100,
                               keep=("states", "controls"))
    assert mc.t.size == same.t.size == 11 and np.array_equal(mc.states, same.states)
    assert cli.main(["mc", str(path), "--cases", "4", "--keep", "none", "--out", str(tmp_path / "f")]) == 0
    assert "no figures: the states were not kept" in capsys.readouterr().out
    assert cli.main(["mc", str(path), "--cases", "4", "--keep", "state", "--out", ""]) == 2
    assert "'state' is not one of" in capsys.readouterr().err


def _short_nominal() -> str:
    return _nominal_text().replace("t_final = 60.0", "t_final = 0.5").replace("dt = 0.001", "dt = 0.01")


# the probe's command lines (issue 24): each exits with its code and one stderr line naming the
# file, whether the fault is found while reading the file or later, while running it
BAD_RUNS = {
    "arrays nested beyond the parser's recursion": (
        lambda t: t + "x = " + "[" * 100_000 + "]" * 100_000 + "\n", ["run"], 2, "nested too deeply"),
    "an integer beyond a double": (
        lambda t: t.replace("t_final = 0.5", f"t_final = {10**400}"), ["run"], 2, "violates finite values"),
    "a horizon beyond the step cap, in a campaign (not a memory refusal of 10^288 PiB)": (
        lambda t: t.replace("t_final = 0.5", f"t_final = {10**300}"), ["mc", "--cases", "3"], 2,
        "t_final = 1e+300 violates t_final / dt <= 2^40"),
    "a step longer than the horizon (found by the core, when it runs)": (
        lambda t: t.replace("dt = 0.01", "dt = 1e300"), ["run"], 2, "t_final = 0.5 violates t_final >= dt"),
    "a case count of 300 digits": (
        lambda t: t, ["mc", "--cases", str(10**300)], 2, "n = about 10^300 violates n <= max_cases"),
}


@pytest.mark.parametrize("what", list(BAD_RUNS))
def test_a_bad_file_or_argument_exits_with_one_line_naming_the_file(what, tmp_path, capsys):
    edit, command, code, rule = BAD_RUNS[what]
    path = write_file(tmp_path, edit(_short_nominal()))
    assert cli.main([command[0], str(path), *command[1:], "--out", ""]) == code
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and str(path) in err[0] and rule in err[0], err
    assert len(err[0]) < 400  # no number of hundreds of digits


def test_warnings_are_one_line_each(tmp_path, capsys):
    # every case diverges (an initial position of 1e200 m): flagged, said in one line, and the
    # report's statistics of no case are nan without numpy's warnings
    path = write_file(tmp_path, preset("mars_monte_carlo").to_toml().replace("t_final = 60.0", "t_final = 0.5")
                      .replace("mean = [-2000.0,", "mean = [1e200,"))
    assert cli.main(["mc", str(path), "--cases", "3", "--out", "", "--no-progress"]) == 0
    err = capsys.readouterr().err.splitlines()
    assert err and all(line.startswith("landing: DivergenceWarning: 3 of 3 cases diverged") for line in err), err


@pytest.mark.io
def test_a_full_disk_exits_1_with_one_line_naming_the_store_and_the_remedy(tmp_path, capsys, monkeypatch):
    # a failure, not bad input: exit 1 (bad input is 2), one line naming the file and saying how
    # to resume; the same command then completes the campaign
    import errno
    import os

    text = preset("mars_monte_carlo").to_toml().replace("t_final = 60.0", "t_final = 1.0")
    path = write_file(tmp_path, text)
    store = tmp_path / "campaign"
    real = os.replace

    def full(src, dst, *args, **kwargs):
        if os.path.basename(dst) == "part-000001.parquet":
            raise OSError(errno.ENOSPC, "No space left on device", str(dst))
        return real(src, dst, *args, **kwargs)

    args = ["mc", str(path), "--cases", "6", "--chunk-size", "2", "--store", str(store), "--no-progress",
            "--out", ""]
    with monkeypatch.context() as m:
        m.setattr(os, "replace", full)
        assert cli.main(args) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    assert "part-000001.parquet" in err[0] and "No space left on device" in err[0] and "free space" in err[0]
    assert cli.main(args) == 0
    assert "6 cases" in capsys.readouterr().out
