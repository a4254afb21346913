"""The package's import graph (every import, at module level or inside a function) has no
circle: data flows one way, case -> flanks -> placement -> contact -> loaded -> result ->
report/pictures (docs/DESIGN.md)."""

import ast
from pathlib import Path

PACKAGE = Path(__file__).parent.parent / "src" / "toothcontact"


def module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imports() -> dict[str, set[str]]:
    """Each module of the package -> the package's modules it imports."""
    modules = {module_name(p): p for p in PACKAGE.rglob("*.py")}
    graph = {}
    for name, path in modules.items():
        package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
        found = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom):
                base = package
                for _ in range(max(node.level - 1, 0)):
                    base = base.rsplit(".", 1)[0]
                target = (f"{base}.{node.module}" if node.module else base) if node.level \
                    else (node.module or "")
                for alias in node.names:
                    child = f"{target}.{alias.name}"
                    found.add(child if child in modules else target)
            elif isinstance(node, ast.Import):
                found.update(a.name for a in node.names)
        graph[name] = {m for m in found if m in modules and m != name}
    return graph


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                out.append(sorted(component))

    for v in graph:
        if v not in index:
            visit(v)
    return out


def test_the_import_graph_has_no_circle():
    """No module imports, directly or through others, a module that imports it back."""
    assert cycles(imports()) == []


def test_the_walk_sees_a_circle():
    """The walk finds a circle where there is one (so the test above can fail)."""
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]


def packages(graph: dict[str, set[str]]) -> dict[str, set[str]]:
    """The graph of the package's parts: each subpackage (toothcontact.contact, ...) or
    top-level module one node, its modules' imports merged."""

    def part(module: str) -> str:
        return ".".join(module.split(".")[:2])

    out: dict[str, set[str]] = {}
    for name, targets in graph.items():
        out.setdefault(part(name), set()).update(part(t) for t in targets)
    return {name: targets - {name} for name, targets in out.items()}


def test_the_packages_have_no_circle_between_them():
    """No subpackage imports, through any module, one that imports it back (surfaces/
    importing modify, which imported surfaces/jet, was such a circle, which the module
    graph does not show)."""
    assert cycles(packages(imports())) == []


#: what each lower layer may import from the package (besides its own modules)
LOWER_LAYERS = {
    "toothcontact.analytic": set(),
    "toothcontact.surfaces": set(),
    "toothcontact.contact": {"toothcontact.surfaces", "toothcontact.analytic",
                             "toothcontact.parallel"},
}


def test_the_contact_engine_and_the_surfaces_import_nothing_above_them():
    """contact/ and surfaces/ (and analytic/) import none of the layers above them: not the
    case schema, the gear set, the analyses, the runner or the views (issue 54), so that the
    solver is used and tested without a case file."""
    parts = packages(imports())
    for layer, allowed in LOWER_LAYERS.items():
        assert parts[layer] <= allowed, f"{layer} imports {sorted(parts[layer] - allowed)}"


def test_the_package_graph_sees_a_layer_broken():
    """The merged graph keeps an import from a lower layer to an upper one (so the test above
    can fail)."""
    graph = {"toothcontact.contact.cycle": {"toothcontact.case"},
             "toothcontact.contact.field": {"toothcontact.contact.cycle"},
             "toothcontact.case": set()}
    assert packages(graph) == {"toothcontact.contact": {"toothcontact.case"},
                               "toothcontact.case": set()}


def test_every_import_inside_the_package_names_something_that_exists():
    """Each `from X import name` of the package's own modules, at module level or inside a
    function, names a module and a name that exist (an import inside a function is run only
    when that function is: a moved module would otherwise fail a user's run, not the
    suite). Modules that need an extra not installed here are left out."""
    import importlib

    missing = []
    for path in PACKAGE.rglob("*.py"):
        name = module_name(path)
        package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
        for node in ast.walk(ast.parse(path.read_text())):
            if not isinstance(node, ast.ImportFrom):
                continue
            if not node.level and not (node.module or "").startswith("toothcontact"):
                continue
            base = package
            for _ in range(max(node.level - 1, 0)):
                base = base.rsplit(".", 1)[0]
            target = (f"{base}.{node.module}" if node.module else base) if node.level \
                else node.module
            try:
                module = importlib.import_module(target)
            except ModuleNotFoundError as exc:
                if not (exc.name or "").startswith("toothcontact"):
                    continue                    # an extra's library (cadquery, pyvista)
                missing.append(f"{path.name}: {target}")
                continue
            for alias in node.names:
                if not hasattr(module, alias.name) and \
                        importlib.util.find_spec(f"{target}.{alias.name}") is None:
                    missing.append(f"{path.name}: {target}.{alias.name}")
    assert missing == []


def test_the_source_passes_its_linter():
    """ruff, as pyproject.toml's [tool.ruff] configures it, finds nothing in src/ (the
    test extra installs it; skipped where it is not installed)."""
    import shutil
    import subprocess
    import sys

    ruff = shutil.which("ruff") or str(Path(sys.executable).parent / "ruff")
    if not Path(ruff).exists():
        import pytest

        pytest.skip("ruff is not installed (pip install -e '.[test]' installs it)")
    done = subprocess.run([ruff, "check", "--no-cache", str(PACKAGE)], capture_output=True,
                          text=True, cwd=PACKAGE.parents[1])
    assert done.returncode == 0, done.stdout[-3000:]
