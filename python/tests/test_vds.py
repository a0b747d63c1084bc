"""The Python module against analytic solids, the exact classifier and the GPU."""
import gc
import pickle
import subprocess
import sys
import threading

import numpy as np
import pytest

import vds
from conftest import DATA, box_mesh, gl_or_skip, signed_volume, sphere_mesh

RNG = np.random.default_rng(20250609)


def uniform(lo, hi, n, dtype=np.float64):
    return RNG.uniform(lo, hi, (n, 3)).astype(dtype)


def box_distance(points, lo, hi):
    """Distance from each point to the box's surface (inside or out)."""
    lo, hi = np.asarray(lo), np.asarray(hi)
    outside = np.linalg.norm(np.maximum(np.maximum(lo - points, points - hi), 0), axis=1)
    inside = np.min(np.minimum(points - lo, hi - points), axis=1)
    return np.where(outside > 0, outside, np.maximum(inside, 0))


LO, HI = (-1.0, 0.0, 0.5), (2.0, 1.0, 3.0)


def test_mesh_helpers_are_outward_solids():
    V, F = box_mesh(LO, HI)
    assert signed_volume(V, F) == pytest.approx(3 * 1 * 2.5)
    V, F = sphere_mesh()
    assert signed_volume(V, F) == pytest.approx(4 / 3 * np.pi, rel=0.01)


def test_load_mesh_counts_what_the_obj_holds():
    V, F = vds.load_mesh(DATA / "spot.obj")
    lines = (DATA / "spot.obj").read_text().splitlines()
    first = [ln.split() for ln in lines if ln.startswith("v ")][0]
    assert V.shape == (sum(ln.startswith("v ") for ln in lines), 3) and V.dtype == np.float64
    assert F.shape == (sum(ln.startswith("f ") for ln in lines), 3) and F.dtype == np.int32
    assert V[0] == pytest.approx([float(x) for x in first[1:4]], rel=1e-6)
    assert F.min() == 0 and F.max() == len(V) - 1


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_box_matches_analytic_answers(dtype):
    V, F = box_mesh(LO, HI)
    sprite = vds.bake(V, F, resolution=64, method="cpu")
    assert sprite.status == "closed" and sprite.depth_complexity == 2 and sprite.resolution == 64
    np.testing.assert_allclose(sprite.box, [LO, HI])
    points = uniform(np.subtract(LO, 0.5), np.add(HI, 0.5), 200_000, dtype)
    truth = np.all((points > LO) & (points < HI), axis=1)
    labels = sprite.contains(points)
    assert labels.dtype == np.bool_ and labels.shape == (len(points),)
    texel = 3.0 / 64
    far = box_distance(points.astype(np.float64), LO, HI) > texel
    assert np.array_equal(labels[far], truth[far])
    assert 0.2 < truth.mean() < 0.5
    # The exact classifier is exact everywhere (no point lies on a face).
    assert np.array_equal(vds.exact_contains(V, F, points), truth)


@pytest.mark.parametrize("dtype", [np.float32, np.float64])
@pytest.mark.parametrize("rule", ["parity", "winding"])
def test_sphere_matches_analytic_answers(dtype, rule):
    V, F = sphere_mesh(radius=1.0, centre=(0.25, -0.5, 1.0))
    sprite = vds.bake(V, F, resolution=128, axis="x", method="cpu")
    assert sprite.axis == "x"
    points = uniform(-1.5, 1.5, 200_000, dtype) + np.array([0.25, -0.5, 1.0], dtype)
    r = np.linalg.norm(points.astype(np.float64) - [0.25, -0.5, 1.0], axis=1)
    # The 64 x 32 UV sphere lies between radius cos(pi/32)^2 > 0.99 and 1.
    sure = (r < 0.97) | (r > 1.02)
    labels = sprite.contains(points, rule=rule)
    assert np.array_equal(labels[sure], r[sure] < 1)
    assert np.array_equal(vds.exact_contains(V, F, points, rule=rule)[sure], r[sure] < 1)


def test_sprite_agrees_with_exact_classifier_on_spot(spot):
    V, F, sprite = spot
    points = uniform(V.min(0) - 0.05, V.max(0) + 0.05, 100_000)
    exact = vds.exact_contains(V, F, points)
    labels = sprite.contains(points)
    assert 0.1 < exact.mean() < 0.6
    assert np.mean(labels != exact) < 0.005  # docs/accuracy.md: ~0.1 % at 256 near the surface only


def test_bake_methods_and_auto_axis_give_the_same_answers(spot):
    V, F, cpu = spot
    points = uniform(V.min(0), V.max(0), 50_000, np.float32)
    expected = cpu.contains(points)
    gl_or_skip()
    for method in ("lists", "peel"):
        sprite = vds.bake(V, F, resolution=256, method=method)
        assert sprite.axis == cpu.axis and sprite.depth_complexity == cpu.depth_complexity
        assert np.array_equal(sprite.contains(points), expected), method


def test_strided_and_converted_inputs_answer_as_contiguous(spot):
    V, F, sprite = spot
    base = uniform(V.min(0), V.max(0), 30_000, np.float32)
    expected = sprite.contains(base)
    wide = np.zeros((len(base), 5), np.float32)
    wide[:, 1:4] = base
    assert np.array_equal(sprite.contains(wide[:, 1:4]), expected)           # row stride 20 bytes, in place
    assert np.array_equal(sprite.contains(np.asfortranarray(base)), expected)  # column stride N*4: copied
    assert np.array_equal(sprite.contains(base[::-1])[::-1], expected)         # negative row stride
    assert np.array_equal(sprite.contains(base[::2]), expected[::2])
    assert np.array_equal(sprite.contains(base[:, ::-1][:, ::-1]), expected)
    assert np.array_equal(sprite.contains(base.astype(np.float64)), expected)
    assert np.array_equal(sprite.contains(base.tolist()), expected)
    assert np.array_equal(sprite.contains(base.astype(">f4")), expected)  # big-endian: converted
    assert np.array_equal(sprite.contains(pickle.loads(pickle.dumps(base))), expected)  # an equal, not identical, dtype
    assert sprite.contains(np.zeros((0, 3))).shape == (0,)
    assert np.array_equal(sprite.contains(base, threads=1), expected)


@pytest.mark.parametrize("bad", [np.zeros((4, 2)), np.zeros(3), np.zeros((2, 3, 1)), np.zeros((2, 4), np.float32)])
def test_wrong_shapes_raise_value_error(spot, bad):
    with pytest.raises(ValueError, match=r"shape \(N, 3\)"):
        spot[2].contains(bad)


@pytest.mark.parametrize("value", [np.nan, np.inf, -np.inf, 1e300])
@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_non_finite_points_raise_value_error_naming_the_row(spot, value, dtype):
    if dtype == np.float32 and value == 1e300:
        pytest.skip("1e300 is inf as float32: covered by inf")
    points = np.zeros((10, 3), dtype)
    points[7, 1] = value
    with pytest.raises(ValueError, match=r"points\[7\]"):
        spot[2].contains(points)
    with pytest.raises(ValueError, match=r"points\[7\]"):
        vds.exact_contains(spot[0], spot[1], points)


def test_other_bad_arguments_raise_value_error(spot):
    V, F, sprite = spot
    with pytest.raises(ValueError, match="float32 or float64"):
        sprite.contains(np.zeros((2, 3), np.complex64))
    with pytest.raises(ValueError, match="rule"):
        sprite.contains(np.zeros((2, 3)), rule="sideways")
    with pytest.raises(ValueError, match="not a vertex index"):
        vds.bake(V, np.array([[0, 1, len(V)]]), method="cpu")
    with pytest.raises(ValueError, match="not a vertex index"):
        vds.bake(V, np.array([[0, 1, -1]]), method="cpu")
    with pytest.raises(ValueError, match="resolution"):
        vds.bake(V, F, resolution=0, method="cpu")
    with pytest.raises(ValueError, match="axis"):
        vds.bake(V, F, axis="w", method="cpu")
    with pytest.raises(ValueError, match="method"):
        vds.bake(V, F, method="magic")
    with pytest.raises(vds.InvalidMesh):
        vds.bake(np.zeros((0, 3)), np.zeros((0, 3), np.int32), method="cpu")
    with pytest.raises(ValueError, match=r"\(4, 4\)"):
        sprite.transform(np.eye(3))


def test_file_errors_map_to_python_exceptions(tmp_path):
    with pytest.raises(OSError) as missing:
        vds.read(tmp_path / "missing.vds")
    assert isinstance(missing.value, vds.IoError) and "missing.vds" in str(missing.value)
    with pytest.raises(OSError):
        vds.load_mesh(tmp_path / "missing.obj")
    corrupt = tmp_path / "corrupt.vds"
    corrupt.write_bytes(b"v/1\x01" + bytes(200))
    with pytest.raises(ValueError) as bad:
        vds.read(corrupt)
    assert isinstance(bad.value, vds.FormatError) and "\n" not in str(bad.value)
    with pytest.raises(vds.FormatError):
        vds.from_bytes(b"not a sprite")
    (tmp_path / "broken.obj").write_text("v 0 0 0\nf 1 2 3\n")
    with pytest.raises(ValueError):
        vds.load_mesh(tmp_path / "broken.obj")


def test_save_read_bytes_and_pickle_round_trip(spot, tmp_path):
    _, _, sprite = spot
    path = tmp_path / "spot.vds"
    sprite.save(path)
    assert path.read_bytes() == sprite.to_bytes()
    copies = [vds.read(path), vds.read(str(path)), vds.from_bytes(sprite.to_bytes()), pickle.loads(pickle.dumps(sprite))]
    points = uniform(sprite.box[0], sprite.box[1], 20_000)
    expected = sprite.contains(points)
    for copy in copies:
        assert copy.to_bytes() == sprite.to_bytes()
        assert (copy.resolution, copy.depth_complexity, copy.axis, copy.status) == (
            sprite.resolution, sprite.depth_complexity, sprite.axis, sprite.status)
        assert np.array_equal(copy.contains(points), expected)


def test_transform_moves_the_solid():
    V, F = box_mesh(LO, HI)
    sprite = vds.bake(V, F, resolution=64, method="cpu")
    model = np.diag([2.0, 1.0, 0.5, 1.0])
    model[:3, 3] = [10.0, -3.0, 1.0]
    sprite.transform(model)
    lo = model[:3, :3] @ LO + model[:3, 3]
    hi = model[:3, :3] @ HI + model[:3, 3]
    points = uniform(lo - 1, hi + 1, 100_000)
    far = box_distance(points, lo, hi) > 2 * 3.0 / 64
    truth = np.all((points > lo) & (points < hi), axis=1)
    assert np.array_equal(sprite.contains(points)[far], truth[far])
    np.testing.assert_allclose(sprite.box, [LO, HI])  # the baked box, before the placement


def test_winding_numbers_of_closed_and_open_boxes():
    V, F = box_mesh((0, 0, 0), (1, 1, 1))
    w = vds.winding_numbers(V, F, np.array([[0.5, 0.5, 0.5], [2.0, 0.5, 0.5], [0.1, 0.9, 0.2]]))
    assert w.dtype == np.float64
    np.testing.assert_allclose(w, [1.0, 0.0, 1.0], atol=1e-12)
    # Without its top face the cube's centre sees five of six faces: 5/6.
    open_box = vds.ExactClassifier(V, F[[0, 1, 4, 5, 6, 7, 8, 9, 10, 11]])
    assert open_box.boundary_edges == 4
    np.testing.assert_allclose(open_box.winding_numbers(np.array([[0.5, 0.5, 0.5]])), [5 / 6], atol=1e-9)
    assert open_box.contains(np.array([[0.5, 0.5, 0.5]]), rule="generalized-winding")[0]


def test_threads_classify_at_once_with_the_gil_released(spot):
    _, _, sprite = spot
    points = uniform(sprite.box[0], sprite.box[1], 200_000, np.float32)
    expected = sprite.contains(points)
    results = [None] * 4

    def work(k):
        results[k] = sprite.contains(points, threads=1)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert all(np.array_equal(r, expected) for r in results)


@pytest.mark.parametrize("rule", ["parity", "winding"])
def test_gpu_answers_equal_cpu_answers(spot, rule):
    gl_or_skip()
    _, _, sprite = spot
    points = uniform(sprite.box[0] - 0.1, sprite.box[1] + 0.1, 300_000)
    cpu = sprite.contains(points, rule=rule)
    assert np.array_equal(sprite.contains(points, rule=rule, gpu=True), cpu)
    assert np.array_equal(sprite.contains(points[:, :].astype(np.float32)[::3], rule=rule, gpu=True), cpu[::3])


def test_interpreter_exits_cleanly_with_gl_in_use():
    gl_or_skip()
    script = (
        "import numpy as np, vds, sys\n"
        "sys.path.insert(0, %r)\n"
        "from conftest import box_mesh\n"
        "V, F = box_mesh((0, 0, 0), (1, 1, 1))\n"
        "keep = vds.bake(V, F, resolution=32)\n"  # GL fragment lists on the module's context
        "print(int(keep.contains(np.full((5, 3), 0.5), gpu=True).sum()))\n"
    ) % str(DATA.parent.parent / "python" / "tests")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "5"


# ---- resident GPU sprites ---------------------------------------------------


def open_sphere(cap_z=0.8, segments=48, rings=24):
    """A UV sphere without the triangles whose vertices all lie above z = cap_z:
    an open surface with one hole around the north pole."""
    V, F = sphere_mesh(segments=segments, rings=rings)
    keep = ~np.all(V[F][:, :, 2] > cap_z, axis=1)
    return V, F[keep]


@pytest.mark.parametrize("rule", ["parity", "winding"])
def test_repeated_gpu_calls_reuse_one_upload_and_agree_with_cpu(spot, rule):
    gl_or_skip()
    _, _, sprite = spot
    copy = pickle.loads(pickle.dumps(sprite))  # a fresh sprite, nothing resident yet
    before = vds._gpu_resident()
    for k in range(5):
        points = uniform(sprite.box[0] - 0.1, sprite.box[1] + 0.1, 50_000 + 1000 * k).astype(
            np.float32 if k % 2 else np.float64)
        assert np.array_equal(copy.contains(points, rule=rule, gpu=True), copy.contains(points, rule=rule))
        assert vds._gpu_resident() == before + 1  # uploaded once, kept


def test_gpu_answers_follow_transform_of_a_resident_sprite():
    gl_or_skip()
    V, F = box_mesh(LO, HI)
    sprite = vds.bake(V, F, resolution=64, method="cpu")
    points = uniform(np.subtract(LO, 1), np.add(HI, 1), 50_000)
    assert np.array_equal(sprite.contains(points, gpu=True), sprite.contains(points))  # now resident
    model = np.diag([2.0, 1.0, 0.5, 1.0])
    model[:3, 3] = [10.0, -3.0, 1.0]
    sprite.transform(model)
    lo = model[:3, :3] @ LO + model[:3, 3]
    hi = model[:3, :3] @ HI + model[:3, 3]
    moved = uniform(lo - 1, hi + 1, 100_000)
    gpu = sprite.contains(moved, gpu=True)
    assert np.array_equal(gpu, sprite.contains(moved))
    far = box_distance(moved, lo, hi) > 2 * 3.0 / 64
    truth = np.all((moved > lo) & (moved < hi), axis=1)
    assert np.array_equal(gpu[far], truth[far])
    assert gpu.sum() > 1000  # the moved box is found where it went
    sprite.transform(np.linalg.inv(model))  # and back
    assert np.array_equal(sprite.contains(points, gpu=True), sprite.contains(points))


def test_gpu_generalized_winding_of_an_open_mesh_agrees_with_cpu():
    gl_or_skip()
    V, F = open_sphere()
    with pytest.warns(vds.MeshWarning, match="open"):
        sprite = vds.bake(V, F, resolution=128, method="cpu")
    assert sprite.status == "open"
    points = uniform((-1.2, -1.2, -1.2), (1.2, 1.2, 1.2), 100_000)
    cpu = sprite.contains(points, rule="generalized-winding")
    gpu = sprite.contains(points, rule="generalized-winding", gpu=True)
    assert np.array_equal(gpu, sprite.contains(points, rule="generalized-winding", gpu=True))  # resident, repeatable
    w = vds.winding_numbers(V, F, points)
    near_half = np.abs(w - 0.5) < 1e-4
    assert np.array_equal(gpu[~near_half], cpu[~near_half]), np.flatnonzero((gpu != cpu) & ~near_half)[:10]
    # The hole matters: many points have a fractional winding number.
    assert ((w > 0.05) & (w < 0.95)).sum() > 1000
    assert (cpu == (w > 0.5)).mean() > 0.99


def test_deleting_a_resident_sprite_then_using_another():
    gl_or_skip()
    V, F = box_mesh(LO, HI)
    points = uniform(np.subtract(LO, 1), np.add(HI, 1), 20_000)
    first = vds.bake(V, F, resolution=32, method="cpu")
    expected = first.contains(points)
    assert np.array_equal(first.contains(points, gpu=True), expected)
    gc.collect()  # other tests' sprites go first
    resident = vds._gpu_resident()
    del first
    gc.collect()
    assert vds._gpu_resident() == resident - 1  # freed with the sprite
    second = vds.bake(V, F, resolution=32, method="cpu")
    assert np.array_equal(second.contains(points, gpu=True), expected)
    assert vds._gpu_resident() == resident


def test_threads_free_and_use_resident_sprites_at_once(spot):
    gl_or_skip()
    _, _, sprite = spot
    data = sprite.to_bytes()
    points = uniform(sprite.box[0], sprite.box[1], 30_000, np.float32)
    expected = sprite.contains(points)
    failures = []
    sprite.contains(points[:10], gpu=True)
    gc.collect()
    resident = vds._gpu_resident()

    def work():
        try:
            for _ in range(4):
                mine = vds.from_bytes(data)
                for _ in range(2):
                    if not np.array_equal(mine.contains(points, gpu=True), expected):
                        failures.append("labels")
                del mine  # freed on this thread, maybe while another holds GL
        except Exception as error:  # noqa: BLE001 (reported below)
            failures.append(repr(error))

    threads = [threading.Thread(target=work) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not failures
    sprite.contains(points[:10], gpu=True)  # frees the copies left to the GL holder
    assert vds._gpu_resident() == resident


def test_interpreter_exits_cleanly_with_resident_gpu_sprites():
    gl_or_skip()
    script = (
        "import gc, numpy as np, vds, sys\n"
        "sys.path.insert(0, %r)\n"
        "from conftest import box_mesh\n"
        "V, F = box_mesh((0, 0, 0), (1, 1, 1))\n"
        "p = np.full((5, 3), 0.5)\n"
        "keep = vds.bake(V, F, resolution=32, method='cpu')\n"
        "gone = vds.bake(V, F, resolution=32)\n"
        "class Cycle: pass\n"
        "cycle = Cycle(); cycle.me = cycle; cycle.sprite = vds.bake(V, F, resolution=16, method='cpu')\n"
        "total = sum(int(s.contains(p, gpu=True).sum()) for s in (keep, gone, cycle.sprite))\n"
        "del gone; gc.collect()\n"
        "after = vds.bake(V, F, resolution=16, method='cpu'); after.contains(p, gpu=True)\n"
        "vds._release_gl()\n"  # resident copies go with the context ...
        "print(total, vds._gpu_resident())\n"
        "del after; gc.collect()\n"  # ... and a sprite freed later calls no GL
        "print(int(keep.contains(p, gpu=True).sum()), vds._gpu_resident())\n"  # a new context, uploaded again
        "del cycle\n"  # collected during finalization, after the atexit release
    ) % str(DATA.parent.parent / "python" / "tests")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["15", "0", "5", "1"], done.stdout
    assert "rror" not in done.stderr, done.stderr
