"""The package's layers: no module imports a module of a higher layer, and no imports run in a
circle, except the one inside the wavy physics (the periodic and the series kernels call each
other). Imports are read from the source (ast), those inside functions and under TYPE_CHECKING
included. docs/architecture.md draws the same table."""
import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "stressfields"

#: lowest first; a module may import its own layer and those below. A module belongs to the layer
#: of the longest prefix that names it ("" is the package itself, `import stressfields`)
LAYERS = [
    ("base", ["errors", "units", "textfiles", "version"]),
    ("physics", ["physics"]),
    ("declarations", ["scenarios", "cf", "schema"]),
    ("output", ["output"]),
    ("recipe", ["recipe", "points", "pointfiles", "plotkeys", "splits", "fe.units"]),
    ("dataset", ["build", "reading"]),
    ("services", ["comparison", "procedural", "mlexport", "plot", "hashing"]),
    ("fe", ["fe"]),
    ("front door", ["api", "suite"]),
    ("command line", ["cli", "__main__", ""]),
]
#: the one circle allowed
ALLOWED_CIRCLES = [{"physics.wavy.periodic", "physics.wavy.series"}]


def modules() -> dict[str, Path]:
    """Module name (relative to the package: "output.netcdf", "" for the package) -> its file."""
    out = {}
    for path in PACKAGE.rglob("*.py"):
        parts = list(path.relative_to(PACKAGE).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts = parts[:-1]
        out[".".join(parts)] = path
    return out


def imports(name: str, path: Path, known: dict, unresolved: list | None = None) -> set[str]:
    """The package's modules ``name`` imports, anywhere in its source; an import of the package that
    names no module of it goes to ``unresolved``."""
    package = name.split(".") if path.name == "__init__.py" else name.split(".")[:-1]
    package = [p for p in package if p]
    found = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names if a.name.split(".")[0] == "stressfields"]
            targets = [t.split(".", 1)[1] if "." in t else "" for t in targets]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[:len(package) - (node.level - 1)] + (node.module.split(".") if node.module else [])
            elif node.module and node.module.split(".")[0] == "stressfields":
                base = node.module.split(".")[1:]
            else:
                continue
            stem = ".".join(base)
            targets = [f"{stem}.{a.name}".strip(".") if f"{stem}.{a.name}".strip(".") in known else stem
                       for a in node.names]
        else:
            continue
        for target in targets:
            if target not in known and unresolved is not None:
                unresolved.append(f"{name}: {target}")
            while target not in known and target:
                target = target.rpartition(".")[0]
            if target != name:
                found.add(target)
    return found


def layer_of(name: str) -> int:
    best, rank = -1, None
    for i, (_, prefixes) in enumerate(LAYERS):
        for prefix in prefixes:
            if (name == prefix or (prefix and name.startswith(prefix + "."))) and len(prefix) > best:
                best, rank = len(prefix), i
    return rank


UNRESOLVED: list[str] = []
GRAPH = {name: imports(name, path, modules(), UNRESOLVED) for name, path in modules().items()}


def test_every_import_names_a_module_of_the_package():
    """A name that moved is not found in another installed copy of the package instead."""
    assert UNRESOLVED == []


def test_every_module_has_a_layer():
    assert [name for name in GRAPH if layer_of(name) is None] == []


def test_no_import_runs_upward():
    upward = sorted(f"{name} ({LAYERS[layer_of(name)][0]}) imports {target} ({LAYERS[layer_of(target)][0]})"
                    for name, targets in GRAPH.items() for target in targets
                    if layer_of(name) is not None and layer_of(target) is not None
                    and layer_of(target) > layer_of(name))
    assert upward == []


def circles(graph: dict[str, set[str]]) -> list[set[str]]:
    """The strongly connected components of more than one module (Tarjan)."""
    index, low, stack, on, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = set()
            while True:
                w = stack.pop()
                on.discard(w)
                component.add(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(component)
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def test_no_circles_but_the_allowed_one():
    assert [c for c in circles(GRAPH) if c not in ALLOWED_CIRCLES] == []


def test_the_circle_finder_finds_circles():
    """The check can fail: a circle and an upward import are seen."""
    assert circles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [{"a", "b", "c"}]
    fake = PACKAGE / "output" / "options.py"
    assert "errors" in imports("output.options", fake, modules())
    assert layer_of("fe.units") < layer_of("fe.validate") and layer_of("output.netcdf") == layer_of("output")


@pytest.mark.parametrize("module", ["cli"])
def test_the_command_line_reaches_the_dataset_through_the_api_only(module):
    assert not {t for t in GRAPH[module] if t == "build" or t.startswith("output.") and t not in (
        "output.options", "output.formats", "output.hashing")}


def test_formats_import_the_shared_parts_never_the_table():
    shared = {"output.atomic", "output.compute", "output.options", "output.hashing", "output.form"}
    for name in ("output.netcdf", "output.zarrstore", "output.parts"):
        assert "output.formats" not in GRAPH[name], name
        others = {t for t in GRAPH[name] if t.startswith("output.")} - shared
        assert others <= ({"output.netcdf"} if name == "output.parts" else set()), (name, others)


def test_the_architecture_page_draws_the_same_table():
    text = (PACKAGE.parent / "docs" / "architecture.md").read_text(encoding="utf-8")
    rows = {line.split("|")[1].strip(): line for line in text.splitlines() if line.startswith("| ")}
    for layer, prefixes in LAYERS:
        assert layer in rows, layer
        for prefix in filter(None, prefixes):
            shown = prefix.replace(".", "/")
            assert f"`{shown}`" in rows[layer] or f"`{shown}/`" in rows[layer], (layer, prefix)
    order = [line.split("|")[1].strip() for line in text.splitlines() if line.split("|")[1:2]
             and line.split("|")[1].strip() in dict(LAYERS)]
    assert order == [layer for layer, _ in LAYERS]
