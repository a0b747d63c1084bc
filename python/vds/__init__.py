"""vds: is this point inside that solid? Volumetric depth sprites from Python.

A closed triangle mesh is baked once into a Sprite (layered depth columns);
the sprite then answers inside/outside for millions of points a second, on
the CPU or, with ``gpu=True``, on a headless GL context.

    import numpy as np, vds
    V, F = vds.load_mesh("spot.obj")            # (n, 3) float64, (m, 3) int32
    sprite = vds.bake(V, F, resolution=1024)    # axis "auto", GL fragment lists
    inside = sprite.contains(points)            # (N, 3) float32/float64 -> (N,) bool
    sprite.save("spot.vds"); sprite = vds.read("spot.vds")
    exact = vds.exact_contains(V, F, points)    # the exact answers, on the triangles

Coordinates are the mesh's own units. Errors: ValueError for bad arrays
(shape, dtype, non-finite values) and bad options; vds.IoError (an OSError)
for files that cannot be read or written; vds.FormatError and
vds.InvalidMesh (ValueErrors) for bad files and meshes; vds.GlUnavailable
and vds.GlError (RuntimeErrors) for GL. Every vds error is a vds.Error or
one of the builtin classes named. Scale-out over Dask: ``vds.dask``.
"""
import atexit as _atexit

from ._vds import (  # noqa: F401  (the public API)
    Error,
    ExactClassifier,
    FormatError,
    GlError,
    GlUnavailable,
    InvalidMesh,
    IoError,
    Sprite,
    _gpu_resident,
    _release_gl,
    bake,
    from_bytes,
    gl_available,
    load_mesh,
    read,
)

__all__ = [
    "Error", "ExactClassifier", "FormatError", "GlError", "GlUnavailable", "InvalidMesh", "IoError",
    "Sprite", "bake", "exact_contains", "from_bytes", "gl_available", "load_mesh", "read", "winding_numbers",
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


def winding_numbers(V, F, points):
    """Generalized winding numbers of points (N, 3) w.r.t. the mesh (V, F):
    a (N,) float64 array, 1 inside a closed outward-oriented mesh, 0 outside,
    fractional near holes of an open one (exact integer part, Antipodal
    boundary term in double)."""
    return ExactClassifier(V, F).winding_numbers(points)
