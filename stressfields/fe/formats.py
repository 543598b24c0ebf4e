"""Read an FE model's nodes as they come out of the solver: CSV with the common FE header forms,
NetCDF, Exodus II (a NetCDF schema: read with netCDF4 alone), and through meshio (the optional ``fe``
extra) VTU/VTK, XDMF, MED and Gmsh. The format is told by the file's first bytes (then its suffix);
XML is never parsed as CSV.

Every reader gives tables of columns (one per time step of an Exodus file, one for the nodes and one
for the element centroids), each column with the canonical name of its header (``X[mm]`` -> ``x`` in
mm, ``Node Label`` -> ``node``, ``S-S11`` -> ``sigma_xx``), the unit as written (None where the format
carries none: VTU and Exodus II take theirs from ``--units``) and its values as float64. No message
quotes the file's content: a line and column index and the user's column names only.
"""
from __future__ import annotations

import os
import re
import stat
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..units import LABEL_RULE, canonical, parse_label

#: a file of nodes is read whole: 1 GB holds ~1e7 nodes of a dozen columns
MAX_NODE_FILE_BYTES = 1_000_000_000
#: at most this many nodes per table (a recipe's [points] takes 1e7)
MAX_NODES = 10_000_000
MESHIO_SUFFIXES = (".vtu", ".vtk", ".xdmf", ".xmf", ".med", ".msh")
EXODUS_SUFFIXES = (".e", ".exo", ".ex2", ".exodus")
FORMATS = "CSV, NetCDF (.nc), Exodus II (" + ", ".join(EXODUS_SUFFIXES) + "), " + ", ".join(MESHIO_SUFFIXES)

#: vector and tensor arrays of a mesh file: name (lower case) -> component prefix
VECTORS = ("u", "displacement", "displacements", "disp")
TENSORS = ("sigma", "stress", "s", "cauchy_stress")


class FormatProblem(ValueError):
    """Why a file of nodes cannot be read (one line; the caller names the file)."""


@dataclass
class Column:
    name: str               # canonical (sigma_xx, x, node, r, sigma_rr, ...)
    label: str              # as the file gives it
    unit: str | None        # as written; None: the file gives none
    values: np.ndarray
    component: bool = False     # a mesh's coordinate, or a component of its vector or tensor array


@dataclass
class Table:
    """One set of nodes with their columns (a file, a time step of a file, or element centroids)."""
    label: str
    columns: list[Column]
    dim: int | None = None          # the mesh's dimension (2: a 2-D mesh), None: not a mesh
    carries_units: bool = True      # False: VTU, Exodus II, ... (units from --units)
    extra: dict = field(default_factory=dict)




# --- the entry point ----------------------------------------------------------------------------

def read_nodes(path: str | Path, *, step: int | None = None) -> list[Table]:
    """The tables of a file of nodes (see the module docstring); FormatProblem if it cannot be read.

    ``step`` (from 1) picks one time step of an Exodus II file; None: every step."""
    path = Path(path)
    head = _head(path)
    suffix = path.suffix.lower()
    if head.startswith((b"CDF", b"\x89HDF")) and suffix not in (".med", ".xdmf", ".xmf"):
        if _is_exodus(path):
            return read_exodus(path, step=step)
        if step is not None:
            raise FormatProblem(f"--step {step}: the file has no time steps (not an Exodus II file)")
        return [_plain_netcdf(path)]
    if step is not None:
        raise FormatProblem(f"--step {step}: only an Exodus II file has time steps")
    xml = head.lstrip(b"\xef\xbb\xbf \t\r\n").startswith(b"<")
    if suffix in MESHIO_SUFFIXES or xml or head.startswith((b"# vtk DataFile", b"$MeshFormat")):
        if xml and suffix not in MESHIO_SUFFIXES:
            raise FormatProblem(f"an XML file with the suffix {suffix or '(none)'!r}; give VTU as .vtu, XDMF as "
                                ".xdmf (known formats: " + FORMATS + ")")
        return read_meshio(path)
    if b"\x00" in head or suffix not in (".csv", ".txt", ".rpt", ".dat", ""):
        raise FormatProblem(f"unknown format (suffix {suffix or '(none)'!r}, not text); known formats: {FORMATS}")
    return [read_csv(path)]


def _head(path: Path) -> bytes:
    try:
        info = os.stat(path)
    except OSError as exc:
        raise FormatProblem(f"cannot read it ({exc.strerror})") from None
    if not stat.S_ISREG(info.st_mode):
        raise FormatProblem("not a regular file")
    if info.st_size > MAX_NODE_FILE_BYTES:
        raise FormatProblem(f"{info.st_size:,} bytes; a file of nodes has at most {MAX_NODE_FILE_BYTES:,}")
    if info.st_size == 0:
        raise FormatProblem("the file is empty")
    try:
        with open(path, "rb") as handle:
            return handle.read(4096)
    except OSError as exc:
        raise FormatProblem(f"cannot read it ({exc.strerror})") from None


def _columns(pairs, table_label: str) -> list[Column]:
    """Columns from (header, values): canonical names, each name once."""
    out, seen = [], {}
    for header, values in pairs:
        name, unit = canonical(str(header))
        if not name:
            raise FormatProblem(f"a column has an empty name ({table_label})")
        if name in seen:
            raise FormatProblem(f"columns {seen[name]!r} and {str(header).strip()!r} both name {name!r}")
        seen[name] = str(header).strip()
        arr = np.asarray(values)
        if arr.dtype.kind not in "iuf":
            raise FormatProblem(f"column {str(header).strip()!r} is not numbers")
        out.append(Column(name, str(header).strip(), unit, arr.astype(np.float64, copy=False)))
    if not out:
        raise FormatProblem("it has no columns")
    n = out[0].values.size
    if n > MAX_NODES:
        raise FormatProblem(f"{n:,} nodes; at most {MAX_NODES:,}")
    return out


# --- CSV -----------------------------------------------------------------------------------------

def read_csv(path: Path) -> Table:
    """A CSV read as a `[points] file` is (`pointfiles.csv_header`, `csv_values`: one parse by pandas'
    C reader into float64, a 1e6-row file of eight columns in ~0.6 s here): `#` comment lines, a header
    naming the columns (the FE forms of ``canonical``), rows of numbers. A bad value is named by its
    data row (from 0), line and column header only."""
    from ..pointfiles import FileProblem, csv_header, csv_values, file_bytes

    try:
        # resolved first: the reader follows no symbolic link, and the user may name one
        raw = file_bytes(Path(os.path.realpath(path)), str(path), MAX_NODE_FILE_BYTES)
        headers, line, start = csv_header(raw)
        for k, h in enumerate(headers):
            if parse_label(h) is None:      # not quoted: a file that is no CSV of nodes may hold anything
                raise FormatProblem(f"column {k + 1} (from 1) of the header is not {LABEL_RULE}")
        data = csv_values(raw, start, headers, line, by_row=True)
    except FileProblem as exc:
        raise FormatProblem(str(exc)) from None
    missing = np.isnan(data)
    if missing.any():
        row, k = map(int, np.argwhere(missing)[0])
        raise FormatProblem(f"data row {row} (from 0), column {headers[k]!r}: NaN; every value must be a number")
    return Table(str(path), _columns(((h, data[:, k]) for k, h in enumerate(headers)), str(path)))


# --- NetCDF and Exodus II ------------------------------------------------------------------------

def _is_exodus(path: Path) -> bool:
    import netCDF4

    try:
        with netCDF4.Dataset(path, "r") as ds:
            return "coordx" in ds.variables or ("coord" in ds.variables and "num_nodes" in ds.dimensions)
    except (OSError, RuntimeError, ValueError):
        raise FormatProblem("not a readable NetCDF file") from None


def _plain_netcdf(path) -> Table:
    """A NetCDF file of nodes along one dimension (units from ``units`` attributes), or the same as an
    xr.Dataset in memory."""
    from ..comparison import CompareError, read_user_data

    try:
        columns, label = read_user_data(path)
    except CompareError as exc:         # its message names the file already: keep what follows
        raise FormatProblem(str(exc).split(": ", 1)[-1]) from None
    return _same_length(Table(label, _columns(((c.label + (f"[{c.unit}]" if c.unit else ""), c.values)
                                               for c in columns), label)))


def user_table(data) -> Table:
    """An xr.Dataset along one dimension, or a mapping of header (``sigma_xx[MPa]``) -> values, as a
    table (`sf.compare`'s user data in memory): a column without a unit is in the declared one."""
    from collections.abc import Mapping

    if not isinstance(data, Mapping) or hasattr(data, "data_vars"):
        return _plain_netcdf(data)
    pairs = []
    for header, values in data.items():
        arr = np.asarray(values)
        if arr.ndim != 1 or arr.dtype.kind not in "iuf":
            raise FormatProblem(f"column {str(header).strip()!r}: must be one column of numbers")
        pairs.append((header, arr))
    return _same_length(Table("the user data", _columns(pairs, "the user data")))


def _same_length(table: Table) -> Table:
    lengths = {c.label: c.values.size for c in table.columns}
    if len(set(lengths.values())) != 1 or not table.columns[0].values.size:
        raise FormatProblem("the columns must have one length of at least 1; "
                            + ", ".join(f"{k} has {n}" for k, n in lengths.items()))
    return table


def _names(ds, var: str) -> list[str]:
    """An Exodus name array (char, len_string) as strings."""
    if var not in ds.variables:
        return []
    import netCDF4

    raw = ds.variables[var][:]
    return [n.strip() for n in netCDF4.chartostring(np.ma.filled(raw, b"")).tolist()]


def read_exodus(path: Path, *, step: int | None = None) -> list[Table]:
    """Exodus II (the NetCDF schema of MOOSE, Cubit, Sierra): node coordinates ``coordx/y/z`` (or
    ``coord``), nodal variables named by ``name_nod_var`` in ``vals_nod_var{i}(time_step, num_nodes)``
    (or one ``vals_nod_var(time_step, num_nod_var, num_nodes)``), element variables
    ``vals_elem_var{i}eb{j}`` at the centroids of the elements of block j (``connect{j}``). One table
    per time step (``step``, from 1: that one only) and kind (nodes, element centroids)."""
    import netCDF4

    label = str(path)
    try:
        ds = netCDF4.Dataset(path, "r")
    except (OSError, RuntimeError, ValueError):
        raise FormatProblem("not a readable NetCDF (Exodus II) file") from None
    with ds:
        ds.set_auto_mask(False)
        try:
            dim = int(len(ds.dimensions["num_dim"])) if "num_dim" in ds.dimensions else None
            if "coordx" in ds.variables:
                axes = [ds.variables[f"coord{a}"][:] for a in "xyz" if f"coord{a}" in ds.variables]
            else:
                axes = list(ds.variables["coord"][:])
            dim = dim or len(axes)
            xyz = np.stack([np.asarray(a, dtype=np.float64) for a in axes[:dim]], axis=1)
            steps = len(ds.dimensions["time_step"]) if "time_step" in ds.dimensions else 0
            times = ds.variables["time_whole"][:] if "time_whole" in ds.variables else np.arange(1, steps + 1)
            if step is not None and not 1 <= step <= steps:
                raise FormatProblem(f"--step {step} is not a time step of the file: it has {steps} (1 to {steps})")
            chosen = [step] if step is not None else list(range(1, steps + 1))
            nod_names = _names(ds, "name_nod_var")
            elem_names = _names(ds, "name_elem_var")
            blocks = sorted(int(m.group(1)) for v in ds.variables if (m := re.fullmatch(r"connect(\d+)", v)))
            centroids = ([_centroids(ds, xyz, b) for b in blocks] if elem_names else [])
            tables = []
            for s in chosen:
                tag = f"{label} step {s} (time {float(times[s - 1]):g})" if steps > 1 or step else label
                nodal = []
                for i, name in enumerate(nod_names, 1):
                    if f"vals_nod_var{i}" in ds.variables:
                        nodal.append((name, ds.variables[f"vals_nod_var{i}"][s - 1, :]))
                    elif "vals_nod_var" in ds.variables:
                        nodal.append((name, ds.variables["vals_nod_var"][s - 1, i - 1, :]))
                if nodal:
                    tables.append(Table(tag, _mesh_columns(xyz, nodal, tag), dim=dim, carries_units=False,
                                        extra={"step": s, "time": float(times[s - 1]), "kind": "nodes"}))
                if elem_names and centroids:
                    values = []
                    for i, name in enumerate(elem_names, 1):
                        parts = [ds.variables[f"vals_elem_var{i}eb{b}"][s - 1, :] if f"vals_elem_var{i}eb{b}"
                                 in ds.variables else np.full(len(c), np.nan) for b, c in zip(blocks, centroids)]
                        values.append((name, np.concatenate(parts)))
                    tables.append(Table(f"{tag}, element centroids", _mesh_columns(
                        np.concatenate(centroids), values, tag), dim=dim, carries_units=False,
                        extra={"step": s, "time": float(times[s - 1]), "kind": "element centroids"}))
        except FormatProblem:
            raise
        except (KeyError, IndexError, ValueError, RuntimeError, OSError) as exc:
            raise FormatProblem(f"not a readable Exodus II file ({type(exc).__name__} reading its variables)") from None
    if not tables:
        raise FormatProblem("the Exodus II file has no time step with nodal or element variables")
    return tables


def _centroids(ds, xyz: np.ndarray, block: int) -> np.ndarray:
    connect = np.asarray(ds.variables[f"connect{block}"][:], dtype=np.int64) - 1      # Exodus counts from 1
    if connect.min() < 0 or connect.max() >= len(xyz):
        raise FormatProblem(f"connect{block} names nodes outside 1..{len(xyz)}")
    return xyz[connect].mean(axis=1)


def _mesh_columns(xyz: np.ndarray, arrays, label: str) -> list[Column]:
    """Coordinate columns x, y(, z) of a mesh and its named arrays: scalars as they are, vectors
    (u, displacement) as u_x, u_y(, u_z), full 3x3 tensors (sigma, stress) as the six components."""
    pairs = [(a, xyz[:, k]) for k, a in enumerate("xyz"[: xyz.shape[1]])]
    parts = set(range(len(pairs)))          # the columns a frame may rename (coordinates, components)
    n = xyz.shape[0]
    for name, values in arrays:
        arr = np.asarray(values)
        key = str(name).strip()
        low = re.sub(r"[\s\-]+", "_", key).lower()
        if arr.shape[:1] != (n,):
            raise FormatProblem(f"array {key!r} has {arr.shape[0] if arr.ndim else 0} values for {n} points")
        if arr.ndim == 1 or (arr.ndim == 2 and arr.shape[1] == 1):
            pairs.append((key, arr.reshape(n)))
            continue
        start = len(pairs)
        if low in VECTORS and arr.ndim == 2 and arr.shape[1] in (2, 3):
            pairs += [(f"u_{a}", arr[:, k]) for k, a in enumerate("xyz"[: arr.shape[1]])]
        elif low in TENSORS and arr.size == 9 * n:
            t = arr.reshape(n, 3, 3)
            pairs += [(f"sigma_{'xyz'[i]}{'xyz'[j]}", t[:, i, j]) for i, j in
                      ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))]
        else:
            raise FormatProblem(f"array {key!r} has shape {arr.shape}: give scalars, a displacement vector "
                                "(u, displacement) or a full 3x3 stress tensor (sigma, stress)")
        parts.update(range(start, len(pairs)))
    columns = _columns(pairs, label)
    for k in parts:
        columns[k].component = True
    return columns


# --- meshio: VTU/VTK, XDMF, MED, Gmsh -------------------------------------------------------------

def read_meshio(path: Path) -> list[Table]:
    """A mesh file through meshio (the ``fe`` extra): its point data at the nodes, its cell data at the
    cell centroids (a second table). A 2-D mesh (two coordinates, or a third that is 0 everywhere) is
    marked dim = 2: its coordinates are (r, z) with --axisymmetric."""
    try:
        import meshio
    except ImportError:
        raise FormatProblem("reading VTU/VTK, XDMF, MED or Gmsh needs meshio: pip install 'stressfields[fe]'") from None
    try:
        mesh = meshio.read(path)
    except Exception as exc:        # meshio raises many types on a damaged or foreign file
        raise FormatProblem(f"meshio cannot read it as {path.suffix or 'a mesh'} ({type(exc).__name__})") from None
    pts = np.asarray(mesh.points, dtype=np.float64)
    dim = 2 if pts.shape[1] == 2 or not np.any(pts[:, 2:]) else 3
    xyz = pts[:, :dim]
    label = str(path)
    tables = []
    if mesh.point_data:
        tables.append(Table(label, _mesh_columns(xyz, mesh.point_data.items(), label), dim=dim,
                            carries_units=False, extra={"kind": "nodes"}))
    if mesh.cell_data:
        cents = np.concatenate([xyz[np.asarray(b.data)].mean(axis=1) for b in mesh.cells])
        arrays = [(name, np.concatenate([np.asarray(v) for v in parts])) for name, parts in mesh.cell_data.items()
                  if not name.startswith("gmsh:")]
        if arrays:
            tables.append(Table(f"{label}, cell centroids", _mesh_columns(cents, arrays, label), dim=dim,
                                carries_units=False, extra={"kind": "cell centroids"}))
    if not tables:
        raise FormatProblem("the mesh has no point or cell data to compare")
    return tables
