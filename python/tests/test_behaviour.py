"""Python that behaves like Python: bools, pickling, errors, warnings at the
caller's line, the version; one account of a mis-oriented mesh; outputs that
respect what they land on."""
import os
import pickle
import re
import stat
import threading
import warnings

import numpy as np
import pytest

import vds
from conftest import box_mesh


def multibody():
    """Two closed boxes, the second turned inside out, one triangle of the
    first reversed: closed, 3 conflicting edges and an inside-out part."""
    Va, Fa = box_mesh((0, 0, 0), (1, 1, 1))
    Vb, Fb = box_mesh((2, 0, 0), (3, 1, 1))
    Fa = Fa.copy()
    Fa[0] = Fa[0][[0, 2, 1]]
    return np.vstack([Va, Vb]), np.vstack([Fa, Fb[:, [0, 2, 1]] + len(Va)]).astype(np.int32)


def open_box():
    V, F = box_mesh((0, 0, 0), (1, 1, 1))
    return V, F[:-1]


def test_gl_available_is_a_bool_and_the_reason_is_apart():
    ok = vds.gl_available()
    assert isinstance(ok, bool)
    reason = vds.gl_unavailable_reason()
    assert isinstance(reason, str) and (reason == "") == ok


def test_version_is_the_projects():
    assert re.fullmatch(r"\d+\.\d+\.\d+", vds.__version__)
    pyproject = os.path.join(os.path.dirname(__file__), "..", "..", "pyproject.toml")
    assert 'version = "%s"' % vds.__version__ in open(pyproject).read()


def test_grid_and_classifiers_pickle_by_what_rebuilds_them():
    V, F = box_mesh((-1, -1, -1), (1, 0.5, 2))
    grid = vds.Grid((-1.5, -1.5, -1.5), (1.5, 1.5, 2.5), (5, 6, 7))
    again = pickle.loads(pickle.dumps(grid))
    assert repr(again) == repr(grid) and again.dims == grid.dims
    points = np.random.default_rng(1).uniform(-1.5, 2.5, (500, 3))
    exact = vds.ExactClassifier(V, F, axis="x")
    copy = pickle.loads(pickle.dumps(exact))
    assert (copy.contains(points) == exact.contains(points)).all()
    assert copy.boundary_edges == exact.boundary_edges
    for made in (vds.Classifier(V, F, "certified", resolution=32, name="box"),
                 vds.Classifier(vds.bake(V, F, resolution=32, method="cpu"), "sprite")):
        copy = pickle.loads(pickle.dumps(made))
        assert copy.method == made.method and copy.summary == made.summary
        assert (copy.classify(points) == made.classify(points)).all()
        assert (copy.occupancy(grid) == made.occupancy(grid)).all()


def test_a_tuple_for_a_grid_is_a_vds_error():
    V, F = box_mesh((0, 0, 0), (1, 1, 1))
    sprite = vds.bake(V, F, resolution=16, method="cpu")
    for call in (lambda g: vds.occupancy(V, F, g), lambda g: sprite.occupancy(g),
                 lambda g: vds.Classifier(V, F, "exact").occupancy(g)):
        with pytest.raises(vds.Error, match="grid must be a vds.Grid") as caught:
            call(((0, 0, 0), (1, 1, 1), 4))
        assert isinstance(caught.value, TypeError)


def test_text_options_of_the_wrong_type_are_vds_errors():
    V, F = box_mesh((0, 0, 0), (1, 1, 1))
    points = np.full((2, 3), 0.5)
    sprite = vds.bake(V, F, resolution=16, method="cpu")
    for call, what in ((lambda: vds.exact_contains(V, F, points, rule=None), "rule"),
                       (lambda: sprite.contains(points, rule=1), "rule"),
                       (lambda: vds.bake(V, F, resolution=16, axis=2), "axis"),
                       (lambda: vds.bake(V, F, resolution=16, method=None), "method"),
                       (lambda: vds.ExactClassifier(V, F, axis=0), "axis")):
        with pytest.raises(vds.DTypeError, match=what + " must be a str, not") as caught:
            call()
        assert isinstance(caught.value, vds.Error) and isinstance(caught.value, TypeError)


def test_threads_are_validated_like_the_command_line():
    V, F = box_mesh((0, 0, 0), (1, 1, 1))
    points = np.full((4, 3), 0.5)
    assert vds.exact_contains(V, F, points, threads=10**6).all()  # the CLI takes any 32-bit count
    for bad in (-1, 2**32, 1.5, True, "2"):
        with pytest.raises(vds.InvalidArgument, match="threads must be a whole number 0..4294967295"):
            vds.exact_contains(V, F, points, threads=bad)


def test_warnings_point_at_the_callers_line_in_pythons_words():
    V, F = open_box()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        vds.exact_contains(V, F, np.zeros((2, 3)))  # through vds/__init__.py
        line = test_warnings_point_at_the_callers_line_in_pythons_words.__code__.co_firstlineno + 4
    assert len(caught) == 1 and caught[0].category is vds.MeshWarning
    assert caught[0].filename == __file__ and caught[0].lineno == line
    text = str(caught[0].message)
    assert 'rule="generalized-winding"' in text and "--" not in text  # no command-line flag named


def test_a_mis_oriented_closed_mesh_has_one_account_everywhere():
    V, F = multibody()
    report = vds.validate_mesh(V, F)
    assert report["status"] == "mis-oriented" and report["closed"]
    assert report["inside_out_parts"] == 1 and report["inconsistent_edges"] == 3
    # Every count of one mesh agrees: the exact classifier's boundary is the validation's.
    assert vds.ExactClassifier(V, F).boundary_edges == report["winding_boundary_edges"] == 6
    assert report["summary"].startswith("closed but mis-oriented (3 inconsistently oriented edges, 1 inside-out part")
    with pytest.warns(vds.MeshWarning) as baked:
        sprite = vds.bake(V, F, resolution=16, method="cpu")
    assert sprite.status == "mis-oriented" and sprite.validation == report["summary"]
    message = str(baked[0].message)
    for says in ("is closed but mis-oriented", "the parity rule", "the winding rule does not define inside",
                 "the generalized winding number sees an inside-out part as outside"):
        assert says in message, message
    # What it says each rule answers, inside the inside-out box.
    inside_out = np.array([[2.5, 0.5, 0.5]])
    with pytest.warns(vds.MeshWarning):
        assert vds.exact_contains(V, F, inside_out, rule="parity").all()
    assert not vds.exact_contains(V, F, inside_out, rule="generalized-winding").any()
    assert vds.winding_numbers(V, F, inside_out)[0] == pytest.approx(-1.0, abs=0.05)  # near -1: outside
    Vo, Fo = open_box()
    assert vds.validate_mesh(Vo, Fo)["status"] == "open"
    assert vds.validate_mesh(*box_mesh((0, 0, 0), (1, 1, 1)))["status"] == "closed"


def test_on_sheet_ties_are_answered_alike():
    # A square sheet (two triangles, open): its own points have winding number 1/2 exactly.
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], float)
    F = np.array([[0, 1, 2], [2, 1, 3]], np.int32)
    rng = np.random.default_rng(3)
    points = np.column_stack([rng.uniform(0.05, 0.95, (300, 2)), np.zeros(300)])
    w = vds.winding_numbers(V, F, points)
    labels = vds.exact_contains(V, F, points, rule="generalized-winding")
    assert ((w > 0.5) == labels).all()
    assert (w == 0.5).all()


def test_sprite_save_writes_through_symlinks_and_into_fifos(tmp_path):
    V, F = box_mesh((0, 0, 0), (1, 1, 1))
    sprite = vds.bake(V, F, resolution=16, method="cpu")
    (tmp_path / "real").mkdir()
    os.symlink("real/s.vds", tmp_path / "link.vds")
    sprite.save(tmp_path / "link.vds")
    assert os.path.islink(tmp_path / "link.vds")
    assert vds.read(tmp_path / "real" / "s.vds").to_bytes() == sprite.to_bytes()
    os.mkfifo(tmp_path / "pipe")
    got = []
    reader = threading.Thread(target=lambda: got.append(open(tmp_path / "pipe", "rb").read()))
    reader.start()
    sprite.save(tmp_path / "pipe")
    reader.join()
    assert got == [sprite.to_bytes()]
    assert stat.S_ISFIFO(os.lstat(tmp_path / "pipe").st_mode)
    with pytest.raises(vds.IoError):
        sprite.save(tmp_path / "real")  # a directory


def test_docstrings_say_what_the_code_does():
    assert vds.Sprite.source_name.__doc__
    assert "0 outside the sprite's box" not in vds.Sprite.winding_numbers.__doc__
    # Outside the box of an open mesh's sprite the value is the boundary term: not 0 near a hole.
    V, F = open_box()
    with pytest.warns(vds.MeshWarning):
        sprite = vds.bake(V, F, resolution=32, method="cpu")
    near_hole = np.array([[0.5, 0.5, 1.2]])  # above the missing face, outside the box
    expected = vds.winding_numbers(V, F, near_hole)[0]
    assert abs(expected) > 0.05
    assert sprite.winding_numbers(near_hole)[0] == pytest.approx(expected, abs=1e-3)


def test_an_edge_on_sheet_is_refused_like_the_others():
    # The tilted plane x = y has extent along every axis; along z a sprite sees it edge-on.
    V = np.array([[0, 0, 0], [1, 1, 0], [0, 0, 1], [1, 1, 1]], float)
    F = np.array([[0, 1, 2], [2, 1, 3]], np.int32)
    for axis in ("x", "z", "auto"):
        with pytest.raises(vds.InvalidMesh, match=r"is flat \(all its triangles lie in one plane\)"):
            vds.bake(V, F, resolution=16, axis=axis, method="cpu")
