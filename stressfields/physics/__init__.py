"""Pure NumPy contact-mechanics kernels: arrays in, arrays out; no xarray, no dask, no I/O."""
