"""vds: is this point inside that solid? Volumetric depth sprites from Python.

A closed triangle mesh is baked once into a Sprite (layered depth columns);
the sprite then answers inside/outside for millions of points a second, on
the CPU or, with ``gpu=True``, on a headless GL context. Every other way the
library answers (the exact and certified classifiers, the GPU sprite, the
voxel representations) is a ``Classifier`` of the same method names as the
command line's ``--method`` (``vds.methods()`` lists them), and every
occupancy grid is a ``Grid``.

    import numpy as np, vds
    V, F = vds.load_mesh("spot.obj")            # (n, 3) float64, (m, 3) int32
    sprite = vds.bake(V, F, resolution=1024)    # axis, method "auto" (CPU baker without a GPU)
    inside = sprite.contains(points)            # (N, 3) float32/float64 -> (N,) bool
    sprite.save("spot.vds"); sprite = vds.read("spot.vds")
    exact = vds.Classifier(V, F, "exact").classify(points)
    labels, stats = vds.Classifier(V, F, "certified").classify(points, stats=True)
    grid = vds.Grid(V.min(0), V.max(0), 128)    # occupancy arrays are grid.shape, [i, j, k]
    cells = vds.occupancy(V, F, grid)           # exact; sprite.occupancy(grid, gpu=True) too
    vds.save_grid("cells.npz", cells, grid)     # with its geometry, as `vds voxelize -o cells.npz`
    cells, grid = vds.load_grid("cells.npz")

Coordinates are the mesh's own units. Errors: every exception vds raises is a
``vds.Error``, and also the builtin class its kind fits: ``InvalidArgument``
(bad shapes, values, option names; a ValueError), ``DTypeError`` (points not
float32/float64, faces not integers; an InvalidArgument and a TypeError),
``InvalidMesh`` (a ValueError), ``IoError`` (an OSError), ``FormatError`` (a
ValueError), ``GlUnavailable`` and ``GlError`` (RuntimeErrors),
``OutOfMemory`` (a MemoryError); an argument of the wrong type where vds
checks it (points, faces, a grid, a rule, axis or method) is a ``DTypeError``. A mesh that bounds no
solid by the rule asked (open, or closed but mis-oriented) gets a
``vds.MeshWarning`` with the command-line tool's text in Python's words,
pointing at the caller's line. ``vds.gl_available()`` is True where GL work
can run (``vds.gl_unavailable_reason()`` says why not). Grid, Sprite,
Classifier and ExactClassifier pickle (a classifier as what rebuilds it).
GL work runs on one thread of the module's, for every Python thread in turn;
a process forked while it runs cannot use GL (``GlUnavailable`` says so): use
multiprocessing's "spawn" start method.
Scale-out over Dask: ``vds.dask``.
"""
import atexit as _atexit
import collections as _collections
import operator as _operator
import os as _os

from ._vds import (  # noqa: F401  (the public API)
    Classifier,
    DTypeError,
    Error,
    ExactClassifier,
    FEATURES,
    FormatError,
    GlError,
    GlUnavailable,
    Grid,
    InvalidArgument,
    InvalidMesh,
    IoError,
    MeshWarning,
    NO_TRIANGLE,
    OutOfMemory,
    SignedDistance,
    Sprite,
    _gpu_resident,
    _mesh_copies,
    _methods,
    __version__,
    _release_gl,
    _sample_surface,
    bake,
    closest_points,
    from_bytes,
    gl_available,
    gl_unavailable_reason,
    load_mesh,
    occupancy,
    read,
    sdf,
    signed_distance,
    validate_mesh,
    vdb_available,
    write_vdb,
)
from ._grid_files import load_grid, save_grid  # noqa: F401  (the public API)

__all__ = [
    "Classifier", "DTypeError", "Error", "ExactClassifier", "FEATURES", "FormatError", "GlError", "GlUnavailable", "Grid",
    "InvalidArgument", "InvalidMesh", "IoError", "MeshWarning", "MethodInfo", "NO_TRIANGLE", "OutOfMemory", "SignedDistance", "Sprite", "bake",
    "closest_points", "exact_contains", "from_bytes", "gl_available", "gl_unavailable_reason", "load_grid", "load_mesh",
    "methods", "occupancy", "read", "sample_surface", "save_grid", "sdf", "signed_distance", "validate_mesh",
    "vdb_available", "write_vdb",
    "winding_numbers",
]

# The module's GL context is freed while the interpreter finalizes, before the
# C library's exit handlers tear EGL down: GL is never called from those.
_atexit.register(_release_gl)


def exact_contains(V, F, points, rule="parity", threads=0):
    """Exact inside tests on the triangles themselves (no sprite).

    V: (n, 3) float vertex positions; F: (m, 3) integer vertex indices,
    counter-clockwise seen from outside; points: (N, 3) float32 or float64 in
    the same units. rule: "parity", "winding" or "generalized-winding" (the
    last answers open meshes and soups too; the others count crossings on
    any mesh, meaningful only for one that bounds a solid). Returns a (N,)
    bool array.
    Builds an ExactClassifier for the call: keep one to ask many times.
    """
    return ExactClassifier(V, F).contains(points, rule=rule, threads=threads)


def sample_surface(mesh, n, seed=0):
    """n points on the surface of a mesh, area-weighted and reproducible.

    mesh: (V, F) as vds.load_mesh returns them, or a mesh file's path.
    n: how many points; seed: an integer 0 <= seed < 2**64. Each point lies
    on a triangle chosen with probability its area over the total, uniform
    on it. Returns (points, triangles): (n, 3) float64 positions and (n,)
    uint32 indices into F of the triangle each lies on. The same mesh, n and
    seed give the same points bit for bit, here and in C++ (vds::sampleSurface
    of <vds/sample.h>, which states the generator: SplitMix64 read as a
    counter, so the points do not depend on numpy's generators). Raises
    vds.InvalidMesh for a mesh with no area (no triangles, all degenerate),
    bad indices or a corner that is not finite; vds.InvalidArgument for a
    negative n or a seed out of range.
    """
    if isinstance(mesh, (str, bytes, _os.PathLike)):
        V, F = load_mesh(mesh)
    elif isinstance(mesh, (tuple, list)) and len(mesh) == 2:
        V, F = mesh
    else:
        raise DTypeError(f"mesh must be (V, F) or a mesh file's path, not {type(mesh).__name__}")
    try:
        n, seed = _operator.index(n), _operator.index(seed)
    except TypeError:
        raise DTypeError(f"n and seed must be integers, not {type(n).__name__} and {type(seed).__name__}") from None
    if n < 0 or not 0 <= seed < 1 << 64:
        raise InvalidArgument(f"sample_surface: n must be 0 or more and seed in 0..2**64-1, not {n} and {seed}")
    return _sample_surface(V, F, n, seed)


def winding_numbers(V, F, points):
    """Generalized winding numbers of points (N, 3) w.r.t. the mesh (V, F):
    a (N,) float64 array, 1 inside a closed outward-oriented mesh, 0 outside,
    fractional near holes of an open one (exact integer part, Antipodal
    boundary term in double). ``exact_contains(..., rule="generalized-winding")``
    is True exactly where this is above 1/2 by more than 1e-9 (a point on a
    sheet, at 1/2, is outside for both)."""
    return ExactClassifier(V, F).winding_numbers(points)


MethodInfo = _collections.namedtuple(
    "MethodInfo", "name exact gpu needs_closed_mesh from_sprite rules default_resolution layer summary")
MethodInfo.__doc__ = """One row of the library's method table (C++ ``vds::MethodInfo``).

name: the method's name, for ``Classifier(..., method=name)`` and the CLI's
``--method``; exact: its labels equal the exact classifier's on every point;
gpu: its queries run on the GPU; needs_closed_mesh: it refuses open meshes;
from_sprite: it can be made from a Sprite; rules: the rules it answers;
default_resolution: texels or cells on the box's longest side when none is
given (0: none); layer: "core", "gl" or "voxel"; summary: one line."""


def methods():
    """Every way vds answers "inside?", as a list of ``MethodInfo`` in the
    order of the C++ ``Method`` enum (less ``custom``, which names
    classifiers written in C++ outside the library)."""
    return [MethodInfo(**row) for row in _methods()]
