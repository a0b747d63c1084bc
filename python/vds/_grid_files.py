"""Grid files: a grid's values and its geometry in one numpy .npz, the file
``vds sdf -o SDF.npz`` and ``vds voxelize -o GRID.npz`` write (docs/format.md,
"Grid files"), so the command line's grids and vds.sdf / vds.occupancy's
arrays travel the same way."""
import os
import tempfile

import numpy as np

from ._vds import DTypeError, FormatError, Grid, InvalidArgument, IoError, __version__

_KINDS = ("occupancy", "sdf", "band")
_RULES = ("parity", "winding", "generalized-winding")
_GEOMETRY = ("values", "lo", "hi", "dims")


def _member(f, name, path):
    if name not in f.files:
        raise FormatError(f"{path}: not a vds grid file: no member '{name}' (members: {', '.join(f.files)})")
    return f[name]


def _grid_of(f, path):
    lo, hi, dims = (_member(f, name, path) for name in ("lo", "hi", "dims"))
    if lo.shape != (3,) or hi.shape != (3,) or dims.shape != (3,) or dims.dtype.kind not in "iu":
        raise FormatError(f"{path}: lo, hi and dims must be 3 numbers each, dims integers")
    try:
        return Grid(lo, hi, tuple(int(n) for n in dims))
    except InvalidArgument as e:
        raise FormatError(f"{path}: {e}") from None


def load_grid(path, unpack=True):
    """Reads a grid file: ``(values, grid)``, the array and its vds.Grid.

    path: a .npz as ``vds sdf -o SDF.npz``, ``vds voxelize -o GRID.npz`` or
    ``vds.save_grid`` write it. values: float32 distances (kind "sdf" or
    "band") or bool occupancy of grid.shape, [i, j, k] the value at cell
    (i, j, k)'s centre, grid.cell_centres(); a packed occupancy (``vds
    voxelize --packed``) is unpacked unless unpack=False, which returns its
    (nx, ny, ceil(nz / 8)) uint8 rows. The rest of the file (kind, rule,
    band, version) reads with ``np.load(path)``. Raises vds.IoError where the
    file cannot be read, vds.FormatError where it is not a grid file.
    """
    try:
        f = np.load(path, allow_pickle=False)
    except OSError as e:
        raise IoError(f"{os.fspath(path)}: cannot read: {e.strerror or e}") from None
    except ValueError as e:
        raise FormatError(f"{os.fspath(path)}: not a grid file: {e}") from None
    if not isinstance(f, np.lib.npyio.NpzFile):
        raise FormatError(f"{os.fspath(path)}: not a grid file (.npz): a single array")
    with f:
        grid = _grid_of(f, path)
        values = _member(f, "values", path)
        packed = bool(f["packed"]) if "packed" in f.files else False
    nx, ny, nz = grid.shape
    shape = (nx, ny, (nz + 7) // 8) if packed else grid.shape
    if values.shape != shape:
        raise FormatError(f"{os.fspath(path)}: values of shape {values.shape}, not the grid's {shape}")
    if packed and unpack:
        values = np.unpackbits(values, axis=-1, count=nz).astype(bool)
    return values, grid


def _kind_of(values, kind, band):
    if kind is None:
        kind = "occupancy" if values.dtype == np.bool_ else ("band" if band else "sdf")
    if kind not in _KINDS:
        raise InvalidArgument(f"kind must be one of {', '.join(_KINDS)}, not {kind!r}")
    if (kind == "band") != (band is not None):
        raise InvalidArgument("band: the band's half-width, given exactly for kind 'band'")
    return kind


def save_grid(path, values, grid, rule="parity", kind=None, band=None):
    """Writes ``values`` with ``grid``'s geometry as a grid file, the .npz
    ``load_grid`` reads and ``vds sdf`` / ``vds voxelize`` write.

    values: an array of grid.shape (vds.sdf's float32, vds.occupancy's bool);
    grid: a whole vds.Grid (not a block); rule: the rule the values were made
    by; kind: "occupancy", "sdf" or "band" (default: occupancy for bool
    values, else "band" when band is given, else "sdf"); band: the band's
    half-width for kind "band". Written to a temporary file beside path and
    renamed into place once whole. Raises vds.InvalidArgument, vds.DTypeError.
    """
    if not isinstance(grid, Grid):
        raise DTypeError(f"grid must be a vds.Grid, not {type(grid).__name__}")
    if grid.whole is not None:
        raise InvalidArgument("save_grid: grid is a block of a larger grid: save the whole grid")
    values = np.ascontiguousarray(values)
    if values.shape != grid.shape:
        raise InvalidArgument(f"save_grid: values of shape {values.shape}, not the grid's {grid.shape}")
    kind = _kind_of(values, kind, band)
    if rule not in _RULES:
        raise InvalidArgument(f"rule must be one of {', '.join(_RULES)}, not {rule!r}")
    lo, hi = np.array(grid.lo, np.float64), np.array(grid.hi, np.float64)
    dims = np.array(grid.dims, np.int64)
    members = dict(values=values, lo=lo, hi=hi, dims=dims, spacing=(hi - lo) / dims, kind=np.array(kind),
                   rule=np.array(rule), version=np.array(__version__))
    if kind == "band":
        members["band"] = np.array(float(band))
    if kind == "occupancy":
        members["packed"] = np.array(False)
    path = os.fspath(path)
    try:
        fd, temporary = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(path)), prefix=".vds-grid-", suffix=".npz")
    except OSError as e:
        raise IoError(f"{path}: cannot write: {e.strerror or e}") from None
    try:
        with os.fdopen(fd, "wb") as out:
            np.savez(out, **members)  # stored, uncompressed, as the command line writes it
        os.replace(temporary, path)
    except BaseException:
        os.unlink(temporary)
        raise
