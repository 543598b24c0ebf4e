"""The repository stands alone: nothing in the code, tests, docs, recipes or written files reads,
cites or names a document outside it, and every equation reference of a docstring resolves to the
theory manual (docs/theory)."""
import re
import subprocess
from pathlib import Path

import pytest

import stressfields as sf

ROOT = Path(__file__).resolve().parents[1]
SCANNED = ("stressfields", "tests", "docs", "recipes", "benchmarks", "README.md", "data_schema.md", ".ci")
# written in pieces so that this file does not match itself
OUTSIDE = re.compile("|".join([r"\.\./" + "shared", "shared/" + "(formulas|notes|seeds)",
                               "formula" + " sheet", "sheet" + " §", "seed00" + r"\d"]))
CITATION = re.compile(r"docs/theory/(\w+)\.md \(([A-Z]+\d+[a-z]?)(?:[,\-–][^)]*)?\)")


def _text_files():
    try:
        out = subprocess.run(["git", "ls-files", "-co", "--exclude-standard", *SCANNED], cwd=ROOT,
                             capture_output=True, text=True, check=True).stdout.split()
        files = [ROOT / f for f in out]
    except (OSError, subprocess.CalledProcessError):       # not a git checkout: walk the tree
        files = [p for s in SCANNED for p in ((ROOT / s).rglob("*") if (ROOT / s).is_dir() else [ROOT / s])]
    for path in files:
        if path.is_file() and path.suffix not in (".nc", ".png", ".npy", ".npz", ".zarr"):
            try:
                yield path, path.read_text(encoding="utf-8")
            except UnicodeDecodeError:
                continue


def test_nothing_names_a_document_outside_the_repository():
    hits = [f"{p.relative_to(ROOT)}:{i}: {line.strip()[:100]}"
            for p, text in _text_files() for i, line in enumerate(text.splitlines(), 1)
            if OUTSIDE.search(line)]
    assert not hits, "\n".join(hits)


def test_theory_citations_resolve():
    """Every `docs/theory/<page>.md (X<n>)` cited anywhere names a page that exists and an equation
    label that the page defines."""
    pages = {}
    bad = []
    for path, text in _text_files():
        for page, label in CITATION.findall(text):
            if page not in pages:
                f = ROOT / "docs" / "theory" / f"{page}.md"
                pages[page] = f.read_text(encoding="utf-8") if f.exists() else None
            if pages[page] is None or f"({label})" not in pages[page]:
                bad.append(f"{path.relative_to(ROOT)}: docs/theory/{page}.md ({label})")
    assert not bad, "unresolved citations:\n" + "\n".join(sorted(set(bad)))


@pytest.mark.parametrize("page", ["axisymmetric", "graded", "wavy"])
def test_theory_pages_have_errata_with_tests(page):
    """Each family's page exists and its errata section names the tests that prove each entry, and
    those tests exist."""
    text = (ROOT / "docs" / "theory" / f"{page}.md").read_text(encoding="utf-8")
    m = re.search(r"^#+ [^\n]*Errata[^\n]*$(.*?)(?=^# |\Z)", text, re.M | re.S)
    assert m, f"{page}.md has no errata section"
    refs = re.findall(r"(tests/[\w/]+\.py)::(\w+)", m.group(1))
    assert refs, f"the errata of {page}.md name no test"
    for file, name in refs:
        source = (ROOT / file).read_text(encoding="utf-8")
        assert re.search(rf"^\s*def {name}\(", source, re.M), f"{file}::{name} (cited in {page}.md) not found"


@pytest.mark.parametrize("scenario, params", [
    ("wavy", {"amplitudes": [1.0], "wavenumbers": [1], "a": 0.4, "x": [0.0]}),
    ("conical", {"x": [0.5], "y": 0.0}),
    ("graded_normal", {"profile": "parabolic", "R": 1.0, "k": 0.5, "nu": 0.3, "E0": 1e9, "contact_radius": 0.1,
                       "rho": [0.5]}),
])
def test_written_attributes_stand_alone(scenario, params):
    ds = sf.generate({"scenario": scenario, "parameters": params})
    texts = [str(v) for v in ds.attrs.values()]
    texts += [str(v) for var in ds.variables.values() for v in var.attrs.values()]
    assert not [t for t in texts if OUTSIDE.search(t)]
    assert "docs/theory/" in ds.attrs["references"]
