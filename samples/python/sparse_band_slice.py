"""A slice of a sparse narrow band as a PNG: vds.write_vdb writes the band of
a mesh (cubic cells, N along the box's longest side, +-3 cells) as an
OpenVDB level set, pyopenvdb (Debian's python3-openvdb) reads it back, and
the slice at mid z shows what the file holds: the band cells (blue inside,
orange outside, darker nearer the surface), the 8^3 blocks that hold them
(grey), tiles inside (pale blue) and nothing outside (white).

    PYTHONPATH=build/python python3 samples/python/sparse_band_slice.py MESH OUT.png [N]
"""
import os
import struct
import sys
import tempfile
import zlib

import numpy as np
import pyopenvdb

import vds

V, F = vds.load_mesh(sys.argv[1])
n = int(sys.argv[3]) if len(sys.argv) > 3 else 512
h = float((V.max(0) - V.min(0)).max()) / n
band = 3 * h
with tempfile.TemporaryDirectory() as folder:
    path = os.path.join(folder, "band.vdb")
    stored = vds.write_vdb(path, V, F, voxel_size=h, band=band, rule="generalized-winding")
    level = pyopenvdb.read(path, "sdf")
(i0, j0, k0), (i1, j1, k1) = level.evalActiveVoxelBoundingBox()
k = (k0 + k1) // 2
values = np.empty((i1 + 1, j1 + 1, 1), np.float32)
level.copyToArray(values, ijk=(0, 0, k))
d = values[:, :, 0].T[::-1]  # rows top to bottom = y descending, columns = x
in_band = np.abs(d) < np.float32(band)
rows, cols = d.shape
# The 8^3 blocks that hold a band cell of this slice (the leaves the file keeps).
blocks = np.zeros(((rows + 7) // 8 * 8, (cols + 7) // 8 * 8), bool)
blocks[:rows, :cols] = in_band
blocks = blocks.reshape(blocks.shape[0] // 8, 8, blocks.shape[1] // 8, 8).any(axis=(1, 3))
leaf = np.repeat(np.repeat(blocks, 8, 0), 8, 1)[:rows, :cols]
rgb = np.ones(d.shape + (3,))
rgb[np.signbit(d) & ~leaf] = (0.80, 0.87, 0.97)
rgb[leaf] = (0.86, 0.86, 0.86)
edge = np.zeros_like(leaf)
edge[::8, :] = edge[:, ::8] = True
rgb[leaf & edge] = (0.62, 0.62, 0.62)
t = np.clip(np.abs(d) / band, 0, 1)[..., None]
inside_colour = np.array([0.10, 0.25, 0.75]) * (1 - t) + np.array([0.55, 0.70, 0.95]) * t
outside_colour = np.array([0.85, 0.35, 0.05]) * (1 - t) + np.array([0.98, 0.75, 0.50]) * t
colour = np.where(np.signbit(d)[..., None], inside_colour, outside_colour)
rgb[in_band] = colour[in_band]
pixels = (rgb * 255).astype(np.uint8)
scanlines = b"".join(b"\x00" + row.tobytes() for row in pixels)
parts = [(b"IHDR", struct.pack(">IIBBBBB", cols, rows, 8, 2, 0, 0, 0)), (b"IDAT", zlib.compress(scanlines, 9)),
         (b"IEND", b"")]
with open(sys.argv[2], "wb") as out:
    out.write(b"\x89PNG\r\n\x1a\n")
    for kind, data in parts:
        out.write(struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
print(f"wrote {sys.argv[2]}: slice z = {k} of a {level.evalActiveVoxelDim()} band, {stored} band cells in the file; "
      f"this slice: {int(in_band.sum())} band cells in {int(blocks.sum())} blocks of {rows * cols} cells")
