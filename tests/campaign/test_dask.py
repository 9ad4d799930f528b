"""Campaigns on a Dask cluster (a LocalCluster of two worker processes on loopback): the same
bits as the local run whatever the chunking, a worker killed mid-run, Ctrl-C and resume, the
store written by the cluster read back by landing.load, the command line's --scheduler, and
nothing of Dask on the local path."""

from __future__ import annotations

import asyncio
import json
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
from typing import Any

import pytest

import landing
from _cases import assert_same_campaign
from landing import scenarios
from landing.errors import ParameterTypeError

distributed = pytest.importorskip("distributed")

pytestmark = pytest.mark.dask


def small(**kw: Any) -> landing.scenarios.Scenario:
    return scenarios.mars_monte_carlo(t_final=5.0, dt=2e-3, record_every=25, **kw)


def need_io() -> None:
    for name in ("pyarrow", "zarr", "xarray", "pandas"):
        pytest.importorskip(name)




@pytest.fixture(scope="module")
def cluster():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                  dashboard_address=None) as c:
        yield c


@pytest.fixture(scope="module")
def client(cluster):
    with distributed.Client(cluster) as c:
        yield c


@pytest.fixture(scope="module")
def local():
    """The local runs the cluster's must reproduce."""
    return {
        "small": landing.monte_carlo(small(), 30, seed=3),
        "light": landing.monte_carlo(small(), 30, seed=3, keep=("controls",), record_every=50),
        "long": landing.monte_carlo(small(), 48, seed=5),
    }


def chunk_tasks(client, wait: float = 10.0) -> list[str]:
    """The campaign chunks the scheduler still knows, once it has forgotten them or after
    ``wait`` seconds (releasing and cancelling reach the scheduler asynchronously)."""
    deadline = time.monotonic() + wait
    while True:
        keys = client.run_on_scheduler(
            lambda dask_scheduler: [str(k) for k in dask_scheduler.tasks if str(k).startswith("landing-chunk")]
        )
        if not keys or time.monotonic() > deadline:
            return keys
        time.sleep(0.05)


@pytest.mark.parametrize("chunk_size", [1, 7, 30])
def test_same_bits_as_the_local_run_whatever_the_chunks(client, local, chunk_size):
    mc = landing.monte_carlo(small(), 30, seed=3, client=client, chunk_size=chunk_size, threads=1)
    assert_same_campaign(mc, local["small"])
    assert chunk_tasks(client) == []  # every chunk released once gathered (none left behind)


def test_signals_not_kept_are_dropped_on_the_workers(client, local):
    mc = landing.monte_carlo(small(), 30, seed=3, client=client, chunk_size=8, keep=("controls",),
                             record_every=50)
    assert mc.states is None and mc.diagnostics == {}
    assert_same_campaign(mc, local["light"])


@pytest.mark.io
def test_a_store_written_by_the_cluster_loads_as_the_local_run(client, local, tmp_path):
    need_io()
    path = tmp_path / "campaign"
    mc = landing.monte_carlo(small(), 30, seed=3, client=client, chunk_size=7, store=path)
    assert mc.store == str(path)
    manifest = json.loads((path / "manifest.json").read_text())
    assert manifest["complete"] and [c["index"] for c in manifest["chunks"]] == [0, 1, 2, 3, 4]
    assert_same_campaign(mc, local["small"])
    assert_same_campaign(landing.load(path), local["small"])


@pytest.mark.io
def test_ctrl_c_cancels_the_outstanding_chunks_and_a_rerun_resumes(client, local, tmp_path, monkeypatch):
    need_io()
    from landing.campaign.store import CampaignStore

    written: list[int] = []
    interrupted: list[bool] = []
    original = CampaignStore.write_chunk

    def write_then_interrupt(self, index, *args, **kwargs):
        original(self, index, *args, **kwargs)
        written.append(index)
        if len(written) == 3 and not interrupted:  # Ctrl-C once the third chunk is stored
            interrupted.append(True)
            raise KeyboardInterrupt

    path = tmp_path / "campaign"
    monkeypatch.setattr(CampaignStore, "write_chunk", write_then_interrupt)
    with pytest.raises(KeyboardInterrupt):
        landing.monte_carlo(small(), 48, seed=5, client=client, chunk_size=4, store=path)
    manifest = json.loads((path / "manifest.json").read_text())
    assert sorted(c["index"] for c in manifest["chunks"]) == sorted(written) and len(written) == 3
    assert chunk_tasks(client) == [], "the outstanding chunks were not cancelled"

    first = list(written)
    written.clear()
    mc = landing.monte_carlo(small(), 48, seed=5, client=client, store=path)  # the store's chunk size
    assert sorted(written) == sorted(set(range(12)) - set(first))  # only the missing chunks ran
    assert_same_campaign(mc, local["long"])
    assert_same_campaign(landing.load(path), local["long"])


def test_a_fetch_cancelled_by_an_earlier_ctrl_c_does_not_break_the_next_campaign(client, local):
    # Ctrl-C inside future.result() can leave distributed's shared fetch cancelled in place
    # (Client._gather_future); every later fetch on the client then failed. Put the client in
    # that state on purpose, then run a campaign on it.
    async def cancelled_fetch() -> None:
        pending = asyncio.get_running_loop().create_future()
        pending.cancel()
        client._gather_future = pending
        client._gather_keys = set()

    client.sync(cancelled_fetch)
    mc = landing.monte_carlo(small(), 30, seed=3, client=client)
    assert_same_campaign(mc, local["small"])


@pytest.mark.io
@pytest.mark.slow
def test_a_real_sigint_mid_campaign_then_a_rerun_gives_the_same_bits(client, tmp_path):
    need_io()
    # 12 chunks of 8 cases x 6e4 steps: a tenth of a second or more each on one thread
    scenario = scenarios.mars_monte_carlo(record_every=2000)
    path = tmp_path / "campaign"

    def stored() -> int:
        try:
            return len(json.loads((path / "manifest.json").read_text())["chunks"])
        except (OSError, ValueError, KeyError):
            return 0

    def ctrl_c_after_one_chunk() -> None:
        deadline = time.monotonic() + 60
        while stored() < 1 and time.monotonic() < deadline:
            time.sleep(0.005)
        os.kill(os.getpid(), signal.SIGINT)

    sender = threading.Thread(target=ctrl_c_after_one_chunk, daemon=True)
    sender.start()
    with pytest.raises(KeyboardInterrupt):
        landing.monte_carlo(scenario, 96, seed=2, client=client, chunk_size=8, store=path, progress=False)
        time.sleep(5)  # the campaign ended before the signal: let it land here, and fail below
    sender.join(timeout=10)
    assert 1 <= stored() < 12, "the signal did not come mid-campaign"
    assert chunk_tasks(client) == [], "the outstanding chunks were not cancelled"
    mc = landing.monte_carlo(scenario, 96, seed=2, client=client, store=path, progress=False)
    reference = landing.monte_carlo(scenario, 96, seed=2, progress=False)
    assert_same_campaign(mc, reference)
    assert_same_campaign(landing.load(path), reference)


@pytest.mark.io
def test_the_command_line_runs_on_a_scheduler(cluster, local, tmp_path, capsys):
    need_io()
    from landing.cli import main

    toml = tmp_path / "small.toml"
    toml.write_text(small().to_toml())
    path = tmp_path / "campaign"
    code = main(["mc", str(toml), "--cases", "30", "--seed", "3", "--chunk-size", "10", "--store", str(path),
                 "--scheduler", cluster.scheduler_address, "--no-progress", "--out", ""])
    assert code == 0, capsys.readouterr().err
    assert "30 cases in" in capsys.readouterr().out
    assert_same_campaign(landing.load(path), local["small"])


def test_a_client_of_another_type_is_refused():
    with pytest.raises(ParameterTypeError, match="client must be a distributed.Client, got str"):
        landing.monte_carlo(small(), 2, client="tcp://127.0.0.1:8786")


def test_a_scenario_that_cannot_reach_the_workers_is_refused_by_name(client):
    from landing.errors import ParameterError

    lock = threading.Lock()

    def locked(t, e, de, ref, drift, inertia, params, memory):
        with lock:
            return -drift - e - de

    # a law no file can name (a closure) and no pickle can carry (it holds a lock)
    s = small().replace(controller=landing.controllers.PythonLaw(locked))
    with pytest.raises(ParameterError, match="scenario = 'mars_monte_carlo' cannot be sent to the cluster"):
        landing.monte_carlo(s, 4, client=client)


def test_without_dask_the_error_names_the_extra(monkeypatch, capsys):
    from landing.cli import main

    monkeypatch.setitem(sys.modules, "distributed", None)  # "import distributed" now raises ImportError
    with pytest.raises(ImportError, match='pip install "landing\\[dask\\]"'):
        landing.monte_carlo(small(), 2, client=object())
    assert main(["mc", "mars_monte_carlo", "--cases", "2", "--scheduler", "tcp://127.0.0.1:1", "--out", ""]) == 1
    assert 'pip install "landing[dask]"' in capsys.readouterr().err


LOCAL_PATH = textwrap.dedent(
    """
    import sys, tempfile
    import landing

    def loaded():
        return sorted(m for m in sys.modules
                      if m.split(".")[0] in ("dask", "distributed") or m == "landing.campaign.dask")

    s = landing.scenarios.mars_monte_carlo(t_final=1.0, dt=2e-3)
    landing.monte_carlo(s, 4, seed=1, chunk_size=2)
    print(loaded())
    try:
        import pyarrow, zarr, xarray, pandas
    except ImportError:
        print([])
    else:
        with tempfile.TemporaryDirectory() as d:
            landing.monte_carlo(s, 4, seed=1, chunk_size=2, store=d + "/c")
            landing.load(d + "/c")
        # xarray's Zarr writer imports dask itself when it is installed; the scheduler, never
        print([m for m in loaded() if m.split(".")[0] != "dask"])
    """
)


def test_the_local_path_imports_nothing_of_dask():
    out = subprocess.run([sys.executable, "-c", LOCAL_PATH], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split("\n")[:2] == ["[]", "[]"], out.stdout


def lost_chunks(client) -> list[str]:
    """Chunks the scheduler took back from a worker that died while it ran them or held their
    result (transitions out of "processing" or "memory" caused by the worker's removal)."""

    def scan(dask_scheduler) -> list[str]:
        out = []
        for key, start, finish, _, stimulus, *_ in dask_scheduler.transition_log:
            if (str(key).startswith("landing-chunk") and start in ("processing", "memory")
                    and finish in ("released", "waiting") and "worker" in str(stimulus)
                    and "client" not in str(stimulus)):
                out.append(f"{key}: {start} -> {finish} ({stimulus})")
        return out

    return client.run_on_scheduler(scan)


# last: it kills one of the module's workers (its nanny starts another)
@pytest.mark.io
@pytest.mark.slow
def test_a_worker_killed_mid_run_costs_only_its_chunks(client, tmp_path):
    need_io()
    # 24 chunks of 16 cases x 6e4 steps: a few tenths of a second each on one thread
    scenario = scenarios.mars_monte_carlo(record_every=1000)
    reference = landing.monte_carlo(scenario, 384, seed=11, record_every=1000, progress=False)
    pids = client.run(os.getpid)
    assert len(pids) == 2
    assert lost_chunks(client) == []
    path = tmp_path / "campaign"
    n_chunks = 24
    killed: dict[str, Any] = {}

    def completed() -> int:
        try:
            return len(json.loads((path / "manifest.json").read_text())["chunks"])
        except (OSError, ValueError, KeyError):
            return 0

    def kill_one_after_two_chunks() -> None:
        deadline = time.monotonic() + 60
        address, victim = next(iter(pids.items()))
        while time.monotonic() < deadline:  # two chunks stored, and the victim running one
            if completed() >= 2 and client.processing(workers=[address])[address]:
                break
            time.sleep(0.01)
        killed["running"] = client.processing(workers=[address])[address]
        killed["done_before"] = completed()
        os.kill(victim, signal.SIGKILL)
        killed["pid"] = victim

    killer = threading.Thread(target=kill_one_after_two_chunks, daemon=True)
    killer.start()
    mc = landing.monte_carlo(scenario, 384, seed=11, client=client, chunk_size=16, store=path, progress=False)
    killer.join(timeout=30)
    assert "pid" in killed, "no worker was killed"
    # the kill came while chunks were outstanding, one of them on the victim
    assert 2 <= killed["done_before"] < n_chunks, killed
    assert killed["running"], killed
    lost = lost_chunks(client)
    assert lost, "no chunk was taken back from the killed worker"
    assert_same_campaign(mc, reference)
    assert completed() == n_chunks
    assert_same_campaign(landing.load(path), reference)


@pytest.mark.dask
def test_a_cluster_without_workers_is_an_error_after_the_timeout_not_a_wait_for_ever(monkeypatch):
    distributed = pytest.importorskip("distributed")
    import time

    from landing.errors import SimulationError

    monkeypatch.setenv("LANDING_NO_WORKER_TIMEOUT", "2")
    with distributed.LocalCluster(n_workers=0, processes=True, host="127.0.0.1", dashboard_address=":0") as cluster, \
            distributed.Client(cluster) as client:
        start = time.monotonic()
        with pytest.raises(SimulationError, match="no worker for 2 s"):
            landing.monte_carlo(small(), 8, seed=1, client=client, chunk_size=4, check_bounds=False)
        assert time.monotonic() - start < 30
    monkeypatch.setenv("LANDING_NO_WORKER_TIMEOUT", "soon")
    from landing.campaign.dask import no_worker_timeout

    with pytest.raises(landing.ParameterError, match="LANDING_NO_WORKER_TIMEOUT"):
        no_worker_timeout()
