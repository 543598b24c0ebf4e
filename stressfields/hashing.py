"""Content hash of a dataset: what the file says, not how HDF5 happened to lay it out.

Lazy NetCDF writes are not byte-reproducible (HDF5 places chunks in arrival order), so the
reproducibility contract is a SHA-256 over, for every variable in name order: its name, dims,
dtype, shape, little-endian values, and its attributes with their stored types (an int8
``flag_values`` is not an int64 one); plus the global attributes except `history` (a timestamp) and
the hash itself. Strings hash alike whatever array type holds them (NetCDF gives Python objects,
Zarr NumPy's StringDType). Same recipe, same environment: same hash, whatever the chunking or the
scheduler.

Files written before attribute types were hashed carry the hash without them (``legacy``);
`file_hash` accepts that one when the stored hash is it, so they still verify.
"""
from __future__ import annotations

import hashlib
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


def content_hash(ds: xr.Dataset, legacy: bool = False) -> str:
    h = hashlib.sha256()
    attr = _plain if legacy else _typed
    attrs = {k: attr(v) for k, v in sorted(ds.attrs.items()) if k not in _SKIP_GLOBAL}
    h.update(json.dumps(attrs, sort_keys=True).encode())
    for item in _prefetched(_stream(ds, legacy)):
        h.update(item)
    return h.hexdigest()


def _stream(ds: xr.Dataset, legacy: bool = False):
    """What is hashed, in order: per variable (by name) a JSON head, then a reader per value slab."""
    attr = _plain if legacy else _typed
    for name in sorted(map(str, ds.variables)):
        var = ds.variables[name]
        dtype = str(var.dtype) if legacy or var.dtype.kind not in "OUT" else "string"
        head = {"name": name, "dims": list(var.dims), "dtype": dtype, "shape": list(var.shape),
                "attrs": {k: attr(v) for k, v in sorted(var.attrs.items())}}
        yield lambda head=head: json.dumps(head, sort_keys=True).encode()
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


def stamp(path: str | Path) -> str:
    """Compute the content hash of a written NetCDF file and store it as a global attribute."""
    import netCDF4

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


def _bytes(values: np.ndarray) -> bytes:
    if values.dtype.kind in "OUST":
        return json.dumps([str(v) for v in values.ravel().tolist()]).encode()
    return np.ascontiguousarray(values, dtype=values.dtype.newbyteorder("<")).tobytes()


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
