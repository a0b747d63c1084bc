"""vds.dask.occupancy and vds.dask.sdf: grids larger than memory, block by block.

Each block of the dask array is one task that labels (or measures) its own
cells only, as a vds.Grid block of the whole grid (Grid(..., first=,
whole=)): the library gives a block's cells the centres they have in the
whole grid, so every block equals the one-call result cell for cell, and
the whole grid is never held. ``.to_zarr(store)`` writes it out of core.
"""
import functools
import itertools
import math

import dask
import dask.array as da
import numpy as np
from dask.highlevelgraph import HighLevelGraph

from . import Grid, InvalidArgument
from ._dask_ship import method_for, ship

# Cells an occupancy block holds when no chunks are given: 16 MiB of one-byte labels.
_BLOCK_CELLS = 1 << 24
# Cells along each side of an SDF block when no chunks are given (8 MiB of float32).
_SDF_BLOCK_SIDE = 128
# SDF blocks this process filled without a distance per cell (tests read it).
far_blocks = 0


class _Block:
    """One block: `dims` cells from cell `first` of the grid of `whole` cells over [lo, hi]."""

    __slots__ = ("lo", "hi", "whole", "first", "dims")

    def __init__(self, lo, hi, whole, first, dims):
        self.lo, self.hi, self.whole, self.first, self.dims = lo, hi, whole, first, dims

    def __getstate__(self):
        return (self.lo, self.hi, self.whole, self.first, self.dims)

    def __setstate__(self, state):
        self.lo, self.hi, self.whole, self.first, self.dims = state

    def grid(self):
        return Grid(self.lo, self.hi, self.dims, first=self.first, whole=self.whole)

    def centre(self, offset):
        """The centre of this block's cell `offset`, float32 as the library computes it."""
        first = tuple(f + o for f, o in zip(self.first, offset))
        return Grid(self.lo, self.hi, (1, 1, 1), first=first, whole=self.whole).cell_centres()[0, 0, 0]


def _whole_grid(grid):
    """(lo, hi, whole cells, first cell, shape) of a vds.Grid (a block of one
    included) or of (lo, hi, dims): the latter names grids past the 2^34 cells
    one vds.Grid may hold."""
    if isinstance(grid, Grid):
        return grid.lo, grid.hi, grid.whole or grid.dims, grid.first, grid.dims
    try:
        lo, hi, dims = grid
    except (TypeError, ValueError):
        raise InvalidArgument("grid must be a vds.Grid or (lo, hi, dims)") from None
    dims = (int(dims),) * 3 if np.ndim(dims) == 0 else tuple(int(d) for d in dims)
    if len(dims) != 3 or min(dims) < 1:
        raise InvalidArgument(f"grid dims must be one positive cell count or three, not {dims}")
    lo = tuple(float(v) for v in lo)
    hi = tuple(float(v) for v in hi)
    return lo, hi, dims, (0, 0, 0), dims


def _block_chunks(shape, chunks, columns):
    """dask's chunks of a grid of `shape`: as given (an int, three, or
    dask's tuples of tuples); else, with `columns`, blocks of about
    _BLOCK_CELLS cells, whole columns along z (every sweep runs along z) and
    square in x and y, or cubes of _SDF_BLOCK_SIDE cells (small enough that
    most blocks of a band lie wholly outside it)."""
    if chunks is None and columns:
        nz = min(shape[2], _BLOCK_CELLS)
        side = max(1, math.isqrt(_BLOCK_CELLS // nz))
        chunks = (min(shape[0], side), min(shape[1], side), nz)
    elif chunks is None:
        chunks = tuple(min(n, _SDF_BLOCK_SIDE) for n in shape)
    return da.core.normalize_chunks(chunks, shape=shape, dtype=np.uint8)


def _blocks_array(prefix, src, grid, chunks, block_function, dtype, out_chunks, token_args):
    """A dask array whose block (a, b, c) is block_function(source, _Block)."""
    lo, hi, whole, base, _ = grid
    source = src.delayed()
    name = prefix + "-" + dask.base.tokenize(src.digest, grid, chunks, token_args)
    starts = [np.cumsum((0,) + c[:-1]) for c in chunks]
    layer = {}
    for index in itertools.product(*(range(len(c)) for c in chunks)):
        first = tuple(int(base[a] + starts[a][index[a]]) for a in range(3))
        dims = tuple(int(chunks[a][index[a]]) for a in range(3))
        layer[(name,) + index] = (block_function, source.key, _Block(lo, hi, whole, first, dims))
    graph = HighLevelGraph.from_collections(name, layer, dependencies=[source])
    return da.Array(graph, name, out_chunks, dtype=dtype, meta=np.empty((0, 0, 0), dtype=dtype))


def _prepared(grid, chunks, packed=False, columns=True):
    grid = _whole_grid(grid)
    chunks = _block_chunks(grid[4], chunks, columns)
    if packed and any(c % 8 for c in chunks[2][:-1]):
        raise InvalidArgument(f"packed blocks need z chunks of a multiple of 8 cells (a byte each), not {chunks[2]}")
    lo, hi, whole, base, _ = grid
    Grid(lo, hi, tuple(c[0] for c in chunks), first=base, whole=whole)  # a bad grid fails here
    return grid, chunks


def _occupancy_block(src, block, method, resolution, rule, packed, threads):
    cells = src.build("classifier", method, resolution).occupancy(block.grid(), rule=rule, threads=threads)
    return np.packbits(cells, axis=2) if packed else cells


def occupancy(source, grid, chunks=None, rule="parity", packed=False, method=None, resolution=0, threads=1):
    """Inside labels of every cell of a grid, block by block: a lazy dask
    array of grid.shape (bool), or with packed=True of (NX, NY, ceil(NZ / 8))
    uint8, each z row eight cells to a byte (numpy.packbits(cells, axis=2),
    as `vds voxelize --packed` writes).

    source: as for vds.dask.classify. grid: a vds.Grid (a block of one
        too), or (lo, hi, dims) for a grid past a vds.Grid's 2^34 cells.
    chunks: block shape: an int, three ints or dask's chunks; None: about
        2^24 cells a block, whole columns along z. Packed, z chunks are a
        multiple of 8 cells (but the last).
    rule, method, resolution, threads: as for vds.dask.classify; method
        None: "exact" for a mesh (the labels of vds.occupancy(V, F, grid)),
        "sprite" for a sprite (Sprite.occupancy's).
    Each block equals the one-call grid's cells; ``.to_zarr(store)`` writes
    the grid without holding it.
    """
    src = ship(source, rule)
    method = method_for(src, method, rule)
    grid, chunks = _prepared(grid, chunks, packed)
    out_chunks = (chunks[0], chunks[1], tuple((c + 7) // 8 for c in chunks[2])) if packed else chunks
    block = functools.partial(_occupancy_block, method=method, resolution=resolution, rule=rule, packed=packed,
                              threads=threads)
    return _blocks_array("vds-occupancy", src, grid, chunks, block, np.uint8 if packed else bool, out_chunks,
                         (method, resolution, rule, packed))


def _far_labels(src, block, rule, band, threads):
    """A block's inside labels when every one of its cells lies farther than
    `band` from the surface, else None. One distance decides: the middle
    cell's, less its distance to the farthest corner cell (distance is
    1-Lipschitz; the cells lie in the corners' box). The labels are then the
    middle cell's for all (a rule that defines the inside is constant off
    the surface), or the exact sweep's where the rule does not define it
    (an open mesh; the generalized winding number)."""
    middle = block.centre(tuple(d // 2 for d in block.dims))
    reach = max(np.linalg.norm(block.centre(corner).astype(np.float64) - middle)
                for corner in itertools.product(*((0, d - 1) for d in block.dims)))
    distance = src.build("distance", rule).distance(middle[None], threads=1)[0]
    if abs(distance) - reach <= band * (1 + 1e-6):
        return None
    report = src.build("report")
    if (rule == "parity" and report["closed"]) or (rule == "winding" and report["oriented"]):
        return np.full(block.dims, np.signbit(distance))
    return src.build("classifier", "exact", 0).occupancy(block.grid(), rule=rule, threads=threads)


def _sdf_block(src, block, rule, band, threads):
    global far_blocks
    if band > 0:
        inside = _far_labels(src, block, rule, band, threads)
        if inside is not None:
            far_blocks += 1
            return np.where(inside, np.float32(-band), np.float32(band))
    return src.build("distance", rule).sdf(block.grid(), band=band, threads=threads)


def sdf(source, grid, band=0.0, chunks=None, rule="parity", threads=1):
    """Signed distances of every cell centre of a grid, block by block: a
    lazy float32 dask array of grid.shape, equal cell for cell to
    vds.sdf(V, F, grid, rule, band) (exact; negative inside by `rule`).

    source: a mesh (V, F) or a mesh file's path. grid: as for
        vds.dask.occupancy. chunks: block shape; None: cubes of 128 cells.
        band > 0: cells farther than band from the
        surface hold -band or +band, and a block wholly that far is filled
        without a distance per cell (one at its middle decides).
    """
    src = ship(source, rule)
    src.require_mesh("sdf")
    band = float(band)
    if not (math.isfinite(band) and band >= 0.0):
        raise InvalidArgument(f"the band's half-width must be a finite distance >= 0 (0: the full grid), not {band}")
    grid, chunks = _prepared(grid, chunks, columns=False)
    block = functools.partial(_sdf_block, rule=rule, band=band, threads=threads)
    return _blocks_array("vds-sdf", src, grid, chunks, block, np.float32, chunks, (rule, band))
