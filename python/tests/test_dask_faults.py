"""A worker process killed mid-computation: the grid written to Zarr is still
the one-call grid, and every chunk of the store was written exactly once."""
import collections
import os
import pathlib
import signal
import time

import dask
import dask.array as da
import numpy as np
import pytest

import vds
import vds.dask
from conftest import local_cluster, sphere_mesh

distributed = pytest.importorskip("distributed")
zarr = pytest.importorskip("zarr")


class CountingStore(zarr.storage.DirectoryStore):
    """Zarr's directory store (each chunk file replaced whole) that also
    appends the key of every completed write to a log beside it, one line a
    write from whichever process made it (O_APPEND: lines do not interleave)."""

    def __init__(self, path, log):
        super().__init__(path)
        self.log = log

    def __setitem__(self, key, value):
        super().__setitem__(key, value)
        fd = os.open(self.log, os.O_WRONLY | os.O_APPEND | os.O_CREAT)
        try:
            os.write(fd, f"{key}\n".encode())
        finally:
            os.close(fd)


def writes(log):
    """How many times each chunk (not the metadata) was written."""
    keys = pathlib.Path(log).read_text().split()
    return collections.Counter(k for k in keys if not k.startswith("."))


def chunk_files(store):
    return [p for p in pathlib.Path(store).iterdir() if not p.name.startswith(".")]


def test_a_killed_worker_leaves_the_same_grid(tmp_path):
    V, F = sphere_mesh(segments=96, rings=48)
    grid = vds.Grid(V.min(0) - 0.3, V.max(0) + 0.3, 128)
    store = str(tmp_path / "sdf.zarr")
    distances = vds.dask.sdf((V, F), grid, chunks=32)  # the full grid: every block a few tens of ms
    assert distances.numblocks == (4, 4, 4)
    with local_cluster() as cluster, distributed.Client(cluster) as client:
        pids = client.run(os.getpid)
        log = str(tmp_path / "writes.log")
        future = client.compute(vds.dask.to_zarr(distances, CountingStore(store, log), compute=False))
        deadline = time.monotonic() + 60
        while (not os.path.isdir(store) or len(chunk_files(store)) < 4) and time.monotonic() < deadline:
            time.sleep(0.005)
        busy = [address for address, keys in client.processing().items() if keys] or list(pids)
        os.kill(pids[busy[0]], signal.SIGKILL)  # mid-task: no goodbye to the scheduler
        written_at_kill = len(chunk_files(store))
        future.result(timeout=120)
        assert set(client.run(os.getpid).values()) != set(pids.values())  # the nanny started a new one
    assert written_at_kill < 64
    files = chunk_files(store)
    assert len(files) == 64 and not any(".partial" in p.name for p in files)
    assert np.array_equal(zarr.open_array(store, mode="r")[...], vds.sdf(V, F, grid))
    # Each chunk written once: the killed worker's unfinished blocks by the
    # new one, none a second time (a rerun of a finished block would log it twice).
    counts = writes(log)
    assert sorted(counts) == sorted(p.name for p in files) and set(counts.values()) == {1}, counts


def test_to_zarr_writes_each_block_once_and_refuses_uneven_blocks(tmp_path):
    V, F = sphere_mesh()
    grid = vds.Grid(V.min(0) - 0.1, V.max(0) + 0.1, (20, 12, 16))
    labels = vds.dask.occupancy((V, F), grid, chunks=(8, 8, 16))
    log = str(tmp_path / "writes.log")
    with dask.config.set(scheduler="sync"):
        z = vds.dask.to_zarr(labels, CountingStore(str(tmp_path / "grid.zarr"), log))
        assert np.array_equal(z[...], vds.occupancy(V, F, grid))
        assert writes(log) == {f"{i}.{j}.0": 1 for i in range(3) for j in range(2)}
        with pytest.raises(ValueError, match="regular blocks"):
            vds.dask.to_zarr(labels.rechunk(((5, 15), (12,), (16,))), str(tmp_path / "uneven.zarr"))
    assert np.array_equal(zarr.open_array(str(tmp_path / "grid.zarr"), mode="r")[...], vds.occupancy(V, F, grid))


def test_a_temporary_chunk_a_killed_write_left_is_removed(tmp_path):
    # Zarr's directory store writes '<key>.<hex>.partial', then renames it: a
    # worker killed in between leaves that file. Made by hand here, between
    # the array's creation and its blocks' writes.
    V, F = sphere_mesh()
    grid = vds.Grid(V.min(0) - 0.1, V.max(0) + 0.1, 16)
    labels = vds.dask.occupancy((V, F), grid, chunks=8)
    store = tmp_path / "grid.zarr"
    with dask.config.set(scheduler="sync"):
        write = vds.dask.to_zarr(labels, str(store), compute=False)
        (store / "1.0.1.0123456789abcdef.partial").write_bytes(b"half a chunk")
        write.compute()
    assert sorted(p.name for p in chunk_files(store)) == sorted(
        f"{i}.{j}.{k}" for i in range(2) for j in range(2) for k in range(2))
    assert np.array_equal(zarr.open_array(str(store), mode="r")[...], vds.occupancy(V, F, grid))
