"""A store never returns wrong data: each kind of damage to a chunk's files (a flipped byte, a
truncated or deleted file, Parquet parts swapped) is named by ``load`` and ``landing report``,
never read as data or as fill, and a resume re-runs exactly the damaged chunks, after which the
campaign is the uninterrupted run's bit for bit."""

from __future__ import annotations

import os
import pickle
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import landing
from _cases import assert_same_campaign
from landing import scenarios
from landing.errors import StoreError, StoreWarning

pytest.importorskip("pyarrow")
pytest.importorskip("zarr")

pytestmark = pytest.mark.io

N, CHUNK = 20, 5


def small():
    return scenarios.mars_monte_carlo(t_final=5.0, dt=2e-3, record_every=25)


@pytest.fixture(scope="module")
def whole() -> landing.MonteCarloResult:
    return landing.monte_carlo(small(), N, seed=3)


@pytest.fixture()
def store(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("s") / "c"
    landing.monte_carlo(small(), N, seed=3, chunk_size=CHUNK, store=path)
    return path


def flip(file: Path, at: float = 0.5) -> None:
    data = bytearray(file.read_bytes())
    data[int(len(data) * at)] ^= 0xFF
    file.write_bytes(bytes(data))


def zarr_chunk(store: Path, array: str, index: int) -> Path:
    files = sorted((store / "trajectories.zarr" / array).glob(f"{index}.*"))
    assert files, f"no Zarr chunk {index} of {array}"
    return files[0]


DAMAGE = {
    "a flipped byte in a Zarr chunk": lambda s: flip(zarr_chunk(s, "states", 2)),
    "a deleted Zarr chunk": lambda s: zarr_chunk(s, "controls", 2).unlink(),
    "a flipped byte in a metrics part": lambda s: flip(s / "chunks" / "metrics" / "part-000002.parquet", 0.3),
    "a truncated initial-state part": lambda s: (s / "chunks" / "initial" / "part-000002.parquet").write_bytes(
        (s / "chunks" / "initial" / "part-000002.parquet").read_bytes()[:100]),
    "a deleted metrics part": lambda s: (s / "chunks" / "metrics" / "part-000002.parquet").unlink(),
    "metrics parts swapped": lambda s: swap(s / "chunks" / "metrics" / "part-000002.parquet",
                                           s / "chunks" / "metrics" / "part-000001.parquet"),
}


def swap(a: Path, b: Path) -> None:
    tmp = a.with_suffix(".tmp")
    shutil.move(a, tmp)
    shutil.move(b, a)
    shutil.move(tmp, b)


@pytest.mark.parametrize("kind", list(DAMAGE))
def test_damage_is_named_by_load_and_report_and_resume_runs_the_chunk_again(kind, store, whole, capsys):
    DAMAGE[kind](store)
    with pytest.raises(StoreError, match=r"chunk (1|2) \(cases (5\.\.9|10\.\.14)\) is damaged") as info:
        landing.load(store)
    assert str(store) in str(info.value) and "re-runs the damaged chunks" in str(info.value)
    from landing.cli import main

    assert main(["report", str(store), "--out", ""]) == 2
    assert "is damaged" in capsys.readouterr().err
    # the resume: the damaged chunk(s) run again, then everything reads back as the whole run
    with pytest.warns(StoreWarning, match="running it again"):
        resumed = landing.monte_carlo(small(), N, seed=3, store=store)
    assert_same_campaign(resumed, whole)
    assert_same_campaign(landing.load(store), whole)


def test_an_undamaged_store_reads_without_warning(store, whole):
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error", StoreWarning)
        assert_same_campaign(landing.monte_carlo(small(), N, seed=3, store=store), whole)


def test_the_manifest_holds_a_checksum_of_every_part_of_every_chunk(store):
    import json

    manifest = json.loads((store / "manifest.json").read_text())
    assert len(manifest["chunks"]) == N // CHUNK
    for c in manifest["chunks"]:
        assert set(c["sha256"]) == {"metrics", "initial", "trajectories"}
        assert all(len(h) == 64 and int(h, 16) >= 0 for h in c["sha256"].values())
    # the checksum is of the content: a NaN's payload does not change it
    from landing.campaign.store import _digest

    a = np.array([1.0, np.nan])
    b = a.copy()
    b.view(np.uint64)[1] |= 1  # another NaN
    assert _digest({"x": a}) == _digest({"x": b}) != _digest({"x": np.array([1.0, 2.0])})


def edit(path: Path, change) -> None:
    import json

    d = json.loads(path.read_text())
    change(d)
    path.write_text(json.dumps(d))


PROVENANCE_EDITS = {
    "the seed": lambda d: d["key"].update(seed=d["key"]["seed"] + 1),
    "the scenario's text": lambda d: d["key"].update(scenario=d["key"]["scenario"].replace("isp = 225.0",
                                                                                           "isp = 230.0")),
    "keep": lambda d: d["key"].update(keep=["states"]),
    "record_every": lambda d: d["key"].update(record_every=50),
}


@pytest.mark.parametrize("what", list(PROVENANCE_EDITS))
def test_a_provenance_edited_against_its_data_is_refused(what, store):
    edit(store / "provenance.json", PROVENANCE_EDITS[what])
    with pytest.raises(landing.LandingError) as info:
        landing.load(store)
    assert str(store) in str(info.value) or "store" in str(info.value)


RECORD_DAMAGE = {
    # the probe's foreign errors (issue 24): JSONDecodeError, TypeError, KeyError, AttributeError,
    # FileNotFoundError from a store's records and tree
    "provenance not JSON": (lambda s: (s / "provenance.json").write_text("{not json"),
                            r"its provenance\.json \(.*provenance\.json\) cannot be read"),
    "provenance a list": (lambda s: (s / "provenance.json").write_text("[]"),
                          r"its provenance\.json \(.*\) is not a JSON object"),
    "the seed gone from the provenance": (lambda s: edit(s / "provenance.json", lambda d: d["key"].pop("seed")),
                                          r"its provenance\.json \(.*\) does not record the campaign"),
    "n a string": (lambda s: edit(s / "provenance.json", lambda d: d["key"].update(n="twenty")),
                   r"records key\.n = 'twenty', which must be an integer >= 1"),
    "manifest deleted": (lambda s: (s / "manifest.json").unlink(), r"its manifest\.json is missing \(.*manifest"),
    "manifest a list": (lambda s: (s / "manifest.json").write_text("[1, 2]"),
                        r"its manifest\.json \(.*\) is not a JSON object"),
    "a chunk's bounds edited": (lambda s: edit(s / "manifest.json", lambda d: d["chunks"][1].update(start="five")),
                                r"its manifest\.json \(.*\) records a chunk that is not one of the campaign's 4"),
    "a chunk's stop gone": (lambda s: edit(s / "manifest.json", lambda d: d["chunks"][0].pop("stop")),
                            r"records a chunk that is not one of the campaign's 4"),
    "the Zarr tree deleted": (lambda s: shutil.rmtree(s / "trajectories.zarr"),
                              r"its Zarr tree is damaged: .*trajectories\.zarr.* cannot be read"),
    "a flipped byte in a coordinate's metadata": (
        lambda s: flip(s / "trajectories.zarr" / "axis" / ".zarray", 0.2),
        r"its Zarr tree is damaged: .*axis/\.zarray does not match its checksum"),
    "the time coordinate truncated": (
        lambda s: (s / "trajectories.zarr" / "time" / "0").write_bytes(b""),
        r"its Zarr tree is damaged: .*time/0 does not match its checksum"),
}


@pytest.mark.parametrize("what", list(RECORD_DAMAGE))
def test_a_damaged_record_or_tree_is_a_store_error_naming_the_file(what, store, whole, capsys):
    damage, pattern = RECORD_DAMAGE[what]
    damage(store)
    with pytest.raises(StoreError, match=pattern) as info:
        landing.load(store)
    assert f"store = '{store}'" in str(info.value) and "run the campaign again" in str(info.value)
    from landing.cli import main

    assert main(["report", str(store), "--out", ""]) == 2
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 1 and str(store) in err[0], err
    if what == "manifest deleted":
        # a store with no manifest is one whose creation was interrupted: a resume runs every chunk
        assert_same_campaign(landing.monte_carlo(small(), N, seed=3, store=store), whole)
    else:
        # a resume is refused the same way, not with a foreign error
        with pytest.raises(StoreError, match=pattern):
            landing.monte_carlo(small(), N, seed=3, store=store)


def test_a_store_of_an_unknown_format_is_refused(store):
    edit(store / "manifest.json", lambda d: d.update(format=99))
    with pytest.raises(StoreError, match="format 99 is not this version's"):
        landing.load(store)


def test_a_full_disk_is_a_store_error_naming_the_file_and_the_resume_completes(tmp_path, whole, monkeypatch):
    import errno
    import os

    path = tmp_path / "c"
    real = os.replace

    def full(src, dst, *args, **kwargs):
        if os.path.basename(dst) == "part-000001.parquet":  # a Parquet part of chunk 1
            raise OSError(errno.ENOSPC, "No space left on device", str(dst))
        return real(src, dst, *args, **kwargs)

    with monkeypatch.context() as m:
        m.setattr(os, "replace", full)
        with pytest.raises(StoreError, match=r"writing chunk \d .* failed .*: No space left on device; free space"):
            landing.monte_carlo(small(), N, seed=3, chunk_size=CHUNK, store=path)
    assert_same_campaign(landing.monte_carlo(small(), N, seed=3, store=path), whole)


def _read_only_copy(store: Path, where: Path) -> Path:
    """A copy of ``store`` no one may write: every file 0444, every folder 0555."""
    copy = where / "read-only"
    shutil.copytree(store, copy)
    for p in sorted(copy.rglob("*"), reverse=True) + [copy]:
        p.chmod(0o555 if p.is_dir() else 0o444)
    return copy


def _without_write_access() -> list[str]:
    """The command prefix that runs a process subject to file modes: none for a user that is not
    root; for root, setpriv dropping the capabilities that override them (the store's owner is
    then refused writes by its 0444 and 0555 modes, like any user)."""
    if os.geteuid() != 0:
        return []
    setpriv = shutil.which("setpriv")
    if setpriv is None:
        pytest.skip("running as root, which ignores file modes, and setpriv (util-linux) is missing to drop that")
    caps = "-dac_override,-dac_read_search,-fowner"
    return [setpriv, f"--inh-caps={caps}", f"--bounding-set={caps}", "--"]


@pytest.mark.skipif(os.name != "posix", reason="file modes and capabilities are POSIX")
def test_a_complete_store_reads_without_write_access(store, whole, tmp_path):
    copy = _read_only_copy(store, tmp_path)
    prefix = _without_write_access()
    try:
        # the prefix does take write access away: the child cannot create a file in the copy
        probe = subprocess.run(prefix + [sys.executable, "-c", f"open({str(copy / 'x')!r}, 'w')"],
                               capture_output=True, text=True)
        assert probe.returncode != 0 and "Permission denied" in probe.stderr
        loaded = subprocess.run(
            prefix + [sys.executable, "-c",
                      f"import pickle, sys, landing; pickle.dump(landing.load({str(copy)!r}), sys.stdout.buffer)"],
            capture_output=True)
        assert loaded.returncode == 0, loaded.stderr.decode()
        assert_same_campaign(pickle.loads(loaded.stdout), whole)
        for args in (["report", str(copy), "--out", ""], ["verify", str(copy), "fuel_used >= 0", "--p", "0.5"]):
            cli = subprocess.run(prefix + [sys.executable, "-m", "landing", *args], capture_output=True, text=True)
            assert cli.returncode == 0 and cli.stderr == "", (args, cli.stderr)
        assert not (copy / "x").exists()
    finally:
        for p in [copy, *copy.rglob("*")]:
            p.chmod(0o755 if p.is_dir() else 0o644)
