"""Campaigns as data: stores (Parquet, Zarr, provenance), load, resume, refusal; xarray and
pandas conversions; keep=; the preallocated output's memory; bands; the optional imports."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import landing
from _cases import ROOT, assert_same_bits, assert_same_campaign
from landing import scenarios
from landing.errors import ParameterError

pd = pytest.importorskip("pandas")
xr = pytest.importorskip("xarray")
pytest.importorskip("pyarrow")
pytest.importorskip("zarr")

pytestmark = pytest.mark.io

from landing.campaign.store import CampaignStore  # noqa: E402


def small(**kw):
    return scenarios.mars_monte_carlo(t_final=5.0, dt=2e-3, record_every=25, **kw)


@pytest.fixture(scope="module")
def reference_run() -> landing.MonteCarloResult:
    """20 cases in memory, one chunk."""
    return landing.monte_carlo(small(), 20, seed=3)


def test_store_round_trip_is_bit_identical(tmp_path, reference_run):
    s = small()
    stored = landing.monte_carlo(s, 20, seed=3, chunk_size=7, store=tmp_path / "c")
    assert_same_campaign(stored, reference_run)
    back = landing.load(tmp_path / "c", scenario=s)
    assert_same_campaign(back, reference_run)
    assert back.checks is not None and set(back.checks) == {"s1", "s2"}
    for name in ("s1", "s2"):
        assert_same_bits(back.checks[name].violations, reference_run.checks[name].violations, name)
    assert back.report() == reference_run.report()

    # the layout: Parquet per chunk, Zarr, provenance and manifest
    root = tmp_path / "c"
    assert sorted(p.name for p in (root / "chunks" / "metrics").iterdir()) == [
        "part-000000.parquet", "part-000001.parquet", "part-000002.parquet"]
    assert sorted(p.name for p in (root / "chunks" / "initial").iterdir()) == [
        "part-000000.parquet", "part-000001.parquet", "part-000002.parquet"]
    manifest = json.loads((root / "manifest.json").read_text())
    assert manifest["complete"] and manifest["n_chunks"] == 3 and manifest["completed_cases"] == 20
    assert [(c["start"], c["stop"]) for c in manifest["chunks"]] == [(0, 7), (7, 14), (14, 20)]
    prov = json.loads((root / "provenance.json").read_text())
    assert prov["version"] == landing.__version__ and prov["seed"] == 3 and prov["n"] == 20
    assert prov["chunk_size"] == 7 and prov["scenario"] == s.to_toml()
    session = prov["sessions"][0]
    assert session["kernel"] == reference_run.result.kernel and session["kernel"] in landing.kernel_levels()
    assert session["machine"]["cores"] == os.cpu_count() and session["machine"]["cpu"]
    assert prov["created"].endswith("+00:00")

    # the Parquet files read without landing: metrics with axis names, x0 and the draws
    table = pd.read_parquet(root / "chunks" / "metrics")
    assert table["case"].tolist() == list(range(20))
    np.testing.assert_array_equal(table["final_error_z"].to_numpy(), reference_run.metrics["final_error"][:, 2])
    assert table["diverged_reason"].dtype == np.uint8 and table["diverged"].dtype == bool
    initial = pd.read_parquet(root / "chunks" / "initial")
    np.testing.assert_array_equal(initial[[f"x0_{n}" for n in ("rx", "ry", "rz", "vx", "vy", "vz", "m")]].to_numpy(),
                                  reference_run.x0)
    # Mars states are the draws themselves
    np.testing.assert_array_equal(initial[[f"draw_{j}" for j in range(7)]].to_numpy(), reference_run.x0)


def test_the_metric_columns_carry_their_units(tmp_path, reference_run):
    import pyarrow.parquet as pq

    landing.monte_carlo(small(), 20, seed=3, chunk_size=7, store=tmp_path / "c")
    schema = pq.read_schema(tmp_path / "c" / "chunks" / "metrics" / "part-000001.parquet")

    def units(name: str) -> str | None:
        meta = schema.field(name).metadata
        return None if meta is None else meta[b"units"].decode()

    # the Mars lander: q in m, the command in N
    expected = {"final_position_error": "m", "final_error_y": "m", "final_velocity_error": "m/s",
                "fuel_used": "kg", "peak_command": "N", "peak_command_axis_z": "N", "control_effort": "N s",
                "iae_axis_x": "m s", "chattering_variation": "N/s", "chattering_hf_share": "1",
                "touchdown_time": "s", "touchdown_speed": "m/s", "diverged_time": "s"}
    assert {name: units(name) for name in expected} == expected
    assert units("case") is None and units("diverged") is None and units("diverged_reason") is None
    ds = reference_run.to_xarray()
    assert ds["touchdown_velocity"].attrs["units"] == "m/s" and ds["peak_command"].attrs["units"] == "N"


def test_zarr_opens_in_xarray_with_dims_coords_and_units(tmp_path, reference_run):
    landing.monte_carlo(small(), 20, seed=3, chunk_size=7, store=tmp_path / "c")
    ds = xr.open_zarr(tmp_path / "c" / "trajectories.zarr")
    assert ds["states"].dims == ("case", "time", "state")
    assert ds["controls"].dims == ("case", "time", "control")
    assert ds["s1"].dims == ("case", "time", "axis") and ds["final_state"].dims == ("case", "state")
    assert ds["state"].values.tolist() == ["rx", "ry", "rz", "vx", "vy", "vz", "m"]
    assert ds["control"].values.tolist() == ["Fx", "Fy", "Fz"]
    assert ds["axis"].values.tolist() == ["x", "y", "z"]
    assert ds["state_units"].values.tolist() == ["m", "m", "m", "m/s", "m/s", "m/s", "kg"]
    assert ds["control_units"].values.tolist() == ["N", "N", "N"]
    assert ds["time"].attrs["units"] == "s" and ds["time"].dtype == np.float64
    assert ds["case"].values.tolist() == list(range(20))
    assert_same_bits(ds["time"].values, reference_run.t, "time")
    assert_same_bits(ds["states"].values, reference_run.states, "states")
    assert_same_bits(ds["s2"].values, reference_run.diagnostics["s2"], "s2")
    rz = ds["states"].sel(state="rz", case=4).values
    assert_same_bits(rz, reference_run.states[4, :, 2], "rz of case 4")


def test_resume_after_an_interruption_equals_an_uninterrupted_run(tmp_path, monkeypatch, reference_run):
    s = small()
    path = tmp_path / "c"
    calls = {"manifests": 0}
    original = CampaignStore._write_manifest

    class Interrupted(Exception):
        pass

    def crash_on_the_third_chunk(self):
        calls["manifests"] += 1
        # the first call writes the empty manifest; calls 2 and 3 complete chunks 0 and 1;
        # call 4 would complete chunk 2, whose files are written: a crash before the manifest
        if calls["manifests"] == 4:
            raise Interrupted
        original(self)

    with monkeypatch.context() as m:
        m.setattr(CampaignStore, "_write_manifest", crash_on_the_third_chunk)
        with pytest.raises(Interrupted):
            landing.monte_carlo(s, 20, seed=3, chunk_size=5, store=path)
    manifest = json.loads((path / "manifest.json").read_text())
    assert [c["index"] for c in manifest["chunks"]] == [0, 1] and not manifest["complete"]
    assert (path / "chunks" / "metrics" / "part-000002.parquet").exists()  # written, not committed
    with pytest.raises(ParameterError, match="incomplete.*10 of 20 cases"):
        landing.load(path, scenario=s)

    ran: list[int] = []
    run_cases = scenarios.Scenario.simulate_cases

    def counting(self, x0, start, n, **kw):
        ran.append(start)
        return run_cases(self, x0, start, n, **kw)

    monkeypatch.setattr(scenarios.Scenario, "simulate_cases", counting)
    resumed = landing.monte_carlo(s, 20, seed=3, store=path)  # the store's chunk size is kept
    assert ran == [10, 15]  # chunks 0 and 1 were read, not re-run
    assert_same_campaign(resumed, reference_run)
    assert_same_campaign(landing.load(path, scenario=s), reference_run)
    prov = json.loads((path / "provenance.json").read_text())
    assert [x["resumed_chunks"] for x in prov["sessions"]] == [0, 2]

    ran.clear()  # a complete store is only read
    assert_same_campaign(landing.monte_carlo(s, 20, seed=3, store=path), reference_run)
    assert ran == []


def test_the_zarr_tree_is_created_with_the_store_and_never_again(tmp_path, monkeypatch, reference_run):
    s = small()
    path = tmp_path / "c"

    class Interrupted(Exception):
        pass

    def no_chunk(self, *args, **kwargs):
        raise Interrupted

    # created, then stopped before any chunk is written: the whole tree is already there
    with monkeypatch.context() as m:
        m.setattr(CampaignStore, "write_chunk", no_chunk)
        with pytest.raises(Interrupted):
            landing.monte_carlo(s, 20, seed=3, chunk_size=5, store=path)
    manifest = json.loads((path / "manifest.json").read_text())
    assert manifest["chunks"] == [] and manifest["layout"]["arrays"][:3] == ["final_state", "states", "controls"]
    ds = xr.open_zarr(path / "trajectories.zarr")
    assert ds["states"].shape == reference_run.states.shape
    assert ds["controls"].shape == reference_run.controls.shape
    assert ds["final_state"].shape == reference_run.result.final_state.shape
    assert_same_bits(ds["time"].values, reference_run.t, "the time grid written at creation")
    tree = {p: (p.stat().st_ino, p.stat().st_mtime_ns, p.read_bytes())
            for p in (path / "trajectories.zarr").rglob("*") if p.is_file()}
    assert any(p.name in (".zarray", "zarr.json") for p in tree)

    # every chunk then writes regions of it: no file of the tree is replaced
    assert_same_campaign(landing.monte_carlo(s, 20, seed=3, store=path), reference_run)
    after = {p: (p.stat().st_ino, p.stat().st_mtime_ns, p.read_bytes()) for p in tree}
    assert after == tree
    assert_same_campaign(landing.load(path, scenario=s), reference_run)


def test_a_store_of_another_campaign_is_refused(tmp_path):
    s = small()
    path = tmp_path / "c"
    landing.monte_carlo(s, 10, seed=3, chunk_size=5, store=path)
    with pytest.raises(ParameterError, match=r"another campaign[\s\S]*seed: 3 in the store, 4 here"):
        landing.monte_carlo(s, 10, seed=4, chunk_size=5, store=path)
    # the scenarios' difference key by key, not their texts whole
    with pytest.raises(ParameterError, match=r"scenario: dt = 0\.002 in the store's, 0\.004 in this one's; "
                                             r"record_every = 25 in the store's, 12 in this one's\n"):
        landing.monte_carlo(small().replace(dt=4e-3, record_every=12), 10, seed=3, chunk_size=5, store=path)
    with pytest.raises(ParameterError, match=r"is not the scenario of the store at .*: dt = 0\.002 in the store's, "
                                             r"0\.004 in this one's$"):
        landing.load(path, scenario=small().replace(dt=4e-3))
    with pytest.raises(ParameterError, match="n: 10 in the store, 12 here"):
        landing.monte_carlo(s, 12, seed=3, chunk_size=5, store=path)
    with pytest.raises(ParameterError, match="chunk_size: 5 in the store, 2 here"):
        landing.monte_carlo(s, 10, seed=3, chunk_size=2, store=path)
    with pytest.raises(ParameterError, match="record_every: 25 in the store, 50 here"):
        landing.monte_carlo(s, 10, seed=3, chunk_size=5, record_every=50, store=path)
    with pytest.raises(ParameterError,
                       match=r"keep: \('states', 'controls', 'diagnostics'\) in the store, \('states',\) here"):
        landing.monte_carlo(s, 10, seed=3, chunk_size=5, keep=("states",), store=path)
    with pytest.raises(ParameterError, match="not the scenario of the store"):
        landing.load(path, scenario=small().replace(dt=4e-3))
    # a modified preset is rebuilt from the TOML the store keeps
    assert landing.load(path).scenario.to_toml() == s.to_toml()
    with pytest.raises(TypeError, match="store must be a directory path"):
        landing.monte_carlo(s, 10, seed=3, store=7)
    (tmp_path / "other").mkdir()
    (tmp_path / "other" / "notes.txt").write_text("mine")
    with pytest.raises(ParameterError, match="not a campaign store"):
        landing.monte_carlo(s, 10, seed=3, store=tmp_path / "other")
    with pytest.raises(ParameterError, match="not a campaign store"):
        landing.load(tmp_path / "other")


def _holding(path: Path) -> subprocess.Popen:
    """A second process that opens the store for writing and holds it until killed."""
    code = textwrap.dedent(f"""
        import sys, time
        import landing
        from landing.campaign.store import open_campaign_store
        s = landing.scenarios.mars_monte_carlo(t_final=5.0, dt=2e-3, record_every=25)
        store = open_campaign_store({str(path)!r}, s, seed=3, n=10, x0=s.initial_states(10, seed=3),
                                    keep=("states", "controls", "diagnostics"), record_every=25,
                                    chunk_size=5, threads=1, check_bounds=True)
        print("holding", flush=True)
        time.sleep(600)
    """)
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    assert proc.stdout is not None and proc.stdout.readline().strip() == "holding"
    return proc


@pytest.mark.skipif(os.name != "posix", reason="the writer lock is POSIX flock")
def test_a_second_writer_is_refused_naming_the_holder_and_a_killed_one_frees_the_store(tmp_path):
    path = tmp_path / "c"
    s = small()
    reference = landing.monte_carlo(s, 10, seed=3, chunk_size=5)
    holder = _holding(path)
    try:
        with pytest.raises(landing.StoreError,
                           match=rf"is being written by another process \(host \S+, pid {holder.pid}, since "):
            landing.monte_carlo(s, 10, seed=3, chunk_size=5, store=path)
        # nothing was written by the refused one: the holder's store is as it left it
        assert not (path / "chunks" / "metrics" / "part-000000.parquet").exists()
    finally:
        holder.kill()  # SIGKILL: no clean-up runs, the operating system frees the lock
        holder.wait()
    mc = landing.monte_carlo(s, 10, seed=3, chunk_size=5, store=path)
    assert_same_campaign(mc, reference)
    # the campaign released the lock at its end: another run (a resume of a complete store) opens it
    assert_same_campaign(landing.monte_carlo(s, 10, seed=3, chunk_size=5, store=path), reference)
    # and one refused after taking the lock (another campaign's store) releases it too
    with pytest.raises(ParameterError):
        landing.monte_carlo(s, 10, seed=4, chunk_size=5, store=path)
    assert_same_campaign(landing.monte_carlo(s, 10, seed=3, chunk_size=5, store=path), reference)


def test_a_preset_campaign_loads_without_its_scenario(tmp_path):
    s = scenarios.mars_thrust_limited()
    mc = landing.monte_carlo(s, 3, seed=2, store=tmp_path / "c")
    back = landing.load(tmp_path / "c")
    assert back.scenario.name == "mars_thrust_limited"
    assert_same_campaign(back, mc)


def test_keep_selects_what_is_recorded(tmp_path, reference_run):
    only_states = landing.monte_carlo(small(), 20, seed=3, chunk_size=6, keep=("states",))
    assert only_states.controls is None and only_states.diagnostics == {} and only_states.checks is None
    assert only_states.keep == ("states",)
    assert_same_bits(only_states.states, reference_run.states, "states")
    for k in reference_run.metrics:
        assert_same_bits(only_states.metrics[k], reference_run.metrics[k], k)
    assert_same_bits(only_states.result.final_state, reference_run.result.final_state, "final_state")

    nothing = landing.monte_carlo(small(), 20, seed=3, keep=())
    assert nothing.states is None and nothing.controls is None and nothing.diagnostics == {}
    assert_same_bits(nothing.metrics["fuel_used"], reference_run.metrics["fuel_used"], "fuel_used")

    stored = landing.monte_carlo(small(), 20, seed=3, chunk_size=8, keep=["diagnostics", "controls"],
                                 store=tmp_path / "c")
    assert stored.keep == ("controls", "diagnostics") and stored.states is None
    ds = xr.open_zarr(tmp_path / "c" / "trajectories.zarr")
    assert "states" not in ds and {"controls", "s1", "s2", "final_state"} <= set(ds.data_vars)
    back = landing.load(tmp_path / "c", scenario=small())
    assert back.states is None
    assert_same_bits(back.controls, reference_run.controls, "controls")
    assert_same_bits(back.diagnostics["s1"], reference_run.diagnostics["s1"], "s1")

    with pytest.raises(ParameterError, match=r"keep = \('states', 'thrust'\): 'thrust' is not one of"):
        landing.monte_carlo(small(), 2, keep=("states", "thrust"))


def test_to_xarray_in_memory(reference_run):
    ds = reference_run.to_xarray()
    assert ds["states"].dims == ("case", "time", "state") and ds["s1"].dims == ("case", "time", "axis")
    assert ds["final_error"].dims == ("case", "axis") and ds["fuel_used"].dims == ("case",)
    assert ds["x0"].dims == ("case", "state")
    assert ds["state_units"].values.tolist() == ["m", "m", "m", "m/s", "m/s", "m/s", "kg"]
    assert ds["time"].attrs["units"] == "s" and ds["settle_time"].attrs["units"] == "s"
    assert ds["fuel_used"].attrs["units"] == "kg"
    assert ds.attrs["seed"] == 3 and ds.attrs["kernel"] in landing.kernel_levels()
    assert_same_bits(ds["controls"].values, reference_run.controls, "controls")
    assert_same_bits(ds["diverged_reason"].values, reference_run.metrics["diverged_reason"], "reasons")
    assert_same_bits(ds["x0"].values, reference_run.x0, "x0")

    one = scenarios.mars_nominal(t_final=2.0).simulate()
    ds1 = one.to_xarray()
    assert "case" not in ds1.dims
    assert ds1["states"].dims == ("time", "state") and ds1["final_error"].dims == ("axis",)
    assert_same_bits(ds1["states"].values, one.states, "one case's states")


def test_metrics_to_pandas(reference_run):
    df = reference_run.metrics.to_pandas()
    assert df.index.name == "case" and df.index.tolist() == list(range(20))
    assert {"final_error_x", "final_error_y", "final_error_z", "peak_command_axis_z", "iae_axis_x"} <= set(df)
    assert not any(c.startswith("final_error_0") for c in df)
    assert (df["seed"] == 3).all()
    np.testing.assert_array_equal(df["x0_rz"].to_numpy(), reference_run.x0[:, 2])
    np.testing.assert_array_equal(df["final_error_y"].to_numpy(), reference_run.metrics["final_error"][:, 1])
    assert df["diverged"].dtype == bool and df["diverged_reason"].dtype == np.uint8

    one = scenarios.mars_nominal(t_final=2.0).simulate()
    df1 = one.metrics.to_pandas()
    assert len(df1) == 1 and df1.index.tolist() == [0]
    assert df1["final_error_z"].iloc[0] == one.metrics["final_error"][2]
    assert df1["fuel_used"].iloc[0] == one.metrics["fuel_used"]
    assert df1["x0_m"].iloc[0] == 1905.0  # the nominal mass, recorded at t = 0

    tether = landing.simulate(landing.plants.TetheredSatellite(fidelity="simplified"),
                              landing.controllers.FixedTimeNTSMC(),
                              landing.plants.TetheredSatellite(fidelity="simplified").initial_state(0.01, 0.01),
                              t_final=1.0, dt=0.01)
    assert {"final_error_phi", "final_error_theta"} <= set(tether.metrics.to_pandas())


def test_bands_are_per_instant_percentiles_over_the_cases():
    mc = landing.monte_carlo(small(), 6, seed=1)
    b = mc.bands("rz", percentiles=(0, 50, 100))
    rz = mc.states[:, :, 2]
    assert b.values.shape == (3, mc.t.size) and b.t is mc.t
    assert_same_bits(b[0], rz.min(axis=0), "p0")
    assert_same_bits(b[100], rz.max(axis=0), "p100")
    srt = np.sort(rz, axis=0)
    np.testing.assert_allclose(b[50], 0.5 * (srt[2] + srt[3]), rtol=1e-15)
    s1 = mc.bands("s1", percentiles=(5, 95))
    assert s1.values.shape == (2, mc.t.size, 3)

    # a diverged case (NaN from some instant on) is left out from then on
    states = mc.states.copy()
    states[0, 10:] = np.nan
    import dataclasses

    nan_run = dataclasses.replace(mc, result=dataclasses.replace(mc.result, states=states))
    b = nan_run.bands("rz", percentiles=(50,))
    assert b.n[:10].tolist() == [6] * 10 and b.n[10:].tolist() == [5] * (mc.t.size - 10)
    rest = np.sort(states[1:, 10:, 2], axis=0)
    assert_same_bits(b[50][10:], rest[2], "median of the five left")
    with pytest.raises(ParameterError, match="signal = 'vq' is not a recorded signal"):
        mc.bands("vq")
    with pytest.raises(ParameterError, match="percentiles"):
        mc.bands("rz", percentiles=(50, 120))


MEMORY_SCRIPT = textwrap.dedent(
    """
    import sys
    import landing
    from landing import scenarios

    s = scenarios.mars_monte_carlo(t_final=5.0, dt=2e-3, record_every=5)
    landing.monte_carlo(s, 8, seed=0, chunk_size=4)  # warm up (threads, allocator)

    def status(field: str) -> int:  # bytes
        with open("/proc/self/status") as f:
            return next(int(line.split()[1]) * 1024 for line in f if line.startswith(field + ":"))

    try:  # reset the high-water mark to the current resident set (Linux >= 4.0)
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
    except OSError:
        pass  # then the peak since the start counts: the measure can only be larger
    before = status("VmRSS")
    mc = landing.monte_carlo(s, 2000, seed=0, chunk_size=100)
    peak = status("VmHWM")  # this process's peak (ru_maxrss would include the parent's before exec)
    kept = (mc.states.nbytes + mc.controls.nbytes + sum(v.nbytes for v in mc.diagnostics.values())
            + mc.result.final_state.nbytes + sum(v.nbytes for v in mc.result.metrics.values()))
    print(peak - before, kept, mc.states.shape, mc.controls.shape, mc.diagnostics["s1"].shape)
    """
)


@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="reads the peak from /proc (Linux)")
def test_peak_memory_is_within_1_2_of_the_kept_data():
    """2,000 cases in chunks of 100: the process's peak resident memory grows by at most 1.2x
    the kept data (the output is allocated once; a chunk at a time is in flight). Keeping the
    chunks and concatenating them would take 2x."""
    out = subprocess.run([sys.executable, "-c", MEMORY_SCRIPT], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    grown, kept, *shapes = out.stdout.split(maxsplit=2)
    grown, kept = int(grown), int(kept)
    # (2000 cases, 501 instants, 7 states + 3 controls + 6 sliding variables) float64
    assert kept >= 2000 * 501 * (7 + 3 + 6) * 8
    assert grown <= 1.2 * kept, f"peak grew by {grown / 2**20:.1f} MiB for {kept / 2**20:.1f} MiB kept"


PLAIN_PATH = textwrap.dedent(
    """
    import sys
    import landing
    s = landing.scenarios.mars_monte_carlo(t_final=1.0, dt=1e-2, record_every=10)
    mc = landing.monte_carlo(s, 4, seed=0, chunk_size=2, keep=("states",))
    mc.report(); mc.bands("rz"); mc.metrics.row(0)
    print(sorted(m for m in ("pyarrow", "zarr", "xarray", "pandas") if m in sys.modules))
    """
)


def test_the_plain_path_imports_none_of_the_io_packages():
    out = subprocess.run([sys.executable, "-c", PLAIN_PATH], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "[]"


@pytest.mark.parametrize("missing", ["pyarrow", "zarr", "xarray", "pandas"])
def test_missing_io_packages_say_how_to_install_them(tmp_path, monkeypatch, reference_run, missing):
    monkeypatch.setitem(sys.modules, missing, None)  # "import missing" now raises ImportError
    hint = 'pip install "landing\\[io\\]"'
    with pytest.raises(ImportError, match=hint):
        landing.monte_carlo(small(), 2, store=tmp_path / "c")
    assert not (tmp_path / "c").exists()
    with pytest.raises(ImportError, match=hint):
        landing.load(tmp_path / "c")
    if missing in ("xarray", "pandas"):
        with pytest.raises(ImportError, match=hint):
            (reference_run.to_xarray if missing == "xarray" else reference_run.metrics.to_pandas)()


def test_bound_checks_in_slices_equal_the_whole_check():
    """monte_carlo checks the bounds 256 cases at a time (small temporaries): the same checks as
    theory.check_mss on the whole result."""
    from landing.theory import check_mss

    mc = landing.monte_carlo(small(), 600, seed=1, chunk_size=200)
    whole = check_mss(mc.result, mc.bounds)
    assert set(whole) == set(mc.checks)
    for k, a in whole.items():
        b = mc.checks[k]
        assert a.name == b.name
        assert_same_bits(np.asarray(a.bound), np.asarray(b.bound), f"{k} bound")
        assert_same_bits(a.measured, b.measured, f"{k} measured")
        assert set(a.extra) == set(b.extra)
        for e in a.extra:
            assert_same_bits(np.asarray(a.extra[e]), np.asarray(b.extra[e]), f"{k} {e}")
        np.testing.assert_array_equal(a.violations, b.violations)


def test_the_readme_example_runs(tmp_path, monkeypatch):
    import re

    readme = (ROOT / "docs" / "guide" / "stores.md").read_text()
    section = readme[readme.index("# Campaigns as data"):]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    monkeypatch.chdir(tmp_path)
    for _ in range(2):  # the second run resumes the complete store: read back, not re-run
        ns: dict = {}
        exec(compile(code, "docs/guide/stores.md", "exec"), ns)
        assert_same_campaign(ns["same"], ns["mc"])
        assert ns["light"].states is None and ns["light"].controls is not None
    assert ns["df"].shape[0] == 40 and ns["traj"]["states"].dims == ("case", "time", "state")
