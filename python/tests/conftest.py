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
    ok, reason = vds.gl_available()
    if not ok:
        if os.environ.get("VDS_REQUIRE_GL") == "1":
            pytest.fail("no GL: " + reason)
        pytest.skip("no GL: " + reason)


@pytest.fixture(scope="session")
def spot():
    V, F = vds.load_mesh(DATA / "spot.obj")
    return V, F, vds.bake(V, F, resolution=256, method="cpu")
