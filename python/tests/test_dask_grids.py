"""vds.dask.occupancy and vds.dask.sdf: every block against the whole-grid call, cell for cell."""
import pickle

import dask
import numpy as np
import pytest

import vds
import vds.dask
from conftest import icosphere, sphere_mesh

pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def sphere():
    return sphere_mesh(segments=24, rings=12)


def grid_around(V, dims, margin=0.1):
    lo, hi = V.min(0), V.max(0)
    pad = margin * (hi - lo)
    return vds.Grid(lo - pad, hi + pad, dims)


def test_grid_blocks_have_the_whole_grids_cells():
    g = vds.Grid((0, 0, 0), (1, 2, 3), (4, 5, 6))
    assert g.first == (0, 0, 0) and g.whole is None
    b = vds.Grid((0, 0, 0), (1, 2, 3), (2, 2, 2), first=(1, 2, 3), whole=(4, 5, 6))
    assert b.first == (1, 2, 3) and b.whole == (4, 5, 6) and b.shape == (2, 2, 2)
    assert np.array_equal(b.cell_centres(), g.cell_centres()[1:3, 2:4, 3:5])
    back = pickle.loads(pickle.dumps(b))
    assert (back.first, back.whole, back.dims) == (b.first, b.whole, b.dims) and "first=(1, 2, 3)" in repr(back)
    # Past one vds.Grid's 2^34 cells as a whole, a block of it is fine.
    assert vds.Grid((0, 0, 0), (1, 1, 1), (2, 2, 2), first=(0, 0, 4094), whole=4096).whole == (4096,) * 3
    with pytest.raises(vds.InvalidArgument, match="past its whole grid"):
        vds.Grid((0, 0, 0), (1, 2, 3), (2, 2, 2), first=(3, 3, 5), whole=(4, 5, 6))
    with pytest.raises(vds.InvalidArgument, match="needs whole"):
        vds.Grid((0, 0, 0), (1, 2, 3), (2, 2, 2), first=(1, 0, 0))
    with pytest.raises(vds.InvalidArgument, match="cell indices"):
        vds.Grid((0, 0, 0), (1, 2, 3), (2, 2, 2), first=(-1, 0, 0), whole=6)


@pytest.mark.parametrize("rule", ["parity", "generalized-winding"])
def test_occupancy_blocks_equal_the_whole_grid(client, sphere, rule):
    V, F = sphere
    if rule != "parity":  # an open cup: the generalized winding number's own sweep
        F = F[V[F].mean(axis=1)[:, 2] < 0.5]
    grid = grid_around(V, (37, 41, 45))
    expected = vds.occupancy(V, F, grid, rule=rule)
    assert 0.05 < expected.mean() < 0.6
    labels = vds.dask.occupancy((V, F), grid, chunks=(16, 20, 13), rule=rule)
    assert labels.shape == grid.shape and labels.dtype == bool and labels.numblocks == (3, 3, 4)
    assert np.array_equal(labels.compute(), expected)
    packed = vds.dask.occupancy((V, F), grid, chunks=(10, 41, 16), rule=rule, packed=True)
    assert packed.shape == (37, 41, 6) and packed.dtype == np.uint8
    assert np.array_equal(packed.compute(), np.packbits(expected, axis=2))


def test_sprite_and_method_occupancy_blocks_equal_the_whole_grid(client, sphere):
    V, F = sphere
    grid = grid_around(V, 40)
    sprite = vds.bake(V, F, resolution=48, method="cpu")
    got = vds.dask.occupancy(sprite, grid, chunks=(13, 17, 40)).compute()
    assert np.array_equal(got, sprite.occupancy(grid))
    got = vds.dask.occupancy((V, F), grid, chunks=(13, 17, 11), method="certified").compute()
    assert np.array_equal(got, vds.Classifier(V, F, "certified").occupancy(grid))


@pytest.mark.parametrize("band", [0.0, 0.08])
def test_sdf_blocks_equal_the_whole_grid(client, sphere, band):
    V, F = sphere
    grid = grid_around(V, (33, 30, 36), margin=0.4)
    expected = vds.sdf(V, F, grid, band=band)
    got = vds.dask.sdf((V, F), grid, band=band, chunks=(11, 10, 12))
    assert got.dtype == np.float32 and got.shape == grid.shape
    assert np.array_equal(got.compute(), expected)


@pytest.mark.parametrize("cup, rule", [(False, "parity"), (True, "generalized-winding")])
def test_far_sdf_blocks_are_filled_without_distances_and_still_equal(sphere, cup, rule):
    V, F = sphere
    if cup:
        F = F[V[F].mean(axis=1)[:, 2] < 0.5]
    grid = grid_around(V, 48, margin=0.8)
    band = 0.1
    expected = vds.sdf(V, F, grid, band=band, rule=rule)
    before = vds._dask_grids.far_blocks
    with dask.config.set(scheduler="threads"):  # in this process, where far_blocks counts
        got = vds.dask.sdf((V, F), grid, band=band, chunks=8, rule=rule).compute()
    assert np.array_equal(got, expected)
    far = vds._dask_grids.far_blocks - before
    assert 0 < far < 6 ** 3  # the blocks of the margin (all cells there at +-band), not those on the surface
    assert (np.abs(expected) == np.float32(band)).mean() > 0.5


def test_to_zarr_writes_the_grid_block_by_block(client, tmp_path):
    zarr = pytest.importorskip("zarr")
    V, F = icosphere(2)
    grid = grid_around(V, (40, 32, 48))
    packed = vds.dask.occupancy((V, F), grid, chunks=(16, 16, 24), packed=True)
    packed.to_zarr(str(tmp_path / "grid.zarr"))
    stored = zarr.open_array(str(tmp_path / "grid.zarr"), mode="r")
    assert stored.chunks == (16, 16, 3) and stored.dtype == np.uint8
    assert np.array_equal(np.unpackbits(stored[...], axis=2), vds.occupancy(V, F, grid))


def test_a_grid_past_one_vds_grid_is_lazy_and_right_where_computed(sphere):
    V, F = sphere
    lo, hi = (-1.5, -1.5, -1.5), (1.5, 1.5, 1.5)
    labels = vds.dask.occupancy((V, F), (lo, hi, 4096), chunks=(64, 64, 4096), packed=True)
    assert labels.shape == (4096, 4096, 512) and labels.numblocks == (64, 64, 1)
    with dask.config.set(scheduler="sync"):
        column = np.unpackbits(labels[2048, 2050].compute())
    # That column's cell centres, computed here as the Grid doc states them.
    step = 3.0 / 4096
    z = np.float32(-1.5 + (np.arange(4096) + 0.5) * step)
    centres = np.stack([np.full(4096, np.float32(-1.5 + 2048.5 * step)), np.full(4096, np.float32(-1.5 + 2050.5 * step)),
                        z], axis=1)
    assert np.array_equal(column.astype(bool), vds.exact_contains(V, F, centres))
    assert 0.6 < column.mean() < 0.7


def test_bad_grids_and_chunks_fail_at_the_call(sphere):
    V, F = sphere
    grid = grid_around(V, 32)
    with pytest.raises(vds.InvalidArgument, match="multiple of 8"):
        vds.dask.occupancy((V, F), grid, chunks=(16, 16, 12), packed=True)
    with pytest.raises(vds.InvalidArgument, match="band"):
        vds.dask.sdf((V, F), grid, band=-1.0)
    with pytest.raises(vds.InvalidArgument, match="needs a mesh"):
        vds.dask.sdf(vds.bake(V, F, resolution=32, method="cpu"), grid)
    with pytest.raises(vds.InvalidArgument, match="empty"):
        vds.dask.occupancy((V, F), ((0, 0, 0), (0, 1, 1), 8))
    with pytest.raises(vds.InvalidArgument, match="vds.Grid"):
        vds.dask.occupancy((V, F), "grid")
