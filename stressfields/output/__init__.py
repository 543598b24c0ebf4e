"""The output wing: everything that turns a lazy dataset into files, and reads them back raw.

    formats.py    the table of formats (FORMATS, found by suffix), the one target check, write,
                  export, file_hash, verify, and the free-space check
    form.py       the on-disk form every format writes (choices as CF flags, the output options applied)
    options.py    the output options (dtype, compression, nonfinite): names, check, recorded form (no xarray)
    atomic.py     temporaries named after their owner, stale clean-up, publishing, the run lock
    compute.py    computing the tasks on the local threads or a cluster, the progress bar
    hashing.py    the content hash and the values hash of a dataset
    netcdf.py     NetCDF: laid out, then every block written once; published when complete
    parts.py      NetCDF in resumable parts, written in place into one file
    zarrstore.py  Zarr stores: every worker writes its own chunks

A format module imports the shared modules (atomic, compute, options, hashing, and parts the netcdf
module it extends), never the table. Nothing here is imported by this file: the recipe check reads
`options` without loading xarray.
"""
