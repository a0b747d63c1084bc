"""Exact distances from Python: vds.signed_distance, vds.closest_points,
vds.sdf and vds.SignedDistance against a brute-force distance computed here
in numpy (plane or nearest edge, over every triangle), the sign against the
exact classifier of the same rule, and bad input."""
import sys
import warnings

import numpy as np
import pytest

import vds
from conftest import box_mesh, sphere_mesh


def _segment_distance(P, A, B):
    AB = B - A
    t = np.clip(np.einsum("pij,pij->pi", P[:, None, :] - A, AB[None]) / np.maximum(np.einsum("ij,ij->i", AB, AB), 1e-300),
                0.0, 1.0)
    return np.linalg.norm(P[:, None, :] - (A + t[..., None] * AB), axis=-1)


def brute_force(V, F, P, as_float32=True):
    """Distance of each point to the nearest triangle: to the plane where the
    point projects inside the triangle, else to the nearest of its edges."""
    P = (P.astype(np.float32) if as_float32 else P).astype(np.float64)  # points as the library reads them
    V = np.asarray(V).astype(np.float32).astype(np.float64)
    A, B, C = (V[F[:, k]].astype(np.float64) for k in range(3))
    edges = np.minimum(np.minimum(_segment_distance(P, A, B), _segment_distance(P, B, C)), _segment_distance(P, C, A))
    N = np.cross(B - A, C - A)
    inside = np.ones(edges.shape, bool)
    for X, Y in ((A, B), (B, C), (C, A)):
        inside &= np.einsum("pij,ij->pi", np.cross(Y - X, P[:, None, :] - X), N) >= 0
    plane = np.abs(np.einsum("pij,ij->pi", P[:, None, :] - A, N)) / np.linalg.norm(N, axis=1)
    return np.where(inside, np.minimum(plane, edges), edges).min(axis=1)


def sample(V, n=300, seed=1):
    rng = np.random.default_rng(seed)
    lo, hi = V.min(0), V.max(0)
    pad = 0.2 * (hi - lo)
    return rng.uniform(lo - pad, hi + pad, size=(n, 3)).astype(np.float32)


def open_cup():
    V, F = sphere_mesh(segments=32, rings=16)
    centroids = V[F].mean(axis=1)
    return V, F[centroids[:, 2] < 0.5]


@pytest.mark.parametrize("mesh, rule", [(sphere_mesh(segments=32, rings=16), "parity"),
                                        (box_mesh((0, 0, 0), (1, 2, 3)), "winding"),
                                        (open_cup(), "generalized-winding")])
def test_signed_distance_equals_brute_force_and_the_classifier(mesh, rule):
    V, F = mesh
    P = sample(V)
    d = vds.signed_distance(V, F, P, rule=rule)
    assert d.dtype == np.float64 and d.shape == (len(P),)
    np.testing.assert_allclose(np.abs(d), brute_force(V, F, P), rtol=0, atol=1e-12)
    inside = vds.exact_contains(V, F, P, rule=rule)
    np.testing.assert_array_equal(np.signbit(d), inside)
    assert 0 < inside.sum() < len(P)


def test_closest_points_lie_at_the_distance():
    V, F = sphere_mesh(segments=32, rings=16)
    P = sample(V, 200, seed=2)
    Q, d, T = vds.closest_points(V, F, P)
    assert Q.shape == (len(P), 3) and T.dtype == np.uint32
    np.testing.assert_allclose(np.linalg.norm(P.astype(np.float64) - Q, axis=1), d, rtol=0, atol=1e-12)
    V = V.astype(np.float32)
    np.testing.assert_allclose(d, brute_force(V, F, P), rtol=0, atol=1e-12)
    # Each closest point lies on its own triangle.
    for k in range(0, len(P), 7):
        assert brute_force(V, F[T[k:k + 1]], Q[k:k + 1], as_float32=False)[0] < 1e-12


def test_one_query_many_calls_and_double_points():
    V, F = sphere_mesh(segments=32, rings=16)
    query = vds.SignedDistance(V, F, rule="winding")
    P = sample(V, 100, seed=3)
    np.testing.assert_array_equal(query.distance(P.astype(np.float64)), query.distance(P))
    np.testing.assert_array_equal(np.abs(query.distance(P)), query.unsigned_distance(P, threads=1))
    assert query.rule == "winding"


def test_sdf_equals_the_distances_of_the_cell_centres():
    V, F = sphere_mesh(segments=32, rings=16)
    grid = vds.Grid((-1.3, -1.2, -1.1), (1.2, 1.3, 1.4), (17, 19, 21))
    cells = vds.sdf(V, F, grid, rule="parity")
    assert cells.dtype == np.float32 and cells.shape == grid.shape
    centres = grid.cell_centres().reshape(-1, 3)
    expected = vds.signed_distance(V, F, centres).astype(np.float32).reshape(grid.shape)
    np.testing.assert_array_equal(cells, expected)
    np.testing.assert_array_equal(np.signbit(cells), vds.occupancy(V, F, grid))
    band = vds.sdf(V, F, grid, band=0.1)
    far = np.abs(expected) >= np.float32(0.1)
    assert far.any() and (~far).any()
    np.testing.assert_array_equal(band[~far], expected[~far])
    np.testing.assert_array_equal(band[far], np.where(np.signbit(expected[far]), -0.1, 0.1).astype(np.float32))


def test_propagated_sdf_is_exact_near_the_surface_and_within_its_bound_beyond():
    V, F = sphere_mesh(segments=32, rings=16)
    grid = vds.Grid((-1.3, -1.2, -1.1), (1.2, 1.3, 1.4), (17, 19, 21))
    exact = vds.sdf(V, F, grid).astype(np.float64)
    propagated = vds.sdf(V, F, grid, propagated=True).astype(np.float64)
    diagonal = np.linalg.norm((np.array([1.2, 1.3, 1.4]) - np.array([-1.3, -1.2, -1.1])) / np.array(grid.shape))
    np.testing.assert_array_equal(np.signbit(propagated), np.signbit(exact))
    near = np.abs(exact) < diagonal
    assert near.any() and (~near).any()
    np.testing.assert_array_equal(propagated[near], exact[near])
    error = np.abs(propagated) - np.abs(exact)
    assert error.min() >= -1e-6 and error.max() <= 4 * diagonal + 1e-6
    with pytest.raises(vds.InvalidArgument, match="full grid"):
        vds.sdf(V, F, grid, band=0.1, propagated=True)


def test_bad_input_raises_one_clear_error():
    V, F = sphere_mesh(segments=16, rings=8)
    P = np.array([[0, 0, 0], [np.nan, 0, 0]], np.float32)
    with pytest.raises(vds.InvalidArgument, match="not finite"):
        vds.signed_distance(V, F, P)
    with pytest.raises(vds.InvalidMesh):
        vds.signed_distance(np.zeros((0, 3)), np.zeros((0, 3), np.int32), P[:1])
    flat = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float)
    with pytest.raises(vds.InvalidMesh, match="flat"):
        vds.signed_distance(flat, np.array([[0, 1, 2]]), P[:1], rule="generalized-winding")
    with pytest.warns(vds.MeshWarning, match="open"):
        vds.signed_distance(*open_cup(), P[:1], rule="parity")
    grid = vds.Grid((-1, -1, -1), (1, 1, 1), 4)
    for band in (-1.0, float("nan"), float("inf")):
        with pytest.raises(vds.InvalidArgument):
            vds.sdf(V, F, grid, band=band)


def test_the_command_line_gives_the_same_values(tmp_path):
    """vds distance (the C++ library through the CLI) and Python on the same points."""
    import pathlib
    import subprocess

    tool = pathlib.Path(vds.__file__).resolve().parents[2] / "tools" / "vds"
    if not tool.exists():
        pytest.skip("the vds tool is not built beside this module")
    V, F = sphere_mesh(segments=32, rings=16)
    with open(tmp_path / "sphere.obj", "w") as f:
        f.writelines(f"v {x:.9g} {y:.9g} {z:.9g}\n" for x, y, z in V.astype(np.float32))
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in F)
    P = sample(V, 200, seed=4)
    np.save(tmp_path / "points.npy", P)
    subprocess.run([str(tool), "distance", str(tmp_path / "sphere.obj"), str(tmp_path / "points.npy"), "-o",
                    str(tmp_path / "d.npy"), "--closest-points", str(tmp_path / "q.npy"), "--rule", "winding",
                    "--quiet"], check=True, capture_output=True)
    np.testing.assert_array_equal(np.load(tmp_path / "d.npy"), vds.signed_distance(V, F, P, rule="winding"))
    np.testing.assert_array_equal(np.load(tmp_path / "q.npy"), vds.closest_points(V, F, P)[0])


def _distances(args):
    """A worker's distances (module level, so that multiprocessing finds it)."""
    query, points = args
    return query.distance(points, threads=1)


def test_warnings_point_at_the_callers_line_in_pythons_words():
    import warnings

    P = np.zeros((1, 3), np.float32)
    V, F = open_cup()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        first = sys._getframe().f_lineno + 1
        vds.signed_distance(V, F, P, rule="parity")
        vds.SignedDistance(V, F, rule="winding")
        vds.sdf(V, F, vds.Grid((-1, -1, -1), (1, 1, 1), 4))
    assert [w.lineno for w in caught] == [first, first + 1, first + 2]
    for w in caught:
        assert issubclass(w.category, vds.MeshWarning) and w.filename == __file__, (w.filename, w.lineno)
        assert "--" not in str(w.message) and 'rule="generalized-winding"' in str(w.message), str(w.message)


def test_wrong_types_raise_dtype_error_not_a_signature_dump():
    V, F = sphere_mesh(segments=16, rings=8)
    P = sample(V, 4)
    query = vds.SignedDistance(V, F)
    grid = vds.Grid((-1, -1, -1), (1, 1, 1), 4)
    bad = [lambda: vds.SignedDistance(V, F, rule=3),
           lambda: vds.signed_distance(V, F, P, rule=None),
           lambda: vds.sdf(V, F, (4, 4, 4)),
           lambda: vds.sdf(V, F, grid, rule=b"parity"),
           lambda: vds.sdf(V, F, grid, band="0.1"),
           lambda: vds.sdf(V, F, grid, propagated="yes"),
           lambda: query.sdf((4, 4, 4)),
           lambda: query.sdf(grid, band=None),
           lambda: query.sdf(grid, propagated=1)]
    for call in bad:
        with pytest.raises(vds.DTypeError) as caught:
            call()
        assert isinstance(caught.value, TypeError)
        assert len(str(caught.value)) < 200 and "array(" not in str(caught.value), str(caught.value)
    np.testing.assert_array_equal(query.sdf(grid, band=np.float32(0.5)), query.sdf(grid, band=0.5))
    np.testing.assert_array_equal(query.sdf(grid, propagated=np.bool_(False)), query.sdf(grid))


def test_signed_distance_pickles_and_goes_to_other_processes():
    import multiprocessing
    import pickle

    V, F = sphere_mesh(segments=16, rings=8)
    P = sample(V, 50)
    query = vds.SignedDistance(V, F, rule="winding")
    copy = pickle.loads(pickle.dumps(query))
    assert copy.rule == "winding" and repr(copy) == repr(query)
    np.testing.assert_array_equal(copy.distance(P), query.distance(P))
    with multiprocessing.get_context("fork").Pool(2) as pool:
        results = pool.map(_distances, [(query, P[:25]), (query, P[25:])])
    np.testing.assert_array_equal(np.concatenate(results), query.distance(P))


def test_method_typos_get_a_suggestion_and_custom_is_no_choice():
    V, F = box_mesh((0, 0, 0), (1, 1, 1))
    with pytest.raises(vds.InvalidArgument, match=r"did you mean 'exact'\?") as caught:
        vds.Classifier(V, F, method="exakt")
    assert "custom" not in str(caught.value)
    with pytest.raises(vds.InvalidArgument) as caught:
        vds.Classifier(V, F, method="custom")
    assert "custom" not in str(caught.value).split("expected")[1]
    with pytest.raises(vds.InvalidArgument, match=r"did you mean 'parity'\?"):
        vds.signed_distance(V, F, np.zeros((1, 3)), rule="parit")


def test_a_flat_mesh_has_unsigned_distances_and_closest_points_but_no_sign():
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], float)
    F = np.array([[0, 1, 2]])
    P = np.array([[0.25, 0.25, 2.0], [-3.0, 0.0, 4.0]], np.float32)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # by parity too: a sheet has no sign to be "answered anyway"
        vds.SignedDistance(V, F)
    sheet = vds.SignedDistance(V, F, rule="generalized-winding")
    np.testing.assert_array_equal(sheet.unsigned_distance(P), [2.0, 5.0])
    Q, d, t = vds.closest_points(V, F, P)
    np.testing.assert_array_equal(Q, [[0.25, 0.25, 0.0], [0.0, 0.0, 0.0]])
    np.testing.assert_array_equal(d, [2.0, 5.0])
    np.testing.assert_array_equal(t, [0, 0])
    with pytest.raises(vds.InvalidMesh, match="flat.*no sign|no sign.*flat|signed one is not"):
        sheet.distance(P)
    with pytest.raises(vds.InvalidMesh, match="flat"):
        sheet.sdf(vds.Grid((-1, -1, -1), (1, 1, 1), 2))


def test_max_distance_bounds_the_search_and_marks_what_it_did_not_reach():
    V, F = box_mesh((0, 0, 0), (1, 1, 1))
    P = np.array([[0.5, 0.5, 1.05], [0.5, 0.5, 5.0], [0.5, 0.5, 0.4], [9.0, 0.5, 0.5]], np.float32)
    query = vds.SignedDistance(V, F)
    unbounded = query.distance(P)
    bounded = query.distance(P, max_distance=1.0)
    near = np.abs(unbounded) <= 1.0
    assert near.tolist() == [True, False, True, False]
    np.testing.assert_array_equal(bounded[near], unbounded[near])
    np.testing.assert_array_equal(bounded[~near], [1.0, 1.0])  # outside: +max_distance
    np.testing.assert_array_equal(query.unsigned_distance(P, max_distance=1.0), np.abs(bounded))
    np.testing.assert_array_equal(vds.signed_distance(V, F, P, max_distance=1.0), bounded)
    Q, d, T = query.closest_points(P, max_distance=1.0)
    Q0, d0, T0 = query.closest_points(P)
    np.testing.assert_array_equal(T[near], T0[near])
    np.testing.assert_array_equal(Q[near], Q0[near])
    assert (T[~near] == vds.NO_TRIANGLE).all() and (d[~near] == 1.0).all()
    with pytest.raises(vds.InvalidArgument, match="max_distance must be positive"):
        query.distance(P, max_distance=0)
    with pytest.raises(vds.DTypeError, match="max_distance must be a number"):
        query.distance(P, max_distance="far")


def test_closest_points_name_the_face_edge_or_corner_they_lie_on():
    V, F = box_mesh((0, 0, 0), (1, 1, 1))
    V = V.astype(np.float64)
    P = np.array([[0.25, 0.5, 2.0], [0.5, -1.0, -1.0], [-1.0, -2.0, -3.0]], np.float32)
    Q, d, T, feature, index = vds.closest_points(V, F, P, features=True)
    assert vds.FEATURES == ("face", "edge", "vertex")
    assert [vds.FEATURES[f] for f in feature] == ["face", "edge", "vertex"]
    np.testing.assert_array_equal(Q, [[0.25, 0.5, 1.0], [0.5, 0.0, 0.0], [0.0, 0.0, 0.0]])
    tri = F[T]
    # The edge from corner i to corner (i + 1) % 3 holds its closest point.
    a, b = V[tri[1, index[1]]], V[tri[1, (index[1] + 1) % 3]]
    assert np.linalg.norm(np.cross(b - a, Q[1] - a)) == 0 and {a[0], b[0]} == {0.0, 1.0}
    np.testing.assert_array_equal(V[tri[2, index[2]]], Q[2])  # the corner itself
    assert index[0] == 0
    assert len(vds.closest_points(V, F, P)) == 3  # without features: as before
    with pytest.raises(vds.DTypeError, match="features must be True or False"):
        vds.closest_points(V, F, P, features="yes")


def test_a_grid_carries_its_spacing_and_its_centres_follow_it():
    grid = vds.Grid((0, 0, 0), (1, 2, 3), (2, 4, 5))
    assert grid.spacing == (0.5, 0.5, 0.6)  # (hi - lo) / dims, in double
    centres = grid.cell_centres()
    lo, step = np.array(grid.lo), np.array(grid.spacing)
    for i, j, k in [(0, 0, 0), (1, 3, 4), (1, 2, 0)]:
        np.testing.assert_array_equal(centres[i, j, k], (lo + (np.array([i, j, k]) + 0.5) * step).astype(np.float32))
    block = vds.Grid((0, 0, 0), (1, 2, 3), (1, 4, 5), first=(1, 0, 0), whole=(2, 4, 5))
    assert block.spacing == grid.spacing
    np.testing.assert_array_equal(block.cell_centres()[0], centres[1])


def test_bake_stores_a_distance_grid_the_sprite_keeps_and_writes():
    V, F = sphere_mesh(segments=32, rings=16)
    sprite = vds.bake(V, F, resolution=64, method="cpu", distance=16)
    values, grid = sprite.distance
    assert values.dtype == np.float32 and values.shape == grid.shape and max(grid.dims) == 16
    np.testing.assert_array_equal(values, vds.sdf(V, F, grid, rule="parity"))
    again, again_grid = vds.from_bytes(sprite.to_bytes()).distance
    np.testing.assert_array_equal(again, values)
    assert (again_grid.lo, again_grid.hi, again_grid.dims) == (grid.lo, grid.hi, grid.dims)
    assert vds.bake(V, F, resolution=64, method="cpu").distance is None
    by_gwn, _ = vds.bake(V, F, resolution=32, method="cpu", distance=8, distance_rule="generalized-winding").distance
    np.testing.assert_array_equal(np.signbit(by_gwn), np.signbit(vds.sdf(V, F, _, rule="generalized-winding")))
    for bad, why in ((2, "out of range"), (5000, "out of range"), (1000, "more than a sprite file holds")):
        with pytest.raises(vds.InvalidArgument, match=why):
            vds.bake(V, F, resolution=32, method="cpu", distance=bad)
