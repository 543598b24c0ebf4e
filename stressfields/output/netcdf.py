"""NetCDF output: written beside the target under a temporary name (`atomic.temporary`), laid out
first and then every block written once where it belongs, hashed, and published when complete.
"""
from __future__ import annotations

import os
import zlib
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import netCDF4
import numpy as np
import xarray as xr
from xarray.backends.locks import HDF5_LOCK, NETCDFC_LOCK, combine_locks

from ..errors import OutputError
from .atomic import clean_stale, fsync_path, publish, removed_on_failure, temporary, umask
from .compute import compute, local
from .hashing import ATTR, slabs, stored_hash
from .options import FILL_VALUES, OutputOptions

#: bytes per write call: a block is handed to HDF5 in C-order pieces of at most this size. Writes of
#: 8 MB (a 1e6-point block) into new pages of the page cache cost 3-5x the system time of 2 MB ones,
#: close to half the CPU of a large run (docs/bench/tuning.md)
WRITE_BYTES = 2 * 2 ** 20


def write(ds: xr.Dataset, target: Path, *, progress: bool = False, scheduler=None, overwrite: bool = False) -> Path:
    """Compute ``ds`` chunk by chunk and write it to ``target`` atomically.

    The file appears under its final name only once it is complete, with its content hash (see
    `hashing`) stored as a global attribute, read back from the written file; the caller has checked
    the target (`formats.check_target`);
    without ``overwrite`` a file another run published meanwhile is never replaced (`publish`).
    ``scheduler`` is passed to dask (None: the local threads).
    """
    target = Path(target)
    clean_stale(target)
    tmp = str(temporary(target, ".tmp"))
    with removed_on_failure(tmp, target):
        encoding = encodings(ds)
        lazy = sources(ds, encoding)
        if not lazy or local(scheduler):
            # laid out with fill mode off, then every block written once (`store`); a dataset in
            # memory (a comparison's) is written whole by the layout, without importing dask.array
            layout(ds, tmp)
            if lazy:
                with open_values(tmp) as nc:
                    store(nc, lazy, scheduler, progress)
        else:
            # on a cluster xarray's writer: its locks reach the workers
            compute(ds.to_netcdf(tmp, engine="netcdf4", encoding=encoding, compute=False), progress=progress,
                    scheduler=scheduler)
        os.chmod(tmp, 0o666 & ~umask())     # mkstemp makes 0600; publish like any new file
        finish(Path(tmp), target, overwrite)
    return target


def finish(tmp: Path, target: Path, overwrite: bool) -> None:
    """Hash the complete file ``tmp``, store the hash, make it durable and publish it as ``target``."""
    flushing = _flush_soon(str(tmp))       # the disk takes the values while they are hashed
    try:
        stamp(tmp)
        flushing.result()
    finally:
        flushing.cancel()
    with open(tmp, "rb+") as fh:
        os.fsync(fh.fileno())
    publish(tmp, target, overwrite)


def stamp(path: str | Path) -> str:
    """Compute the content hash of a written NetCDF file and store it as a global attribute."""
    with read(path, raw=True) as ds:
        digest, _ = stored_hash(ds)
    with netCDF4.Dataset(path, "a") as nc:
        nc.setncattr(ATTR, digest)
        nc.setncattr("id", digest)
    return digest


def layout(ds: xr.Dataset, path: Path | str) -> None:
    """Create the NetCDF file ``path`` for ``ds``: dimensions, attributes, encodings and in-memory
    variables, the values of its dask variables unwritten (`store` writes them). Fill mode is off:
    with it, HDF5 first writes every chunk with the fill value and then the values, twice the bytes
    (2.85 GB written for a 1.42 GB file, measured). The file is closed and durable on return."""
    lazy_text = [name for name, var in ds.variables.items() if hasattr(var.data, "dask") and not _numeric(var)]
    if lazy_text:       # text (a Zarr store's string coordinates): small, and encoded by xarray alone
        ds = ds.copy(deep=False)
        for name in lazy_text:
            ds.variables[name].load()
    nc = netCDF4.Dataset(path, "w", format="NETCDF4")
    try:
        nc.set_fill_off()
        # xarray's own write minus the values of dask variables: they are registered for a later
        # store that never runs here
        ds.dump_to_store(xr.backends.NetCDF4DataStore(nc), encoding=encodings(ds))
    finally:
        nc.close()
    with open(path, "rb+") as fh:
        os.fsync(fh.fileno())


class open_values:
    """The laid-out file, open to write or read values as stored (no masking or scaling), without
    HDF5's chunk caches: blocks are written (and read back) whole, chunk-aligned, so a cache only
    copies them once more and holds them (a 3.6e7-point run of eleven fields in chunks: 16.0 s wall,
    8-9 s of system time and 1.28 GB peak memory with netCDF's default caches, measured).

    Every write and the closing hold xarray's NetCDF/HDF5 lock (HDF5 is not thread safe), and a write after the
    closing is refused: after an interrupt the main thread closes the file while a worker thread may
    still be writing a block (closing under it crashed the process: 3 of 40 runs given SIGHUP).
    """

    def __init__(self, path: Path | str):
        self.nc = netCDF4.Dataset(path, "a")
        self.nc.set_auto_maskandscale(False)
        for var in self.nc.variables.values():
            if var.chunking() != "contiguous":
                var.set_var_chunk_cache(size=0)
        # xarray's own NetCDF/HDF5 lock, not one of ours: a dataset read lazily from NetCDF files
        # (sf.open_mfdataset, then sf.write) is read by xarray in the same tasks that write here, and
        # HDF5 reads under xarray's lock beside writes under another gave "NetCDF: HDF error" and crashes
        self.lock = combine_locks([NETCDFC_LOCK, HDF5_LOCK])
        self.closed = False

    def __getitem__(self, name: str):
        return self.nc[name]

    def write(self, name: str, index, values) -> None:
        """Store ``values`` at ``index`` (a slice per dimension), in pieces of at most WRITE_BYTES."""
        with self.lock:
            if self.closed:
                raise OutputError("the file was closed before this block was written (the run was interrupted)")
            var = self.nc[name]
            if values.ndim == 0:
                var[index] = values
                return
            for piece in slabs(values.shape, values.itemsize, WRITE_BYTES):
                at = tuple(s.start + p if isinstance(p, int) else slice(s.start + p.start, s.start + p.stop)
                           for s, p in zip(index, piece)) + tuple(index[len(piece):])
                var[at] = values[piece]

    def sync(self) -> None:
        with self.lock:
            self.nc.sync()

    def close(self) -> None:
        with self.lock:
            if not self.closed:
                self.closed = True
                self.nc.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


def sources(ds: xr.Dataset, encoding: dict, dim: str | None = None, lo: int = 0, hi: int | None = None,
            first: bool = True) -> list:
    """(name, dask array of stored values, region in the file) of the numeric dask variables of ``ds``, in
    name order: whole, or their rows lo:hi along ``dim`` (a part, `parts`), the variables without
    ``dim`` only with the ``first`` part. The values pass the encoding the file's variable has
    (`stored_form`)."""
    out = []
    for name in sorted(map(str, ds.variables)):
        var = ds.variables[name]
        if not hasattr(var.data, "dask") or not _numeric(var) or (dim is not None and dim not in var.dims
                                                                   and not first):
            continue
        region = tuple(slice(lo, hi) if d == dim else slice(0, n) for d, n in zip(var.dims, var.shape))
        data = var.data[tuple(slice(r.start, r.stop) for r in region)]
        data = data.map_blocks(stored_form(name, var, encoding), dtype=var.dtype,
                               meta=np.empty((0,) * var.ndim, var.dtype))
        out.append((name, data, region))
    return out


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


def _numeric(var) -> bool:
    """Numbers stored as they are computed (text and booleans pass xarray's encoders at layout)."""
    return var.dtype.kind in "iuf"


def blocks(sources: list):
    """(name, index in the file) of every block of ``sources``: by variable, then in C order."""
    for name, data, region in sources:
        starts = [np.concatenate([[0], np.cumsum(c)]).astype(int) + r.start for c, r in zip(data.chunks, region)]
        for loc in np.ndindex(*data.numblocks):
            yield name, tuple(slice(int(s[i]), int(s[i + 1])) for s, i in zip(starts, loc))


def store(nc, sources: list, scheduler, progress: bool, crcs: bool = False) -> list[int] | None:
    """Compute the blocks of ``sources`` (`sources`) and write each where it belongs in ``nc``
    (`open_values`); with ``crcs``, their CRC-32s in the order of `blocks`."""
    import dask
    import dask.array as da

    kept: dict | None = {} if crcs else None
    targets = [_Target(nc, name, kept) for name, _, _ in sources]
    arrays = [data for _, data, _ in sources]
    regions = [region for _, _, region in sources]
    if local(scheduler):
        # one graph: a field's variables come from one task per block
        stored = da.store(arrays, targets, regions=regions, lock=False, compute=False)
        compute(dask.delayed(_done)(stored), progress=progress, scheduler=scheduler)
    else:       # a cluster computes, this process writes: the sources' values in memory at once
        for source, target, values in zip(sources, targets, dask.compute(*arrays, scheduler=scheduler)):
            region = source[2]
            for _, index in blocks([source]):
                target[index] = values[tuple(slice(i.start - r.start, i.stop - r.start) for i, r in zip(index, region))]
    if kept is None:
        return None
    return [kept[(name, tuple(s.start for s in index))] for name, index in blocks(sources)]


def crc(values) -> int:
    """CRC-32 of an array's stored bytes (zlib, 6.8 GB/s here against 2.0 for SHA-256)."""
    values = np.ascontiguousarray(values)
    return zlib.crc32(values.reshape(-1).view(np.uint8)) if values.size else 0


def _done(_):
    return None


class _Target:
    """A variable of an `open_values` file as a target of `dask.array.store`, keeping the CRC-32 of
    each block by the block's start when ``crcs`` is a dict (taken outside the file's lock: zlib
    releases the GIL)."""

    def __init__(self, values: open_values, name: str, crcs: dict | None):
        self.values, self.name, self.crcs = values, name, crcs
        self.dtype = values[name].dtype

    def __setitem__(self, index, values):
        values = np.ascontiguousarray(values, dtype=self.dtype)
        check = crc(values) if self.crcs is not None else None
        self.values.write(self.name, index, values)
        if self.crcs is not None:
            self.crcs[(self.name, tuple(s.start for s in index))] = check


def _flush_soon(path: str):
    """fsync ``path`` in a thread: the file's values reach the disk while they are read back from the
    page cache and hashed (both release the GIL). Measured after writing a 1e7-point cone file of
    eleven fields (0.9 GB): fsync alone 0.27 s; hashing 0.50 s alone and 0.50 s with the fsync beside
    it. The caller fsyncs again after storing the hash."""
    pool = ThreadPoolExecutor(1)

    try:
        return pool.submit(fsync_path, path)
    finally:
        pool.shutdown(wait=False)


def read(path, raw: bool = False, **kw) -> xr.Dataset:
    """The file as a dataset: decoded (``kw`` as for `xr.open_dataset`, e.g. ``chunks={}``), or
    ``raw`` (stored values and attributes, for hashing; slabs are read one at a time, never the whole
    variable)."""
    if raw:
        return xr.open_dataset(path, engine="netcdf4", decode_cf=False, mask_and_scale=False, decode_times=False,
                               cache=False)
    return xr.open_dataset(path, **{"engine": "netcdf4", **kw})


#: the largest HDF5 chunk: what `xr.open_dataset(f, chunks={})` hands dask as one chunk
CHUNK_BYTES = 64 * 2 ** 20
#: uncompressed variables up to this size are stored contiguous (see `_layout`)
CONTIGUOUS_BYTES = 256 * 2 ** 20


def encodings(ds: xr.Dataset) -> dict:
    """Per variable: no implicit fill value; HDF5 chunks aligned with the dask chunks (so a task
    writes whole chunks and a reader gets them back with `chunks={}`), at most `CHUNK_BYTES`;
    zlib with byte shuffling when the options (`options.OutputOptions`) ask for compression;
    `_FillValue` for the ``fill`` option; text as UTF-8 char arrays."""
    options = OutputOptions.from_attrs(ds.attrs)
    enc: dict = {}
    for name, var in ds.variables.items():
        if var.dtype.kind in "OUT":
            # text as a char array with _Encoding = "utf-8" (xarray reads it back as str): ParaView's
            # CF reader crashes on a netCDF-4 variable-length string coordinate
            enc[name] = {"dtype": "S1"}
            continue
        e: dict = {"_FillValue": None}
        if options.nonfinite == "fill" and var.dtype.kind == "f" and name not in ds.coords:
            e["_FillValue"] = var.dtype.type(FILL_VALUES[var.dtype.itemsize])
        if var.ndim:
            e.update(_layout(var, options.compression or 0))
        enc[name] = e
    return enc


def _layout(var, level: int) -> dict:
    """Contiguous when not compressed and at most CONTIGUOUS_BYTES: one read, no chunk index, and
    the fastest write (measured, `sf.write` of 1e7 points x 11 fields, 80 MB a variable, two runs
    each: 2.7-3.8 s contiguous against 5.9-6.7 s in dask-aligned HDF5 chunks; on 4e6 points x 7
    fields the two were alike). Chunked like dask otherwise (compression needs chunks; a larger
    variable reopened with `chunks={}` then comes back in pieces of at most CHUNK_BYTES)."""
    compressed = level > 0
    if not compressed and var.nbytes <= CONTIGUOUS_BYTES:
        return {"contiguous": True}
    shape = [int(c[0]) for c in var.chunks] if var.chunks else list(var.shape)
    shape = [max(1, n) for n in shape]
    for k in range(len(shape)):       # leading dimensions shrink first: a line along x stays whole
        rest = var.dtype.itemsize * int(np.prod(shape[k + 1:]))
        shape[k] = max(1, min(shape[k], CHUNK_BYTES // max(1, rest)))
        if rest * shape[k] <= CHUNK_BYTES:
            break
    e: dict = {"contiguous": False, "chunksizes": tuple(shape)}
    if compressed:
        e.update(zlib=True, complevel=level, shuffle=True)
    return e
