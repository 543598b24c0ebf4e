"""The published reference suite: canonical recipes, their registered hashes, build and verify.

The suite lives in ``suite/`` at the repository root (beside ``benchmarks/``, not in the package):
``recipes/*.toml`` (one or more per scenario family and the FE benchmark geometries, in grid and
point form), ``registry.json`` (the suite version and, per dataset, its recipe, whether it is part
of the release gate, and the content and values hashes of the file it makes) and ``catalog.yaml``
(an intake catalog of the built files). `build` writes every dataset into a directory and skips
those already present whose hashes verify (so an interrupted build resumes); `verify` recomputes
every hash. Two hashes per dataset: the content hash (`output.hashing.content_hash`, what
``stressfields hash`` checks: values and every attribute) and the values hash
(`output.hashing.values_hash`: values, names, dims and types only), which the release gate
(tests/test_suite.py) holds fixed: a changed value needs a new ``suite_version`` and a CHANGELOG line.
"""
from __future__ import annotations

import csv
import io
import json
import math
import time
from pathlib import Path
from typing import Callable

import numpy as np

from .errors import OutputError
from .textfiles import write_text as _write_text

#: the suite shipped with this source tree
SUITE_DIR = Path(__file__).resolve().parents[1] / "suite"
REGISTRY = "registry.json"
CATALOG = "catalog.yaml"
KEY_VALUES = "key_values.csv"
KEY_COLUMNS = ("dataset", "variable", "statistic", "value", "units", "where")
#: a variable of at most this many values is listed whole in the key-value table, a larger one by
#: its largest and smallest finite value and where they sit
LIST_WHOLE = 12


def suite_dir(path: str | Path | None = None) -> Path:
    folder = Path(path) if path is not None else SUITE_DIR
    if not (folder / REGISTRY).is_file():
        raise OutputError(f"{folder}: no {REGISTRY} (the reference suite lives in suite/ of a stressfields clone)")
    return folder


def registry(folder: str | Path | None = None) -> dict:
    """The registry: ``suite_version`` and ``datasets`` {name: {recipe, gate, content_sha256, values_sha256}}."""
    return json.loads((suite_dir(folder) / REGISTRY).read_text(encoding="utf-8"))


def recipe_path(name: str, folder: str | Path | None = None) -> Path:
    folder = suite_dir(folder)
    return folder / registry(folder)["datasets"][name]["recipe"]


def make(name: str, target: Path, folder: str | Path | None = None, overwrite: bool = False) -> Path:
    """Generate dataset ``name`` of the suite into ``target`` (NetCDF, float64, uncompressed)."""
    from .api import generate
    from .output.formats import write

    return write(generate(recipe_path(name, folder)), target, overwrite=overwrite)


def file_hashes(path: str | Path) -> tuple[str, str]:
    """(content hash, values hash) of a written file after checking its stored content hash
    (`output.formats.verify`: OutputError if it is damaged or has none)."""
    from .output.formats import format_for, verify
    from .output.hashing import values_hash

    content = verify(path)
    with format_for(path).read(path, raw=True) as ds:
        return content, values_hash(ds)


def build(out_dir: str | Path, folder: str | Path | None = None, say: Callable[[str], None] = print,
          only: list[str] | None = None) -> list[str]:
    """Write every dataset of the suite into ``out_dir`` as ``<name>.nc``, with ``key_values.csv``,
    ``catalog.yaml`` and ``registry.json`` beside them. A file already there whose stored content hash
    verifies and whose hashes are the registered ones is kept (an interrupted build resumes);
    anything else there under a dataset's name is replaced. Returns the problems (hashes that
    differ from the registry); nothing is raised for them, so the caller decides."""
    folder = suite_dir(folder)
    reg = registry(folder)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    names = list(reg["datasets"]) if only is None else only
    problems = []
    for i, name in enumerate(names, 1):
        entry, target = reg["datasets"][name], out / f"{name}.nc"
        head = f"[{i}/{len(names)}] {name}"
        if target.exists() and _matches(target, entry) == []:
            say(f"{head}: present, hashes verify; kept")
            continue
        start = time.perf_counter()
        make(name, target, folder, overwrite=True)
        found = _matches(target, entry)
        problems += [f"{name}: {p}" for p in found]
        say(f"{head}: built in {time.perf_counter() - start:.1f} s" + (f"; {'; '.join(found)}" if found else ""))
    _write_text(out / KEY_VALUES, key_values_csv(out, names))
    _write_text(out / CATALOG, (folder / CATALOG).read_text(encoding="utf-8"))
    _write_text(out / REGISTRY, (folder / REGISTRY).read_text(encoding="utf-8"))
    return problems


def verify(out_dir: str | Path, folder: str | Path | None = None, say: Callable[[str], None] = print) -> list[str]:
    """Recompute the hashes of every dataset of the suite in ``out_dir``; the problems (a missing or
    damaged file, a hash that differs from the registered one), one per dataset, [] if none."""
    reg = registry(folder)
    problems = []
    for name, entry in reg["datasets"].items():
        target = Path(out_dir) / f"{name}.nc"
        found = ["missing"] if not target.exists() else _matches(target, entry)
        say(f"{name}: {'ok' if not found else '; '.join(found)}")
        problems += [f"{name}: {p}" for p in found]
    return problems


def _matches(target: Path, entry: dict) -> list[str]:
    """How ``target`` differs from its registry entry ([] if it does not)."""
    try:
        content, values = file_hashes(target)
    except OutputError as exc:
        return [str(exc)]
    found = []
    if values != entry["values_sha256"]:
        found.append(f"values hash {values} differs from the registered {entry['values_sha256']}")
    if content != entry["content_sha256"]:
        found.append(f"content hash {content} differs from the registered {entry['content_sha256']}")
    return found


def register(folder: str | Path | None = None, version: str | None = None,
             say: Callable[[str], None] = print) -> dict:
    """Rebuild every dataset in a temporary directory and write the registry (with ``version``, or
    the current one), the catalog and the key-value table of the suite's README. For maintainers:
    run it after a deliberate change, bump the version when a values hash changes, and say why in
    CHANGELOG.md."""
    import tempfile

    folder = Path(folder) if folder is not None else SUITE_DIR
    old = json.loads((folder / REGISTRY).read_text(encoding="utf-8")) if (folder / REGISTRY).exists() else {}
    recipes = sorted((folder / "recipes").glob("*.toml"))
    datasets = {}
    with tempfile.TemporaryDirectory() as tmp:
        for path in recipes:
            name = path.stem
            target = Path(tmp) / f"{name}.nc"
            from .api import generate
            from .output.formats import write

            write(generate(path), target)
            content, values = file_hashes(target)
            gate = old.get("datasets", {}).get(name, {}).get("gate", True)
            datasets[name] = {"recipe": f"recipes/{path.name}", "gate": gate, "content_sha256": content,
                              "values_sha256": values, "bytes": target.stat().st_size}
            say(f"{name}: {values[:16]} (values), {content[:16]} (content)")
        table = key_values_rows(Path(tmp), list(datasets))
    reg = {"suite_version": version or old.get("suite_version", "1.0.0"), "datasets": datasets}
    _write_text(folder / REGISTRY, json.dumps(reg, indent=2) + "\n")
    _write_text(folder / CATALOG, catalog_yaml(reg, folder))
    readme = folder / "README.md"
    if readme.exists():
        _write_text(readme, replace_table(readme.read_text(encoding="utf-8"), key_values_markdown(table)))
    return reg


# -- key values ------------------------------------------------------------------------------------

def key_values_rows(out_dir: Path, names: list[str]) -> list[dict]:
    """The key-value table of the datasets ``names`` written in ``out_dir``, from their own values."""
    rows = []
    for name in names:
        rows += dataset_key_values(name, Path(out_dir) / f"{name}.nc")
    return rows


def dataset_key_values(name: str, path: Path) -> list[dict]:
    """Per float variable of the file: every value if it has at most LIST_WHOLE (contact radius,
    peaks and their depths, pull-off force per case...), else its largest and smallest finite value
    and the coordinates where they sit (the first in C order)."""
    from .reading import open_dataset

    rows = []
    with open_dataset(path) as ds:
        for vname in sorted(map(str, ds.data_vars)):
            var = ds[vname]
            if var.dtype.kind != "f" or "flag_values" in var.attrs or vname.endswith("_index") or any(
                    d.endswith("_index") for d in var.dims):
                continue
            values = np.asarray(var.values)
            units = str(var.attrs.get("units", ""))
            if values.size <= LIST_WHOLE:
                for index in np.ndindex(values.shape):
                    rows.append(_row(name, vname, "value", values[index], units, _where(var, index)))
                continue
            finite = np.isfinite(values)
            if not finite.any():
                continue
            for stat, pick in (("max", np.nanargmax), ("min", np.nanargmin)):
                flat = int(pick(np.where(finite, values, np.nan)))
                index = np.unravel_index(flat, values.shape)
                rows.append(_row(name, vname, stat, values[index], units, _where(var, index)))
    return rows


def _row(name, vname, stat, value, units, where) -> dict:
    return {"dataset": name, "variable": vname, "statistic": stat, "value": _number(value), "units": units,
            "where": where}


def _number(value) -> str:
    value = float(value)
    return repr(value) if not math.isfinite(value) else f"{value:.10g}"


def _where(var, index) -> str:
    """The coordinates of ``index`` along the variable's dims, and the [points] columns there."""
    parts = []
    for dim, i in zip(var.dims, index):
        coords = [c for c in var.coords if var.coords[c].dims == (dim,)] or [dim]
        for c in coords:
            v = var.coords[c].values[i] if c in var.coords else i
            parts.append(f"{c}={_number(v) if np.asarray(v).dtype.kind in 'iuf' else v}")
    return " ".join(parts)


def key_values_csv(out_dir: Path, names: list[str]) -> str:
    buf = io.StringIO()
    writer = csv.DictWriter(buf, fieldnames=KEY_COLUMNS, lineterminator="\n")
    writer.writeheader()
    writer.writerows(key_values_rows(out_dir, names))
    return buf.getvalue()


TABLE_START = "<!-- key values: written by stressfields.suite.register -->"
TABLE_END = "<!-- end of key values -->"


def key_values_markdown(rows: list[dict]) -> str:
    lines = ["| " + " | ".join(KEY_COLUMNS) + " |", "|" + "---|" * len(KEY_COLUMNS)]
    lines += ["| " + " | ".join(str(r[k]) or "-" for k in KEY_COLUMNS) + " |" for r in rows]
    return "\n".join(lines)


def replace_table(text: str, table: str) -> str:
    """``text`` with the part between TABLE_START and TABLE_END replaced by ``table`` (appended if absent)."""
    block = f"{TABLE_START}\n{table}\n{TABLE_END}"
    if TABLE_START in text and TABLE_END in text:
        head, rest = text.split(TABLE_START, 1)
        return head + block + rest.split(TABLE_END, 1)[1]
    return text.rstrip("\n") + "\n\n" + block + "\n"


# -- catalog ---------------------------------------------------------------------------------------

def catalog_yaml(reg: dict, folder: Path) -> str:
    """An intake (v1) catalog of the built files: the netcdf driver of intake-xarray, with the engine
    named (it hands xarray a file object, which a NetCDF-4 file can only be read from by netcdf4 or
    h5netcdf)."""
    import tomllib

    import yaml

    sources = {}
    for name, entry in reg["datasets"].items():
        recipe = tomllib.loads((folder / entry["recipe"]).read_text(encoding="utf-8"))
        sources[name] = {
            "description": recipe.get("title", name),
            "driver": "netcdf",
            "args": {"urlpath": "{{ CATALOG_DIR }}/" + f"{name}.nc", "xarray_kwargs": {"engine": "netcdf4"}},
            "metadata": {"scenario": recipe["scenario"], "recipe": entry["recipe"], "gate": entry["gate"],
                         "content_sha256": entry["content_sha256"], "values_sha256": entry["values_sha256"]},
        }
    doc = {"metadata": {"version": 1, "title": "stressfields reference suite",
                        "suite_version": reg["suite_version"]}, "sources": sources}
    return "# written by stressfields.suite.register from registry.json and recipes/\n" + yaml.safe_dump(
        doc, sort_keys=False, width=120)
