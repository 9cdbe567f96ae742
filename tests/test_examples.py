"""The worked examples in docs/examples run, and print what the documents show."""

import pathlib
import re
import shlex

import pytest

from thermocontact.cli import main

EXAMPLES = pathlib.Path(__file__).parent.parent / "docs" / "examples"


def _command_and_output(text: str):
    """The ``$ thermocontact ...`` command of the console block and the next plain block."""
    console = re.search(r"```console\n(.*?)```", text, re.S).group(1)
    command = console.replace("\\\n", " ").strip()
    assert command.startswith("$ thermocontact ")
    after = text[text.index("```console"):]
    output = re.search(r"```\n(.*?)```", after[after.index("```", 10) + 3:], re.S).group(1)
    return shlex.split(command[2:])[1:], output


@pytest.mark.parametrize("name", ["electrical_contact.md", "brake_block.md",
                                  "gear_rolling_sliding.md"])
def test_example_prints_what_the_document_shows(name, tmp_path, monkeypatch, capsys):
    args, shown = _command_and_output((EXAMPLES / name).read_text())
    monkeypatch.chdir(tmp_path)  # the --plot file goes there
    assert main(args) == 0
    printed = capsys.readouterr().out
    assert printed == shown, f"{name}: regenerate the output block from the command"
    assert any(p.suffix == ".png" for p in tmp_path.iterdir())


def test_brake_block_example_is_neither_valid_nor_applicable():
    """The brake-block example under the paper's reading: valid = false and
    applicable = false, each with its reasons, in the JSON record."""
    import json

    args, _ = _command_and_output((EXAMPLES / "brake_block.md").read_text())
    args = [a for a in args if a != "--plot" and not a.endswith(".png")] + ["--json"]
    import io
    import contextlib

    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(args) == 0
    rec = json.loads(out.getvalue())
    assert rec["valid"] is False and rec["applicable"] is False
    assert rec["applicability_reasons"] and rec["branches"][0]["reason"].startswith("invalid")
