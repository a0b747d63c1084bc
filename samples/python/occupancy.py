#!/usr/bin/env python3
"""Occupancy labels for 10^7 points on Spot the cow, as for training an
implicit-surface network: uniform points in the box, one bool each.

    PYTHONPATH=build/python python3 samples/python/occupancy.py [--points N] [--gpu]
"""
import argparse
import pathlib
import time

import numpy as np

import vds

parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
parser.add_argument("--points", type=float, default=1e7)
parser.add_argument("--gpu", action="store_true", help="classify on the GL compute shader")
args = parser.parse_args()
mesh = pathlib.Path(__file__).resolve().parents[1] / "data" / "spot.obj"

start = time.perf_counter()
V, F = vds.load_mesh(mesh)                                # (n, 3) float64, (m, 3) int32
sprite = vds.bake(V, F, resolution=1024, method="cpu")    # once per mesh; sprite.save("spot.vds") to keep it
baked = time.perf_counter()
lo, hi = V.min(axis=0), V.max(axis=0)
points = np.random.default_rng(0).uniform(lo, hi, (int(args.points), 3)).astype(np.float32)
made = time.perf_counter()
occupancy = sprite.contains(points, gpu=args.gpu)         # (N,) bool; trimesh: mesh.contains(points)
done = time.perf_counter()

print(f"{mesh.name}: {len(F)} triangles, {sprite}")
print(f"baked in {baked - start:.2f} s; {len(points):.3g} points labelled in {done - made:.3f} s "
      f"({len(points) / (done - made) / 1e6:.1f} M points/s{', GPU' if args.gpu else ''}); "
      f"{occupancy.mean():.1%} inside")
