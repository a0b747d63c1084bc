"""vds.dask: inside tests for a dask array of points, classified on the workers.

    import dask.array as da, vds, vds.dask
    points = da.random.random((10**9, 3), chunks=(2**22, 3))   # made on the workers
    labels = vds.dask.contains("spot.vds", points)              # lazy (N,) bool dask array
    inside = labels.sum().compute()

The sprite travels as its .vds file bytes (``Sprite.to_bytes``), once: the
bytes are one task of the graph, which the scheduler hands to each worker that
runs a chunk, once per worker and computation, and each worker process
decodes them once and keeps the Sprite (keyed by the bytes' SHA-256) for the
chunks and computations after. Works with any scheduler: distributed, the
threaded one, processes or synchronous.
"""
import hashlib
import os
import threading

import dask
import dask.array as da
import numpy as np

from . import Sprite, from_bytes

# Per worker process: decoded sprites by digest (a few, oldest dropped first),
# and how many decodes this process made (tests read it through Client.run).
_CACHE_LIMIT = 4
_cache = {}
_cache_lock = threading.Lock()
decodes = 0


class SpriteBytes:
    """A sprite's .vds file bytes and their SHA-256, as shipped to workers."""

    __slots__ = ("digest", "data")

    def __init__(self, data):
        self.data = bytes(data)
        self.digest = hashlib.sha256(self.data).hexdigest()

    def __getstate__(self):
        return (self.digest, self.data)

    def __setstate__(self, state):
        self.digest, self.data = state

    def sprite(self):
        """The decoded Sprite, from this process's cache when it has it."""
        global decodes
        with _cache_lock:
            sprite = _cache.get(self.digest)
            if sprite is None:
                sprite = from_bytes(self.data, "vds.dask:" + self.digest[:12])
                decodes += 1
                while len(_cache) >= _CACHE_LIMIT:
                    _cache.pop(next(iter(_cache)))
                _cache[self.digest] = sprite
            return sprite


def sprite_bytes(sprite_or_path):
    """SpriteBytes of a Sprite, a .vds file path, bytes, or SpriteBytes."""
    if isinstance(sprite_or_path, SpriteBytes):
        return sprite_or_path
    if isinstance(sprite_or_path, Sprite):
        return SpriteBytes(sprite_or_path.to_bytes())
    if isinstance(sprite_or_path, (bytes, bytearray, memoryview)):
        return SpriteBytes(sprite_or_path)
    with open(os.fspath(sprite_or_path), "rb") as f:
        return SpriteBytes(f.read())


def _classify_chunk(points, blob, rule, threads):
    return blob.sprite().contains(points, rule=rule, threads=threads)


def contains(sprite_or_path, points, rule="parity", threads=1):
    """Inside tests of a dask array of points: a lazy (N,) bool dask array.

    sprite_or_path: a vds.Sprite, the path of a .vds file (read here, on the
        client), or the file's bytes.
    points: (N, 3) dask array (or anything dask.array.asarray takes) of
        float32 or float64 in the sprite's world coordinates; chunked along N
        only (it is rechunked to whole rows if not).
    rule: "parity", "winding" or "generalized-winding".
    threads: CPU threads per chunk; 1 by default, since Dask runs chunks in
        parallel already (0: one per hardware thread).
    The sprite's bytes are checked here (decoded once on the client), so a
    bad file fails at the call, not on a worker. Errors on chunks (a
    non-finite point: ValueError) surface when the result is computed.
    """
    blob = sprite_bytes(sprite_or_path)
    if not isinstance(sprite_or_path, Sprite):
        from_bytes(blob.data, "vds.dask")  # fail early, here, for a bad file
    points = da.asarray(points)
    if points.ndim != 2 or points.shape[1] != 3:
        raise ValueError(f"points must have shape (N, 3), not {points.shape}")
    if points.dtype not in (np.float32, np.float64):
        raise ValueError(f"points must be float32 or float64, not {points.dtype}")
    if len(points.chunks[1]) != 1:
        points = points.rechunk({1: 3})
    shipped = dask.delayed(blob, name="vds-sprite-" + blob.digest, pure=True)
    return da.map_blocks(_classify_chunk, points, blob=shipped, rule=rule, threads=threads,
                         drop_axis=1, dtype=bool, meta=np.empty((0,), dtype=bool),
                         name="vds-contains")
