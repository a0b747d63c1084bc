"""vds.dask: every question of vds, lazily, on Dask: points, grids, many meshes.

    import dask.array as da, vds, vds.dask
    points = da.random.random((10**9, 3), chunks=(2**22, 3))    # made on the workers
    labels = vds.dask.classify("part.obj", points, method="exact")  # lazy (N,) bool
    inside = labels.sum().compute()
    vds.dask.occupancy("part.obj", vds.Grid(lo, hi, 2048), packed=True).to_zarr("grid.zarr")
    vds.dask.dataset(["a.obj", "b.obj"], "samples.zarr")            # one Zarr group a mesh

Points (any chunking along rows; columns are joined): ``classify``,
``contains``, ``signed_distance``, ``closest_points``, ``winding_numbers``.
Grids, block by block, each block equal cell for cell to the one-call
result: ``occupancy``, ``sdf``; ``to_zarr`` writes one with each chunk
written once, a killed worker's finished blocks included. Many meshes: ``dataset`` (vds/_dask_dataset.py).

A source is a mesh ``(V, F)``, a mesh file's path (OBJ, PLY, STL, OFF), a
``vds.Sprite`` or a ``.vds`` file's path. Files are read on the client, and
what travels is the mesh's arrays or the sprite's file bytes: one task of
the graph, handed once to each worker that needs it. Each worker process
builds the classifier or distance index once and keeps it, keyed by the
bytes' SHA-256 and the arguments, for every chunk and computation after
(vds/_dask_ship.py). Works on any scheduler: distributed, threads,
processes, synchronous. A bad source fails at the call; a mesh whose inside
the rule does not define warns there (vds.MeshWarning), as the one-process
calls do. A chunk of points with a non-finite coordinate fails when
computed with the library's message naming the chunk and the row.
"""
import re

import dask.array as da
import numpy as np

from . import InvalidArgument
from ._dask_dataset import dataset  # noqa: F401  (the public API)
from ._dask_grids import occupancy, sdf  # noqa: F401  (the public API)
from ._dask_ship import method_for, ship
from ._dask_zarr import to_zarr  # noqa: F401  (the public API)

__all__ = ["classify", "closest_points", "contains", "dataset", "occupancy", "sdf", "signed_distance",
           "to_zarr", "winding_numbers"]


def _points(points):
    points = da.asarray(points)
    if points.ndim != 2 or points.shape[1] != 3:
        raise ValueError(f"points must have shape (N, 3), not {points.shape}")
    if points.dtype not in (np.float32, np.float64):
        raise ValueError(f"points must be float32 or float64, not {points.dtype}")
    if len(points.chunks[1]) != 1:
        points = points.rechunk({1: 3})
    return points


def _in_chunk(ask, points, block_info):
    """ask(points), with the chunk and its rows named in a bad point's message
    (points[k] of the chunk becomes points[row] of the whole array)."""
    try:
        return ask(points)
    except InvalidArgument as e:
        info = block_info[0]
        start, stop = info["array-location"][0]
        chunk = info["chunk-location"][0]
        text = re.sub(r"^points\[(\d+)\]", lambda m: f"points[{start + int(m.group(1))}]", str(e))
        raise type(e)(f"vds.dask: points chunk {chunk} (rows {start} to {stop - 1}): {text}") from None


def _labels_chunk(points, src, method, resolution, rule, threads, block_info=None):
    classifier = src.build("classifier", method, resolution)
    return _in_chunk(lambda p: classifier.classify(p, rule=rule, threads=threads), points, block_info)


def _distance_chunk(points, src, rule, threads, block_info=None):
    distance = src.build("distance", rule)
    return _in_chunk(lambda p: distance.distance(p, threads=threads), points, block_info)


def _winding_chunk(points, src, block_info=None):
    index = src.build("sprite") if src.kind == "sprite" else src.build("exact")
    return _in_chunk(index.winding_numbers, points, block_info)


def _closest_chunk(points, src, threads, block_info=None):
    distance = src.build("distance", "generalized-winding")
    xyz, d, triangles = _in_chunk(lambda p: distance.closest_points(p, threads=threads), points, block_info)
    return np.column_stack([xyz, d, triangles])  # triangle indices < 2^32: exact in float64


def _per_row(chunk_function, points, src, dtype, name, **kwargs):
    """A lazy (N,) array: chunk_function on each chunk of rows, the source
    one shared task."""
    return da.map_blocks(chunk_function, points, src=src.delayed(), drop_axis=1, dtype=dtype,
                         meta=np.empty((0,), dtype=dtype), name=name, **kwargs)


def classify(source, points, method=None, rule="parity", resolution=0, threads=1):
    """Inside tests of a dask array of points: a lazy (N,) bool dask array.

    source: a mesh (V, F), a mesh file's path, a vds.Sprite or a .vds path.
    points: (N, 3) dask array (or anything dask.array.asarray takes) of
        float32 or float64 in the source's coordinates, chunked along N.
    method: any name of vds.methods() ("exact", "certified", "sprite",
        "sprite-gpu", the voxel methods...); None: "exact" for a mesh,
        "sprite" for a sprite. A sprite answers its from_sprite methods
        only; the GPU methods run on each worker's headless GL context.
    rule: "parity", "winding" or "generalized-winding". An unknown method,
        one a sprite cannot make, or one that cannot answer the rule fails
        at the call.
    resolution: as vds.Classifier's (0: the method's default).
    threads: CPU threads per chunk; 1 by default, since Dask runs chunks in
        parallel already (0: one per hardware thread).
    Labels equal vds.Classifier(source, method).classify(points, rule).
    """
    src = ship(source, rule)
    method = method_for(src, method, rule)
    return _per_row(_labels_chunk, _points(points), src, bool, "vds-classify", method=method,
                    resolution=resolution, rule=rule, threads=threads)


def contains(sprite_or_path, points, rule="parity", threads=1):
    """classify(sprite_or_path, points, rule=rule): a sprite's (or a mesh's
    exact) inside tests, the name Sprite.contains uses."""
    return classify(sprite_or_path, points, rule=rule, threads=threads)


def signed_distance(source, points, rule="parity", threads=1):
    """Exact signed distances of a dask array of points to a mesh: a lazy
    (N,) float64 dask array, equal to vds.signed_distance(V, F, points,
    rule): negative exactly where the exact classifier of `rule` says inside.
    source: a mesh (V, F) or a mesh file's path (a sprite keeps no
    triangles). points, threads: as for classify."""
    src = ship(source, rule)
    src.require_mesh("signed_distance")
    return _per_row(_distance_chunk, _points(points), src, np.float64, "vds-signed-distance", rule=rule,
                    threads=threads)


def winding_numbers(source, points):
    """Generalized winding numbers of a dask array of points: a lazy (N,)
    float64 dask array; a mesh's are vds.winding_numbers(V, F, points)
    (exact), a sprite's Sprite.winding_numbers(points)."""
    src = ship(source, None)
    return _per_row(_winding_chunk, _points(points), src, np.float64, "vds-winding-numbers")


def closest_points(source, points, threads=1):
    """Each point's nearest point of a mesh's surface, lazily: (points (N, 3)
    float64, distances (N,) float64, triangles (N,) uint32) dask arrays, as
    vds.closest_points(V, F, points); computed together (dask.compute(*r)),
    each chunk is searched once. source: a mesh (V, F) or a mesh file."""
    src = ship(source, None)
    src.require_mesh("closest_points")
    points = _points(points)
    rows = da.map_blocks(_closest_chunk, points, src=src.delayed(), threads=threads, chunks=(points.chunks[0], (5,)),
                         dtype=np.float64, meta=np.empty((0, 5)), name="vds-closest-points")
    return rows[:, :3], rows[:, 3], rows[:, 4].astype(np.uint32)
