"""What vds.dask ships to the workers, and what each worker process keeps.

A source (a mesh or a sprite) travels as bytes: a mesh as its vertex and
face arrays, a sprite as its .vds file. The bytes are one task of the graph
(``Shipped.delayed``), which the scheduler hands once to each worker that
runs a task needing it. On the worker, ``Shipped.build`` makes what a task
asks for (a classifier, a distance index, the decoded sprite, the mesh's
report) once per process and keeps it keyed by the bytes' SHA-256 and the
arguments, for every chunk and computation after, on any scheduler.
"""
import collections
import hashlib
import os
import threading
import warnings

import dask
import numpy as np

from . import Classifier, ExactClassifier, InvalidArgument, MeshWarning, SignedDistance, Sprite, from_bytes, load_mesh
from . import methods, validate_mesh

# Per worker process: what was built, by (digest, what, arguments), at most
# _CACHE_LIMIT of them (the least recently used dropped first), and how many
# builds of each kind this process made (tests read it through Client.run).
_CACHE_LIMIT = 8
_cache = collections.OrderedDict()
_cache_lock = threading.Lock()
builds = collections.Counter()


class _Entry:
    __slots__ = ("lock", "value")

    def __init__(self):
        self.lock = threading.Lock()
        self.value = None


def _cached(key, make):
    """make() once per process for `key` (concurrent askers wait for the one build)."""
    with _cache_lock:
        entry = _cache.get(key)
        if entry is None:
            entry = _cache[key] = _Entry()
            while len(_cache) > _CACHE_LIMIT:
                _cache.popitem(last=False)
        else:
            _cache.move_to_end(key)
    with entry.lock:
        if entry.value is None:
            # The client warned once for the mesh; workers would repeat it into their logs.
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", MeshWarning)
                entry.value = make()
            builds[key[1]] += 1
        return entry.value


class Shipped:
    """A mesh's arrays or a sprite's .vds bytes, with their SHA-256 and a
    name for messages: what travels to the workers."""

    __slots__ = ("kind", "name", "digest", "parts")

    def __init__(self, kind, name, parts):
        self.kind, self.name, self.parts = kind, name, parts
        h = hashlib.sha256(kind.encode())
        for part in parts:
            h.update(part if isinstance(part, bytes) else repr(part).encode())
        self.digest = h.hexdigest()

    def __getstate__(self):
        return (self.kind, self.name, self.digest, self.parts)

    def __setstate__(self, state):
        self.kind, self.name, self.digest, self.parts = state

    @classmethod
    def of_mesh(cls, V, F, name):
        V = np.ascontiguousarray(V)
        F = np.ascontiguousarray(F)
        return cls("mesh", name, (V.dtype.str, V.shape, V.tobytes(), F.dtype.str, F.shape, F.tobytes()))

    @classmethod
    def of_sprite(cls, data, name):
        return cls("sprite", name, (bytes(data),))

    def delayed(self):
        """This source as one task of a graph, named by its digest (so every
        array made from the same bytes shares it)."""
        return dask.delayed(self, name="vds-source-" + self.digest, pure=True)

    def mesh(self):
        """(V, F), read-only views of the shipped bytes."""
        vt, vs, vb, ft, fs, fb = self.parts
        return np.frombuffer(vb, dtype=vt).reshape(vs), np.frombuffer(fb, dtype=ft).reshape(fs)

    def build(self, what, *args):
        """What `what` names, built once per process (see the module doc)."""
        return _cached((self.digest, what) + args, lambda: _BUILDERS[what](self, *args))

    def require_mesh(self, call):
        if self.kind != "mesh":
            raise InvalidArgument(f"vds.dask.{call} needs a mesh ((V, F) or a mesh file), not a sprite: "
                                  "a sprite keeps no triangles to measure distances to")


def _classifier(src, method, resolution):
    if src.kind == "sprite":
        return Classifier(src.build("sprite"), method)
    V, F = src.mesh()
    return Classifier(V, F, method, resolution=resolution, name=src.name)


def _exact(src):
    V, F = src.mesh()
    return ExactClassifier(V, F)


def _distance(src, rule):
    V, F = src.mesh()
    return SignedDistance(V, F, rule)


def _report(src):
    return validate_mesh(*src.mesh())


_BUILDERS = {
    "classifier": _classifier,
    "exact": _exact,
    "distance": _distance,
    "report": _report,
    "sprite": lambda src: from_bytes(src.parts[0], src.name),
}


def _is_sprite_path(path):
    return os.fsdecode(path).lower().endswith(".vds")


def ship(source, rule):
    """Shipped bytes of a source: (V, F), a mesh file's path, a vds.Sprite,
    a .vds file's path. Files are read here, on the client, so a missing or
    malformed one fails at the call; so does a mesh that cannot be used,
    and one whose inside `rule` does not define gets its vds.MeshWarning
    here, at the caller's line, as from the one-process calls (the workers
    stay quiet). rule None: no rule is asked."""
    if isinstance(source, Sprite):
        shipped, local = Shipped.of_sprite(source.to_bytes(), source.source_name or "<sprite>"), source
    elif isinstance(source, tuple) and len(source) == 2:
        shipped = Shipped.of_mesh(source[0], source[1], "<mesh>")
        local = source
    elif isinstance(source, (str, bytes, os.PathLike)):
        name = os.path.basename(os.fsdecode(source))
        if _is_sprite_path(source):
            with open(os.fspath(source), "rb") as f:
                shipped = Shipped.of_sprite(f.read(), name)
            local = from_bytes(shipped.parts[0], name)
        else:
            local = load_mesh(source)
            shipped = Shipped.of_mesh(local[0], local[1], name)
    else:
        raise InvalidArgument("a vds.dask source is a mesh (V, F), a mesh file's path, a vds.Sprite or a .vds "
                              f"file's path, not {type(source).__name__}")
    nothing = np.empty((0, 3), np.float32)
    if shipped.kind == "mesh":
        ExactClassifier(*local).contains(nothing, rule=rule or "generalized-winding")
    elif rule is not None:
        local.contains(nothing, rule=rule)
    return shipped


def method_for(shipped, method, rule):
    """The method a classify or occupancy call runs: `method`, or "exact" for
    a mesh and "sprite" for a sprite when None; one the source cannot make
    or that cannot answer `rule` fails here, at the call."""
    table = {m.name: m for m in methods()}
    if method is None:
        method = "sprite" if shipped.kind == "sprite" else "exact"
    if method not in table:
        raise InvalidArgument(f"unknown method {method!r}: one of {', '.join(table)}")
    if shipped.kind == "sprite" and not table[method].from_sprite:
        made = ", ".join(m for m in table if table[m].from_sprite)
        raise InvalidArgument(f"method {method!r} is not made from a sprite (from a sprite: {made}); give the mesh")
    if rule not in table[method].rules:
        raise InvalidArgument(f"method {method!r} answers rule {' or '.join(table[method].rules)}, not {rule!r}")
    return method
