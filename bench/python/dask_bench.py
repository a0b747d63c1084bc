#!/usr/bin/env python3
"""Points/s of vds.dask.contains on a LocalCluster of 1 and 2 worker processes,
against the same work in one process (sprite.contains on each chunk in turn).

Points are uniform in the mesh's box (5 % margin), float32, made chunk by chunk
where they are classified: on the workers (dask.array.random), never on the
client; the baseline makes its chunks the same way in its own process. Each
worker has one thread and classifies with one thread, as does the baseline,
so "1 worker" against "one process" is the overhead of Dask itself (graph,
scheduling, shipping the sprite, summing), and "2 workers" the scale-out.
Only the computations are timed, not starting the cluster. Run from the
repository root after building:

    PYTHONPATH=build/python python3 bench/python/dask_bench.py              # 10^9 points
    PYTHONPATH=build/python python3 bench/python/dask_bench.py --points 1e7 # a quick run
"""
import argparse
import pathlib
import time

import dask.array as da
import numpy as np
from distributed import Client, LocalCluster

import vds
import vds.dask

ROOT = pathlib.Path(__file__).resolve().parents[2]


def box_of(sprite):
    lo, hi = sprite.box
    margin = 0.05 * (hi - lo)
    return lo - margin, hi + margin


def single_process(sprite, n, chunk, seed, classify=True):
    lo, hi = box_of(sprite)
    inside = 0
    start = time.perf_counter()
    for k, first in enumerate(range(0, n, chunk)):
        unit = np.random.RandomState(seed + k).random_sample((min(chunk, n - first), 3))
        points = (lo + (hi - lo) * unit).astype(np.float32)
        if classify:
            inside += int(sprite.contains(points, threads=1).sum())
    return time.perf_counter() - start, inside


def on_cluster(sprite, n, chunk, seed, workers):
    lo, hi = box_of(sprite)
    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None,
                      worker_dashboard_address=None) as cluster, Client(cluster) as client:
        client.run(lambda: __import__("vds.dask"))  # imports done before the clock starts
        unit = da.random.RandomState(seed).random_sample(size=(n, 3), chunks=(chunk, 3))
        points = (lo + (hi - lo) * unit).astype(np.float32)
        # Warm up: the first task of a fresh worker pays for more than its work.
        vds.dask.contains(sprite, points[:1000], threads=1).sum().compute()
        start = time.perf_counter()
        inside = int(vds.dask.contains(sprite, points, threads=1).sum().compute())
        return time.perf_counter() - start, inside


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--points", type=float, default=1e9, help="points in all (default 1e9)")
    parser.add_argument("--chunk", type=int, default=1 << 22, help="points a chunk (default 4194304)")
    parser.add_argument("--mesh", default=str(ROOT / "samples" / "data" / "spot.obj"))
    parser.add_argument("--resolution", type=int, default=1024)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    n = int(args.points)

    V, F = vds.load_mesh(args.mesh)
    sprite = vds.bake(V, F, resolution=args.resolution, method="cpu", name=pathlib.Path(args.mesh).name)
    print(f"{pathlib.Path(args.mesh).name}: {sprite}, {n:.3g} points in chunks of {args.chunk}")
    print(f"{'run':<34} {'seconds':>9} {'M points/s':>11} {'inside':>8}  vs one process")
    generate, _ = single_process(sprite, n, args.chunk, args.seed, classify=False)
    base, inside = single_process(sprite, n, args.chunk, args.seed)
    rows = [("one process, 1 thread (baseline)", base, inside)]
    for workers in (1, 2):
        t, inside = on_cluster(sprite, n, args.chunk, args.seed, workers)
        rows.append((f"Dask, {workers} worker process{'es' if workers > 1 else ''} x 1 thread", t, inside))
    for name, t, inside in rows:
        print(f"{name:<34} {t:9.2f} {n / t / 1e6:11.1f} {inside / n:8.4f}  {t / base:5.2f}x the time")
    print(f"{'(making the points alone, 1 proc)':<34} {generate:9.2f} {n / generate / 1e6:11.1f}")
    print(f"Dask overhead, 1 worker vs one process: {100 * (rows[1][1] / base - 1):+.1f} %; "
          f"2 workers vs 1: {rows[1][1] / rows[2][1]:.2f}x faster")


if __name__ == "__main__":
    main()
