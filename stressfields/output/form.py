"""A dataset in its on-disk form, the same for every format (`prepare`): string-labelled choice
dimensions become CF flag coordinates (`encode_choices`), and the output options (dtype,
non-finite values; `options.OutputOptions`) are applied lazily and recorded in the global attribute
``stressfields_output``, from which each format derives its own encoding. A dataset whose
coordinates go beyond the recipe it carries is refused first (`check_provenance`).
"""
from __future__ import annotations

import numpy as np
import xarray as xr

from ..errors import OutputError
from .options import FLOAT32_NOTE, OPTIONS_ATTR, OutputOptions

#: the global attribute of a dataset merged from files of several recipes (`reading.open_mfdataset`):
#: the SHA-256 of every source recipe
SOURCES_ATTR = "stressfields_source_recipe_sha256"


def encode_choices(ds: xr.Dataset) -> xr.Dataset:
    """The CF form of string-labelled dimensions (a sweep over choices): CF coordinate variables
    must be numeric, so the labels become int8 codes with ``flag_values``/``flag_meanings``, and the
    names stand beside them as the auxiliary string coordinate ``<name>_name``. Datasets already in
    that form are returned unchanged (`reading.decode_choices` is the inverse)."""
    labelled = [d for d in ds.dims if d in ds.coords and ds[d].dims == (d,) and ds[d].dtype.kind in "OUT"]
    if not labelled:
        return ds
    coords, data_vars = {}, {}
    for name, var in ds.variables.items():
        if name not in labelled:
            (coords if name in ds.coords else data_vars)[name] = var
            continue
        labels = [str(v) for v in var.values]
        bad = [label for label in labels if not label or any(c.isspace() for c in label)]
        if bad or len(set(labels)) != len(labels) or len(labels) > 127:
            raise OutputError(f"dimension {name!r}: its labels must be at most 127 distinct words without "
                              f"blanks (CF flag_meanings); got {labels[:10]}")
        codes = np.arange(len(labels), dtype=np.int8)
        attrs = {**var.attrs, "flag_values": codes, "flag_meanings": " ".join(labels)}
        coords[name] = xr.Variable((name,), codes, attrs)
        coords[f"{name}_name"] = xr.Variable((name,), np.array(labels, dtype=object),
                                             {"long_name": f"{var.attrs.get('long_name', name)} (name)",
                                              "coverage_content_type": "coordinate"})
    return xr.Dataset(data_vars, coords=coords, attrs=ds.attrs)


def check_provenance(ds: xr.Dataset) -> None:
    """Refuse a dataset whose coordinates go beyond the recipe it carries: merged from files of
    other recipes by a reader that kept the first file's attributes (``xr.open_mfdataset``'s default).
    Written as it is, the file would claim a recipe that did not make it. A selection of a recipe's
    points (``ds.sel(mu=0.3)``) stays within it and passes; `reading.open_mfdataset` records every
    source recipe instead of one (``stressfields_source_recipe_sha256``) and passes too."""
    import json

    canonical = ds.attrs.get("stressfields_recipe_canonical")
    if not canonical or SOURCES_ATTR in ds.attrs:
        return
    try:
        params = json.loads(canonical).get("parameters", {})
    except (ValueError, AttributeError):
        return
    for dim in ds.dims:
        swept = params.get(dim)
        if dim not in ds.coords or not isinstance(swept, list) or ds[dim].ndim != 1:
            continue
        values = np.asarray(ds[dim].values)
        if "flag_meanings" in ds[dim].attrs:        # a choice in its stored form: codes -> names
            codes = np.ravel(ds[dim].attrs["flag_values"]).tolist()
            names = dict(zip(codes, str(ds[dim].attrs["flag_meanings"]).split()))
            values = np.array([names.get(v, v) for v in values.tolist()], dtype=object)
        kind = object if values.dtype.kind in "OUT" or any(isinstance(v, str) for v in swept) else float
        values = values.astype(kind)
        beyond = ~np.isin(values, np.asarray(swept, dtype=kind))
        if beyond.any():
            recipe, first = str(ds.attrs.get("stressfields_recipe_sha256", ""))[:16], _plain(values[beyond][0])
            raise OutputError(f"{dim} = {first!r} is not a value of the recipe this dataset carries "
                              f"(stressfields_recipe_sha256 {recipe}): merged from files of other recipes? open them "
                              "with sf.open_mfdataset, which records every source recipe")


def _plain(value):
    return value.item() if isinstance(value, np.generic) else value


def prepare(ds: xr.Dataset, options: OutputOptions | None = None) -> xr.Dataset:
    """``ds`` in its on-disk form for ``options`` (default `OutputOptions()`): choices as CF flags,
    float32 and non-finite values applied lazily, the options recorded in ``stressfields_output``.
    A dataset whose coordinates go beyond its own recipe is refused (`check_provenance`)."""
    options = options or OutputOptions()
    check_provenance(ds)
    ds = encode_choices(ds)
    changed = {}
    for name, var in ds.data_vars.items():
        out = _stored(name, var, options)
        if out is not var:
            changed[name] = out
    if changed:
        ds = ds.assign(changed)
    else:
        ds = ds.copy(deep=False)        # the caller's dataset keeps its attributes
    ds.attrs = {**ds.attrs, OPTIONS_ATTR: options.text()}
    return ds


def _stored(name: str, var: xr.DataArray, options: OutputOptions) -> xr.DataArray:
    """One data variable as stored: float32 (an error bound rounded upwards, so it stays a bound)
    and +-inf -> NaN for ``nan``/``fill``. The recipe's array inputs (dims ``<name>_index``) are kept."""
    if var.dtype.kind != "f" or var.dims == (f"{name}_index",):
        return var
    single = options.dtype == "float32"
    if not single and options.nonfinite == "keep":
        return var
    convert = _converter(name, single, upward="error_estimate" in name, no_inf=options.nonfinite != "keep")
    dtype = np.float32 if single else var.dtype
    if hasattr(var.data, "map_blocks"):
        data = var.data.map_blocks(convert, dtype=dtype)
    else:
        data = convert(np.asarray(var.values))
    out = var.copy(data=data)
    if single and "stressfields_accuracy" in out.attrs:
        out.attrs["stressfields_accuracy"] = f"{out.attrs['stressfields_accuracy'].rstrip()} {FLOAT32_NOTE}"
    return out


def _converter(name: str, single: bool, upward: bool, no_inf: bool):
    def convert(block: np.ndarray) -> np.ndarray:
        out = block
        if single:
            with np.errstate(over="ignore"):     # an overflow is refused just below
                out = block.astype(np.float32)
            overflow = np.isinf(out) & np.isfinite(block)
            if overflow.any():    # a finite value must never read as unbounded
                raise OutputError(f"{name}: the finite value {block[overflow].flat[0]:.6g} exceeds the float32 "
                                  "range (3.4e38); write it as float64")
            if upward:
                low = out.astype(block.dtype) < block
                out[low] = np.nextafter(out[low], np.float32(np.inf))
        if no_inf:
            out = np.where(np.isinf(out), out.dtype.type(np.nan), out)
        return out
    return convert


def stored_bytes(ds: xr.Dataset, options: OutputOptions | None = None) -> int:
    """The bytes the values of ``ds`` take when stored with ``options`` (`prepare`; uncompressed, so
    an upper bound for compressed output): what a run must find free before it starts. From the
    shapes and dtypes alone, nothing computed."""
    prepared = prepare(ds, options)
    return int(sum(v.size * v.dtype.itemsize for v in prepared.variables.values()))
