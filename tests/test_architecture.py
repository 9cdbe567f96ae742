"""The layers of docs/architecture.md, enforced: a module imports only from its own
layer or the layers below it, and nothing registers itself by being imported."""

import ast
import pathlib

import pytest

import thermocontact

PACKAGE = pathlib.Path(thermocontact.__file__).parent
#: Lowest layer first, as drawn in docs/architecture.md.
LAYERS = ("_version", "problem", "io", "execution", "physics", "numerics", "discretisation", "analysis",
          "solvers", "studies", "plotting", "figures", "api", "cli", "__main__")


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


@pytest.mark.parametrize("name, path", list(_modules()), ids=[m for m, _ in _modules()])
def test_imports_only_from_lower_layers(name, path):
    """Each import's layer is at or below the importer's."""
    mine = LAYERS.index(_layer(name))
    for target in _imports(name, path):
        if target == "thermocontact":
            pytest.fail(f"{name} imports the package root; import the module instead")
        theirs = LAYERS.index(_layer(target))
        assert theirs <= mine, f"{name} ({LAYERS[mine]}) imports {target} ({LAYERS[theirs]})"


def test_methods_are_an_explicit_registry():
    """Every registered method is a record whose representation and scheme exist."""
    from thermocontact.discretisation.methods import METHODS, Method

    assert set(METHODS) == {"graded", "graded-collocation", "galerkin", "product", "paper"}
    for name, m in METHODS.items():
        assert isinstance(m, Method) and m.name == name
        assert m.scheme in ("collocation", "projection") and m.summary
