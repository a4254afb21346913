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
