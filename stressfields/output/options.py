"""The output options: their names, their check and their recorded form, without xarray (a
recipe's [output] table is checked with them before anything heavy is imported, `stressfields
validate`).

A written file records the options it was written with in the global attribute `OPTIONS_ATTR`;
each format derives its own encoding from that record (`OutputOptions.from_attrs`). A dataset of
`sf.generate` carries its recipe's options in ``ds.encoding[OPTIONS_ATTR]`` (`carried`), which
`sf.write` applies unless it is given others.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from ..errors import OutputError

DTYPES = ("float64", "float32")
NONFINITE = ("keep", "nan", "fill")
#: the keys of the options (a recipe's [output] dtype, compression, nonfinite; `write`'s keywords)
KEYS = ("dtype", "compression", "nonfinite")

#: the global attribute recording the output options a file was written with, and the key of
#: ``ds.encoding`` under which a generated dataset carries its recipe's options
OPTIONS_ATTR = "stressfields_output"
#: what float32 storage adds to every stated accuracy (float32 has a 24-bit significand)
FLOAT32_NOTE = ("Stored as float32: add a rounding error of at most 6e-8 (2^-24) of |value| "
                "(at most 1.4e-45 absolute below |value| = 1.2e-38).")
#: the fill value of the ``fill`` option per float size: NetCDF's default fill values (netCDF4's
#: ``default_fillvals["f4"]`` and ``["f8"]``, held equal by tests/test_front_door.py), which readers
#: that mask (netCDF4, xarray) know; the Zarr writer stores the same
FILL_VALUES = {4: 9.969209968386869e36, 8: 9.969209968386869e36}


def output_option_problems(dtype="float64", compression=None, nonfinite="keep") -> list[str]:
    """Every problem of a set of output options, each naming the key, the value and what is allowed
    (for a recipe's ``[output]`` to report them with its other problems)."""
    problems = []
    if dtype not in DTYPES:
        problems.append(f"dtype = {dtype!r}: must be one of {', '.join(DTYPES)}")
    if compression is not None and (isinstance(compression, bool) or not isinstance(compression, (int, np.integer))
                                    or not 0 <= compression <= 9):
        problems.append(f"compression = {compression!r}: must be an integer from 0 (none) to 9")
    if nonfinite not in NONFINITE:
        problems.append(f"nonfinite = {nonfinite!r}: must be one of {', '.join(NONFINITE)}")
    return problems


@dataclass(frozen=True)
class OutputOptions:
    """How values are stored. ``dtype``: float data variables as float64 (exact) or float32
    (coordinates and the recipe's array inputs stay float64); ``compression``: None for the format's
    default (NetCDF: none; Zarr: zarr's default compressor), 0 for none, 1-9 for zlib (NetCDF) or
    Blosc/zstd (Zarr) at that level; ``nonfinite``: ``keep`` +-inf and NaN, turn +-inf into NaN
    (``nan``), or store +-inf and NaN as the variable's ``_FillValue`` (``fill``). Validity flags are
    always kept: they say why a value is not finite."""
    dtype: str = "float64"
    compression: int | None = None
    nonfinite: str = "keep"

    def text(self) -> str:
        level = "default" if self.compression is None else str(self.compression)
        return f"dtype={self.dtype}; compression={level}; nonfinite={self.nonfinite}"

    @classmethod
    def from_attrs(cls, attrs) -> OutputOptions:
        """The options recorded in a dataset's global attributes (defaults if none are)."""
        text = attrs.get(OPTIONS_ATTR)
        if not isinstance(text, str):
            return cls()
        items = dict(item.strip().partition("=")[::2] for item in text.split(";") if "=" in item)
        level = items.get("compression", "default")
        return output_options(dtype=items.get("dtype", "float64"),
                              compression=None if level == "default" else int(level),
                              nonfinite=items.get("nonfinite", "keep"))


def output_options(dtype: str = "float64", compression: int | None = None, nonfinite: str = "keep") -> OutputOptions:
    """The checked output options of `write`.

    Parameters
    ----------
    dtype : {"float64", "float32"}
        Storage of the float fields.
    compression : int, optional
        0-9: lossless compression level (None: the format's default).
    nonfinite : {"keep", "nan", "fill"}
        What becomes of +-inf and NaN at singular points.

    Returns
    -------
    OutputOptions

    Raises
    ------
    OutputError
        Naming every problem at once.
    """
    problems = output_option_problems(dtype, compression, nonfinite)
    if problems:
        raise OutputError("output options: " + "; ".join(problems))
    return OutputOptions(dtype, None if compression is None else int(compression), nonfinite)


def resolved(carried: Mapping[str, Any] | None = None, **given: Any) -> OutputOptions:
    """The checked options of a write: those ``given`` (None: not given) over those ``carried`` (a
    recipe's [output] options, `carried`), over the defaults."""
    chosen = {**(carried or {}), **{k: v for k, v in given.items() if v is not None}}
    return output_options(**chosen)


def carried(ds) -> dict[str, Any]:
    """The recipe's output options a dataset carries ({} if none: a dataset not made by `sf.generate`,
    or one an operation stripped of its encoding)."""
    options = getattr(ds, "encoding", {}).get(OPTIONS_ATTR)
    return dict(options) if isinstance(options, Mapping) else {}
