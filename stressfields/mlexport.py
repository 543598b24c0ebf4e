"""ML-ready layouts of a written file: `export_layout(FILE, DIR, "well" | "parquet")`.

Both hold every point of the file as one sample (a point cloud, as AirfRANS does; a grid's points
keep their coordinates as inputs), split by the recipe's ``[splits]`` table (splits.py; stored in
the file's canonical recipe and so covered by its hashes) into train, valid and test:

- ``well`` (the layout of The Well): ``data/{train,valid,test}/<name>.hdf5`` (HDF5 through h5py):
  ``inputs/<coordinate or parameter>`` (n,), ``t0_fields/<scalar field>`` (n,), ``t1_fields/u``
  (n, 3) for the displacement, ``t2_fields/sigma`` (n, 3, 3) for the symmetric stress tensor,
  ``flags/<flag>`` (n,) int8, ``scalars/<fixed parameter>`` (0-d); ``stats.yaml`` (per field mean
  and std over the finite values of the train split only, per component; population std); and
  ``<name>.yaml`` (fields by tensor order, their components and units, the inputs, the constant
  scalars: fixed parameters with their values, swept parameters per sample, the splits).
- ``parquet``: ``{train,valid,test}.parquet``, one row per point and one column per input,
  component and flag (needs pyarrow: the ``ml`` extra), with the same ``stats.yaml`` and metadata.

Both write ``croissant.json``, a Croissant 1.0 JSON-LD card (distribution with SHA-256 per file,
the splits, how the data were made and the accuracy contract). The directory appears complete or
not at all: it is written beside the target under a temporary name and renamed.
"""
from __future__ import annotations

import hashlib
import json
import os
import shutil
from pathlib import Path

import numpy as np

from .errors import OutputError
from .splits import CODES

LAYOUTS = ("well", "parquet")
#: the points of a file an export holds in memory at once (fields, inputs and the split)
MAX_POINTS = 50_000_000
STRESS = ("sigma_xx", "sigma_xy", "sigma_xz", "sigma_xy", "sigma_yy", "sigma_yz", "sigma_xz", "sigma_yz", "sigma_zz")
DISPLACEMENT = ("u_x", "u_y", "u_z")


def export_layout(source: str | os.PathLike, target: str | os.PathLike, layout: str, *,
                  overwrite: bool = False) -> Path:
    """Write the file ``source`` (NetCDF or Zarr, its content hash verified first) into the directory
    ``target`` in ``layout``; returns ``target``. Raises OutputError (one line) for a file without
    [splits], a split left empty of train points, a missing pyarrow, or a target that exists."""
    from .output.form import encode_choices
    from .output.formats import verify
    from .reading import open_dataset

    if layout not in LAYOUTS:
        raise OutputError(f"--layout {layout!r} must be one of {', '.join(LAYOUTS)}")
    import importlib.util

    needs = "pyarrow" if layout == "parquet" else "h5py"
    if importlib.util.find_spec(needs) is None:
        raise OutputError(f"--layout {layout} needs {needs}: pip install 'stressfields[ml]'")
    source, target = Path(source), Path(target)
    if not source.exists():
        raise OutputError(f"{source}: no such file or store")
    if os.path.lexists(target) and not (overwrite and target.is_dir()):
        raise OutputError(f"{target} exists; give --overwrite to replace it" if target.is_dir() else
                          f"{target} exists and is not a directory")
    digest = verify(source)
    with open_dataset(source) as decoded:
        canonical = json.loads(decoded.attrs.get("stressfields_recipe_canonical", "{}"))
        spec = canonical.get("splits")
        if not spec:
            raise OutputError(f"{source}: its recipe has no [splits] table; declare train/valid/test there "
                              "(e.g. [splits] seed = 1, valid = { fraction = 0.1 }, test = { fraction = 0.1 })")
        size = int(np.prod([decoded.sizes[d] for d in decoded.dims], dtype=np.int64))
        if size > MAX_POINTS:
            raise OutputError(f"{source}: {size:,} points; an ML export holds at most {MAX_POINTS:,} in memory")
        table = flatten(encode_choices(decoded).load())
    from .splits import assign

    try:
        code = assign(spec, {**table["inputs"], **table["edges"]}, table["n"])
    except ValueError as exc:
        raise OutputError(f"{source}: {exc}") from None
    name = source.name.split(".")[0]
    tmp = target.with_name(f".{target.name}.{os.getpid()}.tmp")
    shutil.rmtree(tmp, ignore_errors=True)
    try:
        tmp.mkdir(parents=True)
        files = (_write_well if layout == "well" else _write_parquet)(tmp, name, table, code)
        meta = metadata(name, table, code, spec, digest, decoded.attrs, layout)
        _yaml(tmp / "stats.yaml", stats(table, code))
        _yaml(tmp / f"{name}.yaml", meta)
        files += [tmp / "stats.yaml", tmp / f"{name}.yaml"]
        (tmp / "croissant.json").write_text(json.dumps(card(name, tmp, files, table, meta, layout, decoded.attrs),
                                                       indent=2) + "\n", encoding="utf-8")
        if os.path.lexists(target):
            old = target.with_name(f".{target.name}.{os.getpid()}.old")
            os.rename(target, old)
            os.rename(tmp, target)
            shutil.rmtree(old, ignore_errors=True)
        else:
            os.rename(tmp, target)
    except OSError as exc:
        raise OutputError(f"{target}: {exc.strerror or exc}") from None
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return target


def flatten(ds) -> dict:
    """Every point of ``ds`` as columns: ``inputs`` (coordinates and parameters that vary), ``fields``
    {name: (n,) or (n, 3) or (n, 3, 3) float}, ``flags`` {name: (n,) int8}, ``constants`` (fixed
    parameters), ``edges`` (contact_radius, stick_radius per point, for region splits), the
    fields' ``order`` (tensor rank), ``components``, ``units`` and ``n``."""
    import xarray as xr

    dims = max((v.dims for v in ds.data_vars.values()), key=len)
    shape = tuple(ds.sizes[d] for d in dims)
    n = int(np.prod(shape, dtype=np.int64))

    def column(var):
        return np.ascontiguousarray(xr.broadcast(var, xr.DataArray(np.empty(shape), dims=dims))[0]
                                    .transpose(*dims).values).reshape(n)
    inputs, constants, labels = {}, {}, {}
    for name, var in ds.coords.items():
        name = str(name)
        if name.endswith("_name"):
            labels[name[:-5]] = [str(v) for v in np.atleast_1d(var.values)]
        elif var.ndim == 0:
            constants[name] = var.values.item()
        elif var.dtype.kind in "iuf":
            inputs[name] = column(var)
    for name, var in ds.data_vars.items():          # the recipe's arrays (wavy amplitudes): constants
        if var.dims and all(d.endswith("_index") for d in var.dims):
            constants[str(name)] = var.values.tolist()
    floats = {str(k): v for k, v in ds.data_vars.items() if v.dtype.kind == "f" and "flag_values" not in v.attrs
              and not any(d.endswith("_index") for d in v.dims)}
    flags = {str(k): column(v).astype(np.int8) for k, v in ds.data_vars.items() if "flag_values" in v.attrs}
    fields, order, components, units = {}, {}, {}, {}
    groups = (("sigma", STRESS, 2), ("u", DISPLACEMENT, 1))
    taken = set()
    for name, parts, rank in groups:
        if all(p in floats for p in set(parts)):
            cols = {p: column(floats[p]) for p in set(parts)}
            stacked = np.stack([cols[p] for p in parts], axis=-1)
            fields[name] = stacked.reshape((n, 3, 3) if rank == 2 else (n, 3))
            order[name], units[name] = rank, floats[parts[0]].attrs.get("units", "")
            components[name] = [list(parts[i:i + 3]) for i in range(0, 9, 3)] if rank == 2 else list(parts)
            taken |= set(parts)
    for name, var in floats.items():
        if name not in taken:
            fields[name], order[name], units[name] = column(var), 0, var.attrs.get("units", "")
    edges = {k: fields[k] for k in ("contact_radius", "stick_radius") if k in fields and order[k] == 0}
    return {"n": n, "dims": list(dims), "shape": list(shape), "inputs": inputs, "constants": constants,
            "labels": labels, "fields": fields, "flags": flags, "order": order, "components": components,
            "units": units, "edges": edges,
            "input_units": {k: ds.coords[k].attrs.get("units", "") for k in inputs}}


def stats(table: dict, code: np.ndarray) -> dict:
    """Mean and std (population, ``np.std``) of every field over the finite values of the train split,
    per component (a list for rank 1, a 3x3 nested list for rank 2); NaN where a component has none."""
    train = code == CODES["train"]
    out = {"mean": {}, "std": {}}
    for name, values in table["fields"].items():
        v = values[train]
        mean, std = np.full(v.shape[1:], np.nan), np.full(v.shape[1:], np.nan)
        for index in np.ndindex(v.shape[1:]):
            x = v[(slice(None), *index)]
            x = x[np.isfinite(x)]
            if x.size:
                mean[index], std[index] = np.mean(x), np.std(x)
        out["mean"][name], out["std"][name] = _plain(mean), _plain(std)
    return out


def _plain(a):
    a = np.asarray(a, dtype=float)
    return float(a) if a.ndim == 0 else a.tolist()


def metadata(name, table, code, spec, digest, attrs, layout) -> dict:
    spatial = [d for d in ("x", "y", "z") if d in table["inputs"]]
    grid = "point" not in table["dims"]
    return {
        "dataset_name": name,
        "layout": layout,
        "n_spatial_dims": len(spatial),
        "spatial_names": spatial,
        "grid_type": "cartesian (flattened to points)" if grid else "point_cloud",
        "spatial_resolution": [table["shape"][table["dims"].index(d)] for d in table["dims"] if d in spatial]
        if grid else [table["n"]],
        "dims": table["dims"],
        "field_names": {r: [f for f, o in table["order"].items() if o == r] for r in (0, 1, 2)},
        "field_components": table["components"],
        "field_units": table["units"],
        "input_names": list(table["inputs"]),
        "input_units": table["input_units"],
        "flag_names": list(table["flags"]),
        "scalar_names": [],
        # The Well's constant scalars: the swept parameters (per sample) and the fixed ones (values below)
        "constant_scalar_names": [k for k in table["inputs"] if k not in spatial] + list(table["constants"]),
        "constant_scalars": table["constants"],
        "choice_labels": table["labels"],
        "n_samples": {s: int((code == c).sum()) for s, c in CODES.items()},
        "splits": spec,
        "source_content_sha256": digest,
        "stressfields_version": str(attrs.get("stressfields_version", "")),
        "scenario": str(attrs.get("stressfields_scenario", "")),
    }


def _write_well(folder: Path, name: str, table: dict, code: np.ndarray) -> list[Path]:
    import h5py

    files = []
    for split, c in CODES.items():
        mask = code == c
        path = folder / "data" / split / f"{name}.hdf5"
        path.parent.mkdir(parents=True, exist_ok=True)
        with h5py.File(path, "w") as f:
            f.attrs["dataset_name"], f.attrs["split"], f.attrs["n_samples"] = name, split, int(mask.sum())
            for group, columns in (("inputs", table["inputs"]), ("flags", table["flags"])):
                g = f.create_group(group)
                for k, v in columns.items():
                    g.create_dataset(k, data=v[mask])
            groups = {r: f.create_group(f"t{r}_fields") for r in (0, 1, 2)}
            for k, v in table["fields"].items():
                d = groups[table["order"][k]].create_dataset(k, data=v[mask])
                d.attrs["units"] = table["units"][k]
            scalars = f.create_group("scalars")
            for k, v in table["constants"].items():
                scalars.create_dataset(k, data=np.asarray(v))
        files.append(path)
    return files


def parquet_columns(table: dict, mask: np.ndarray) -> dict:
    """The columns of one parquet file: inputs, every component of every field, flags."""
    cols = {k: v[mask] for k, v in table["inputs"].items()}
    for k, v in table["fields"].items():
        rank = table["order"][k]
        if rank == 0:
            cols[k] = v[mask]
        else:
            names = table["components"][k] if rank == 1 else sum(table["components"][k], [])
            flat = v[mask].reshape(int(mask.sum()), 3 if rank == 1 else 9)
            for i, comp in enumerate(names):
                cols.setdefault(comp, flat[:, i])
    cols.update({k: v[mask] for k, v in table["flags"].items()})
    return cols


def _write_parquet(folder: Path, name: str, table: dict, code: np.ndarray) -> list[Path]:
    import pyarrow as pa
    import pyarrow.parquet as pq

    files = []
    for split, c in CODES.items():
        path = folder / f"{split}.parquet"
        pq.write_table(pa.table(parquet_columns(table, code == c)), path)
        files.append(path)
    return files


def _yaml(path: Path, data) -> None:
    import yaml

    path.write_text(yaml.safe_dump(data, sort_keys=False, width=120), encoding="utf-8")


def _sha256(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


CROISSANT_CONTEXT = {
    "@language": "en", "@vocab": "https://schema.org/", "citeAs": "cr:citeAs", "column": "cr:column",
    "conformsTo": "dct:conformsTo", "cr": "http://mlcommons.org/croissant/", "rai": "http://mlcommons.org/croissant/RAI/",
    "data": {"@id": "cr:data", "@type": "@json"}, "dataType": {"@id": "cr:dataType", "@type": "@vocab"},
    "dct": "http://purl.org/dc/terms/", "examples": {"@id": "cr:examples", "@type": "@json"},
    "extract": "cr:extract", "field": "cr:field", "fileProperty": "cr:fileProperty", "fileObject": "cr:fileObject",
    "fileSet": "cr:fileSet", "format": "cr:format", "includes": "cr:includes", "isLiveDataset": "cr:isLiveDataset",
    "jsonPath": "cr:jsonPath", "key": "cr:key", "md5": "cr:md5", "parentField": "cr:parentField", "path": "cr:path",
    "recordSet": "cr:recordSet", "references": "cr:references", "regex": "cr:regex", "repeated": "cr:repeated",
    "replace": "cr:replace", "sc": "https://schema.org/", "separator": "cr:separator", "source": "cr:source",
    "subField": "cr:subField", "transform": "cr:transform", "samplingRate": "cr:samplingRate",
    "equivalentProperty": "cr:equivalentProperty",
}


def card(name, folder, files, table, meta, layout, attrs) -> dict:
    """A Croissant 1.0 JSON-LD card: the files with their SHA-256, one record set per split (parquet:
    its columns as fields; well: the HDF5 files, which Croissant cannot address inside), how the data
    were made and the accuracy contract the values keep."""
    contract = str(attrs.get("stressfields_accuracy_contract", ""))
    description = (f"{attrs.get('title', name)}. Exact contact-mechanics fields computed by stressfields "
                   f"{attrs.get('stressfields_version', '')} (scenario '{attrs.get('stressfields_scenario', '')}') "
                   "from closed forms and 1-D integrals, split into train/valid/test by the recipe's [splits] "
                   f"table {json.dumps(meta['splits'], sort_keys=True)}. Accuracy contract:\n{contract}")
    encoding = {"well": "application/x-hdf5", "parquet": "application/x-parquet", "yaml": "application/x-yaml"}
    distribution = []
    for path in files:
        rel = path.relative_to(folder).as_posix()
        distribution.append({"@type": "cr:FileObject", "@id": rel, "name": rel, "contentUrl": rel,
                             "encodingFormat": encoding["yaml" if rel.endswith(".yaml") else layout],
                             "sha256": _sha256(path)})
    record_sets = []
    if layout == "parquet":
        columns = parquet_columns(table, np.zeros(table["n"], dtype=bool))
        for split in CODES:
            fields = []
            for col, values in columns.items():
                kind = "sc:Float" if values.dtype.kind == "f" else "sc:Integer"
                fields.append({"@type": "cr:Field", "@id": f"{split}/{col}", "name": col, "dataType": kind,
                               "source": {"fileObject": {"@id": f"{split}.parquet"}, "extract": {"column": col}}})
            record_sets.append({"@type": "cr:RecordSet", "@id": split, "name": split,
                                "description": f"the {split} split: one record per point", "field": fields})
    return {
        "@context": CROISSANT_CONTEXT,
        "@type": "sc:Dataset",
        "name": name,
        "description": description,
        "conformsTo": "http://mlcommons.org/croissant/1.0",
        "license": "https://opensource.org/licenses/MIT",
        "version": str(attrs.get("stressfields_version", "0.0.0")),
        "citeAs": str(attrs.get("references", "")),
        "distribution": distribution,
        "recordSet": record_sets,
    }
