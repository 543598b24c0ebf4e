"""Content hash of a dataset: what the file says, not how HDF5 happened to lay it out.

Lazy NetCDF writes are not byte-reproducible (HDF5 places chunks in arrival order), so the
reproducibility contract is a SHA-256 over the global attributes except `history` and
`date_created` (times) and the hash itself (also stored as the ACDD `id`), then, for every variable
in name order: its name, dims, dtype, shape and its attributes with their stored types (an int8
``flag_values`` is not an int64 one), followed by the SHA-256 digest of its little-endian values in
C order. Strings hash alike whatever array type holds them (NetCDF gives Python objects, Zarr NumPy's
StringDType). Same recipe, same environment: same hash, whatever the chunking or the scheduler.

A digest per variable lets the values of two variables be read back and hashed at once, one per
core (`content_hash`): SHA-256 itself is sequential, and it is what a run does last (1e7 points of
eleven fields, 0.9 GB: 0.33-0.46 s instead of 0.48-0.51 as one stream, three runs each). The values are read
from the written file, so the hash is of what the file holds.

Two earlier forms still verify (`stored_hash` tries them when the current one differs): one SHA-256
stream over every variable's values (``FORMS["stream"]``), and before that without attribute types
(``FORMS["untyped"]``).
"""
from __future__ import annotations

import hashlib
import json

import numpy as np
import xarray as xr

ATTR = "stressfields_content_sha256"
#: the ACDD ``id`` a file carries is its content hash; ``date_created``, like ``history``, is a time
_SKIP_GLOBAL = {"history", "date_created", "id", ATTR}
#: slabs read for hashing: small enough for reading and hashing to overlap, large enough to stream
_READ_BYTES = 8 * 2 ** 20


#: the forms of the content hash, newest first: (attributes with their types, values by per-variable
#: digest); `stored_hash` accepts a stored hash of any of them
FORMS = {"current": (True, True), "stream": (True, False), "untyped": (False, False)}


def content_hash(ds: xr.Dataset, form: str = "current") -> str:
    """The content hash of ``ds`` (a raw dataset, as `read(path, raw=True)` gives it) in ``form``
    (`FORMS`); per-variable digests are read two variables at a time (`_read_digests`)."""
    typed, nested = FORMS[form]
    attr = _typed if typed else _plain
    ds = text_as_strings(ds)
    h = hashlib.sha256()
    attrs = {k: attr(v) for k, v in sorted(ds.attrs.items()) if k not in _SKIP_GLOBAL}
    h.update(json.dumps(attrs, sort_keys=True).encode())
    names = sorted(map(str, ds.variables))
    if nested:
        digests = _read_digests(ds, names)
    for name in names:
        var = ds.variables[name]
        dtype = str(var.dtype) if not typed or var.dtype.kind not in "OUT" else "string"
        head = {"name": name, "dims": list(var.dims), "dtype": dtype, "shape": list(var.shape),
                "attrs": {k: attr(v) for k, v in sorted(var.attrs.items())}}
        h.update(json.dumps(head, sort_keys=True).encode())
        if nested:
            h.update(digests[name])
        else:
            for piece in _prefetched(_value_readers(var)):
                h.update(piece)
    return h.hexdigest()


def text_as_strings(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` (raw) with every UTF-8 char array (``_Encoding``, its last dimension the characters) as
    the strings it holds: text hashes alike as a char array (written now: ParaView's CF reader crashes
    on netCDF-4 strings) and as a netCDF-4 string (written before), so stored names keep their hash."""
    chars = [n for n, v in ds.variables.items() if v.dtype == np.dtype("S1") and "_Encoding" in v.attrs and v.ndim]
    if not chars:
        return ds
    replaced = {}
    for name in chars:
        var = ds.variables[name]
        raw = np.asarray(var.values)
        text = np.array([b"".join(row).decode(var.attrs["_Encoding"]) for row in raw.reshape(-1, raw.shape[-1])],
                        dtype=object).reshape(raw.shape[:-1])
        replaced[name] = xr.Variable(var.dims[:-1], text, {k: v for k, v in var.attrs.items() if k != "_Encoding"})
    out = ds.copy(deep=False)
    for name, var in replaced.items():
        out[name] = var
    return out.drop_dims([d for d in {ds.variables[n].dims[-1] for n in chars}
                          if not any(d in v.dims for v in out.variables.values())], errors="ignore")


def _value_readers(var):
    """A reader per slab of ``var``'s values, in C order."""
    for index in slabs(var.shape, var.dtype.itemsize, _READ_BYTES):
        yield lambda index=index: _bytes(np.asarray(var[index].values))


def _read_digests(ds: xr.Dataset, names: list[str]) -> dict[str, bytes]:
    """The SHA-256 digests of the values of ``names``, read from ``ds``: largest first, two variables
    at a time, each reading its next slab while it hashes one (reading and hashing release the GIL;
    xarray serialises the reads of one NetCDF file). Measured on 1e8 points of eleven fields (8.8 GB
    in the page cache): 4.6 s, 5.2 s without the read-ahead, 5.6 s as one stream."""
    from concurrent.futures import ThreadPoolExecutor

    def digest(name):
        h = hashlib.sha256()
        for piece in _prefetched(_value_readers(ds.variables[name])):
            h.update(piece)
        return name, h.digest()
    order = sorted(names, key=lambda n: -ds.variables[n].size)
    if len(order) <= 1:
        return dict(map(digest, order))
    with ThreadPoolExecutor(2) as pool:
        return dict(pool.map(digest, order))


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


def stored_hash(ds: xr.Dataset) -> tuple[str, str | None]:
    """(recomputed hash, hash stored in its attributes or None) of a raw dataset (a written file read
    raw: `formats.file_hash`). A dataset whose stored hash is of an earlier form (`FORMS`) and
    matches it gives that one."""
    digest, stored = content_hash(ds), ds.attrs.get(ATTR)
    if stored is not None and stored != digest:
        for form in list(FORMS)[1:]:
            if content_hash(ds, form) == stored:
                return stored, stored       # written in an earlier form, and intact
    return digest, stored


def slabs(shape: tuple[int, ...], itemsize: int, limit: int):
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


def values_hash(ds: xr.Dataset) -> str:
    """A SHA-256 over the values alone: per variable in name order its name, dims, dtype and shape,
    then the digest of its values (as `content_hash`), without any attribute. It changes when a value
    changes and not when a description does: what the reference suite's release gate holds fixed
    (`stressfields.suite`), where the content hash also covers titles, references and comments."""
    ds = text_as_strings(ds)
    h = hashlib.sha256()
    names = sorted(map(str, ds.variables))
    digests = _read_digests(ds, names)
    for name in names:
        var = ds.variables[name]
        dtype = str(var.dtype) if var.dtype.kind not in "OUT" else "string"
        head = {"name": name, "dims": list(var.dims), "dtype": dtype, "shape": list(var.shape)}
        h.update(json.dumps(head, sort_keys=True).encode())
        h.update(digests[name])
    return h.hexdigest()
