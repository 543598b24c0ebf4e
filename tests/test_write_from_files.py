"""A dataset read lazily from NetCDF files (sf.open_mfdataset, xr.open_dataset with chunks) is written
by the local writer while xarray reads its sources in the same dask tasks: both must hold one lock,
HDF5 being not thread safe (reads under xarray's lock beside writes under another gave
"NetCDF: HDF error" and crashed processes)."""
import numpy as np
import xarray as xr

import stressfields as sf

RECIPE = {"scenario": "conical", "parameters": {"nu": 0.3, "ux0": 0.25, "mu": [0.1, 0.2, 0.3, 0.4],
                                                "y": {"start": -1.0, "stop": 1.0, "num": 40},
                                                "x": {"start": -1.5, "stop": 1.5, "num": 300}},
          "output": {"variables": ["sigma_xx", "sigma_yy", "sigma_zz", "sigma_xz", "von_mises", "dpdz"]}}


def test_writing_a_dataset_read_from_netcdf_files_in_many_threads(tmp_path):
    source = sf.write(sf.generate(RECIPE), tmp_path / "source.nc")
    with xr.open_dataset(source) as want:
        want = want.load()
    for k in range(6):
        # small chunks: many reads of the source beside many writes of the target, on the threads
        ds = sf.open_dataset(source, chunks={"mu": 1, "y": 5})
        target = sf.write(ds, tmp_path / f"copy{k}.nc")
        ds.close()
        with xr.open_dataset(target) as got:
            for name in RECIPE["output"]["variables"]:
                np.testing.assert_array_equal(got[name].values, want[name].values)
