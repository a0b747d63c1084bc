"""Grid files: `vds sdf` / `vds voxelize -o GRID.npz` and vds.save_grid /
vds.load_grid, read back by numpy's own reader (np.load, zipfile), their
values checked against the .npy output byte for byte and their geometry
against the summary line and vds.Grid's cell centres."""
import os
import re
import subprocess
import zipfile

import numpy as np
import pytest

import vds
from conftest import sphere_mesh

TOOL = os.environ.get("VDS_TOOL")
needs_tool = pytest.mark.skipif(not (TOOL and os.path.exists(TOOL)), reason="VDS_TOOL (the vds command line) not given or not built")
DIMS = (13, 11, 9)


@pytest.fixture
def sphere(tmp_path):
    """A sphere's OBJ and (V, F) as the command line reads them."""
    V, F = sphere_mesh(0.9, (0.1, 0.2, 0.3), segments=24, rings=12)
    path = tmp_path / "sphere.obj"
    with open(path, "w") as out:
        out.writelines("v %.17g %.17g %.17g\n" % tuple(v) for v in V)
        out.writelines("f %d %d %d\n" % tuple(t + 1) for t in F)
    return (path, *vds.load_mesh(path))


def tool(*args):
    return subprocess.run([TOOL, *map(str, args)], capture_output=True, text=True)


def write(command, mesh, output, *extra):
    """Runs `vds COMMAND MESH --dims-xyz 13 11 9 -o OUTPUT EXTRA...`; its summary line."""
    r = tool(command, mesh, "--dims-xyz", *DIMS, "-o", output, "--quiet", *extra)
    assert r.returncode == 0, r.stderr
    return r.stdout


def summary_geometry(line):
    """lo, hi and the cells' size as the summary line prints them."""
    m = re.search(r"box \[([^\]]*)\] to \[([^\]]*)\], cells (\S+) x (\S+) x (\S+),", line)
    assert m, line
    return ([float(x) for x in m.group(1).split(",")], [float(x) for x in m.group(2).split(",")],
            [float(m.group(i)) for i in (3, 4, 5)])


def check_file(npz, npy, line, kind):
    """The .npz's values member is the .npy file byte for byte; its geometry
    the summary line's; numpy reads it without pickle. Its members."""
    with zipfile.ZipFile(npz) as z:
        assert z.testzip() is None  # every CRC-32 right
        assert z.read("values.npy") == npy.read_bytes()
    lo, hi, cells = summary_geometry(line)
    with np.load(npz, allow_pickle=False) as f:
        assert f["lo"].dtype == np.float64 and f["hi"].dtype == np.float64 and f["dims"].dtype == np.int64
        assert f["lo"].tolist() == np.float32(lo).tolist() and f["hi"].tolist() == np.float32(hi).tolist()
        assert f["dims"].tolist() == list(DIMS)
        assert f["spacing"].tolist() == ((f["hi"] - f["lo"]) / f["dims"]).tolist()
        np.testing.assert_allclose(f["spacing"], cells, rtol=1e-6)
        assert str(f["kind"]) == kind and str(f["rule"]) == "parity" and str(f["version"]) == vds.__version__
        return {name: f[name] for name in f.files}


@needs_tool
@pytest.mark.parametrize("packed", [False, True])
def test_voxelize_npz_is_the_npy_with_its_geometry(sphere, tmp_path, packed):
    mesh, V, F = sphere
    extra = ["--packed"] if packed else []
    write("voxelize", mesh, tmp_path / "g.npy", *extra)
    line = write("voxelize", mesh, tmp_path / "g.npz", *extra)
    members = check_file(tmp_path / "g.npz", tmp_path / "g.npy", line, "occupancy")
    assert bool(members["packed"]) == packed and "band" not in members
    cells, grid = vds.load_grid(tmp_path / "g.npz")
    assert grid.dims == DIMS and grid.lo == tuple(members["lo"]) and grid.hi == tuple(members["hi"])
    expected = vds.occupancy(V, F, grid)  # the library's labels of vds.Grid's cell centres
    assert 0 < expected.sum() < expected.size
    assert cells.dtype == np.bool_ and np.array_equal(cells, expected)
    if packed:
        rows, _ = vds.load_grid(tmp_path / "g.npz", unpack=False)
        assert np.array_equal(rows, np.packbits(expected, axis=-1))


@needs_tool
@pytest.mark.parametrize("band", [None, 0.2])
def test_sdf_npz_is_the_npy_with_its_geometry(sphere, tmp_path, band):
    mesh, V, F = sphere
    extra = ["--band", band] if band else []
    write("sdf", mesh, tmp_path / "s.npy", *extra)
    line = write("sdf", mesh, tmp_path / "s.npz", *extra)
    members = check_file(tmp_path / "s.npz", tmp_path / "s.npy", line, "band" if band else "sdf")
    assert ("band" in members) == bool(band) and "packed" not in members
    if band:
        assert members["band"].shape == () and float(members["band"]) == band
    values, grid = vds.load_grid(tmp_path / "s.npz")
    assert values.dtype == np.float32 and np.array_equal(values, vds.sdf(V, F, grid, band=band or 0.0))


@needs_tool
def test_slabs_and_zip64_change_nothing_numpy_reads(sphere, tmp_path):
    mesh = sphere[0]
    for command in ("voxelize", "sdf"):
        write(command, mesh, tmp_path / "whole.npz")
        write(command, mesh, tmp_path / "slabs.npz", "--slab-cells", 1)  # one x layer a slab: 13 slabs
        assert (tmp_path / "slabs.npz").read_bytes() == (tmp_path / "whole.npz").read_bytes()
        assert b"PK\x06\x06" not in (tmp_path / "whole.npz").read_bytes()  # small: no ZIP64 record
        with np.load(tmp_path / "whole.npz") as f:
            plain = {name: f[name] for name in f.files}
        # From 0: every size and offset ZIP64; from 150 and 600: the offsets past the first members, then the values' size too.
        for above in (0, 150, 600):
            write(command, mesh, tmp_path / "wide.npz", "--slab-cells", 100, "--zip64-above", above)
            data = (tmp_path / "wide.npz").read_bytes()
            assert b"PK\x06\x06" in data and b"PK\x06\x07" in data, above  # the ZIP64 end record and its locator
            with zipfile.ZipFile(tmp_path / "wide.npz") as z:
                assert z.testzip() is None
            with np.load(tmp_path / "wide.npz", allow_pickle=False) as f:
                assert sorted(f.files) == sorted(plain)
                for name in f.files:
                    assert np.array_equal(f[name], plain[name]), (command, above, name)


@needs_tool
def test_bad_grid_outputs_leave_nothing(sphere, tmp_path):
    mesh = sphere[0]
    before = sorted(os.listdir(tmp_path))
    for command in ("voxelize", "sdf"):
        r = tool(command, mesh, "--dims", 8, "-o", tmp_path / "missing" / "g.npz")
        assert r.returncode == 1 and len(r.stderr.strip().splitlines()) == 1, r.stderr
        assert "missing/g.npz" in r.stderr
    r = tool("sdf", mesh, "--dims", 8, "-o", tmp_path / "g.vdb")  # a .vdb is a band: the dense forms named
    assert r.returncode == 2 and ".npz" in r.stderr, r.stderr
    r = tool("voxelize", mesh, "--dims", 8, "-o", tmp_path / "g.npz", "--zip64-above", -1)
    assert r.returncode == 2, r.stderr
    assert sorted(os.listdir(tmp_path)) == before
    # "-" is the .npy: the stream it writes numpy reads as one array.
    r = subprocess.run([TOOL, "voxelize", str(mesh), "--dims", "8", "-o", "-", "--quiet"], capture_output=True)
    assert r.returncode == 0 and r.stdout.startswith(b"\x93NUMPY")


def test_save_grid_writes_what_load_grid_and_numpy_read(tmp_path):
    V, F = sphere_mesh(1.0)
    grid = vds.Grid((-1.1, -1.2, -1.3), (1.3, 1.2, 1.1), (9, 8, 7))
    cells, distances = vds.occupancy(V, F, grid), vds.sdf(V, F, grid, band=0.25)
    vds.save_grid(tmp_path / "cells.npz", cells, grid)
    vds.save_grid(tmp_path / "band.npz", distances, grid, band=0.25)
    for name, values, kind in (("cells.npz", cells, "occupancy"), ("band.npz", distances, "band")):
        with np.load(tmp_path / name, allow_pickle=False) as f:
            assert str(f["kind"]) == kind and f["dims"].tolist() == [9, 8, 7]
            assert f["lo"].tolist() == list(np.float32([-1.1, -1.2, -1.3]))
            assert np.array_equal(f["values"], values)
        loaded, again = vds.load_grid(tmp_path / name)
        assert np.array_equal(loaded, values) and loaded.dtype == values.dtype
        assert (again.lo, again.hi, again.dims) == (grid.lo, grid.hi, grid.dims)
        assert np.array_equal(again.cell_centres(), grid.cell_centres())


def test_grid_files_refuse_what_they_cannot_hold(tmp_path):
    grid = vds.Grid((0, 0, 0), (1, 1, 1), 4)
    cells = np.zeros(grid.shape, bool)
    with pytest.raises(vds.InvalidArgument, match="shape"):
        vds.save_grid(tmp_path / "g.npz", cells[:3], grid)
    with pytest.raises(vds.InvalidArgument, match="block"):
        vds.save_grid(tmp_path / "g.npz", cells[:2], vds.Grid((0, 0, 0), (1, 1, 1), (2, 4, 4), first=(2, 0, 0), whole=(4, 4, 4)))
    with pytest.raises(vds.InvalidArgument, match="rule"):
        vds.save_grid(tmp_path / "g.npz", cells, grid, rule="majority")
    with pytest.raises(vds.IoError):
        vds.save_grid(tmp_path / "missing" / "g.npz", cells, grid)
    with pytest.raises(vds.IoError):
        vds.load_grid(tmp_path / "none.npz")
    np.save(tmp_path / "plain.npy", cells)
    with pytest.raises(vds.FormatError, match="single array"):
        vds.load_grid(tmp_path / "plain.npy")
    np.savez(tmp_path / "other.npz", values=cells)
    with pytest.raises(vds.FormatError, match="no member 'lo'"):
        vds.load_grid(tmp_path / "other.npz")
    assert sorted(os.listdir(tmp_path)) == ["other.npz", "plain.npy"]  # no temporary file left
