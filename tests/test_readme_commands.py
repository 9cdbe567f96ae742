"""The README's test and docs commands: one each, under its marker, as CI reads them."""

import ast
import re
import shlex
import sys
from pathlib import Path

import pytest

if sys.version_info >= (3, 11):
    import tomllib
else:
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf-8")


def marked_block(marker):
    """The lines of the fenced block right after ``<!-- marker -->`` (the only one)."""
    lines = README.splitlines()
    at = [i for i, line in enumerate(lines) if f"<!-- {marker} -->" in line]
    assert len(at) == 1, f"README has {len(at)} <!-- {marker} --> markers"
    rest = lines[at[0] + 1:]
    assert rest[0].startswith("```"), f"no fenced block right after <!-- {marker} -->"
    end = rest.index("```", 1)
    return [line for line in rest[1:end] if line.strip()]


def ci_command(marker):
    """What .ci/run extracts: the first line starting with 'python3 ' after the marker."""
    after = README.split(f"<!-- {marker} -->", 1)[1]
    return next(line for line in after.splitlines() if line.startswith("python3 "))


@pytest.mark.parametrize("marker", ["test-command", "docs-command"])
def test_one_command_under_the_marker(marker):
    block = marked_block(marker)
    assert len(block) == 1 and block[0].startswith("python3 -m venv .venv && ")
    assert block[0] == ci_command(marker)
    assert f"run_marked {marker}" in (ROOT / ".ci" / "run").read_text(encoding="utf-8")


def test_docs_command_builds_with_warnings_as_errors():
    steps = [shlex.split(step) for step in ci_command("docs-command").split("&&")]
    assert steps[1][-1] == ".[docs]" and steps[1][0] == ".venv/bin/pip"
    build = steps[-1]
    assert build[0] == ".venv/bin/sphinx-build"
    assert {"-W", "--keep-going"} <= set(build) and build[-2:] == ["docs", "docs/_build/html"]


def test_docs_extra_provides_every_extension():
    """Each Sphinx extension of docs/conf.py comes from a package of the ``docs`` extra."""
    extra = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))[
        "project"]["optional-dependencies"]["docs"]
    provided = {re.split(r"[<>=!~; \[]", req, 1)[0].lower().replace("_", "-") for req in extra}
    conf = ast.parse((ROOT / "docs" / "conf.py").read_text(encoding="utf-8"))
    extensions = next(ast.literal_eval(node.value) for node in conf.body
                      if isinstance(node, ast.Assign)
                      and any(getattr(t, "id", None) == "extensions" for t in node.targets))
    packages = {ext.split(".")[0].lower().replace("_", "-") for ext in extensions}
    assert extensions and packages <= provided, packages - provided
