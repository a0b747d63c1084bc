"""Every method of the library's table from Python (vds.Classifier), the
occupancy grids, the sprite's winding numbers, the exception hierarchy, the
mesh warnings and the in-place mesh views, against an analytic convex solid
(an icosphere built in numpy) and the exact classifier."""
import gc
import os
import pathlib
import subprocess
import sys
import threading
import warnings

import numpy as np
import pytest

import vds
from conftest import box_mesh, convex_signed_distance, gl_or_skip, icosphere

RNG = np.random.default_rng(20261125)
CENTRE = np.array([0.3, -0.2, 0.1])
# The solid: a convex polyhedron (320 faces) inscribed in a sphere of radius 1 about CENTRE.
V, F = icosphere(2, centre=CENTRE)
V32 = V.astype(np.float32)  # what the library keeps
BOX_SIDE = 2.0              # the solid's box: about 2 x 2 x 2
METHODS = ["sprite", "exact", "certified", "sprite-gpu", "slicemap", "slicemap-local", "solid", "solid-compute",
           "slicemap-gpu", "slicemap-local-gpu", "solid-gpu", "solid-compute-gpu", "certified-gpu"]
RESOLUTION = 64             # texels or cells on the box's longest side, for the approximate methods


def around(n, margin=0.3, dtype=np.float64):
    return (RNG.uniform(-1 - margin, 1 + margin, (n, 3)) + CENTRE).astype(dtype)


def info(name):
    return next(m for m in vds.methods() if m.name == name)


def make(name, **kwargs):
    if info(name).layer != "core":
        gl_or_skip()
    return vds.Classifier(V, F, name, resolution=RESOLUTION, **kwargs)


# ---- the method table ------------------------------------------------------


def test_the_method_table_names_every_method_as_the_cli_does():
    table = vds.methods()
    assert [m.name for m in table] == METHODS
    assert {m.name for m in table if m.exact} == {"exact", "certified", "certified-gpu"}
    assert all(m.gpu == m.name.endswith("-gpu") for m in table)
    assert {m.name for m in table if m.from_sprite} == {"sprite", "sprite-gpu"}
    assert {m.name for m in table if m.needs_closed_mesh} == {m.name for m in table if m.layer == "voxel"}
    for m in table:
        assert "parity" in m.rules
        assert ("generalized-winding" in m.rules) == (m.layer != "voxel"), m


# ---- labels: exact methods equal the exact classifier, approximate ones agree off the surface


def test_the_exact_classifier_equals_the_analytic_solid():
    points = around(200_000)
    d = convex_signed_distance(V32.astype(np.float64), F, points.astype(np.float32).astype(np.float64))
    sure = np.abs(d) > 1e-6  # not on a face, up to float rounding
    labels = vds.Classifier(V, F, "exact").classify(points)
    assert sure.mean() > 0.999 and 0.2 < labels.mean() < 0.7
    assert np.array_equal(labels[sure], d[sure] < 0)


@pytest.mark.parametrize("name", METHODS)
def test_each_method_answers_as_the_table_says(name):
    classifier = make(name)
    assert classifier.method == name
    assert classifier.memory_bytes > 0 and classifier.summary
    points = around(100_000, dtype=np.float32)
    exact = vds.ExactClassifier(V, F)
    d = convex_signed_distance(V32.astype(np.float64), F, points.astype(np.float64))
    cell = BOX_SIDE / RESOLUTION
    far = np.abs(d) > 3 * cell
    for rule in info(name).rules:
        labels = classifier.classify(points, rule=rule)
        expected = exact.contains(points, rule=rule)
        assert labels.dtype == np.bool_ and labels.shape == (len(points),)
        if info(name).exact:
            assert np.array_equal(labels, expected), (name, rule)
        else:
            assert np.array_equal(labels[far], expected[far]), (name, rule, np.flatnonzero(labels != expected)[:5])
            assert np.mean(labels != expected) < 0.01, (name, rule)
    for rule in {"parity", "winding", "generalized-winding"} - set(info(name).rules):
        with pytest.raises(vds.InvalidArgument, match="rule"):
            classifier.classify(points[:10], rule=rule)


def test_gpu_forms_give_their_cpu_forms_labels():
    gl_or_skip()
    points = around(50_000)
    for m in vds.methods():
        if m.gpu:
            cpu = m.name[: -len("-gpu")]
            assert np.array_equal(make(m.name).classify(points), make(cpu).classify(points)), m.name


@pytest.mark.parametrize("name", ["certified", "certified-gpu"])
def test_certified_stats_count_every_point(name):
    if info(name).gpu:
        gl_or_skip()
    classifier = vds.Classifier(V, F, name, resolution=32)
    points = around(50_000)
    labels, stats = classifier.classify(points, stats=True)
    assert np.array_equal(labels, vds.Classifier(V, F, "exact").classify(points))
    assert stats["certain"] + stats["exact"] == len(points)
    assert stats["exact"] > 0 and stats["certain"] > stats["exact"]  # a few near the surface take the exact path
    _, exact_stats = vds.Classifier(V, F, "exact").classify(points, stats=True)
    assert exact_stats == {"certain": len(points), "exact": 0}


def test_classifiers_from_a_sprite_answer_as_the_sprite():
    sprite = vds.bake(V, F, resolution=RESOLUTION, method="cpu")
    points = around(50_000)
    expected = sprite.contains(points)
    assert np.array_equal(vds.Classifier(sprite).classify(points), expected)
    assert np.array_equal(vds.Classifier(sprite, "sprite").contains(points, rule="winding"),
                          sprite.contains(points, rule="winding"))
    with pytest.raises(vds.InvalidArgument, match="from the mesh"):
        vds.Classifier(sprite, "exact")
    gl_or_skip()
    assert np.array_equal(vds.Classifier(sprite, "sprite-gpu").classify(points), expected)


def test_sprite_method_bakes_along_the_axis_asked():
    for axis in "xyz":
        assert f"along {axis}" in vds.Classifier(V, F, "sprite", resolution=32, axis=axis).summary
    points = around(20_000)
    gl_or_skip()
    # The GL bakers give the CPU baker's sprite.
    assert np.array_equal(vds.Classifier(V, F, "sprite", resolution=32, axis="y", bake_method="lists").classify(points),
                          vds.Classifier(V, F, "sprite", resolution=32, axis="y").classify(points))


def test_voxel_methods_refuse_open_meshes():
    gl_or_skip()
    keep = np.ones(len(F), bool)
    keep[0] = False
    with pytest.raises(vds.InvalidMesh):
        vds.Classifier(V, F[keep], "solid", resolution=16)


def test_inputs_of_any_layout_give_the_same_labels():
    classifier = vds.Classifier(V, F, "certified", resolution=32)
    base = around(20_000, dtype=np.float32)
    expected = classifier.classify(base)
    wide = np.zeros((len(base), 7), np.float64)
    wide[:, 2:5] = base
    for points in (wide[:, 2:5], np.asfortranarray(base), base.astype(">f8"), base.astype(np.float64)):
        assert np.array_equal(classifier.classify(points), expected)
    assert np.array_equal(classifier.classify(base[::-1])[::-1], expected)  # negative row stride: copied


# ---- occupancy grids ---------------------------------------------------------


def numpy_centres(grid):
    """Cell centres by the documented formula, computed here in numpy: lo + (i + 1/2) (hi - lo) / n
    per axis in float64 from the float32 corners, rounded to float32; shape (nx, ny, nz, 3)."""
    lo, hi = np.float32(grid.lo).astype(np.float64), np.float32(grid.hi).astype(np.float64)
    axes = [(lo[a] + (np.arange(n) + 0.5) * (hi[a] - lo[a]) / n).astype(np.float32) for a, n in enumerate(grid.dims)]
    return np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)


def test_grid_matches_the_cpp_grid():
    grid = vds.Grid((-1.1, -0.9, -1.2), (1.3, 1.0, 1.1), (7, 5, 3))
    assert grid.dims == grid.shape == (7, 5, 3) and grid.cell_count == 105
    assert grid.lo == tuple(np.float32([-1.1, -0.9, -1.2]).astype(float))
    assert np.array_equal(grid.cell_centres(), numpy_centres(grid))
    assert vds.Grid((0, 0, 0), (1, 1, 1), 4).dims == (4, 4, 4)
    cubic = vds.Grid.cubic((0, 0, 0), (2, 1, 0.5), 8)
    assert cubic.dims == (8, 4, 2) and cubic.hi == (2.0, 1.0, 0.5)
    for bad in [((0, 0, 0), (1, 1, 1), 0), ((0, 0, 0), (0, 1, 1), 4), ((0, 0, 0), (1, 1, np.inf), 4),
                ((0, 0, 0), (1, 1, 1), (2, 2)), ((0, 0), (1, 1, 1), 2)]:
        with pytest.raises(vds.InvalidArgument):
            vds.Grid(*bad)


def test_exact_occupancy_equals_the_exact_labels_of_the_cell_centres():
    # An asymmetric grid over an off-centre solid: a transposed index order would show.
    grid = vds.Grid(CENTRE - [1.2, 0.9, 1.05], CENTRE + [1.1, 1.3, 0.8], (23, 17, 29))
    cells = vds.occupancy(V, F, grid)
    assert cells.shape == (23, 17, 29) and cells.dtype == np.bool_
    centres = numpy_centres(grid)
    expected = vds.Classifier(V, F, "exact").classify(centres.reshape(-1, 3)).reshape(grid.shape)
    assert np.array_equal(cells, expected)
    d = convex_signed_distance(V32.astype(np.float64), F, centres.reshape(-1, 3).astype(np.float64)).reshape(grid.shape)
    assert np.array_equal(cells[np.abs(d) > 1e-6], (d < 0)[np.abs(d) > 1e-6])
    assert 0.2 < cells.mean() < 0.8
    # A box: inside exactly where the centre is strictly inside.
    lo, hi = np.array([0.1, 0.2, 0.3]), np.array([0.9, 0.7, 0.5])
    BV, BF = box_mesh(lo, hi)
    box_grid = vds.Grid((0, 0, 0), (1, 1, 1), (10, 20, 40))
    c = numpy_centres(box_grid).astype(np.float64)
    truth = np.all((c > np.float32(lo)) & (c < np.float32(hi)), axis=-1)
    assert np.array_equal(vds.occupancy(BV, BF, box_grid), truth)


@pytest.mark.parametrize("name", METHODS)
def test_every_classifier_sweeps_its_own_labels(name):
    classifier = make(name)
    grid = vds.Grid(CENTRE - 1.1, CENTRE + 1.1, (19, 13, 11))
    cells = classifier.occupancy(grid)
    assert cells.shape == grid.shape
    assert np.array_equal(cells, classifier.classify(numpy_centres(grid).reshape(-1, 3)).reshape(grid.shape))


def test_sprite_occupancy_on_cpu_and_gpu():
    sprite = vds.bake(V, F, resolution=RESOLUTION, axis="y", method="cpu")
    grid = vds.Grid(CENTRE - 1.1, CENTRE + 1.1, (21, 16, 12))
    centres = numpy_centres(grid).reshape(-1, 3)
    for rule in ("parity", "winding", "generalized-winding"):
        cpu = sprite.occupancy(grid, rule=rule)
        assert np.array_equal(cpu, sprite.contains(centres, rule=rule).reshape(grid.shape)), rule
    gl_or_skip()
    for rule in ("parity", "winding"):
        assert np.array_equal(sprite.occupancy(grid, rule=rule, gpu=True), sprite.occupancy(grid, rule=rule)), rule
    # Rotated: the cells one by one, the same labels.
    turn = np.eye(4)
    turn[:3, :3] = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]
    sprite.transform(turn)
    assert np.array_equal(sprite.occupancy(grid, gpu=True), sprite.occupancy(grid))
    assert np.array_equal(sprite.occupancy(grid), sprite.contains(centres).reshape(grid.shape))


# ---- winding numbers -----------------------------------------------------------


def test_sprite_winding_numbers_follow_the_exact_ones():
    BV, BF = box_mesh((0, 0, 0), (1, 1, 1))
    points = RNG.uniform(-0.5, 1.5, (20_000, 3))
    d = np.max(np.abs(points - 0.5), axis=1)
    far = np.abs(d - 0.5) > 0.05
    closed = vds.bake(BV, BF, resolution=64, method="cpu")
    np.testing.assert_array_equal(closed.winding_numbers(points)[far], (d < 0.5)[far].astype(float))
    np.testing.assert_allclose(vds.winding_numbers(BV, BF, points)[far], (d < 0.5)[far], atol=1e-12)
    # Without its top face: fractional values, the sprite's within its bound of the exact ones.
    top = [2, 3]  # z = 1: vertices 4..7
    open_faces = np.delete(BF, top, axis=0)
    assert set(np.flatnonzero(np.all(BV[BF][:, :, 2] == 1, axis=1))) == set(top)
    with pytest.warns(vds.MeshWarning):
        sprite = vds.bake(BV, open_faces, resolution=128, axis="z", method="cpu")
    exact = vds.ExactClassifier(BV, open_faces).winding_numbers(points)
    from_sprite = sprite.winding_numbers(points)
    inside_box = np.all((points > 0) & (points < 1), axis=1)
    away = (np.abs(d - 0.5) > 0.1) & inside_box
    assert ((exact[away] > 0.1) & (exact[away] < 0.9)).mean() > 0.5
    np.testing.assert_allclose(from_sprite[away], exact[away], atol=0.02)
    assert np.array_equal(vds.Classifier(sprite).classify(points, rule="generalized-winding"), from_sprite > 0.5)


# ---- errors ------------------------------------------------------------------------


def test_every_error_class_is_a_vds_error_and_its_builtin_kind():
    kinds = {vds.IoError: OSError, vds.FormatError: ValueError, vds.InvalidArgument: ValueError,
             vds.DTypeError: TypeError, vds.InvalidMesh: ValueError, vds.GlUnavailable: RuntimeError,
             vds.GlError: RuntimeError, vds.OutOfMemory: MemoryError}
    for cls, builtin in kinds.items():
        assert issubclass(cls, vds.Error) and issubclass(cls, builtin), cls
        assert cls.__module__ == "vds"
    assert issubclass(vds.DTypeError, vds.InvalidArgument)


def raises_vds_error(call):
    """The exception `call` raises, which must be caught by `except vds.Error`."""
    try:
        call()
    except vds.Error as error:
        assert "\n" not in str(error)
        return error
    pytest.fail("no vds.Error raised")


def test_except_vds_error_catches_each_kind(tmp_path):
    sprite = vds.bake(V, F, resolution=32, method="cpu")
    points = around(10)
    cases = {
        vds.InvalidArgument: [lambda: sprite.contains(points, rule="sideways"),
                              lambda: vds.Classifier(V, F, "magic"),
                              lambda: sprite.contains(np.zeros((4, 2))),
                              lambda: sprite.contains(np.full((2, 3), np.nan)),
                              lambda: vds.bake(V, F, resolution=0, method="cpu"),
                              lambda: sprite.transform(np.eye(3))],
        vds.DTypeError: [lambda: sprite.contains(points.astype(np.int64)),
                         lambda: sprite.contains(points.astype(np.float16)),
                         lambda: sprite.contains(points > 0),
                         lambda: vds.Classifier(V, F, "exact").classify(points.astype(np.int32)),
                         lambda: vds.bake(V, F.astype(np.float64), method="cpu"),
                         lambda: vds.bake(V.astype(np.int64), F, method="cpu")],
        vds.InvalidMesh: [lambda: vds.bake(V, np.array([[0, 1, len(V)]]), method="cpu"),
                          lambda: vds.Classifier(V, np.array([[0, -1, 2]]), "exact"),
                          lambda: vds.ExactClassifier(np.zeros((0, 3)), np.zeros((0, 3), np.int32)),
                          lambda: vds.bake(np.full((3, 3), np.nan), np.array([[0, 1, 2]]), method="cpu")],
        vds.IoError: [lambda: vds.read(tmp_path / "missing.vds"), lambda: vds.load_mesh(tmp_path),
                      lambda: vds.read(str(tmp_path)), lambda: vds.read(os.fsencode(tmp_path)),
                      lambda: sprite.save(tmp_path)],
        vds.FormatError: [lambda: vds.from_bytes(b"not a sprite")],
    }
    for cls, calls in cases.items():
        for call in calls:
            assert type(raises_vds_error(call)) is cls, (cls, call)
    gl_or_skip()
    on_gpu = vds.Classifier(sprite, "sprite-gpu")
    vds._release_gl()  # what atexit runs: GPU classifiers go with the module's context
    assert type(raises_vds_error(lambda: on_gpu.classify(points))) is vds.GlUnavailable
    assert np.array_equal(vds.Classifier(sprite, "sprite-gpu").classify(points), sprite.contains(points))


def test_bad_threads_raise_value_error_naming_the_value():
    sprite = vds.bake(V, F, resolution=32, method="cpu")
    points = around(1000)
    for threads in (-1, 2.5, "2", None):
        with pytest.raises(ValueError, match="threads must be") as error:
            sprite.contains(points, threads=threads)
        assert "array" not in str(error.value) and len(str(error.value)) < 120
    with pytest.raises(ValueError, match="threads"):
        vds.Classifier(V, F, "exact", threads=-3)
    # Other integer options alike: a one-line message, no pybind11 dump of the arrays.
    for call, what in [(lambda: vds.bake(V, F, resolution=-1, method="cpu"), "resolution"),
                       (lambda: vds.Classifier(V, F, "sprite", resolution=2.5), "resolution"),
                       (lambda: vds.Classifier(V, F, "slicemap", slices=-1), "slices"),
                       (lambda: vds.Grid((0, 0, 0), (1, 1, 1), 2.5), "dims"),
                       (lambda: vds.Grid.cubic((0, 0, 0), (1, 1, 1), -2), "n")]:
        with pytest.raises(vds.InvalidArgument, match=what) as error:
            call()
        assert "array" not in str(error.value) and "\n" not in str(error.value)
    assert np.array_equal(sprite.contains(points, threads=np.int64(2)), sprite.contains(points))


def test_float_faces_are_refused_not_truncated():
    with pytest.raises(TypeError, match="integer"):
        vds.bake(V, F + 0.5, method="cpu")
    with pytest.raises(TypeError, match="integer"):
        vds.Classifier(V, F.astype(np.float32), "exact")


def test_paths_may_be_str_bytes_or_pathlike(tmp_path):
    sprite = vds.bake(V, F, resolution=32, method="cpu")
    for path in (tmp_path / "a.vds", str(tmp_path / "b.vds"), os.fsencode(tmp_path / "c.vds")):
        sprite.save(path)
        assert vds.read(path).to_bytes() == sprite.to_bytes()
    obj = tmp_path / "tri.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    for path in (obj, str(obj), os.fsencode(obj), pathlib.PurePath(obj)):
        Vl, Fl = vds.load_mesh(path)
        assert Vl.shape == (3, 3) and Fl.tolist() == [[0, 1, 2]]


# ---- warnings ------------------------------------------------------------------------------


def open_icosphere():
    return V, F[1:]  # one face missing: 3 boundary edges


def test_open_meshes_warn_with_the_libraries_text():
    OV, OF = open_icosphere()
    # The CLI's words, generated in one place in the library (vds::openMeshMessage),
    # with Python's parameter names and no flag Python does not have.
    text = ("mesh is open (3 boundary edges): inside is not defined by the parity rule; the generalized winding "
            "number answers for it (rule=\"generalized-winding\"); answered anyway")
    points = around(100)
    with pytest.warns(vds.MeshWarning) as bake_warnings:
        sprite = vds.bake(OV, OF, resolution=32, method="cpu")
    assert [str(w.message) for w in bake_warnings] == [text]
    with pytest.warns(vds.MeshWarning, match="^" + text.replace("(", r"\(").replace(")", r"\)") + "$"):
        vds.exact_contains(OV, OF, points)
    with pytest.warns(vds.MeshWarning, match="not defined by the winding rule"):
        vds.Classifier(OV, OF, "certified", resolution=16).classify(points, rule="winding")
    with pytest.warns(vds.MeshWarning, match="named-mesh is open"):
        vds.Classifier(OV, OF, "exact", name="named-mesh").classify(points)
    with pytest.warns(vds.MeshWarning, match="the sprite was baked from a mesh that bounds no solid"):
        sprite.contains(points)
    with pytest.warns(vds.MeshWarning):
        vds.occupancy(OV, OF, vds.Grid((-1, -1, -1), (1, 1, 1), 4))
    # The generalized winding number answers for open meshes: nothing to say; nor for closed ones.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        sprite.contains(points, rule="generalized-winding")
        vds.Classifier(OV, OF, "exact").classify(points, rule="generalized-winding")
        vds.exact_contains(V, F, points)
        vds.bake(V, F, resolution=16, method="cpu").contains(points)
    with warnings.catch_warnings():
        warnings.simplefilter("error", vds.MeshWarning)
        with pytest.raises(vds.MeshWarning):
            vds.exact_contains(OV, OF, points)


# ---- meshes viewed in place -------------------------------------------------------------------


def test_meshes_are_read_in_place_when_their_layout_allows():
    assert vds._mesh_copies(V32, F) == (False, False)
    assert vds._mesh_copies(V32, F.astype(np.uint32)) == (False, False)
    assert vds._mesh_copies(V, F) == (True, False)                       # float64 positions
    assert vds._mesh_copies(V32, F.astype(np.int64)) == (False, True)    # int64 indices
    assert vds._mesh_copies(np.asfortranarray(V32), np.asfortranarray(F)) == (True, True)
    assert vds._mesh_copies(V32, F.astype(">i4")) == (False, True)       # the other byte order
    wide = np.zeros((len(F), 4), np.int32)
    wide[:, :3] = F
    assert vds._mesh_copies(V32, wide[:, :3]) == (False, True)           # strided
    raw = np.zeros(V32.nbytes + 1, np.uint8)
    unaligned = raw[1:].view(np.float32).reshape(V32.shape)
    unaligned[:] = V32
    assert vds._mesh_copies(unaligned, F) == (True, False)               # not 4-byte aligned
    # In place or copied, the same sprite.
    expected = vds.bake(V32, F, resolution=32, axis="z", method="cpu").to_bytes()
    for v, f in [(V, F.astype(np.int64)), (np.asfortranarray(V32), F.astype(np.uint32)), (V32, wide[:, :3]),
                 (V32, F.astype(np.uint64)), (V32, F.astype(">i4")), (unaligned, F)]:
        assert vds.bake(v, f, resolution=32, axis="z", method="cpu").to_bytes() == expected


# ---- GPU classifiers: threads and exit ------------------------------------------------------


def test_gpu_classifiers_from_several_threads_take_turns_and_free_safely():
    gl_or_skip()
    sprite = vds.bake(V, F, resolution=RESOLUTION, method="cpu")
    points = around(20_000, dtype=np.float32)
    expected = sprite.contains(points)
    shared = vds.Classifier(sprite, "sprite-gpu")
    failures = []

    def work():
        try:
            for _ in range(3):
                mine = vds.Classifier(sprite, "sprite-gpu")
                for c in (mine, shared):
                    if not np.array_equal(c.classify(points), expected):
                        failures.append("labels")
                del mine  # freed on this thread, maybe while another holds GL
        except Exception as error:  # noqa: BLE001 (reported below)
            failures.append(repr(error))

    threads = [threading.Thread(target=work) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    gc.collect()
    assert not failures
    assert np.array_equal(shared.classify(points), expected)  # frees what was left to the GL holder


def test_interpreter_exits_cleanly_with_gpu_classifiers_alive():
    gl_or_skip()
    script = (
        "import numpy as np, vds, sys\n"
        "sys.path.insert(0, %r)\n"
        "from conftest import icosphere\n"
        "V, F = icosphere(1)\n"
        "p = np.zeros((5, 3))\n"
        "keep = [vds.Classifier(V, F, m, resolution=16) for m in ('sprite-gpu', 'solid-gpu', 'slicemap')]\n"
        "print(*[int(c.classify(p).sum()) for c in keep])\n"
        "class Cycle: pass\n"
        "cycle = Cycle(); cycle.me = cycle; cycle.c = vds.Classifier(V, F, 'slicemap-gpu', resolution=16)\n"
    ) % str(pathlib.Path(__file__).resolve().parent)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["5", "5", "5"], done.stdout
    assert "rror" not in done.stderr, done.stderr


def test_validate_mesh_counts_what_the_mesh_holds():
    report = vds.validate_mesh(V, F)
    assert (report["vertices"], report["triangles"]) == (len(V), len(F))
    assert report["closed"] and report["oriented"] and report["manifold"] and report["usable"]
    assert report["summary"].startswith("closed")
    np.testing.assert_allclose(report["bounds"], [V32.min(0), V32.max(0)])
    opened = vds.validate_mesh(*open_icosphere())
    assert opened["boundary_edges"] == 3 and not opened["closed"] and "3 boundary edges" in opened["summary"]
    flipped = F.copy()
    flipped[0] = flipped[0, ::-1]
    assert vds.validate_mesh(V, flipped)["inconsistent_edges"] == 3


def test_a_forked_child_refuses_gl_its_parent_was_using_instead_of_hanging():
    gl_or_skip()
    script = (
        "import os, numpy as np, vds, sys\n"
        "sys.path.insert(0, %r)\n"
        "from conftest import icosphere\n"
        "V, F = icosphere(1)\n"
        "s = vds.bake(V, F, resolution=32, method='cpu')\n"
        "p = np.zeros((5, 3))\n"
        "def child():\n"
        "    try:\n"
        "        print('child', int(s.contains(p, gpu=True).sum()), vds.gl_available(), flush=True)\n"
        "    except vds.GlUnavailable as e:\n"
        "        print('child refused', 'spawn' in str(e), vds.gl_available(), flush=True)\n"
        "    os._exit(0)\n"
        "print('parent', int(s.contains(p, gpu=True).sum()), flush=True)\n"
        "pid = os.fork()\n"
        "if pid == 0: child()\n"
        "os.waitpid(pid, 0)\n"
        "vds._release_gl()\n"  # nothing live: a child may start GL of its own
        "pid = os.fork()\n"
        "if pid == 0: child()\n"
        "os.waitpid(pid, 0)\n"
        "print('parent', int(s.contains(p, gpu=True).sum()), flush=True)\n"
    ) % str(pathlib.Path(__file__).resolve().parent)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == ["parent 5", "child refused True False", "child 5 True", "parent 5"], done.stdout


# ---- defaults that choose ------------------------------------------------------------------


def test_bake_defaults_choose_the_axis_with_fewest_layers_at_the_resolution_baked():
    # Three slabs (thin along x) stacked along z: a ray along x or y meets one
    # slab (two layers), a ray along z all three (six).
    boxes = []
    for k in range(3):
        lo = np.array([0.0, 0.0, 1.5 * k])
        boxes.append((lo, lo + np.array([0.2, 1.0, 1.0])))
    V, F = [], []
    for lo, hi in boxes:
        corners = np.array([[lo[0] if i & 1 == 0 else hi[0], lo[1] if i & 2 == 0 else hi[1],
                             lo[2] if i & 4 == 0 else hi[2]] for i in range(8)], dtype=np.float32)
        quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
        base = len(V) * 8
        for a, b, c, d in quads:
            F += [(base + a, base + b, base + c), (base + a, base + c, base + d)]
        V.append(corners)
    V, F = np.concatenate(V), np.array(F, dtype=np.int32)
    sprite = vds.bake(V, F, resolution=32)  # axis and method auto
    assert sprite.axis in ("x", "y")  # two layers; along z the three slabs give six
    along_z = vds.bake(V, F, resolution=32, axis="z", method="cpu")
    assert sprite.depth_complexity == 2 and along_z.depth_complexity == 6
    # method auto is the CPU baker on a software renderer or without GL, the
    # fragment lists on a GPU: bit for bit one of the two
    bakers = ["cpu"] + (["lists"] if vds.gl_available() else [])
    assert sprite.to_bytes() in [vds.bake(V, F, resolution=32, axis=sprite.axis, method=m).to_bytes() for m in bakers]
