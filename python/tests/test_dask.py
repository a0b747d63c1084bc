"""vds.dask on points, on a LocalCluster of two worker processes, against the one-process calls."""
import pickle

import dask
import dask.array as da
import numpy as np
import pytest

import vds
import vds.dask
from conftest import box_mesh, gl_or_skip, icosphere, sphere_mesh

pytest.importorskip("distributed")


def worker_builds(client):
    """{worker: {what: builds}} of every worker process."""
    return client.run(lambda: dict(__import__("vds._dask_ship")._dask_ship.builds))


@pytest.fixture(scope="module")
def sprite():
    V, F = box_mesh((-1.0, -0.5, 0.0), (1.0, 0.5, 0.25))
    return vds.bake(V, F, resolution=64, method="cpu")


def random_points(n, chunks, seed=7, scale=1.2):
    return da.random.RandomState(seed).uniform(-scale, scale, size=(n, 3), chunks=(chunks, 3))


def test_cluster_answers_equal_the_single_process_call(client, sprite, tmp_path):
    points = random_points(400_000, 25_000)
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
    builds = worker_builds(client)
    assert len(builds) == 2 and all(b.get("sprite", 0) <= 1 for b in builds.values())
    assert sum(b.get("sprite", 0) for b in builds.values()) >= 1


@pytest.mark.parametrize("method", [m.name for m in vds.methods()])
def test_every_method_on_the_cluster_equals_its_classifier(client, method):
    info = {m.name: m for m in vds.methods()}[method]
    if info.gpu or info.layer != "core":
        gl_or_skip()
    V, F = icosphere(2)
    points = random_points(20_000, 3_000, seed=11)
    P = points.compute()
    expected = vds.Classifier(V, F, method).classify(P)
    assert 0.2 < expected.mean() < 0.5
    assert np.array_equal(vds.dask.classify((V, F), points, method=method).compute(), expected)
    if info.from_sprite:
        sprite = vds.bake(V, F, resolution=64, method="cpu")
        expected = vds.Classifier(sprite, method).classify(P)
        assert np.array_equal(vds.dask.classify(sprite, points, method=method).compute(), expected)


def test_distances_and_winding_numbers_equal_the_one_process_calls(client, tmp_path):
    V, F = sphere_mesh(segments=24, rings=12)
    path = tmp_path / "sphere.obj"
    with open(path, "w") as f:
        f.writelines(f"v {x!r} {y!r} {z!r}\n" for x, y, z in V)
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in F)
    V, F = vds.load_mesh(path)
    # Uneven chunks, and columns split: rejoined.
    points = random_points(30_000, 4_000, seed=5).rechunk(((1_000, 12_000, 17_000), (1, 2))).astype(np.float32)
    P = points.compute()
    assert np.array_equal(vds.dask.signed_distance(path, points).compute(), vds.signed_distance(V, F, P))
    assert np.array_equal(vds.dask.winding_numbers((V, F), points).compute(), vds.winding_numbers(V, F, P))
    xyz, d, triangles = dask.compute(*vds.dask.closest_points(path, points))
    want = vds.closest_points(V, F, P)
    assert np.array_equal(xyz, want[0]) and np.array_equal(d, want[1]) and np.array_equal(triangles, want[2])
    assert triangles.dtype == np.uint32
    # Three chunks, three calls on the same mesh: one distance index per worker process.
    builds = worker_builds(client)
    assert all(b.get("distance", 0) <= 2 for b in builds.values())  # parity, and the closest points'
    again = vds.dask.signed_distance((V, F), points).compute()
    assert np.array_equal(again, vds.signed_distance(V, F, P))
    assert worker_builds(client) == builds  # the same bytes: nothing rebuilt


def test_sprite_winding_numbers_and_a_sprite_refused_for_distances(client, sprite):
    points = random_points(10_000, 2_500, seed=3)
    assert np.array_equal(vds.dask.winding_numbers(sprite, points).compute(),
                          sprite.winding_numbers(points.compute()))
    with pytest.raises(vds.InvalidArgument, match="needs a mesh"):
        vds.dask.signed_distance(sprite, points)


def test_other_schedulers_and_rechunking(sprite):
    points = random_points(30_000, 7_000, seed=3).rechunk((7_000, 1))
    expected = sprite.contains(points.compute())
    for scheduler in ("threads", "sync"):
        with dask.config.set(scheduler=scheduler):
            assert np.array_equal(vds.dask.contains(sprite, points).compute(), expected)
    V, F = icosphere(1)
    with dask.config.set(scheduler="processes", num_workers=2):
        got = vds.dask.signed_distance((V, F), points).compute()
    assert np.array_equal(got, vds.signed_distance(V, F, points.compute()))


def test_bad_input_fails_at_the_call_or_compute(client, sprite, tmp_path):
    with pytest.raises(ValueError, match=r"\(N, 3\)"):
        vds.dask.contains(sprite, da.zeros((10, 2), chunks=5))
    with pytest.raises(ValueError, match="float32 or float64"):
        vds.dask.contains(sprite, da.zeros((10, 3), dtype=np.int32, chunks=5))
    with pytest.raises(OSError):
        vds.dask.contains(tmp_path / "missing.vds", da.zeros((10, 3), chunks=5))
    with pytest.raises(OSError):
        vds.dask.classify(tmp_path / "missing.obj", da.zeros((10, 3), chunks=5))
    (tmp_path / "bad.vds").write_bytes(b"nothing")
    with pytest.raises(vds.FormatError):
        vds.dask.contains(tmp_path / "bad.vds", da.zeros((10, 3), chunks=5))
    with pytest.raises(vds.InvalidMesh):
        vds.dask.classify((np.zeros((3, 3)), np.array([[0, 1, 5]])), da.zeros((10, 3), chunks=5))
    with pytest.raises(vds.InvalidArgument, match="source"):
        vds.dask.classify(42, da.zeros((10, 3), chunks=5))


def test_a_non_finite_point_names_its_chunk_and_row(client, sprite):
    P = np.zeros((30, 3))
    P[23, 1] = np.nan
    points = da.from_array(P, chunks=(10, 3))
    for labels in (vds.dask.contains(sprite, points), vds.dask.signed_distance(box_mesh((0, 0, 0), (1, 1, 1)), points)):
        with pytest.raises(vds.InvalidArgument) as failure:
            labels.compute()
        message = str(failure.value)
        assert "points chunk 2 (rows 20 to 29): points[23] = (0.000000, nan, 0.000000) is not finite" in message
        assert "\n" not in message


def test_an_open_mesh_warns_once_at_the_call(client):
    V, F = icosphere(1)
    cup = (V, F[V[F].mean(axis=1)[:, 2] < 0.5])
    points = random_points(5_000, 2_500, seed=9)
    with pytest.warns(vds.MeshWarning, match="open"):
        labels = vds.dask.classify(cup, points, rule="parity")
    assert np.array_equal(labels.compute(), vds.exact_contains(*cup, points.compute()))


def test_shipped_sources_pickle_with_their_digest():
    V, F = box_mesh((0, 0, 0), (1, 1, 1))
    shipped = vds._dask_ship.ship((V, F), None)
    back = pickle.loads(pickle.dumps(shipped))
    assert back.digest == shipped.digest and len(back.digest) == 64
    assert all(np.array_equal(a, b) for a, b in zip(back.mesh(), (V, F)))
    assert vds._dask_ship.ship((V + 1, F), None).digest != shipped.digest


def test_methods_a_source_cannot_answer_fail_at_the_call(sprite):
    points = random_points(100, 50)
    with pytest.raises(vds.InvalidArgument, match="unknown method 'fastest'"):
        vds.dask.classify(sprite, points, method="fastest")
    with pytest.raises(vds.InvalidArgument, match="not made from a sprite"):
        vds.dask.classify(sprite, points, method="exact")
    with pytest.raises(vds.InvalidArgument, match="answers rule parity, not 'winding'"):
        vds.dask.occupancy(box_mesh((0, 0, 0), (1, 1, 1)), vds.Grid((0, 0, 0), (1, 1, 1), 8), method="solid",
                           rule="winding")
