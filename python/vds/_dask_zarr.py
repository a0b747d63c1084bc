"""vds.dask.to_zarr: a dask array into Zarr with every chunk written once.

dask's own ``Array.to_zarr`` stores each block from a task whose (empty)
result the final task waits for. When a worker process dies, the results it
held are lost, and the distributed scheduler runs those finished tasks again:
their chunks are written a second time (the same bytes, but twice the work,
and a reader may see a chunk replaced under it). Here each block's task
first asks the store whether its chunk is already there, and a chunk file is
only ever there whole (Zarr's directory store writes a temporary file and
renames it), so a task run again after a kill writes nothing. A worker
killed between those two steps leaves its temporary file behind: once every
block is written, the write's last task removes such leftovers from a
directory store.
"""
import os

import dask
import dask.array as da


def _zarr():
    try:
        import zarr
    except ImportError:
        raise ImportError("vds.dask.to_zarr writes Zarr: install python3-zarr (tools/install-deps.sh)") from None
    return zarr


def _remove_leftovers(_written, path):
    """Zarr's directory store writes a chunk to '<key>.<hex>.partial' and then
    renames it into place; a worker killed in between leaves that file. Run
    once every block is written (after `_written`), when no write is under
    way, so every such file is a leftover."""
    for folder, _, names in os.walk(path):
        for name in names:
            if name.endswith(".partial"):
                try:
                    os.remove(os.path.join(folder, name))
                except FileNotFoundError:
                    pass


class _ChunkOnce:
    """A Zarr array as ``da.store``'s target, one block a chunk: a block
    whose chunk the store already holds is not written again."""

    def __init__(self, array):
        self.array = array

    def __setitem__(self, region, block):
        coords = tuple(s.start // c for s, c in zip(region, self.array.chunks))
        if self.array._chunk_key(coords) not in self.array.store:
            self.array[region] = block


def to_zarr(array, store, overwrite=True, compute=True, **kwargs):
    """Writes the dask array `array` to a Zarr array at `store` (a folder's
    path, opened as Zarr's directory store, or any Zarr store), each block
    one chunk, each chunk written once even when a worker dies mid-way and
    its finished blocks are recomputed. Blocks must be regular (all but the
    last of each axis alike), as for dask's to_zarr; kwargs go to
    zarr.create (compressor, ...). compute=False returns the lazy write.
    Returns the Zarr array (or the delayed write)."""
    zarr = _zarr()
    if isinstance(store, (str, os.PathLike)):
        store = zarr.storage.DirectoryStore(os.fspath(store))
    chunks = tuple(c[0] for c in array.chunks)
    if any(len(set(c[:-1])) > 1 or c[-1] > c[0] for c in array.chunks):
        raise ValueError("vds.dask.to_zarr needs regular blocks: rechunk the array first")
    target = zarr.create(shape=array.shape, chunks=chunks, dtype=array.dtype, store=store, overwrite=overwrite,
                         **kwargs)
    write = da.store(array, _ChunkOnce(target), lock=False, compute=False)
    if isinstance(store, zarr.storage.DirectoryStore):
        write = dask.delayed(_remove_leftovers)(write, store.path)
    if not compute:
        return write
    write.compute()
    return target
