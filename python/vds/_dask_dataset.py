"""vds.dask.dataset: occupancy and signed-distance samples for many meshes.

One task a mesh, each writing its own Zarr group, so meshes go in parallel
on any scheduler and one mesh's failure costs only its own group. A group
is complete once its attribute "complete" is true, which is written last
(Zarr's directory store replaces each file whole), so a group cut off
half-way is never taken as complete and is rewritten by the next run.
"""
import os
import zlib

import dask
import numpy as np

from . import Error, InvalidArgument, SignedDistance, load_mesh, sample_surface, validate_mesh

_GROUP_CHUNK = 1 << 16  # points a Zarr chunk


def _zarr():
    try:
        import zarr
    except ImportError:
        raise ImportError("vds.dask.dataset writes Zarr: install python3-zarr (tools/install-deps.sh)") from None
    return zarr


class Settings:
    """What every mesh of one dataset call is sampled with."""

    __slots__ = ("uniform", "near_surface", "sigma", "padding", "rule", "seed", "threads")

    def __init__(self, uniform, near_surface, sigma, padding, rule, seed, threads):
        self.uniform, self.near_surface, self.sigma, self.padding = int(uniform), int(near_surface), sigma, padding
        self.rule, self.seed, self.threads = rule, int(seed), threads

    def __getstate__(self):
        return tuple(getattr(self, k) for k in self.__slots__)

    def __setstate__(self, state):
        for k, v in zip(self.__slots__, state):
            setattr(self, k, v)


def _samples(V, F, name, settings):
    """(uniform points, near-surface points, attributes) of one mesh, float32,
    reproducible from the seed and the mesh's name."""
    rng = np.random.default_rng([settings.seed, zlib.crc32(name.encode())])
    lo, hi = V.min(axis=0).astype(np.float64), V.max(axis=0).astype(np.float64)
    margin = settings.padding * (hi - lo)
    box_lo, box_hi = lo - margin, hi + margin
    uniform = box_lo + rng.random((settings.uniform, 3)) * (box_hi - box_lo)
    sigma = settings.sigma * float(np.linalg.norm(hi - lo))
    surface, _ = sample_surface((V, F), settings.near_surface, rng.integers(1 << 64, dtype=np.uint64))
    near = surface + rng.normal(0.0, sigma, (settings.near_surface, 3))
    attrs = {"box": [box_lo.tolist(), box_hi.tolist()], "sigma": sigma, "sigma_of_diagonal": settings.sigma,
             "padding": settings.padding, "seed": settings.seed}
    return uniform.astype(np.float32), near.astype(np.float32), attrs


def _write_points(group, name, points, distance, threads):
    d = distance.distance(points, threads=threads)
    part = group.create_group(name)
    chunks = (min(_GROUP_CHUNK, max(1, len(points))),)
    part.create_dataset("points", data=points, chunks=chunks + (3,))
    # A distance's sign bit is the exact classifier's label, also on the surface (-0.0 inside).
    part.create_dataset("labels", data=np.signbit(d), chunks=chunks)
    part.create_dataset("sdf", data=d.astype(np.float32), chunks=chunks)


def _one_mesh(path, store, name, settings):
    """Writes group `name` of `store` for the mesh at `path`: "written", or
    "error: ..." (the group then holds only the error and is not complete)."""
    zarr = _zarr()
    root = zarr.open_group(store, mode="a")
    if name in root:
        del root[name]  # half-written, or an earlier error: redone whole
    group = root.create_group(name)
    group.attrs.update({"path": os.fsdecode(path), "complete": False})
    try:
        V, F = load_mesh(path)
        report = validate_mesh(V, F)
        rule = settings.rule or ("parity" if report["closed"] and report["oriented"] else "generalized-winding")
        distance = SignedDistance(V, F, rule)
        uniform, near, attrs = _samples(V, F, name, settings)
        _write_points(group, "uniform", uniform, distance, settings.threads)
        _write_points(group, "near_surface", near, distance, settings.threads)
    except Error as e:
        group.attrs["error"] = str(e).splitlines()[0]
        return "error: " + group.attrs["error"]
    group.attrs.update(dict(attrs, rule=rule, report=report))
    group.attrs["complete"] = True  # last: the group is whole
    return "written"


def _names(mesh_paths):
    names = {}
    for path in mesh_paths:
        name = os.path.splitext(os.path.basename(os.fsdecode(path)))[0]
        if name in names:
            raise InvalidArgument(f"two meshes would share the group {name!r}: {names[name]} and {os.fsdecode(path)}")
        names[name] = os.fsdecode(path)
    return names


def dataset(mesh_paths, store, uniform=100_000, near_surface=100_000, sigma=0.01, padding=0.1, rule=None, seed=0,
            threads=1):
    """Occupancy and signed-distance training samples for many meshes, one
    Zarr group each, in parallel on the current Dask scheduler (a
    distributed Client's cluster where one is made).

    mesh_paths: mesh files (OBJ, PLY, STL, OFF); each one's group is named
        after its file name less the extension (two alike are refused).
    store: a Zarr directory (made if missing).
    For each mesh, group NAME holds "uniform" (uniform points in the mesh's
    box grown by `padding` of its size on every side) and "near_surface"
    (area-weighted surface points displaced by a Gaussian of standard
    deviation `sigma` times the box's diagonal), each with "points" (n, 3)
    float32, "labels" (n,) bool (inside, by the exact classifier) and "sdf"
    (n,) float32 (exact signed distances, negative exactly where labels is
    True); its attributes hold the rule, the mesh's report (vds.validate_mesh),
    the sampling settings and "complete". rule None: the rule the report
    calls for, "parity" for a closed, oriented mesh and
    "generalized-winding" otherwise. seed: with the group's name, fixes
    every point. threads: per mesh.
    A mesh that cannot be read or bounds nothing (empty, flat, bad indices)
    gets a group holding its one-line "error" and the run goes on. Running
    again skips complete groups and rewrites the others (half-written ones,
    errors).
    Returns {name: "written" | "complete" | "error: ..."}.
    """
    zarr = _zarr()
    names = _names(mesh_paths)
    settings = Settings(uniform, near_surface, sigma, padding, rule, seed, threads)
    store = os.fsdecode(store)
    root = zarr.open_group(store, mode="a")
    status, tasks = {}, []
    for name, path in names.items():
        if name in root and root[name].attrs.get("complete"):
            status[name] = "complete"
        else:
            tasks.append((name, dask.delayed(_one_mesh, pure=False)(path, store, name, settings)))
    for (name, _), result in zip(tasks, dask.compute(*[t for _, t in tasks])):
        status[name] = result
    return status
