"""A worker process killed mid-computation: the grid written to Zarr is still the one-call grid."""
import os
import pathlib
import signal
import time

import dask.array as da
import numpy as np
import pytest

import vds
import vds.dask
from conftest import local_cluster, sphere_mesh

distributed = pytest.importorskip("distributed")
zarr = pytest.importorskip("zarr")


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
        future = client.compute(da.to_zarr(distances, store, compute=False))
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
