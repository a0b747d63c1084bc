#!/usr/bin/env python3
"""vds.dask past one machine: grids into Zarr, points from a memory-mapped
.npy, and a dataset of many meshes, on a LocalCluster of worker processes
against the same work in one process. Prints the commit and the machine.

The mesh is a bumpy sphere made here (--triangles, 200k by default: the
figures ask for 100k or more), so the run needs no download. Each worker has
one thread and each task uses one; the one-process baselines use every core.
Peak memory is the largest sum, sampled every 50 ms, of the resident memory
of this process (the client) and every worker process. Run from the
repository root after building:

    PYTHONPATH=build/python python3 bench/dask/dask_bench.py grid --dims 1024 --reference 512
    PYTHONPATH=build/python python3 bench/dask/dask_bench.py sdf --dims 512 --band-cells 3
    PYTHONPATH=build/python python3 bench/dask/dask_bench.py points --points 1e8
    PYTHONPATH=build/python python3 bench/dask/dask_bench.py dataset --meshes 20 --samples 1e5
    PYTHONPATH=build/python python3 bench/dask/dask_bench.py scaling --workers 1,2,4,8,16
    PYTHONPATH=build/python python3 bench/dask/dask_bench.py cli --dims 4096
"""
import argparse
import os
import pathlib
import platform
import shutil
import subprocess
import tempfile
import threading
import time

import dask
import dask.array as da
import numpy as np
import psutil
from distributed import Client, LocalCluster

import vds
import vds.dask

ROOT = pathlib.Path(__file__).resolve().parents[2]


def bumpy_sphere(triangles, seed=0):
    """A closed, outward UV sphere of about `triangles` triangles, its radius
    rippled (1 +- 0.1) so that no axis sees a plain sphere."""
    rings = max(4, int(round((triangles / 4) ** 0.5)))
    segments = 2 * rings
    theta = np.pi * np.arange(1, rings) / rings
    phi = 2 * np.pi * np.arange(segments) / segments
    t, p = np.meshgrid(theta, phi, indexing="ij")
    r = 1 + 0.1 * np.sin(5 * t + seed) * np.sin(4 * p)
    ring = np.stack([r * np.sin(t) * np.cos(p), r * np.sin(t) * np.sin(p), r * np.cos(t)], axis=-1).reshape(-1, 3)
    V = np.vstack([[0, 0, 1], ring, [0, 0, -1]])
    at = lambda i, s: 1 + i * segments + s % segments  # noqa: E731
    F = []
    for s in range(segments):
        F += [[0, at(0, s), at(0, s + 1)], [len(V) - 1, at(rings - 2, s + 1), at(rings - 2, s)]]
        for i in range(rings - 2):
            F += [[at(i, s), at(i + 1, s), at(i + 1, s + 1)], [at(i, s), at(i + 1, s + 1), at(i, s + 1)]]
    return V, np.array(F, dtype=np.int32)


def header(args):
    commit = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip() or "unknown"
    cpu = next((line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo") if line.startswith("model name")), "")
    print(f"vds.dask bench: commit {commit}, {platform.node()}: {os.cpu_count()} cores ({cpu}), "
          f"{psutil.virtual_memory().total / 2**30:.0f} GiB, load {os.getloadavg()[0]:.1f}; {args}")


class PeakMemory:
    """The largest summed resident memory of this process and `pids`, and the
    CPU seconds they used meanwhile (their sum over the wall time: the cores
    the work had, which on a shared machine may be fewer than it asked for)."""

    def __init__(self, pids=()):
        self.processes = [psutil.Process()] + [psutil.Process(p) for p in pids]
        self.peak, self.done = 0, threading.Event()
        self.thread = threading.Thread(target=self._sample, daemon=True)
        self.cpu = 0.0

    def _cpu_seconds(self):
        total = 0.0
        for p in self.processes:
            try:
                t = p.cpu_times()
                total += t.user + t.system + t.children_user + t.children_system
            except psutil.Error:
                pass
        return total

    def _sample(self):
        while not self.done.wait(0.05):
            total = 0
            for p in self.processes:
                try:
                    total += p.memory_info().rss
                except psutil.Error:
                    pass
            self.peak = max(self.peak, total)

    def __enter__(self):
        self.cpu = -self._cpu_seconds()
        self.thread.start()
        return self

    def __exit__(self, *exc):
        self.cpu += self._cpu_seconds()
        self.done.set()
        self.thread.join()


def cluster(workers):
    c = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None,
                     worker_dashboard_address=None)
    return c, Client(c)


def timed(label, cells, work, pids=(), unit=("M/s", 1e-6)):
    with PeakMemory(pids) as memory:
        start = time.perf_counter()
        work()
        seconds = time.perf_counter() - start
    print(f"  {label:<48} {seconds:9.2f} s {cells / seconds * unit[1]:10.1f} {unit[0]} {memory.peak / 2**30:7.2f} GiB "
          f"cpu {memory.cpu:8.1f} s = {memory.cpu / seconds:4.2f} cores, load {os.getloadavg()[0]:.1f}", flush=True)
    return cells / seconds


def grid_of(V, n):
    """(lo, hi, n^3 cells) around the mesh: a grid of any size for vds.dask."""
    lo, hi = V.min(0), V.max(0)
    return tuple(lo - 0.05 * (hi - lo)), tuple(hi + 0.05 * (hi - lo)), (n, n, n)


def run_grid(args, V, F):
    reference = vds.Grid(*grid_of(V, args.reference))
    rate = timed(f"in memory, vds.occupancy {args.reference}^3, {os.cpu_count()} threads", reference.cell_count,
                 lambda: vds.occupancy(V, F, reference))
    big = grid_of(V, args.dims)
    store = tempfile.mkdtemp(prefix="vds-grid-", dir=args.scratch)
    c, client = cluster(args.workers)
    with c, client:
        pids = client.run(os.getpid).values()
        packed = vds.dask.occupancy((V, F), big, packed=True)
        dask_rate = timed(f"vds.dask packed {args.dims}^3 -> Zarr, {args.workers} workers ({packed.numblocks} blocks)",
                          args.dims ** 3, lambda: packed.to_zarr(store, overwrite=True), pids)
    print(f"  ratio to the in-memory rate: {dask_rate / rate:.2f}")
    shutil.rmtree(store)


def run_sdf(args, V, F):
    grid = grid_of(V, args.dims)
    band = args.band_cells * float(np.max((np.array(grid[1]) - grid[0]) / args.dims))
    store = tempfile.mkdtemp(prefix="vds-sdf-", dir=args.scratch)
    if args.dims <= args.reference:
        timed(f"in memory, vds.sdf {args.dims}^3 band {args.band_cells} cells", args.dims ** 3,
              lambda: vds.sdf(V, F, vds.Grid(*grid), band=band))
    c, client = cluster(args.workers)
    with c, client:
        pids = client.run(os.getpid).values()
        sdf = vds.dask.sdf((V, F), grid, band=band)
        timed(f"vds.dask sdf {args.dims}^3 band {args.band_cells} cells -> Zarr, {args.workers} workers",
              args.dims ** 3, lambda: sdf.to_zarr(store, overwrite=True), pids)
    shutil.rmtree(store)


class NpyRows:
    """A memory-mapped .npy as dask reads it: pickled as its path, opened on
    whichever process reads a slice."""

    def __init__(self, path):
        self.path = path
        array = np.load(path, mmap_mode="r")
        self.shape, self.dtype, self.ndim = array.shape, array.dtype, array.ndim

    def __getitem__(self, index):
        return np.load(self.path, mmap_mode="r")[index]


def run_points(args, V, F):
    n = int(args.points)
    path = os.path.join(tempfile.mkdtemp(prefix="vds-points-", dir=args.scratch), "points.npy")
    out = np.lib.format.open_memmap(path, mode="w+", dtype=np.float32, shape=(n, 3))
    lo, hi = V.min(0) * 1.05, V.max(0) * 1.05
    for first in range(0, n, args.chunk):
        rows = min(args.chunk, n - first)
        out[first:first + rows] = lo + (hi - lo) * np.random.default_rng(first).random((rows, 3))
    del out
    sprite = vds.bake(V, F, resolution=1024, method="cpu")
    points = da.from_array(NpyRows(path), chunks=(args.chunk, 3), asarray=False)
    # What a chunk costs without a question: read from the .npy, a task scheduled, one number back.
    empty = lambda: points.map_blocks(lambda b: np.zeros(len(b), bool), drop_axis=1, dtype=bool).sum().compute()  # noqa: E731
    with dask.config.set(scheduler="sync"):
        timed(f"no question: one process ({points.numblocks[0]} chunks)", n, empty)
    c, client = cluster(args.workers)
    with c, client:
        timed(f"no question: {args.workers} worker processes", n, empty, client.run(os.getpid).values())
    for name, source, method in [(m, sprite if m == "sprite" else (V, F), m) for m in args.methods.split(",")]:
        with dask.config.set(scheduler="sync"):  # one process, one chunk at a time
            vds.dask.classify(source, points[:1000], method=method).sum().compute()  # warm, as the workers
            base = timed(f"{name}: one process, 1 thread a chunk", n,
                         lambda: vds.dask.classify(source, points, method=method).sum().compute())
        c, client = cluster(args.workers)
        with c, client:
            pids = client.run(os.getpid).values()
            vds.dask.classify(source, points[:1000], method=method).sum().compute()  # warm: the index built
            rate = timed(f"{name}: {args.workers} worker processes", n,
                         lambda: vds.dask.classify(source, points, method=method).sum().compute(), pids)
        print(f"  {name}: {rate / base:.2f}x one process")
    shutil.rmtree(os.path.dirname(path))


def run_dataset(args, V, F):
    folder = tempfile.mkdtemp(prefix="vds-meshes-", dir=args.scratch)
    paths = []
    for k in range(args.meshes):
        Vk, Fk = bumpy_sphere(args.mesh_triangles, seed=k)
        paths.append(os.path.join(folder, f"mesh{k:04d}.obj"))
        with open(paths[-1], "w") as f:
            f.writelines(f"v {x:.9g} {y:.9g} {z:.9g}\n" for x, y, z in Vk)
            f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in Fk)
    n = int(args.samples)
    rates = {}
    rows = (("a plain loop in one process", 0, 1), ("a plain loop, threads=0 (every core)", 0, 0),
            (f"{args.workers} worker processes", args.workers, 1))
    for label, workers, threads in rows:
        store = os.path.join(folder, f"store{workers}-{threads}.zarr")
        run = lambda: vds.dask.dataset(paths, store, uniform=n, near_surface=n, threads=threads)  # noqa: E731
        if workers == 0:
            with dask.config.set(scheduler="sync"):
                rate = timed(f"dataset, {label}", args.meshes * 60, run, unit=("meshes/min", 1))
        else:
            c, client = cluster(workers)
            with c, client:
                rate = timed(f"dataset, {label}", args.meshes * 60, run, client.run(os.getpid).values(),
                             unit=("meshes/min", 1))
        rates[(workers, threads)] = rate
    print(f"  ratio: {rates[(args.workers, 1)] / rates[(0, 1)]:.2f}x the plain loop, "
          f"{rates[(args.workers, 1)] / rates[(0, 0)]:.2f}x the loop on every core")
    shutil.rmtree(folder)


def run_cli(args, V, F):
    """`vds voxelize MESH --dims N --packed` writing its .npy slab by slab:
    wall time and peak resident memory as /usr/bin/time -v reports them."""
    folder = tempfile.mkdtemp(prefix="vds-cli-", dir=args.scratch)
    mesh, out = os.path.join(folder, "mesh.obj"), os.path.join(folder, "grid.npy")
    with open(mesh, "w") as f:
        f.writelines(f"v {x:.9g} {y:.9g} {z:.9g}\n" for x, y, z in V)
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in F)
    command = [args.tool, "voxelize", mesh, "--dims", str(args.dims), "--packed", "-o", out, "--quiet"]
    result = subprocess.run(["/usr/bin/time", "-v"] + command, capture_output=True, text=True)
    report = dict(line.strip().split(": ", 1) for line in result.stderr.splitlines() if ": " in line)
    print(f"  {' '.join(['vds'] + command[1:2] + ['MESH'] + command[3:6] + ['grid.npy'])}: exit {result.returncode}")
    print(f"  {result.stdout.strip()}")
    print(f"  wall {report.get('Elapsed (wall clock) time (h:mm:ss or m:ss)')}, peak RSS "
          f"{int(report.get('Maximum resident set size (kbytes)', 0)) / 2**20:.2f} GiB, CPU "
          f"{report.get('Percent of CPU this job got')}, load {os.getloadavg()[0]:.1f}; "
          f"file {os.path.getsize(out) / 2**30:.2f} GiB" if result.returncode == 0 else result.stderr[-2000:])
    shutil.rmtree(folder)


def run_scaling(args, V, F):
    grid = grid_of(V, args.dims)
    n = int(args.points)
    points = da.random.RandomState(1).uniform(-1.1, 1.1, size=(n, 3), chunks=(args.chunk, 3)).astype(np.float32)
    base = {}
    for workers in [int(w) for w in args.workers_list.split(",")]:
        c, client = cluster(workers)
        with c, client:
            vds.dask.classify((V, F), points[:1000]).sum().compute()
            r1 = timed(f"exact points, {workers} workers", n,
                       lambda: vds.dask.classify((V, F), points).sum().compute())
            r2 = timed(f"occupancy {args.dims}^3 (sum), {workers} workers", args.dims ** 3,
                       lambda: vds.dask.occupancy((V, F), grid, packed=True).sum().compute())
        base.setdefault("points", r1)
        base.setdefault("grid", r2)
        print(f"  {workers} workers: points {r1 / base['points']:.2f}x, grid {r2 / base['grid']:.2f}x one worker")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("what", choices=["grid", "sdf", "points", "dataset", "scaling", "cli"])
    parser.add_argument("--triangles", type=int, default=200_000)
    parser.add_argument("--dims", type=int, default=1024)
    parser.add_argument("--reference", type=int, default=512, help="in-memory grid for the rate compared")
    parser.add_argument("--band-cells", type=float, default=3.0)
    parser.add_argument("--points", type=float, default=1e8)
    parser.add_argument("--chunk", type=int, default=1 << 22)
    parser.add_argument("--meshes", type=int, default=20)
    parser.add_argument("--mesh-triangles", type=int, default=20_000)
    parser.add_argument("--samples", type=float, default=1e5, help="uniform and near-surface points a mesh, each")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--methods", default="sprite,exact", help="points: the methods timed")
    parser.add_argument("--workers-list", default="1,2,4,8,16")
    parser.add_argument("--tool", default=str(ROOT / "build" / "tools" / "vds"), help="cli: the vds program")
    parser.add_argument("--scratch", default=None, help="folder for the Zarr stores and .npy (default: the temp folder)")
    args = parser.parse_args()
    header(vars(args))
    V, F = bumpy_sphere(args.triangles)
    print(f"mesh: bumpy sphere, {len(F)} triangles")
    {"grid": run_grid, "sdf": run_sdf, "points": run_points, "dataset": run_dataset,
     "scaling": run_scaling, "cli": run_cli}[args.what](args, V, F)


if __name__ == "__main__":
    main()
