"""vds.dask on a LocalCluster of two worker processes, against the single-process call."""
import dask
import dask.array as da
import numpy as np
import pytest

import vds
import vds.dask
from conftest import box_mesh

distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  worker_dashboard_address=None) as cluster, distributed.Client(cluster) as c:
        yield c


@pytest.fixture(scope="module")
def sprite():
    V, F = box_mesh((-1.0, -0.5, 0.0), (1.0, 0.5, 0.25))
    return vds.bake(V, F, resolution=64, method="cpu")


def test_cluster_answers_equal_the_single_process_call(client, sprite, tmp_path):
    points = da.random.RandomState(7).uniform(-1.2, 1.2, size=(400_000, 3), chunks=(25_000, 3))
    expected = sprite.contains(points.compute())
    assert 0.01 < expected.mean() < 0.2
    labels = vds.dask.contains(sprite, points)
    assert isinstance(labels, da.Array) and labels.dtype == bool and labels.shape == (400_000,)
    assert np.array_equal(labels.compute(), expected)
    # From a path, float32 points, and the winding rule.
    path = tmp_path / "box.vds"
    sprite.save(path)
    as32 = points.astype(np.float32)
    got = vds.dask.contains(path, as32, rule="winding").compute()
    assert np.array_equal(got, sprite.contains(as32.compute(), rule="winding"))
    # 16 chunks per computation, twice; each worker process decoded the sprite once.
    decodes = client.run(lambda: __import__("vds.dask").dask.decodes)
    assert len(decodes) == 2 and all(d <= 1 for d in decodes.values()) and sum(decodes.values()) >= 1


def test_other_schedulers_and_rechunking(sprite):
    points = da.random.RandomState(3).uniform(-1.2, 1.2, size=(30_000, 3), chunks=(7_000, 1))
    expected = sprite.contains(points.compute())
    for scheduler in ("threads", "sync"):
        with dask.config.set(scheduler=scheduler):
            assert np.array_equal(vds.dask.contains(sprite, points).compute(), expected)


def test_bad_input_fails_at_the_call_or_compute(sprite, tmp_path):
    with pytest.raises(ValueError, match=r"\(N, 3\)"):
        vds.dask.contains(sprite, da.zeros((10, 2), chunks=5))
    with pytest.raises(ValueError, match="float32 or float64"):
        vds.dask.contains(sprite, da.zeros((10, 3), dtype=np.int32, chunks=5))
    with pytest.raises(OSError):
        vds.dask.contains(tmp_path / "missing.vds", da.zeros((10, 3), chunks=5))
    (tmp_path / "bad.vds").write_bytes(b"nothing")
    with pytest.raises(vds.FormatError):
        vds.dask.contains(tmp_path / "bad.vds", da.zeros((10, 3), chunks=5))
    nan = da.from_array(np.array([[0.0, 0.0, 0.0], [np.nan, 0.0, 0.0]]), chunks=1)
    with dask.config.set(scheduler="sync"), pytest.raises(ValueError, match="not finite"):
        vds.dask.contains(sprite, nan).compute()
