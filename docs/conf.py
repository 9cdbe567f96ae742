"""Sphinx configuration of thermocontact's documentation.

Build (warnings are errors; nothing is fetched from the network):

    sphinx-build -W --keep-going -b html docs docs/_build/html

The API reference is generated from ``thermocontact.__all__`` at every build: one page
per public name in ``api/`` (not kept in the repository), listed by the ``public-names``
directive of ``api.rst``.  A name added to ``__all__`` appears without any change here.
The pages with a ``kernelspec`` (the user guide) are executed by myst-nb at every build;
an example that raises fails the build.
"""

import importlib
import inspect
import re
import shutil
import sys
from pathlib import Path

from docutils import nodes
from docutils.statemachine import StringList
from sphinx.pycode import ModuleAnalyzer
from sphinx.util.docutils import SphinxDirective
from sphinx.util.nodes import nested_parse_with_titles

import thermocontact

HERE = Path(__file__).resolve().parent

project = "thermocontact"
author = "thermocontact contributors"
copyright = "thermocontact contributors"
release = thermocontact.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "numpydoc",
    "myst_nb",
    "sphinx_click",
]

exclude_patterns = ["_build", "**/.ipynb_checkpoints"]
# Pages in MyST (executed by myst-nb where they have a kernelspec) or reST.
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb"}

# Every cross-reference must resolve; one to an object without a page of its own (a
# module's helper, another package's class: nothing is fetched at build time) is shown as
# code by resolve_internal below.
nitpicky = True

# numpydoc renders the sections; autodoc lists the members once.
numpydoc_show_class_members = False
numpydoc_xref_param_type = False
autodoc_typehints = "none"
autodoc_member_order = "bysource"

# MyST: headings get anchors so that `page.md#section` links resolve.
myst_heading_anchors = 3

# myst-nb: execute every page with a kernelspec at every build, fail on any error.
nb_execution_mode = "force"
nb_execution_raise_on_error = True
nb_execution_show_tb = True
nb_execution_timeout = 300
nb_merge_streams = True

# Quotes and ellipses only: "--cylinder" in the command line's help stays two hyphens.
smartquotes_action = "qe"

html_theme = "alabaster"
html_title = f"thermocontact {release}"
html_theme_options = {"description": "Steady thermoelastic sliding contact with frictional heating"}
html_sidebars = {"**": ["about.html", "navigation.html", "searchbox.html"]}
html_show_sourcelink = False

# -- the API reference, from thermocontact.__all__ ------------------------------------

API_DIR = HERE / "api"


def public_names():
    """The documented names: ``thermocontact.__all__`` in its order (``__version__``, a
    string, on the package's own page)."""
    return [name for name in thermocontact.__all__ if name != "__version__"]


def _attribute_comment(name, value):
    """The ``#:`` comment of a public constant, from the module that defines it."""
    for modname in sorted(sys.modules):
        module = sys.modules[modname]
        if not modname.startswith("thermocontact.") or getattr(module, name, None) is not value:
            continue
        doc = ModuleAnalyzer.for_module(modname).find_attr_docs().get(("", name))
        if doc:
            return doc
    raise RuntimeError(f"thermocontact.{name} has no '#:' comment where it is defined")


def _page(name):
    """The reST source of one public name's page."""
    value = getattr(thermocontact, name)
    title = f"thermocontact.{name}"
    lines = [title, "=" * len(title), "", ".. currentmodule:: thermocontact", ""]
    if inspect.isclass(value) and issubclass(value, BaseException):
        lines += [f".. autoexception:: {name}", ""]
    elif inspect.isclass(value):
        lines += [f".. autoclass:: {name}", "   :members:", ""]
    elif callable(value):
        lines += [f".. autofunction:: {name}", ""]
    else:
        shown = repr(value)
        lines += [f".. data:: {name}"]
        if len(shown) <= 60:
            lines += [f"   :value: {shown}"]
        lines += [f"   :type: {type(value).__name__}", ""]
        lines += ["   " + line if line else "" for line in _attribute_comment(name, value)]
        lines += [""]
    return "\n".join(lines)


def write_api_pages(app):
    """One page per public name in ``api/``, rewritten whole at every build."""
    shutil.rmtree(API_DIR, ignore_errors=True)
    API_DIR.mkdir()
    for name in public_names():
        (API_DIR / f"{name}.rst").write_text(_page(name), encoding="utf-8")


def _summary(name):
    """The first paragraph of a public name's documentation, on one line."""
    value = getattr(thermocontact, name)
    if inspect.isclass(value) or callable(value):
        doc = inspect.getdoc(value) or ""
    else:
        doc = "\n".join(_attribute_comment(name, value))
    first = " ".join(doc.strip().split("\n\n")[0].split())
    if not first:
        raise RuntimeError(f"thermocontact.{name} has no docstring")
    return first


class PublicNames(SphinxDirective):
    """A table of the public names of each group (``thermocontact.GROUPS``), their links
    and summaries, and the toctree of their pages."""

    def run(self):
        rst = []
        for group, names in thermocontact.GROUPS.items():
            rst += [group, "-" * len(group), "", ".. list-table::", "   :widths: 25 75", ""]
            for name in names:
                if name == "__version__":
                    continue
                rst += [f"   * - :py:obj:`~thermocontact.{name}`", f"     - {_summary(name)}"]
            rst += [""]
        rst += ["", ".. toctree::", "   :hidden:", ""]
        rst += [f"   api/{name}" for name in public_names()]
        container = nodes.container()
        nested_parse_with_titles(self.state, StringList(rst, source="public-names"), container)
        return container.children


# -- references into the package's modules -------------------------------------------

def _find(path):
    """The object a dotted path names (importing its module if need be), or None."""
    parts = path.split(".")
    for i in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:i]))
        except Exception:  # not a module: try a shorter prefix
            continue
        try:
            for attr in parts[i:]:
                obj = getattr(obj, attr)
        except AttributeError:
            return None
        return obj
    return None


def _candidates(target, node):
    """Where a reference from a docstring may point: the target as written, relative to
    the documented object's module and class, and relative to every loaded module of
    the package (docstrings are written in their defining module)."""
    module, cls = node.get("py:module"), node.get("py:class")
    yield target
    if module:
        yield f"{module}.{target}"
        if cls:
            yield f"{module}.{cls}.{target}"
    for modname in sorted(sys.modules):
        if modname.startswith("thermocontact.") or modname == "thermocontact":
            yield f"{modname}.{target}"


def resolve_internal(app, env, node, contnode):
    """A Python reference to an object of the package that is not on a page of its own.

    If the object is public (the same object as ``thermocontact.<name>``), link to that
    name's page; if it exists but has no page (a module's helper, a dataclass field,
    another package's class), show it as code without a link.  A reference to nothing
    that exists stays a warning.
    """
    if node.get("refdomain") != "py":
        return None
    target = node["reftarget"].lstrip("~.")
    for path in _candidates(target, node):
        obj = _find(path)
        if obj is None:
            continue
        for name in public_names():
            if getattr(thermocontact, name) is obj and not isinstance(obj, (str, int, float)):
                return env.get_domain("py").resolve_xref(
                    env, node["refdoc"], app.builder, node["reftype"],
                    f"thermocontact.{name}", node, contnode)
        return contnode
    return None


# -- the command line's help is plain text, not reST -----------------------------------

_RST_SPECIAL = re.compile(r"([\\*`|_])")


def escape_help(app, ctx, lines):
    """Escape reST's inline markup in click's help text (``|v1 - v2|`` is no
    substitution); directive and field lines and sphinx-click's markup are kept."""
    for i, line in enumerate(lines):
        stripped = line.lstrip()
        if stripped.startswith(".. ") or stripped.startswith(":"):
            continue
        indent = line[: len(line) - len(stripped)]
        # sphinx-click's own markup: a line block, and the mark of a required option.
        keep = next((m for m in ("| ", "**Required**") if stripped.startswith(m)), "")
        lines[i] = indent + keep + _RST_SPECIAL.sub(r"\\\1", stripped[len(keep):])


def skip_field_aliases(app, what, name, obj, skip, options):
    """A NamedTuple's fields (``Method``'s) are documented in its Attributes section:
    not again as "Alias for field number k"."""
    if (getattr(obj, "__doc__", None) or "").startswith("Alias for field number"):
        return True
    return None


def setup(app):
    app.connect("builder-inited", write_api_pages)
    app.connect("autodoc-skip-member", skip_field_aliases)
    app.connect("missing-reference", resolve_internal)
    for event in ("description", "options", "epilog"):
        app.connect(f"sphinx-click-process-{event}", escape_help)
    app.add_directive("public-names", PublicNames)
    return {"parallel_read_safe": True}
