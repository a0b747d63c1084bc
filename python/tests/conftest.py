"""Solids built in numpy, with analytic answers, for the vds tests."""
import os
import pathlib

import numpy as np
import pytest

import vds

DATA = pathlib.Path(os.environ.get("VDS_TEST_DATA", pathlib.Path(__file__).resolve().parents[2] / "samples" / "data"))


def box_mesh(lo, hi):
    """The box [lo, hi] as 8 vertices and 12 triangles, counter-clockwise
    seen from outside (vertex i = (x, y, z) bits of i)."""
    lo, hi = np.asarray(lo, float), np.asarray(hi, float)
    V = np.array([[(hi if (i >> a) & 1 else lo)[a] for a in range(3)] for i in range(8)])
    F = np.array([[0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4],
                  [2, 6, 7], [2, 7, 3], [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5]], dtype=np.int32)
    return V, F


def sphere_mesh(radius=1.0, centre=(0.0, 0.0, 0.0), segments=64, rings=32):
    """A UV sphere: poles plus rings x segments vertices, outward oriented."""
    theta = np.pi * np.arange(1, rings) / rings
    phi = 2 * np.pi * np.arange(segments) / segments
    ring = np.stack([np.outer(np.sin(theta), np.cos(phi)), np.outer(np.sin(theta), np.sin(phi)),
                     np.outer(np.cos(theta), np.ones_like(phi))], axis=-1).reshape(-1, 3)
    V = np.vstack([[0, 0, 1], ring, [0, 0, -1]]) * radius + np.asarray(centre)
    south = len(V) - 1

    def at(r, s):
        return 1 + r * segments + s % segments

    F = []
    for s in range(segments):
        F.append([0, at(0, s), at(0, s + 1)])
        F.append([south, at(rings - 2, s + 1), at(rings - 2, s)])
        for r in range(rings - 2):
            F.append([at(r, s), at(r + 1, s), at(r + 1, s + 1)])
            F.append([at(r, s), at(r + 1, s + 1), at(r, s + 1)])
    return V, np.array(F, dtype=np.int32)


def signed_volume(V, F):
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    return np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0


def gl_or_skip():
    """Skips a GL test where no context can be had, unless VDS_REQUIRE_GL=1
    (as tests/run_tests.sh sets), where that is a failure."""
    if not vds.gl_available():
        reason = vds.gl_unavailable_reason()
        if os.environ.get("VDS_REQUIRE_GL") == "1":
            pytest.fail("no GL: " + reason)
        pytest.skip("no GL: " + reason)


@pytest.fixture(scope="session")
def spot():
    V, F = vds.load_mesh(DATA / "spot.obj")
    return V, F, vds.bake(V, F, resolution=256, method="cpu")


def icosphere(subdivisions=2, radius=1.0, centre=(0.0, 0.0, 0.0)):
    """A convex polyhedron inscribed in a sphere: the icosahedron with each
    triangle split into four `subdivisions` times, vertices pushed onto the
    sphere, faces counter-clockwise seen from outside. V float64, F int32."""
    t = (1 + 5 ** 0.5) / 2
    V = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t],
         [0, -1, -t], [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    F = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2],
         [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5],
         [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    V = [np.asarray(v, float) / np.linalg.norm(v) for v in V]
    for _ in range(subdivisions):
        middle = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                m = V[a] + V[b]
                V.append(m / np.linalg.norm(m))
                middle[key] = len(V) - 1
            return middle[key]

        F = [f for a, b, c in F for f in ([a, mid(a, b), mid(c, a)], [b, mid(b, c), mid(a, b)],
                                          [c, mid(c, a), mid(b, c)], [mid(a, b), mid(b, c), mid(c, a)])]
    V = np.array(V) * radius + np.asarray(centre, float)
    F = np.array(F, dtype=np.int32)
    return V, F


def convex_signed_distance(V, F, points):
    """For a closed convex polyhedron with outward faces: the largest signed
    distance of each point to the faces' planes, in float64. Negative inside
    (then minus the exact distance to the surface), positive outside (then at
    most the distance to the surface)."""
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    n = np.cross(b - a, c - a)
    n /= np.linalg.norm(n, axis=1)[:, None]
    offsets = np.einsum("ij,ij->i", n, a)
    return (points @ n.T - offsets).max(axis=1)


def local_cluster():
    """A real distributed.LocalCluster of two worker processes, one thread each."""
    distributed = pytest.importorskip("distributed")
    return distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                    worker_dashboard_address=None)


@pytest.fixture(scope="module")
def client():
    """A distributed.Client on local_cluster(), one per test module (vds.dask's tests)."""
    distributed = pytest.importorskip("distributed")
    with local_cluster() as cluster, distributed.Client(cluster) as c:
        yield c
