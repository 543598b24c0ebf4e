"""`stressfields export FILE -o OUT.vtu`: a written dataset (NetCDF or Zarr) as a VTU that ParaView
opens (meshio, the optional ``fe`` extra).

- A grid output (dimensions among x, y, z) becomes structured cells: hexahedra over three varying
  coordinates, quads over two, line segments over one.
- A ``[points]`` output (dimension ``point``) becomes vertex cells at its nodes.
- Depth is drawn as -z (the body below the surface, as FE users draw it). The scalar arrays keep the
  dataset's meaning (``u_z`` positive into the body); the tensor ``stress`` and the vector
  ``displacement`` are given in the drawn frame, so sigma_xz, sigma_yz and u_z change sign in them.
- Every array's name carries its units (``sigma_xx [Pa]``).
- Every other dimension (a swept parameter) must have one value: a VTU holds one field per point.
"""
from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from ..errors import OutputError

SPATIAL = ("x", "y", "z")
STRESS = ("sigma_xx", "sigma_yy", "sigma_zz", "sigma_xy", "sigma_xz", "sigma_yz")


def export_vtu(source: str | os.PathLike, target: str | os.PathLike, *, overwrite: bool = False) -> Path:
    """Write ``target`` (.vtu) from the dataset at ``source``; OutputError (one line) if it cannot be."""
    try:
        import meshio
    except ImportError:
        raise OutputError("export to .vtu needs meshio: pip install 'stressfields[fe]'") from None
    from ..output.formats import check_target, format_for

    source, target = Path(source), Path(target)
    if not source.exists():
        raise OutputError(f"{source}: no such file or store")
    target = check_target(target, overwrite=overwrite)
    with format_for(source).read(source) as ds:
        mesh = to_mesh(ds.load(), str(source))
    tmp = target.with_name(f".{target.name}.{os.getpid()}.tmp.vtu")
    try:
        meshio.write(tmp, mesh, binary=True)
        os.replace(tmp, target)
    except OSError as exc:
        raise OutputError(f"{target}: {exc.strerror or exc}") from None
    finally:
        tmp.unlink(missing_ok=True)
    return target


def to_mesh(ds, label: str):
    """The meshio.Mesh of a dataset (module docstring)."""
    import meshio

    spatial = [d for d in SPATIAL if d in ds.dims]
    pointwise = "point" in ds.dims
    others = {d: n for d, n in ds.sizes.items() if d not in SPATIAL and d != "point" and n > 1}
    if others:
        d, n = next(iter(others.items()))
        raise OutputError(f"{label}: it sweeps {d!r} ({n} values); a VTU holds one field per point: export a "
                          f"recipe with one {d} value")
    ds = ds.isel({d: 0 for d in ds.dims if d not in SPATIAL and d != "point"})
    if pointwise:
        n = ds.sizes["point"]
        xyz = np.column_stack([_values(ds, a, ("point",), n) for a in SPATIAL])
        cells = [("vertex", np.arange(n).reshape(-1, 1))]
        order = ("point",)
    elif spatial:
        axes = [np.asarray(ds[a].values, dtype=float) if a in ds.dims else
                np.atleast_1d(float(ds[a].values) if a in ds.coords else 0.0) for a in SPATIAL]
        grid = np.meshgrid(*axes, indexing="ij")
        xyz = np.column_stack([g.ravel() for g in grid])
        cells = [_cells(tuple(len(a) for a in axes))]
        order = SPATIAL
    else:
        raise OutputError(f"{label}: no x, y, z dimension and no point dimension: nothing to draw")
    n = xyz.shape[0]
    point_data = {}
    for name, var in ds.data_vars.items():
        if var.dtype.kind not in "iuf" or not set(var.dims) <= set(order):
            continue
        unit = var.attrs.get("units", "1")
        key = f"{name} [{unit}]"
        point_data[key] = _values(ds, name, order, n)
    if all(s in ds for s in STRESS):
        t = {s: _values(ds, s, order, n) for s in STRESS}
        xx, yy, zz, xy, xz, yz = (t[s] for s in STRESS)
        xz, yz = -xz, -yz                    # the drawn frame: z up
        tensor = np.stack([xx, xy, xz, xy, yy, yz, xz, yz, zz], axis=1)
        point_data[f"stress [{ds['sigma_xx'].attrs.get('units', '1')}] (z up)"] = tensor
    if all(u in ds for u in ("u_x", "u_y", "u_z")):
        point_data[f"displacement [{ds['u_x'].attrs.get('units', '1')}] (z up)"] = np.column_stack(
            [_values(ds, "u_x", order, n), _values(ds, "u_y", order, n), -_values(ds, "u_z", order, n)])
    xyz = xyz.copy()
    xyz[:, 2] = -xyz[:, 2]                   # depth drawn downward
    return meshio.Mesh(xyz, cells, point_data=point_data)


def _values(ds, name: str, order: tuple, n: int) -> np.ndarray:
    """A variable (or coordinate) broadcast over the points in ``order`` (C order), as float64."""
    import xarray as xr

    if name not in ds.variables:
        return np.zeros(n)
    dims = [d for d in order if d in ds.dims]
    template = xr.DataArray(np.zeros([ds.sizes[d] for d in dims]), dims=dims)
    full = xr.DataArray(ds[name].variable).broadcast_like(template).transpose(*dims)
    return np.asarray(full.values, dtype=float).reshape(-1)


def _cells(shape: tuple[int, int, int]):
    """Cells of a structured grid of ``shape`` points (C order), of the dimension that varies."""
    idx = np.arange(int(np.prod(shape))).reshape(shape)
    varying = [k for k, s in enumerate(shape) if s > 1]
    if len(varying) == 3:
        c = idx[:-1, :-1, :-1], idx[1:, :-1, :-1], idx[1:, 1:, :-1], idx[:-1, 1:, :-1], \
            idx[:-1, :-1, 1:], idx[1:, :-1, 1:], idx[1:, 1:, 1:], idx[:-1, 1:, 1:]
        return "hexahedron", np.stack([a.ravel() for a in c], axis=1)
    sq = idx.squeeze()
    if len(varying) == 2:
        c = sq[:-1, :-1], sq[1:, :-1], sq[1:, 1:], sq[:-1, 1:]
        return "quad", np.stack([a.ravel() for a in c], axis=1)
    if len(varying) == 1:
        line = sq.ravel()
        return "line", np.column_stack([line[:-1], line[1:]])
    return "vertex", idx.reshape(-1, 1)
