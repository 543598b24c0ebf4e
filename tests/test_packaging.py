"""What a pip install gets: a build-system floor that reads the license form, the LICENSE, py.typed,
the recipes and examples as package data, one version, and a typed, numpydoc-documented public API.

The wheel itself was built by hand with the floor (`PIP_CONSTRAINT` setuptools==77.0.3, `pip wheel .`);
a build here would download setuptools, too slow and networked for the suite."""
import inspect
import re
import tomllib
from pathlib import Path

import stressfields as sf

ROOT = Path(__file__).resolve().parents[1]
PROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())


def _floor(requirement: str) -> tuple[int, ...]:
    found = re.fullmatch(r"setuptools\s*>=\s*([\d.]+)", requirement.strip())
    assert found, requirement
    return tuple(int(p) for p in found.group(1).split("."))


def test_build_floor_reads_the_license_form():
    """An SPDX string as `license` (PEP 639) needs setuptools 77 or later (68.2.2 fails on it)."""
    (setuptools,) = [r for r in PROJECT["build-system"]["requires"] if r.startswith("setuptools")]
    license_ = PROJECT["project"]["license"]
    if isinstance(license_, str) or "license-files" in PROJECT["project"]:
        assert _floor(setuptools) >= (77,), setuptools
    assert (ROOT / "LICENSE").read_text().startswith("MIT License") and "The stressfields authors" in (
        ROOT / "LICENSE").read_text()


def test_one_version():
    assert "version" not in PROJECT["project"] and "version" in PROJECT["project"]["dynamic"]
    assert PROJECT["tool"]["setuptools"]["dynamic"]["version"] == {"attr": "stressfields.version.__version__"}
    assert re.fullmatch(r"\d+\.\d+\.\d+", sf.__version__)
    from stressfields import version

    assert version.__version__ is sf.__version__


def test_recipes_and_examples_ship_with_the_package():
    """The package data globs take every root recipe and example (stressfields/recipes and
    stressfields/examples are links to the root folders), and py.typed."""
    data = PROJECT["tool"]["setuptools"]["package-data"]["stressfields"]
    package = Path(sf.__file__).parent
    shipped = {p.relative_to(package) for pattern in data for p in package.glob(pattern)}
    assert Path("py.typed") in shipped
    for folder in ("recipes", "examples"):
        for path in (ROOT / folder).rglob("*"):
            if path.is_file() and "__pycache__" not in path.parts:
                assert Path(folder) / path.relative_to(ROOT / folder) in shipped, path
    assert set(sf.examples()) >= {p.stem for p in (ROOT / "recipes").glob("*.toml")}
    assert sf.example("hertz_subsurface").read_text() == (ROOT / "recipes" / "hertz_subsurface.toml").read_text()
    assert "x" in sf.open_example("wavy_fig2").dims


def test_the_public_api_is_typed_and_documented():
    missing = []
    for name in sf.__all__:
        obj = getattr(sf, name)
        if not inspect.isfunction(obj):
            continue
        signature = inspect.signature(obj)
        untyped = [p.name for p in signature.parameters.values() if p.annotation is inspect.Parameter.empty]
        if untyped or signature.return_annotation is inspect.Signature.empty:
            missing.append(f"{name}: annotations missing for {untyped or 'the return'}")
        doc = inspect.getdoc(obj) or ""
        if signature.parameters and "Parameters\n----------" not in doc:
            missing.append(f"{name}: no numpydoc Parameters section")
        if "Returns\n-------" not in doc:
            missing.append(f"{name}: no numpydoc Returns section")
    assert missing == [], "\n".join(missing)
