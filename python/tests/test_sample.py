"""vds.sample_surface: the C++ sampler through the binding, against the
recipe <vds/sample.h> states, re-read here in numpy (SplitMix64 in uint64
arithmetic, a search of the running areas), and the points the C++ test
asserts (tests/core/contract/sample_test.cpp)."""
import numpy as np
import pytest

import vds

# The C++ test's tilted tetrahedron, one degenerate triangle among its faces.
TETRA_V = np.array([[0.1, -0.3, 0.2], [1.7, 0.4, -0.5], [0.3, 1.9, 0.6], [0.2, 0.5, 2.1]], np.float32)
TETRA_F = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3], [0, 0, 1]], np.int32)


def splitmix_uniforms(seed, count):
    """Draws 0 .. count-1 of stream `seed`, as <vds/sample.h> defines them."""
    with np.errstate(over="ignore"):
        z = np.uint64(seed) + (np.arange(count, dtype=np.uint64) + np.uint64(1)) * np.uint64(0x9E3779B97F4A7C15)
        z = (z ^ (z >> np.uint64(30))) * np.uint64(0xBF58476D1CE4E5B9)
        z = (z ^ (z >> np.uint64(27))) * np.uint64(0x94D049BB133111EB)
    z ^= z >> np.uint64(31)
    return (z >> np.uint64(11)).astype(np.float64) * 2.0**-53


def recipe(V, F, n, seed):
    a, b, c = (V[F[:, k]].astype(np.float64) for k in range(3))
    e1, e2 = b - a, c - a
    x = e1[:, 1] * e2[:, 2] - e1[:, 2] * e2[:, 1]
    y = e1[:, 2] * e2[:, 0] - e1[:, 0] * e2[:, 2]
    z = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    sums = np.cumsum(np.sqrt(x * x + y * y + z * z))  # sequential, as the C++ loop
    u = splitmix_uniforms(seed, 3 * n).reshape(n, 3)
    t = np.minimum(np.searchsorted(sums, u[:, 0] * sums[-1], side="right"), np.searchsorted(sums, sums[-1]))
    r = np.sqrt(u[:, 1])[:, None]
    w0, w1, w2 = 1.0 - r, r * (1.0 - u[:, 2:3]), r * u[:, 2:3]
    return w0 * a[t] + w1 * b[t] + w2 * c[t], t


def test_equals_the_stated_recipe_bit_for_bit():
    points, triangles = vds.sample_surface((TETRA_V, TETRA_F), 5000, 77)
    expected, t = recipe(TETRA_V, TETRA_F, 5000, 77)
    assert points.dtype == np.float64 and points.shape == (5000, 3) and triangles.dtype == np.uint32
    np.testing.assert_array_equal(triangles, t)
    assert points.tobytes() == expected.tobytes()


def test_same_points_as_the_cpp_test():
    points, triangles = vds.sample_surface((TETRA_V, TETRA_F), 3, 42)
    assert triangles.tolist() == [2, 1, 0]
    known = ["0x1.210730563865ep+0", "0x1.b00e4a24476eap-1", "0x1.b63bcf1cdfd22p-4",
             "0x1.43ae44d21b358p-3", "-0x1.2c2732174c6f8p-3", "0x1.01e692c656970p-1",
             "0x1.68d999753556ep-1", "0x1.36576a13dfeddp+0", "0x1.c96261a93ced2p-3"]
    assert points.ravel().tolist() == [float.fromhex(h) for h in known]


def test_points_lie_on_their_triangles():
    V, F = TETRA_V.astype(np.float64), TETRA_F
    points, triangles = vds.sample_surface((V, F), 4000, 3)
    assert not np.any(triangles == 4)  # the degenerate face is never chosen
    a, b, c = (V[F[triangles, k]] for k in range(3))
    e1, e2, d = b - a, c - a, points - a
    dot = lambda u, v: np.einsum("ij,ij->i", u, v)
    d11, d12, d22 = dot(e1, e1), dot(e1, e2), dot(e2, e2)
    det = d11 * d22 - d12 * d12
    v = (d22 * dot(d, e1) - d12 * dot(d, e2)) / det
    w = (d11 * dot(d, e2) - d12 * dot(d, e1)) / det
    assert np.all(v >= -1e-12) and np.all(w >= -1e-12) and np.all(v + w <= 1 + 1e-12)
    np.testing.assert_allclose(a + v[:, None] * e1 + w[:, None] * e2, points, atol=1e-12)


def test_counts_follow_the_areas():
    # Areas 1/2 and 3/2: a quarter of the points on the first triangle, within 5 sigma of Binomial(n, 1/4).
    V = np.array([[0, 0, 1], [1, 0, 1], [0, 1, 1], [2, 0, 1], [5, 0, 1], [2, 1, 1]], np.float32)
    F = np.array([[0, 1, 2], [3, 4, 5]])
    n = 100_000
    _, triangles = vds.sample_surface((V, F), n, 2024)
    assert abs(np.count_nonzero(triangles == 0) - n / 4) < 5 * np.sqrt(n * 0.25 * 0.75)


def test_seeds_and_paths(tmp_path):
    a = vds.sample_surface((TETRA_V, TETRA_F), 100, 9)
    b = vds.sample_surface([TETRA_V, TETRA_F], 100, np.uint64(9))
    c = vds.sample_surface((TETRA_V, TETRA_F), 100, 10)
    assert a[0].tobytes() == b[0].tobytes()
    assert not np.any(a[0] == c[0])
    path = tmp_path / "tetra.obj"
    path.write_text("".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in TETRA_V.astype(float)) +
                    "".join(f"f {i + 1} {j + 1} {k + 1}\n" for i, j, k in TETRA_F[:4]))
    np.testing.assert_array_equal(vds.sample_surface(path, 100, 2**64 - 1)[0],
                                  vds.sample_surface((TETRA_V, TETRA_F[:4]), 100, 2**64 - 1)[0])
    assert vds.sample_surface((TETRA_V, TETRA_F), 0, 1)[0].shape == (0, 3)


def test_refusals():
    flat_V = np.array([[0, 0, 0], [1, 1, 1], [2, 2, 2]], np.float32)
    with pytest.raises(vds.InvalidMesh, match=r"^no area to sample: the mesh's triangles \(1\) all have zero area$"):
        vds.sample_surface((flat_V, np.array([[0, 1, 2]])), 10, 0)
    with pytest.raises(vds.InvalidArgument, match="seed"):
        vds.sample_surface((TETRA_V, TETRA_F), 10, 2**64)
    with pytest.raises(vds.InvalidArgument, match="n must be"):
        vds.sample_surface((TETRA_V, TETRA_F), -1, 0)
    with pytest.raises(vds.DTypeError, match="mesh must be"):
        vds.sample_surface(TETRA_V, 10, 0)
    with pytest.raises(vds.DTypeError, match="integers"):
        vds.sample_surface((TETRA_V, TETRA_F), 1.5, 0)
