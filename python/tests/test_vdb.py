"""vds.write_vdb read back with pyopenvdb (Debian's python3-openvdb): the
level set holds vds.sdf's band value in every cell, its band cells active,
class level set, background the half-width, voxel centres on the cell
centres and the metadata; occupancy holds vds.occupancy's labels. Skipped
where pyopenvdb is not importable; in a build without OpenVDB, write_vdb
must refuse in one line."""
import numpy as np
import pytest

import vds
from conftest import sphere_mesh

needs_vdb = pytest.mark.skipif(not vds.vdb_available(), reason="this vds was built without OpenVDB")


def _read(path, name):
    openvdb = pytest.importorskip("pyopenvdb")
    return openvdb.read(str(path), name)


@needs_vdb
def test_a_level_set_holds_the_dense_band(tmp_path):
    V, F = sphere_mesh(radius=1.0, segments=48, rings=24)
    grid = vds.Grid.cubic((-1.3, -1.25, -1.2), (1.3, 1.2, 1.25), 44)
    cell = (grid.hi[0] - grid.lo[0]) / grid.dims[0]
    band = 2.5 * cell
    written = vds.write_vdb(str(tmp_path / "s.vdb"), V, F, grid, band=band, source="sphere")
    dense = vds.sdf(V, F, grid, band=band)
    level = _read(tmp_path / "s.vdb", "sdf")
    assert level.gridClass == "level set"
    assert level.background == np.float32(band)
    assert level["rule"] == "parity" and level["source"] == "sphere" and level["vds_version"] == vds.__version__
    values = np.full(grid.shape, np.nan, np.float32)
    level.copyToArray(values, ijk=(0, 0, 0))
    np.testing.assert_array_equal(values, dense)
    assert np.array_equal(np.signbit(values), np.signbit(dense))
    in_band = int((np.abs(dense) < np.float32(band)).sum())
    assert written == level.activeVoxelCount() == in_band > 0
    centres = grid.cell_centres().reshape(grid.shape + (3,))
    for ijk in [(0, 0, 0), (7, 30, 12), tuple(d - 1 for d in grid.dims)]:
        np.testing.assert_allclose(level.transform.indexToWorld(ijk), centres[ijk], atol=1e-6)


@needs_vdb
def test_a_band_by_voxel_size_needs_no_dense_grid(tmp_path):
    V, F = sphere_mesh(radius=1.0, segments=24, rings=12)
    written = vds.write_vdb(str(tmp_path / "s.vdb"), V, F, voxel_size=0.01, band=0.02)
    level = _read(tmp_path / "s.vdb", "sdf")
    assert written == level.activeVoxelCount() > 4 * np.pi * 100 ** 2  # four layers of a sphere 100 cells round
    assert level.transform.voxelSize()[0] == pytest.approx(0.01, rel=1e-6)


@needs_vdb
def test_occupancy_holds_the_labels(tmp_path):
    V, F = sphere_mesh(radius=1.0, segments=32, rings=16)
    grid = vds.Grid((-1.1, -1.1, -1.1), (1.1, 1.1, 1.1), 40)
    inside = vds.write_vdb(str(tmp_path / "o.vdb"), V, F, grid, occupancy=True, rule="winding")
    labels = vds.occupancy(V, F, grid, "winding")
    occupancy = _read(tmp_path / "o.vdb", "occupancy")
    assert occupancy["rule"] == "winding"
    got = np.zeros(grid.shape, bool)
    occupancy.copyToArray(got, ijk=(0, 0, 0))
    np.testing.assert_array_equal(got, labels)
    assert inside == occupancy.activeVoxelCount() == labels.sum()


@needs_vdb
def test_an_open_mesh_by_parity_warns_as_sdf_does(tmp_path):
    V, F = sphere_mesh(radius=1.0, segments=16, rings=8)
    F = F[1:]  # one triangle fewer: open
    with pytest.warns(vds.MeshWarning, match="open"):
        vds.write_vdb(str(tmp_path / "o.vdb"), V, F, voxel_size=0.1, band=0.2)
    with pytest.warns(vds.MeshWarning, match="open"):
        vds.sdf(V, F, vds.Grid((-1.1, -1.1, -1.1), (1.1, 1.1, 1.1), 8), band=0.2)


def test_bad_requests_are_refused_in_one_line(tmp_path):
    V, F = sphere_mesh(radius=1.0, segments=12, rings=6)
    grid = vds.Grid((-1.1, -1.1, -1.1), (1.1, 1.1, 1.1), 8)
    path = str(tmp_path / "x.vdb")
    calls = [dict(grid=grid), dict(grid=grid, band=0.0), dict(grid=grid, band=0.1, occupancy=True),
             dict(band=0.1), dict(grid=grid, voxel_size=0.1, band=0.1)]
    for kwargs in calls:
        with pytest.raises(vds.InvalidArgument) as error:
            vds.write_vdb(path, V, F, **kwargs)
        assert "\n" not in str(error.value)
        if not vds.vdb_available():
            assert "without OpenVDB" in str(error.value)
    assert not list(tmp_path.iterdir())
