"""Frames and components of an FE model, brought exactly into the scenarios' frame: z is depth (into
the body), Cartesian components. The inverse maps are sign changes and renames, so nothing is rounded:

- ``z_up``: the model's body lies at z <= 0. z, and every component with one z index (sigma_xz,
  sigma_yz, sigma_rz, sigma_tz, u_z) and dp/dz change sign.
- ``axisymmetric``: a 2-D (r, z) model; on the half-plane y = 0, x = r >= 0 the cylindrical
  components are the Cartesian ones (theta = 0): sigma_rr = sigma_xx, sigma_tt = sigma_yy,
  sigma_rz = sigma_xz, sigma_rt = sigma_xy, sigma_tz = sigma_yz, u_r = u_x, u_t = u_y.
- cylindrical names in a 3-D model (x, y, z coordinates): the reference's Cartesian tensor is rotated
  to the node's (r, theta, z) frame (``rotate_reference``); at r = 0 theta is undefined: NaN.
- body 2: the second of two identical bodies (the mirror image of the first, z -> -z, with the
  tangential traction reversed; Dundurs beta = 0, so Cattaneo-Mindlin holds for both). With an
  axisymmetric pressure the field the reversed traction gives at (x, y, h) is the first field at
  (-x, -y, h) turned by pi about the z axis, so body 2's field at (x, y, -h) is the reference at
  (-x, -y, h) with u_x, u_y, u_z and dp/dz negated (``BODY2_FLIP``; the stresses keep their sign:
  each of sigma_xz, sigma_yz changes sign twice).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .formats import Column, Table

#: cylindrical components -> the Cartesian one they equal at theta = 0 (x = r, y = 0)
CYLINDRICAL = {"sigma_rr": "sigma_xx", "sigma_tt": "sigma_yy", "sigma_rt": "sigma_xy", "sigma_rz": "sigma_xz",
               "sigma_tz": "sigma_yz", "u_r": "u_x", "u_t": "u_y"}
#: Cartesian components that are not the same in a cylindrical frame
CARTESIAN_ONLY = {"sigma_xx", "sigma_yy", "sigma_xy", "sigma_xz", "sigma_yz", "u_x", "u_y"}
#: components (and dp/dz) that change sign with z
Z_ODD = {"sigma_xz", "sigma_yz", "sigma_rz", "sigma_tz", "u_z", "dpdz"}
#: reference variables whose sign body 2's mirror image reverses (see the module docstring)
BODY2_FLIP = {"u_x", "u_y", "u_z", "dpdz"}
#: the Cartesian components a cylindrical component is rotated from
NEEDS = {"sigma_rr": ("sigma_xx", "sigma_yy", "sigma_xy"), "sigma_tt": ("sigma_xx", "sigma_yy", "sigma_xy"),
         "sigma_rt": ("sigma_xx", "sigma_yy", "sigma_xy"), "sigma_rz": ("sigma_xz", "sigma_yz"),
         "sigma_tz": ("sigma_xz", "sigma_yz"), "u_r": ("u_x", "u_y"), "u_t": ("u_x", "u_y")}
#: a 2-D mesh's axes and components: x is r, y is z (the out-of-plane third index is theta)
_AXI_LETTERS = {"x": "r", "y": "z", "z": "t", "r": "r", "t": "t"}


class FrameProblem(ValueError):
    """Columns whose frame cannot be told or is not the one the options say (one line)."""


@dataclass
class Frame:
    """The nodes in the scenarios' frame: coordinates x, y, z (z depth), value columns (cylindrical
    names kept when ``cylindrical``), the body of every node, and the columns the file added."""
    coords: list[Column]
    values: list[Column]
    body: np.ndarray
    node: Column | None
    weight: Column | None
    cylindrical: bool
    axisymmetric: bool


def _axi_name(name: str) -> str:
    """A 2-D mesh's component name in (r, z): sigma_xy -> sigma_rz, u_y -> u_z, sigma_zz -> sigma_tt."""
    if name.startswith("u_") and len(name) == 3:
        return "u_" + _AXI_LETTERS.get(name[2], name[2])
    if name.startswith("sigma_") and len(name) == 8:
        i, j = (_AXI_LETTERS.get(c, c) for c in name[6:])
        order = "rtz"
        return "sigma_" + "".join(sorted((i, j), key=order.index))
    return {"x": "r", "y": "z"}.get(name, name)


def to_depth_frame(table: Table, *, z_up: bool = False, axisymmetric: bool = False, body: int = 1) -> Frame:
    """The table's columns in the scenarios' frame (module docstring); FrameProblem when the frame is
    mixed, not the one the options name, or a node lies on the wrong side of the surface."""
    columns = list(table.columns)
    if table.dim == 2:
        if not axisymmetric:
            raise FrameProblem("a 2-D mesh (two coordinates): give --axisymmetric for an (r, z) model (the "
                               "second mesh coordinate is z)")
        # the mesh's axes and the components of its arrays are (r, z); a scalar keeps the name it has
        renamed = [replace(c, name=_axi_name(c.name)) if c.component else c for c in columns]
        seen: dict[str, str] = {}
        for c in renamed:
            if c.name in seen:
                raise FrameProblem(f"mixed frames: {seen[c.name]!r} and {c.label!r} are both {c.name!r} of the "
                                   "(r, z) mesh")
            seen[c.name] = c.label
        columns = renamed
    by = {c.name: c for c in columns}
    cyl = [c.label for c in columns if c.name in CYLINDRICAL]
    cart = [c.label for c in columns if c.name in CARTESIAN_ONLY]
    if cyl and cart:
        raise FrameProblem(f"mixed frames: cylindrical {', '.join(map(repr, cyl))} and Cartesian "
                           f"{', '.join(map(repr, cart))}; give one frame")
    if "r" in by and ({"x", "y"} & set(by)):
        raise FrameProblem("mixed frames: a radius column 'r' beside Cartesian x/y coordinates; give one frame")
    if axisymmetric:
        if "r" not in by:
            raise FrameProblem("--axisymmetric: no radius column r (an (r, z) model gives r and z; x, y: drop "
                               "--axisymmetric)")
        if cart:
            raise FrameProblem(f"--axisymmetric: Cartesian {', '.join(map(repr, cart))} in an (r, z) model; "
                               "name them sigma_rr, sigma_tt, sigma_rz, u_r")
    elif "r" in by:
        raise FrameProblem("column 'r': an (r, z) model; give --axisymmetric")
    node = by.pop("node", None)
    weight = by.pop("weight", None)
    body_col = by.pop("body", None)
    n = columns[0].values.size
    if body_col is not None:
        bodies = body_col.values
        bad = np.flatnonzero((bodies != 1) & (bodies != 2))
        if bad.size:
            raise FrameProblem(f"data row {bad[0]} (from 0), column {body_col.label!r}: the body is 1 or 2")
        bodies = bodies.astype(np.int8)
    else:
        bodies = np.full(n, body, dtype=np.int8)
    coords, values = [], []
    for c in by.values():
        if c.name in ("x", "y", "z", "r"):
            coords.append(c)
        else:
            values.append(c)
    if axisymmetric:
        r = next(c for c in coords if c.name == "r")
        bad = np.flatnonzero(r.values < 0)
        if bad.size:
            raise FrameProblem(f"data row {bad[0]} (from 0), column {r.label!r}: a radius is >= 0")
        coords = [replace(c, name="x") if c.name == "r" else c for c in coords]
        coords.append(Column("y", "y (= 0: the (r, z) half-plane)", None, np.zeros(n)))
        values = [replace(c, name=CYLINDRICAL.get(c.name, c.name)) for c in values]
    if z_up and "z" not in {c.name for c in coords}:
        raise FrameProblem("--z-up: the file has no z column")
    coords = [_depth(c, z_up, bodies) if c.name == "z" else c for c in coords]
    if z_up:
        values = [replace(c, values=-c.values) if c.name in Z_ODD else c for c in values]
    cylindrical = not axisymmetric and bool(cyl)
    if cylindrical and not {"x", "y"} <= {c.name for c in coords}:
        raise FrameProblem(f"cylindrical {', '.join(map(repr, cyl))} in a model without x and y coordinates: "
                           "give --axisymmetric for an (r, z) model")
    return Frame(coords, values, bodies, node, weight, cylindrical, axisymmetric)


def _depth(col: Column, z_up: bool, bodies: np.ndarray) -> Column:
    """z as depth: negated with ``z_up``; body 1 at depth >= 0, body 2 at depth <= 0."""
    depth = -col.values if z_up else col.values
    wrong = np.flatnonzero(np.where(bodies == 1, depth < 0, depth > 0))
    if wrong.size:
        k = int(wrong[0])
        side = "z > 0" if z_up else "z < 0"
        if bodies[k] == 1:
            hint = ("with --z-up the body lies at z <= 0" if z_up else
                    "z is depth into the body here: give --z-up for a model whose body lies at z <= 0")
        else:
            hint = "the second body lies on the other side of the surface than the first"
        raise FrameProblem(f"data row {k} (from 0), column {col.label!r}: a node of body {bodies[k]} at {side} "
                           f"({wrong.size} such rows); {hint} (a second body: --body 2 or a column 'body')")
    return replace(col, values=depth)


def rotate_reference(name: str, ref: dict[str, np.ndarray], x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """The cylindrical component ``name`` of the reference's Cartesian components at nodes (x, y):
    the exact rotation by theta = atan2(y, x); NaN on the axis r = 0 (theta undefined there)."""
    r = np.hypot(x, y)
    with np.errstate(invalid="ignore", divide="ignore"):
        c = np.where(r > 0, x / r, np.nan)
        s = np.where(r > 0, y / r, np.nan)
    if name in ("sigma_rr", "sigma_tt", "sigma_rt"):
        xx, yy, xy = ref["sigma_xx"], ref["sigma_yy"], ref["sigma_xy"]
        return {"sigma_rr": c * c * xx + s * s * yy + 2 * c * s * xy,
                "sigma_tt": s * s * xx + c * c * yy - 2 * c * s * xy,
                "sigma_rt": c * s * (yy - xx) + (c * c - s * s) * xy}[name]
    if name in ("sigma_rz", "sigma_tz"):
        xz, yz = ref["sigma_xz"], ref["sigma_yz"]
        return c * xz + s * yz if name == "sigma_rz" else -s * xz + c * yz
    ux, uy = ref["u_x"], ref["u_y"]
    return c * ux + s * uy if name == "u_r" else -s * ux + c * uy
