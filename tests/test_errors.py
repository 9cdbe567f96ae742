"""The package's errors: one hierarchy under thermocontact.Error, each kind catchable,
picklable with its parameters, and worded in the library's own names (never the
command line's flags)."""

import ast
import builtins
import pathlib
import pickle

import pytest

import thermocontact as tc

SRC = pathlib.Path(tc.__file__).parent


def test_one_hierarchy():
    assert issubclass(tc.InputError, tc.Error) and issubclass(tc.InputError, ValueError)
    assert issubclass(tc.MaterialError, tc.InputError)
    assert issubclass(tc.FileError, tc.InputError)
    assert issubclass(tc.SolveError, tc.Error) and issubclass(tc.SolveError, RuntimeError)
    assert issubclass(tc.NotConvergedError, tc.SolveError)
    assert issubclass(tc.ExecutionError, tc.Error)
    from thermocontact.io.files import WriteError

    assert issubclass(WriteError, tc.FileError)
    # Every public error is one of them.
    public = [getattr(tc, name) for name in tc.__all__ if name.endswith("Error")]
    assert public and all(issubclass(cls, tc.Error) for cls in public)


def _raised_names():
    """``(file, line, name)`` of every ``raise Name(...)`` in the package."""
    for path in sorted(SRC.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Raise) and isinstance(node.exc, ast.Call):
                func = node.exc.func
                name = func.id if isinstance(func, ast.Name) else getattr(func, "attr", None)
                if name:
                    yield path.relative_to(SRC), node.lineno, name


def test_every_error_raised_is_the_package_s_or_a_defect():
    """An error the package raises on purpose is a thermocontact.Error; the built-in
    ones left are internal contracts (a defect if a user ever sees one) and the
    protocol's own (TypeError of a result without a record or field)."""
    from thermocontact.explore import adapter
    from thermocontact.io import files
    from thermocontact.problem import errors, materials

    ours = {name for module in (errors, materials, files, adapter) for name in dir(module)
            if isinstance(getattr(module, name), type)
            and issubclass(getattr(module, name), tc.Error)}
    allowed_builtins = {"ValueError", "TypeError", "AttributeError"}
    found = set()
    for path, line, name in _raised_names():
        if name == "SystemExit" and path.parts[0] == "cli":
            continue  # a command's own end (the explorer's server, stopped)
        if name == "RuntimeError" and str(path) == "explore/browser.py":
            continue  # the tests' browser launcher, not the package's work
        if hasattr(builtins, name):
            assert name in allowed_builtins, f"{path}:{line} raises {name}"
        elif name.endswith("Error"):
            assert name in ours, f"{path}:{line} raises {name}, not a thermocontact.Error"
            found.add(name)
    assert {"InputError", "SolveError", "NotConvergedError", "MaterialError",
            "WriteError"} <= found


def test_errors_survive_a_trip_to_a_worker():
    for exc in (tc.InputError("lam must be in [-1e6, 1e6], got 2e6", parameters=("lam",)),
                tc.FileError("could not read run.nc", parameters=("ds",)),
                tc.NotConvergedError("did not converge"), tc.ExecutionError("lost")):
        back = pickle.loads(pickle.dumps(exc))
        assert type(back) is type(exc) and str(back) == str(exc)
        assert getattr(back, "parameters", ()) == getattr(exc, "parameters", ())


def test_library_messages_name_no_flags():
    """Below the command line, a message names parameters as Python spells them; the
    command line writes them as its flags (InputError.parameters)."""
    offenders = []
    for path in sorted(SRC.rglob("*.py")):
        if path.parent.name == "cli":
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Raise) and isinstance(node.exc, ast.Call):
                for arg in node.exc.args[:1]:
                    for const in ast.walk(arg):
                        if (isinstance(const, ast.Constant) and isinstance(const.value, str)
                                and "--" in const.value.replace("---", "")):
                            offenders.append(f"{path.relative_to(SRC)}:{node.lineno}")
    assert offenders == []


def test_the_command_line_writes_every_package_error_in_one_line(capsys, monkeypatch):
    """A NotConvergedError or an ExecutionError reaching the command line is one line
    and status 2, as an InputError is."""
    from thermocontact.cli import main

    for exc in (tc.NotConvergedError("the edges did not converge"),
                tc.ExecutionError("the executor failed")):
        def failing(*args, exc=exc, **kwargs):
            raise exc
        monkeypatch.setattr("thermocontact.api.solve", failing)
        assert main(["solve", "--pe", "5", "--fhpe", "0.2", "--K2-over-K1", "10",
                     "--lam", "-1"]) == 2
        err = capsys.readouterr().err
        assert err == f"error: {exc}\n"
    with pytest.raises(tc.Error):
        tc.solve(-1, 0.2, 10, lam=-1)
