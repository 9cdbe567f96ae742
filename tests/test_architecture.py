"""The layers of docs/architecture.md, enforced: a module imports only from its own
layer or the layers below it, and nothing registers itself by being imported."""

import ast
import pathlib

import pytest

import thermocontact

PACKAGE = pathlib.Path(thermocontact.__file__).parent
#: Lowest layer first, as drawn in docs/architecture.md.
LAYERS = ("_version", "problem", "io", "execution", "physics", "numerics", "discretisation", "analysis",
          "solvers", "studies", "plotting", "figures", "api", "explore", "cli", "__main__")


def _layer(module: str) -> str:
    """``thermocontact.x.y`` -> ``x``."""
    return module.split(".")[1]


def _modules():
    for path in sorted(PACKAGE.rglob("*.py")):
        rel = path.relative_to(PACKAGE.parent).with_suffix("")
        name = ".".join(rel.parts)
        if name.endswith(".__init__"):
            name = name[: -len(".__init__")]
        if name != "thermocontact":  # the package's public surface imports from all layers
            yield name, path


def _imports(name: str, path: pathlib.Path):
    """Absolute names of the package modules imported by ``name`` (at any depth)."""
    tree = ast.parse(path.read_text())
    package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.startswith("thermocontact"):
                if node.module is None or target.count(".") == 1:
                    # "from .. import x" or "from ..layer import mod": name the modules.
                    for alias in node.names:
                        yield f"{target}.{alias.name}"
                else:
                    yield target
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name.startswith("thermocontact"):
                    yield alias.name


def test_every_module_belongs_to_a_layer():
    found = {_layer(name) for name, _ in _modules()} - {"data"}
    assert found <= set(LAYERS), found - set(LAYERS)


#: Which layers each layer may import (besides its own): the graph drawn in
#: docs/architecture.md.  The command line reaches the computations only through the
#: public calls (api) and the layers that do its own work (files, progress, pictures).
ALLOWED = {
    "_version": set(),
    "problem": set(),
    "io": {"_version", "problem"},
    "execution": {"problem", "io"},
    "physics": {"problem", "io"},
    "numerics": {"problem"},
    "discretisation": {"problem", "physics", "numerics"},
    "analysis": {"problem", "io", "physics", "numerics", "discretisation"},
    "solvers": {"_version", "problem", "io", "execution", "numerics", "discretisation",
                "analysis"},
    "studies": {"_version", "problem", "io", "execution", "physics", "numerics",
                "discretisation", "analysis", "solvers"},
    "plotting": {"problem", "io"},
    "figures": {"problem", "io", "physics", "solvers", "studies", "plotting"},
    "api": {"problem", "execution", "discretisation", "solvers", "studies"},
    # The explorer calls the library through api (one module, explore.adapter), and
    # the lower layers only for what api does not offer: the materials' table, the
    # parsing of a quantity, Hertz's pressure, the writers of files.
    "explore": {"problem", "io", "execution", "physics", "api"},
    "cli": {"_version", "problem", "io", "execution", "discretisation", "plotting",
            "figures", "api", "explore"},
    "__main__": {"_version", "cli"},
}


def test_the_graph_is_the_layers_order():
    """The graph only ever points down the order of LAYERS (so it has no cycle)."""
    assert set(ALLOWED) == set(LAYERS)
    for layer, allowed in ALLOWED.items():
        assert all(LAYERS.index(a) < LAYERS.index(layer) for a in allowed), layer


@pytest.mark.parametrize("name, path", list(_modules()), ids=[m for m, _ in _modules()])
def test_imports_follow_the_graph(name, path):
    """Each import is of the importer's own layer or of one its layer may import."""
    mine = _layer(name)
    for target in _imports(name, path):
        if target == "thermocontact":
            pytest.fail(f"{name} imports the package root; import the module instead")
        theirs = _layer(target)
        assert theirs == mine or theirs in ALLOWED[mine], (
            f"{name} ({mine}) imports {target} ({theirs}), not allowed by the graph")


def _private_imports(name, path):
    """``from <package module> import _x``: a private name taken across modules."""
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and (node.level or (node.module or "").startswith(
                "thermocontact")):
            for alias in node.names:
                if alias.name.startswith("_") and not alias.name.startswith("__"):
                    yield f"{'.' * node.level}{node.module or ''}.{alias.name}"


@pytest.mark.parametrize("name, path", list(_modules()), ids=[m for m, _ in _modules()])
def test_no_private_name_crosses_modules(name, path):
    assert not list(_private_imports(name, path)), (
        f"{name} imports private names: {list(_private_imports(name, path))}")


def test_no_private_name_of_the_package_in_tests_of_the_api():
    """The public surface resolves every exported name to a public one."""
    for name in thermocontact.__all__:
        assert not name.startswith("_") or name == "__version__"


def test_methods_are_an_explicit_registry():
    """Every registered method is a record whose representation and scheme exist."""
    from thermocontact.discretisation.methods import METHODS, Method

    assert set(METHODS) == {"graded", "graded-collocation", "galerkin", "product", "paper"}
    for name, m in METHODS.items():
        assert isinstance(m, Method) and m.name == name
        assert m.scheme in ("collocation", "projection") and m.summary


def test_the_explorer_reaches_the_library_through_its_adapter():
    """Every call of the explorer into the library is in ``explore.adapter``, so that a
    renamed keyword of the public calls changes one module of it."""
    for name, path in _modules():
        if _layer(name) != "explore" or name == "thermocontact.explore.adapter":
            continue
        outside = [t for t in _imports(name, path) if _layer(t) != "explore"]
        assert not outside, f"{name} imports {outside}: go through explore.adapter"


def test_no_import_circle():
    """The modules' imports (at any depth, lazy ones included) form no circle: every
    module can be read after the ones it imports."""
    graph = {name: {m for m in _imports(name, path) if m != name}
             for name, path in _modules()}
    known = set(graph)
    graph = {name: {m for m in deps if m in known} for name, deps in graph.items()}
    state = {}

    def visit(name, trail):
        if state.get(name) == "done":
            return
        assert state.get(name) != "open", " -> ".join(trail + [name])
        state[name] = "open"
        for dep in sorted(graph[name]):
            visit(dep, trail + [name])
        state[name] = "done"
    for name in sorted(graph):
        visit(name, [])
