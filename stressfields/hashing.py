"""Content hash of a dataset: what the file says, not how HDF5 happened to lay it out.

Lazy NetCDF writes are not byte-reproducible (HDF5 places chunks in arrival order), so the
reproducibility contract is a SHA-256 over, for every variable in name order: its name, dims,
dtype, shape, little-endian values, and its attributes with their stored types (an int8
``flag_values`` is not an int64 one); plus the global attributes except `history` (a timestamp) and
the hash itself. Strings hash alike whatever array type holds them (NetCDF gives Python objects,
Zarr NumPy's StringDType). Same recipe, same environment: same hash, whatever the chunking or the
scheduler.

A run hashes the values it writes from memory, as they were computed (`Keeper`): the same bytes in
the same order as reading the file back, without the read. Reading back (`file_hash`, `verify`)
remains the check of a file: `export`, `stressfields hash` and runs in parts (`parts`) use it.

Files written before attribute types were hashed carry the hash without them (``legacy``);
`file_hash` accepts that one when the stored hash is it, so they still verify.
"""
from __future__ import annotations

import hashlib
import os
import json
from pathlib import Path

import numpy as np
import xarray as xr

ATTR = "stressfields_content_sha256"
_SKIP_GLOBAL = {"history", ATTR}
#: values hashed per slice of the first dimension, to keep memory bounded on large files
_SLICE_BYTES = 64 * 2 ** 20
#: slabs read for hashing: small enough for reading and hashing to overlap, large enough to stream
_READ_BYTES = 8 * 2 ** 20


def content_hash(ds: xr.Dataset, legacy: bool = False, values: dict | None = None) -> str:
    """The content hash of ``ds`` (a raw dataset, as `read(path, raw=True)` gives it). ``values``
    optionally maps a numeric variable's name to a callable giving its stored values as arrays whose
    C-order bytes, one after the other, are the variable's C-order bytes (`Keeper.values`): those
    are hashed from memory instead of read from ``ds``. SHA-256 sees one byte stream either way, so
    the digest does not depend on where the bytes came from or how they were cut."""
    h = hashlib.sha256()
    attr = _plain if legacy else _typed
    attrs = {k: attr(v) for k, v in sorted(ds.attrs.items()) if k not in _SKIP_GLOBAL}
    h.update(json.dumps(attrs, sort_keys=True).encode())
    for item in _prefetched(_stream(ds, legacy, values or {})):
        h.update(item)
    return h.hexdigest()


def _stream(ds: xr.Dataset, legacy: bool = False, values: dict | None = None):
    """What is hashed, in order: per variable (by name) a JSON head, then a reader per value slab."""
    attr = _plain if legacy else _typed
    values = values or {}
    for name in sorted(map(str, ds.variables)):
        var = ds.variables[name]
        dtype = str(var.dtype) if legacy or var.dtype.kind not in "OUT" else "string"
        head = {"name": name, "dims": list(var.dims), "dtype": dtype, "shape": list(var.shape),
                "attrs": {k: attr(v) for k, v in sorted(var.attrs.items())}}
        yield lambda head=head: json.dumps(head, sort_keys=True).encode()
        if name in values:
            for piece in values[name]():
                if piece.dtype != var.dtype:
                    raise ValueError(f"{name}: kept values are {piece.dtype}, stored {var.dtype}")
                yield lambda piece=piece: _bytes(piece)
            continue
        for index in slabs(var.shape, var.dtype.itemsize, _READ_BYTES):
            yield lambda var=var, index=index: _bytes(np.asarray(var[index].values))


def _prefetched(readers):
    """Call the readers one ahead in a second thread: the next slab is read while this one is
    hashed (file reads and SHA-256 both release the GIL, so a file costs ~max of the two, not the sum)."""
    from concurrent.futures import ThreadPoolExecutor

    with ThreadPoolExecutor(max_workers=1) as pool:
        pending = None
        for reader in readers:
            nxt = pool.submit(reader)
            if pending is not None:
                yield pending.result()
            pending = nxt
        if pending is not None:
            yield pending.result()


def file_hash(path: str | Path) -> tuple[str, str | None]:
    """(recomputed hash, hash stored in the file or None), for any format of `writers.FORMATS`."""
    from .writers import format_for

    with format_for(path).read(path, raw=True) as ds:
        digest, stored = content_hash(ds), ds.attrs.get(ATTR)
        if stored is not None and stored != digest and content_hash(ds, legacy=True) == stored:
            return stored, stored       # written before attribute types were hashed, and intact
        return digest, stored


def verify(path: str | Path) -> str:
    """The content hash of a written file or store after checking it against the stored one. Raises
    OutputError naming the problem when the input cannot be read, carries no hash (a run that did not
    finish, or a file not written here), or its content changed (a flipped bit, a lost chunk)."""
    from .errors import OutputError

    try:
        digest, stored = file_hash(path)
    except Exception as exc:       # any reader's failure on damaged input: HDF5, zarr, codecs
        raise OutputError(f"{path}: not a readable NetCDF file or Zarr store "
                          f"({type(exc).__name__}: {str(exc)[:200]})") from None
    if stored is None:
        raise OutputError(f"{path}: no stored content hash (unfinished, or not written by stressfields); "
                          "refusing to use it")
    if stored != digest:
        raise OutputError(f"{path}: damaged: its content hash {digest} differs from the stored {stored}")
    return digest


def stamp(path: str | Path, values: dict | None = None) -> str:
    """Compute the content hash of a written NetCDF file and store it as a global attribute.
    ``values`` as for `content_hash`: variables whose written values are still in memory."""
    import netCDF4

    if values:
        from .netcdf import read

        with read(path, raw=True) as ds:
            digest = content_hash(ds, values=values)
    else:
        digest, _ = file_hash(path)
    with netCDF4.Dataset(path, "a") as nc:
        nc.setncattr(ATTR, digest)
    return digest


def slabs(shape: tuple[int, ...], itemsize: int, limit: int = _SLICE_BYTES):
    """Index tuples that cover an array of `shape` in C order, each slab at most ~`limit` bytes."""
    if not shape:
        yield ()
        return
    k, inner = len(shape) - 1, itemsize
    while k > 0 and inner * shape[k] <= limit:
        inner *= shape[k]
        k -= 1
    step = max(1, limit // max(1, inner))
    for outer in np.ndindex(*shape[:k]):
        for start in range(0, shape[k], step):
            yield outer + (slice(start, min(shape[k], start + step)),)


def _bytes(values: np.ndarray):
    """The bytes hashed for a slab: a flat little-endian byte view of numbers (no copy when already
    little-endian and contiguous), the JSON list of text."""
    if values.dtype.kind in "OUST":
        return json.dumps([str(v) for v in values.ravel().tolist()]).encode()
    return np.ascontiguousarray(values, dtype=values.dtype.newbyteorder("<")).reshape(-1).view(np.uint8)


def _typed(value):
    """An attribute with its stored type: NumPy values (what NetCDF gives) name their dtype; text and
    the plain JSON values of Zarr stay as they are."""
    if isinstance(value, (np.ndarray, np.generic)) and value.dtype.kind not in "OUST":
        return {"dtype": str(value.dtype), "value": _plain(value)}
    return _plain(value)


def _plain(value):
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    return value


#: bytes of computed values kept in memory to hash them without reading the file back (and at most a
#: quarter of the memory available when the run starts). Small on purpose: reading back from the page
#: cache overlaps SHA-256 (`_prefetched`), so it costs little, while holding every block until the end
#: costs CPU that grows with the bytes held. Measured (cone, eleven fields, sf.write, CPU s, memory vs
#: read back): 1e6 points (88 MB) 0.65 vs 0.63; 4e6 (350 MB) 2.77 vs 2.53; 1e7 (0.9 GB) 7.68 vs 6.64.
KEEP_BYTES = 128 * 2 ** 20


def keep_budget() -> int:
    try:
        available = os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, AttributeError):
        available = 4 * KEEP_BYTES
    return min(KEEP_BYTES, available // 4)


class Keeper:
    """Keeps the blocks of a dataset's dask variables as they are computed and written, so that the
    written file is hashed from memory (`content_hash(..., values=keeper.values())`) instead of read
    back. The hash is defined per variable in name order, while a task computes one block of every
    variable of its group, so the blocks wait in memory until the whole dataset is written: variables
    are kept, in name order, while their bytes fit ``budget``; the others are read back as before.

    A block is kept as it is stored: after xarray's CF encoding of its variable (``encoding``, e.g. a
    ``_FillValue`` replacing NaN), the very function the writers apply."""

    def __init__(self, budget: int | None = None):
        self.budget = keep_budget() if budget is None else budget
        self.blocks: dict[str, dict] = {}
        self.chunks: dict[str, tuple] = {}

    def wrap(self, ds: xr.Dataset, encoding: dict | None = None) -> xr.Dataset:
        """``ds`` with a pass-through step after each block of the kept variables."""
        out, used = ds.copy(deep=False), 0
        for name in sorted(map(str, ds.variables)):
            var = ds.variables[name]
            if not hasattr(var.data, "map_blocks") or not var.ndim or var.dtype.kind not in "biuf":
                continue
            if used + var.nbytes > self.budget:
                continue
            used += var.nbytes
            self.blocks[name], self.chunks[name] = {}, var.chunks
            keep = self._keeper(name, stored_form(name, var, encoding))
            out.variables[name].data = var.data.map_blocks(keep, dtype=var.dtype, meta=np.empty((0,) * var.ndim,
                                                                                               var.dtype))
        return out

    def _keeper(self, name, stored):
        store = self.blocks[name]

        def keep(block, block_info=None):
            if block_info is None:
                return block
            store[tuple(block_info[None]["chunk-location"])] = stored(block)
            return block
        return keep

    def values(self) -> dict:
        """Per kept variable whose every block arrived: a callable giving its values in C order."""
        return {name: (lambda name=name: self._pieces(name)) for name, blocks in self.blocks.items()
                if len(blocks) == int(np.prod([len(c) for c in self.chunks[name]]))}

    def _pieces(self, name: str):
        """The blocks in an order whose bytes are the variable's C-order bytes: the blocks themselves
        when only single-index blocks precede a split dimension, else bands along the first dimension
        assembled from their blocks. Each is released once handed out."""
        chunks, blocks = self.chunks[name], self.blocks.pop(name)
        grid = [len(c) for c in chunks]
        if all(max(chunks[i]) == 1 for j in range(len(grid)) if grid[j] > 1 for i in range(j)):
            for loc in np.ndindex(*grid):
                yield blocks.pop(loc)
            return
        shape = tuple(sum(c) for c in chunks)
        starts = [np.concatenate([[0], np.cumsum(c)]).astype(int) for c in chunks]
        for i0 in range(grid[0]):
            first = blocks[(i0,) + (0,) * (len(grid) - 1)]
            band = np.empty((chunks[0][i0],) + shape[1:], dtype=first.dtype)
            for rest in np.ndindex(*grid[1:]):
                index = (slice(None),) + tuple(slice(s[i], s[i + 1]) for s, i in zip(starts[1:], rest))
                band[index] = blocks.pop((i0,) + rest)
            yield band


def stored_form(name: str, var: xr.Variable, encoding: dict | None = None):
    """A function giving a block of ``var`` as the writers store it: after xarray's CF encoding of the
    variable (``encoding``: the writers' per-variable encodings)."""
    enc = {k: v for k, v in (encoding or {}).get(name, {}).items() if k == "_FillValue"}
    if enc.get("_FillValue") is None:
        # without a fill value a block is stored as it is, and the encoder is skipped: it costs
        # ~0.13 s per 1e6-value block (measured), for an unchanged copy
        return lambda block: block
    dims, attrs = var.dims, dict(var.attrs)

    def stored(block):
        # the one encoding that changes a stored number here: +-inf/NaN -> the fill value
        return np.asarray(xr.conventions.encode_cf_variable(xr.Variable(dims, block, attrs, enc), name=name).values)
    return stored
