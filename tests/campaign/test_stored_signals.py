"""A stored campaign keeps its recorded signals in the store: ``monte_carlo(..., store=DIR)`` and
``landing.load(DIR)`` hold the metrics, initial and final states in memory and read the states,
controls and diagnostics from the Zarr tree on demand (``StoredArray``), bit for bit the
in-memory campaign's arrays, whatever is asked of them (slices, cases, bands, checks, xarray,
figures); a resumed and a partial campaign too. Its memory does not grow with the trajectories
(measured in child processes), and a campaign too large for memory with its trajectories in it
is not refused with a store."""

from __future__ import annotations

import pickle
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import landing
from _cases import assert_same_bits, assert_same_campaign, crash_after_chunks, small_campaign
from landing.campaign.api import campaign_bytes
from landing.campaign.lazy import StoredArray

pytest.importorskip("pyarrow")
pytest.importorskip("zarr")
xr = pytest.importorskip("xarray")

pytestmark = pytest.mark.io

N, CHUNK, SEED = 23, 5, 4


@pytest.fixture(scope="module")
def whole() -> landing.MonteCarloResult:
    """The truth: the campaign in memory, one batch."""
    return landing.monte_carlo(small_campaign(), N, seed=SEED, progress=False)


@pytest.fixture(scope="module")
def stored(tmp_path_factory) -> tuple[landing.MonteCarloResult, landing.MonteCarloResult]:
    """The same campaign written to a store in chunks (what monte_carlo returns), and loaded."""
    path = tmp_path_factory.mktemp("stored") / "c"
    ran = landing.monte_carlo(small_campaign(), N, seed=SEED, chunk_size=CHUNK, store=path, progress=False)
    return ran, landing.load(path)


def signals(mc: landing.MonteCarloResult) -> dict[str, object]:
    return {"states": mc.states, "controls": mc.controls, **mc.diagnostics}


@pytest.mark.parametrize("which", ["returned", "loaded"])
def test_the_signals_stay_in_the_store_and_read_back_bit_for_bit(which, stored, whole):
    mc = stored[which == "loaded"]
    lazy = signals(mc)
    assert set(lazy) == {"states", "controls", "s1", "s2"}
    assert all(isinstance(v, StoredArray) for v in lazy.values()), {k: type(v) for k, v in lazy.items()}
    # in memory: the metrics, the initial and the final states only
    assert isinstance(mc.result.final_state, np.ndarray) and isinstance(mc.x0, np.ndarray)
    assert_same_campaign(mc, whole)
    truth = signals(whole)
    for name, v in lazy.items():
        x = truth[name]
        assert v.shape == x.shape and v.dtype == x.dtype and len(v) == N and v.ndim == x.ndim
        assert_same_bits(np.asarray(v), x, name)
        # numpy's indexing, the same bits: cases stay lazy, anything else is read
        for key in (slice(3, 17), slice(None, None, -3), [4, 0, 22, 4], np.arange(N) % 3 == 0, np.array([], int)):
            view = v[key]
            assert isinstance(view, StoredArray), (name, key)
            assert_same_bits(np.asarray(view), x[key], f"{name}[{key!r}]")
        for key in (7, -1, (slice(2, 9), -1), (..., 0), (slice(None), slice(5, 40, 7)), (slice(4, 6), [3, 1]),
                    (np.int64(2), slice(None), 1), (..., 0, slice(None)) if x.ndim == 3 else (..., 0)):
            got = v[key]
            assert isinstance(got, np.ndarray), (name, key)
            assert_same_bits(got, x[key], f"{name}[{key!r}]")
        assert_same_bits(np.asarray(v[2:20][[1, 5]][:, -1]), x[2:20][[1, 5]][:, -1], f"{name}, views of views")
        assert_same_bits(np.stack(list(v[:3])), x[:3], f"{name}, its cases iterated")
        with pytest.raises(TypeError, match="read-only"):
            v[0] = 0.0
        with pytest.raises(IndexError):
            v[N]


@pytest.mark.parametrize("which", ["returned", "loaded"])
def test_what_reads_the_signals_gives_the_in_memory_campaign_s_answers(which, stored, whole):
    mc = stored[which == "loaded"]
    for i in (0, 13, N - 1):
        one, truth = mc[i], whole[i]
        assert isinstance(one.states, np.ndarray)
        assert_same_bits(one.states, truth.states, f"mc[{i}].states")
        assert_same_bits(one.diagnostics["s2"], truth.diagnostics["s2"], f"mc[{i}] s2")
    part, truth_part = mc.result.cases(6, 19), whole.result.cases(6, 19)
    assert isinstance(part.controls, StoredArray)
    assert_same_bits(np.asarray(part.controls), truth_part.controls, "cases(6, 19)")
    assert_same_bits(np.asarray(mc.result.cases(np.array([2, 9])).states), whole.result.cases(np.array([2, 9])).states,
                     "cases([2, 9])")
    for signal in ("rz", "Fx", "s1", "s2", "m"):
        a, b = mc.bands(signal, (0, 5, 50, 95, 100)), whole.bands(signal, (0, 5, 50, 95, 100))
        assert_same_bits(a.values, b.values, f"bands({signal!r})")
        assert_same_bits(a.n, b.n, f"bands({signal!r}).n")
    assert_same_bits(mc.result.state("vz"), whole.result.state("vz"), "state('vz')")
    # the initial states the metrics' table adds: the states' first instant, read when asked
    assert mc.result.metrics.to_pandas().equals(whole.result.metrics.to_pandas())
    # xarray: the same Dataset, its signals lazily indexed Zarr variables until their values are asked
    ds, truth_ds = mc.to_xarray(), whole.to_xarray()
    assert not ds["states"].variable._in_memory and not ds["s1"].variable._in_memory
    assert list(ds.data_vars) == list(truth_ds.data_vars)
    xr.testing.assert_identical(ds, truth_ds)
    xr.testing.assert_identical(mc.result.to_xarray(), whole.result.to_xarray())
    assert_same_bits(ds["controls"].isel(case=4).values, whole.controls[4], "to_xarray, one case")
    # a pickled campaign reads from the same store
    assert_same_campaign(pickle.loads(pickle.dumps(mc)), whole)


def test_the_figures_draw_the_stored_campaign_as_the_in_memory_one(stored, whole):
    pytest.importorskip("matplotlib")
    from landing.plots import standard_figures

    def lines(fig):
        return [np.asarray(line.get_data(), dtype=float) for ax in fig.axes for line in ax.get_lines()]

    mine, truth = standard_figures(stored[1]), standard_figures(whole)
    assert list(mine) == list(truth)
    for name in truth:
        a, b = lines(mine[name]), lines(truth[name])
        assert len(a) == len(b), name
        for x, y in zip(a, b):
            assert_same_bits(x, y, name)


def test_a_resumed_and_a_partial_store_read_their_signals_lazily(tmp_path, monkeypatch, whole):
    path = tmp_path / "c"
    with monkeypatch.context() as m:
        crash_after_chunks(m, 2)
        with pytest.raises(KeyboardInterrupt):
            landing.monte_carlo(small_campaign(), N, seed=SEED, chunk_size=CHUNK, store=path, progress=False)
    part = landing.load(path, partial=True)
    assert part.partial and list(part.cases) == list(range(2 * CHUNK))
    assert isinstance(part.states, StoredArray)
    rows = whole.result.cases(0, 2 * CHUNK)
    for name in ("states", "controls"):
        assert_same_bits(np.asarray(getattr(part, name)), getattr(rows, name), f"partial {name}")
    assert_same_bits(np.asarray(part.diagnostics["s1"]), rows.diagnostics["s1"], "partial s1")
    assert_same_bits(part[3].states, whole[3].states, "partial mc[3]")
    resumed = landing.monte_carlo(small_campaign(), N, seed=SEED, store=path, progress=False)
    assert isinstance(resumed.states, StoredArray)
    assert_same_campaign(resumed, whole)
    assert_same_campaign(landing.load(path), whole)


def test_the_memory_check_counts_what_a_stored_campaign_holds():
    # issue 25: 10^6 cases of the main job's 60 s, recording every second (61 instants of 16
    # components: 7 808 bytes a case, 7.3 GiB in all) hold their metrics and states in memory,
    # under 2 GB, and two chunks' batches with a store; without one, everything
    s = landing.scenarios.mars_monte_carlo()
    n, every = 10**6, 1000
    in_memory = campaign_bytes(s, n, every, chunk=n)
    held = campaign_bytes(s, n, every, chunk=landing.campaign.store.default_chunk_size(n), stored=True)
    assert in_memory >= n * 7808
    assert held < 2e9 and held < in_memory / 4, (held, in_memory)


def test_a_campaign_too_large_with_its_trajectories_is_refused_naming_the_store(monkeypatch, tmp_path):
    from landing._internal import limits

    s = landing.scenarios.mars_monte_carlo()
    n, every = 10**6, 1000
    held = campaign_bytes(s, n, every, chunk=landing.campaign.store.default_chunk_size(n), stored=True)
    room = lambda: held + 2**20  # noqa: E731
    monkeypatch.setattr(limits, "available_memory", room)
    monkeypatch.setattr(landing.campaign.api, "available_memory", room)
    with pytest.raises(MemoryError, match=r"what fits: .*store=DIR \(the recorded signals written to disk"):
        landing.monte_carlo(s, n, record_every=every, progress=False)

    # with a store it passes the check: stopped where the store would be opened, after it
    class Opened(Exception):
        pass

    def opened(*args, **kwargs):
        raise Opened

    monkeypatch.setattr(landing.campaign.api, "open_campaign_store", opened)
    with pytest.raises(Opened):
        landing.monte_carlo(s, n, record_every=every, store=tmp_path / "big", progress=False)


#: A child process: a stored campaign with recording, its peak resident set (VmHWM: it starts
#: afresh at exec, unlike ru_maxrss, which a forked child inherits) over its peak after the
#: imports, in bytes.
CHILD = textwrap.dedent("""
    import sys, tempfile
    import numpy, pyarrow.parquet, pandas, xarray, zarr
    import landing

    def peak():
        with open("/proc/self/status") as f:
            return next(int(line.split()[1]) * 1024 for line in f if line.startswith("VmHWM:"))

    n = int(sys.argv[1])
    s = landing.scenarios.mars_monte_carlo(t_final=1.0, dt=2e-3, record_every=1)
    landing.monte_carlo(s, 10, seed=1, store=tempfile.mkdtemp() + "/warm", progress=False)  # first use
    base = peak()
    mc = landing.monte_carlo(s, n, seed=1, store=tempfile.mkdtemp() + "/c", progress=False)
    print(peak() - base)
""")


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="VmHWM is Linux's")
def test_memory_does_not_grow_with_the_trajectories(tmp_path):
    # 1 s at dt = 2 ms, recording every step: 501 instants of 16 components (states, thrust, s1,
    # s2), 64 128 bytes a case. From 2 000 to 20 000 cases the trajectories grow by
    # 18 000 * 64 128 B = 1.15 GB, which an in-memory campaign holds. A stored one holds per case
    # its metrics (27 columns, some per axis: 362 B), x0 and the final state (2 * 56 B) and the
    # theory's checks (about 150 B): 18 000 * 0.6 kB = 11 MB more; the chunk in hand is 1 000
    # cases either way (max(1000, n / 50)), 64 MB of batch. What else grows is glibc's: the
    # chunks' buffers, freed in the arenas of the core's and Zarr's threads, are kept there, so
    # the peak rises over the first chunks and then levels off (measured over the imports:
    # 2 000 cases +190 MB, 10 000 +305 MB, 20 000 +335 MB, 40 000 +365 MB). The growth must stay
    # under a quarter of the trajectories' (289 MB; measured about 150 MB).
    per_case = 8 * 501 * (7 + 3 + 3 + 3)
    growth = {}
    for n in (2_000, 20_000):
        out = subprocess.run([sys.executable, "-c", CHILD, str(n)], capture_output=True, text=True, timeout=120,
                             cwd=tmp_path)
        assert out.returncode == 0, out.stderr
        growth[n] = int(out.stdout.split()[-1])
    trajectories = (20_000 - 2_000) * per_case
    assert growth[20_000] - growth[2_000] < trajectories / 4, (growth, trajectories)
