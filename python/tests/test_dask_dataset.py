"""vds.dask.dataset: many meshes into Zarr on a LocalCluster, bad ones recorded, reruns resumed."""
import numpy as np
import pytest

import vds
import vds.dask
from conftest import icosphere

pytest.importorskip("distributed")
zarr = pytest.importorskip("zarr")


def write_obj(path, V, F):
    with open(path, "w") as f:
        f.writelines(f"v {x!r} {y!r} {z!r}\n" for x, y, z in V)
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in F)
    return path


@pytest.fixture(scope="module")
def meshes(tmp_path_factory):
    folder = tmp_path_factory.mktemp("meshes")
    V, F = icosphere(2)
    cup = F[V[F].mean(axis=1)[:, 2] < 0.3]
    (folder / "garbage.obj").write_text("v 0 0 0\nf 1 2 9\n")
    return {
        "ball": write_obj(folder / "ball.obj", V, F),
        "cup": write_obj(folder / "cup.obj", V, cup),
        "flat": write_obj(folder / "flat.obj", np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0.0]]), np.array([[0, 1, 2]])),
        "garbage": folder / "garbage.obj",
        "missing": folder / "missing.obj",
    }


def check_group(group, path, rule, sigma):
    assert group.attrs["complete"] and group.attrs["rule"] == rule and group.attrs["path"] == str(path)
    V, F = vds.load_mesh(path)
    assert group.attrs["report"] == vds.validate_mesh(V, F) | {"bounds": [list(b) for b in vds.validate_mesh(V, F)["bounds"]]}
    for part in ("uniform", "near_surface"):
        points = group[part]["points"][...]
        assert points.dtype == np.float32 and points.shape == (3000, 3)
        labels, sdf = group[part]["labels"][...], group[part]["sdf"][...]
        assert np.array_equal(labels, vds.exact_contains(V, F, points, rule=rule))
        assert np.array_equal(sdf, vds.signed_distance(V, F, points, rule=rule).astype(np.float32))
        assert np.array_equal(labels, np.signbit(sdf))
    lo, hi = np.array(group.attrs["box"])
    uniform = group["uniform"]["points"][...]
    assert (uniform >= lo.astype(np.float32)).all() and (uniform <= hi.astype(np.float32)).all()
    # Near the surface: displaced by the Gaussian stated (|sdf| <= |displacement|, mostly within 3 sigma).
    near = np.abs(group["near_surface"]["sdf"][...])
    assert group.attrs["sigma"] == pytest.approx(sigma * np.linalg.norm(V.max(0) - V.min(0)))
    assert np.mean(near < 3 * group.attrs["sigma"]) > 0.99 and np.mean(near > 0.1 * group.attrs["sigma"]) > 0.5


def test_a_dataset_of_good_and_bad_meshes_resumes(client, meshes, tmp_path):
    store = str(tmp_path / "samples.zarr")
    paths = list(meshes.values())
    status = vds.dask.dataset(paths, store, uniform=3000, near_surface=3000, sigma=0.02, seed=4)
    assert status["ball"] == status["cup"] == "written"
    for bad in ("flat", "garbage", "missing"):
        assert status[bad].startswith("error: ") and "\n" not in status[bad]
    assert "flat" in status["flat"] or "volume" in status["flat"]
    root = zarr.open_group(store, mode="r")
    check_group(root["ball"], meshes["ball"], "parity", 0.02)
    check_group(root["cup"], meshes["cup"], "generalized-winding", 0.02)
    assert root["missing"].attrs["error"] == status["missing"][len("error: "):] and not root["missing"].attrs["complete"]
    ball = root["ball"]["near_surface"]["points"][...]

    # A run cut off half-way through the cup: its group is not complete, and is rewritten whole.
    cut = zarr.open_group(store, mode="a")
    cut["cup"].attrs["complete"] = False
    del cut["cup"]["near_surface"]
    again = vds.dask.dataset(paths, store, uniform=3000, near_surface=3000, sigma=0.02, seed=4)
    assert again["ball"] == "complete" and again["cup"] == "written" and again["flat"] == status["flat"]
    check_group(zarr.open_group(store, mode="r")["cup"], meshes["cup"], "generalized-winding", 0.02)
    # The same seed gives the same points, wherever the mesh ran.
    assert np.array_equal(zarr.open_group(store, mode="r")["ball"]["near_surface"]["points"][...], ball)


def test_a_named_rule_and_duplicate_names(client, meshes, tmp_path):
    store = tmp_path / "named.zarr"
    status = vds.dask.dataset([meshes["cup"]], store, uniform=3000, near_surface=3000, rule="parity", sigma=0.01)
    assert status == {"cup": "written"}
    check_group(zarr.open_group(str(store), mode="r")["cup"], meshes["cup"], "parity", 0.01)
    with pytest.raises(vds.InvalidArgument, match="share the group 'ball'"):
        vds.dask.dataset([meshes["ball"], tmp_path / "ball.ply"], store)


def test_near_surface_points_are_vds_sample_surface(client, meshes, tmp_path):
    # With no displacement the near-surface points are the library's surface samples, on the triangles.
    store = str(tmp_path / "on_surface.zarr")
    vds.dask.dataset([meshes["cup"]], store, uniform=10, near_surface=2000, sigma=0.0, seed=7)
    points = zarr.open_group(store, mode="r")["cup"]["near_surface"]["points"][...]
    V, F = vds.load_mesh(meshes["cup"])
    _, d, _ = vds.closest_points(V, F, points)
    assert d.max() < 1e-6
    # Reproducible: the same seed, the same points.
    again = str(tmp_path / "again.zarr")
    vds.dask.dataset([meshes["cup"]], again, uniform=10, near_surface=2000, sigma=0.0, seed=7)
    assert np.array_equal(zarr.open_group(again, mode="r")["cup"]["near_surface"]["points"][...], points)
