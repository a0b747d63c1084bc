"""A slice of a signed distance grid as a PNG: vds.sdf over a 512 x 512 x 1
grid across the mesh's box at mid z, by the generalized winding number (open
meshes too); blue inside, orange outside, isolines every 1/40 of the box,
the surface black. numpy only (the PNG is written by hand).

    PYTHONPATH=build/python python3 samples/python/sdf_slice.py MESH OUT.png
"""
import struct
import sys
import zlib

import numpy as np

import vds

V, F = vds.load_mesh(sys.argv[1])
lo, hi = V.min(0), V.max(0)
pad = 0.08 * (hi - lo)
lo, hi = lo - pad, hi + pad
zmid = 0.5 * (lo[2] + hi[2])
n = 512
ext = max(hi[0] - lo[0], hi[1] - lo[1])
cx, cy = 0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])
eps = 1e-4 * ext
grid = vds.Grid((cx - ext / 2, cy - ext / 2, zmid - eps), (cx + ext / 2, cy + ext / 2, zmid + eps), (n, n, 1))
d = vds.sdf(V, F, grid, rule="generalized-winding")[:, :, 0].astype(np.float64)  # [i (x), j (y)]
img = d.T[::-1]  # rows top to bottom = y descending, columns = x
s = ext / 40.0   # isoline spacing
t = np.clip(np.abs(img) / (0.35 * ext), 0, 1)
inside = np.signbit(img)
r = np.where(inside, 0.15 + 0.25 * t, 0.98 - 0.25 * t)
g = np.where(inside, 0.35 + 0.35 * t, 0.65 - 0.25 * t)
b = np.where(inside, 0.85 - 0.2 * t, 0.25 + 0.1 * t)
band = np.abs(img / s - np.round(img / s)) < 0.06
shade = np.where(band, 0.75, 1.0)
zero = np.abs(img) < ext / 400.0
rgb = np.stack([r, g, b], -1) * shade[..., None]
rgb[zero] = 0.0
px = (np.clip(rgb, 0, 1) * 255).astype(np.uint8)
raw = b"".join(b"\x00" + row.tobytes() for row in px)


def chunk(t, data):
    return struct.pack(">I", len(data)) + t + data + struct.pack(">I", zlib.crc32(t + data) & 0xffffffff)


png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", n, n, 8, 2, 0, 0, 0)) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
open(sys.argv[2], "wb").write(png)
print(f"wrote {sys.argv[2]}: distances {d.min():.4f} .. {d.max():.4f}, {int(inside.sum())} pixels inside")
