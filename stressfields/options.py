"""The output options' names and their check, without xarray: a recipe's [output] table is
checked with them before anything heavy is imported (`stressfields validate`)."""
from __future__ import annotations

import numpy as np

DTYPES = ("float64", "float32")
NONFINITE = ("keep", "nan", "fill")

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
