"""Procedural training data: `batches(recipe, batch_size, seed)` yields (inputs, targets) NumPy arrays at
seeded Sobol or uniform points, computed on the fly by the scenario's kernels (no dataset, no dask,
no file).

The recipe is an ordinary one whose ``[points.sample]`` table gives the box to sample
(``{ n = ..., method = "sobol" | "uniform", x = [low, high], nu = [low, high], ... }``; its ``seed``
is replaced by the ``seed`` given here): ``n`` points are drawn in all, in batches of
``batch_size`` (the last one shorter). The stream is the one `points.draw_sample` draws for the
same specification, cut into batches: scipy's scrambled Sobol sequence (or NumPy's PCG64 uniform
stream) continues from batch to batch, and every kernel is evaluated point by point, so the same
(recipe, seed) gives the same bytes whatever the batch size, and the concatenated batches equal
``sf.generate`` of the same recipe bit for bit (tests/test_batches.py). Latin hypercube samples
(``lhs``) are not a stream and are refused.

``inputs`` has one column per sampled parameter (alphabetical order, as `draw_sample` gives them),
``targets`` one per requested float variable, then the ``validity`` flag (as a float) where the
scenario has one; the names are in ``Batches.input_names`` and ``Batches.target_names``.
"""
from __future__ import annotations

import json
import tomllib
import warnings
from pathlib import Path
from typing import Iterator, Mapping

import numpy as np

STREAMABLE = ("sobol", "uniform")
#: a stream is not held in memory: its length is bounded only by what a run can take (scipy's Sobol
#: engine draws at most 2^32 points before the sequence repeats)
MAX_SAMPLES = 2 ** 32


class Batches:
    """An iterable of (inputs, targets) batches; iterate it again to get the same bytes again."""

    def __init__(self, recipe: str | Path | Mapping, batch_size: int, seed: int):
        from .recipe import RecipeError, load

        if isinstance(batch_size, bool) or not isinstance(batch_size, int) or batch_size < 1:
            raise RecipeError([f"batch_size = {batch_size!r} must be an integer >= 1"], "batches")
        if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
            raise RecipeError([f"seed = {seed!r} must be an integer >= 0"], "batches")
        data = _as_dict(recipe)
        label = str(recipe) if not isinstance(recipe, Mapping) else "recipe"
        sample = data.get("points", {}).get("sample") if isinstance(data.get("points"), Mapping) else None
        if not isinstance(sample, Mapping):
            raise RecipeError(["batches need a [points.sample] table: the box to sample, e.g. { n = 1000000, "
                               'method = "sobol", x = [-2.0, 2.0], z = [0.0, 3.0] }'], label)
        if sample.get("method", "sobol") not in STREAMABLE:
            raise RecipeError([f"points.sample.method = {sample.get('method')!r}: batches stream 'sobol' or "
                               "'uniform' points (a Latin hypercube is drawn whole, not as a stream)"], label)
        n = sample.get("n")
        if isinstance(n, bool) or not isinstance(n, int) or not 1 <= n <= MAX_SAMPLES:
            raise RecipeError([f"points.sample.n = {n!r} must be an integer in [1, {MAX_SAMPLES:.0e}] (the points "
                               "drawn in all)"], label)
        # checked as a recipe of one point: every key, range and variable, nothing large drawn
        self.recipe = load({**data, "points": {"sample": {**sample, "n": 1, "seed": seed}}})
        self.spec = {**json.loads(self.recipe.canonical)["points"]["sample"], "n": n, "seed": seed}
        scen = self.recipe.scenario
        self.batch_size = batch_size
        self.input_names = tuple(self.spec["ranges"])
        floats = [v for v in self.recipe.variables if scen.variable(v).dtype.startswith("float")]
        flag = [v.name for v in scen.variables_in(self.recipe.physical) if v.name == "validity"]
        self.target_names = tuple(floats + flag)
        self._low = np.array([self.spec["ranges"][k][0] for k in self.input_names])
        self._high = np.array([self.spec["ranges"][k][1] for k in self.input_names])

    def __len__(self) -> int:
        return -(-self.spec["n"] // self.batch_size)

    def __iter__(self) -> Iterator[tuple[np.ndarray, np.ndarray]]:
        draw = _stream(self.spec["method"], len(self.input_names), self.spec["seed"])
        left = self.spec["n"]
        while left > 0:
            size = min(self.batch_size, left)
            left -= size
            # as points.draw_sample maps its unit sample: low + u (high - low), clipped into the box
            inputs = np.clip(self._low + draw(size) * (self._high - self._low), self._low, self._high)
            yield inputs, self.evaluate(inputs)

    def evaluate(self, inputs: np.ndarray) -> np.ndarray:
        """The targets at the rows of ``inputs`` (columns as ``input_names``)."""
        recipe = self.recipe
        params = {k: v for k, v in recipe.values.items() if k not in recipe.points}
        params.update({k: np.ascontiguousarray(inputs[:, i]) for i, k in enumerate(self.input_names)})
        result = evaluate(recipe, self.target_names, params)
        out = np.empty((inputs.shape[0], len(self.target_names)))
        for j, name in enumerate(self.target_names):
            out[:, j] = np.broadcast_to(np.asarray(result[name], dtype=np.float64), (inputs.shape[0],))
        return out


def evaluate(recipe, names, params: Mapping, sweep: Mapping | None = None) -> dict[str, np.ndarray]:
    """The scenario's values of ``names`` at ``params`` (the recipe's fixed values and arrays of
    points), computed now by its kernels: no xarray, no dask. The one call of a scenario's evaluate
    outside the lazy dataset (`build`): `sf.batches` and `compare`'s reference both come here.

    Parameters
    ----------
    recipe : Recipe
        The checked recipe: its scenario, method, rtol and units mode.
    names : sequence of str
        The variables wanted.
    params : Mapping
        Parameter values; a per-point parameter as a 1-D array (every array of one length).
    sweep : Mapping, optional
        The values of the whole sweep the points belong to (default: ``params``): a kernel whose choice
        of route depends on the sweep (wavy ``auto``) then chooses as for the whole recipe.

    Returns
    -------
    dict of str to numpy.ndarray
        The values by name, as the scenario gives them (a per-case value may be a scalar).
    """
    options = {"method": recipe.method, "rtol": recipe.rtol, "physical": recipe.physical,
               "sweep": params if sweep is None else sweep}
    with np.errstate(all="ignore"):        # singular points give inf/NaN on purpose, flagged in validity
        return recipe.scenario.evaluate(list(names), params, options)


def batches(recipe: str | Path | Mapping, batch_size: int, seed: int) -> Batches:
    """(inputs, targets) batches of points of the recipe's ``[points.sample]`` box, computed on the fly.

    Parameters
    ----------
    recipe : str, Path or Mapping
        A recipe with a ``[points.sample]`` table (method ``sobol`` or ``uniform``).
    batch_size : int
        Points per batch (the last one shorter).
    seed : int
        Replaces the sample's ``seed``: the same (recipe, seed) gives the same bytes.

    Returns
    -------
    Batches
        An iterable of (inputs, targets) NumPy arrays; see the module docstring.
    """
    return Batches(recipe, batch_size, seed)


def _stream(method: str, dims: int, seed: int):
    """draw(k) -> the next k rows of the unit sample `points.draw_sample` would draw for (method, seed)."""
    rng = np.random.default_rng(seed)
    if method == "uniform":
        return lambda k: rng.random((k, dims))
    from scipy.stats import qmc

    engine = qmc.Sobol(dims, scramble=True, seed=rng)

    def draw(k):
        with warnings.catch_warnings():     # balance properties: as in points.draw_sample
            warnings.filterwarnings("ignore", message=".*balance properties.*", category=UserWarning)
            return engine.random(k)
    return draw


def _as_dict(recipe) -> dict:
    if isinstance(recipe, Mapping):
        return dict(recipe)
    from .recipe import RecipeError, _check_shape, _read_text

    path = Path(recipe)
    text = _read_text(path, str(path))
    _check_shape(text, str(path))
    try:
        return tomllib.loads(text)
    except ValueError as exc:
        raise RecipeError([f"not valid TOML: {exc}"], str(path)) from None
