"""The command group and its entry point: errors in one line, exit status 2.

Errors in the input or the solve are reported on one line of standard error with
exit status 2, naming the command's flags; nothing here raises a traceback for bad
input.  Only click and the standard library are imported before a command runs, so
that ``--version`` and ``--help`` answer at once.
"""

from __future__ import annotations

import os
import sys
from importlib import import_module

import click

from .._version import __version__
from ..problem.errors import Error, InputError

__all__ = ["cli", "main"]

#: Command name -> (module of this package, the command in it).  A command's module is
#: imported only when that command runs or its help is shown, so that ``solve --help``
#: does not load the other commands' modules.
COMMANDS = {
    "boundary": (".boundary", "boundary_cmd"),
    "contact": (".contact", "contact_cmd"),
    "explore": (".explore", "explore_cmd"),
    "map": (".maps", "map_cmd"),
    "reproduce": (".reproduce", "reproduce_cmd"),
    "solve": (".solve", "solve_cmd"),
    "tei": (".tei", "tei_cmd"),
    "transient": (".transient", "transient_cmd"),
    "zones": (".contact", "zones_cmd"),
}


class LazyGroup(click.Group):
    """A click group whose commands (:data:`COMMANDS`) are imported on first use; the
    group's help still lists every command with its short help."""

    def make_context(self, info_name, args, parent=None, **extra):
        # The help's width as click finds it (the terminal's, at most 80, less 2, at
        # least 50), given here so that click does not import shutil for it (and
        # with it bz2, lzma and zlib: 3-5 ms of ``solve --help``); the commands'
        # contexts inherit it.
        extra.setdefault("terminal_width", help_width())
        return super().make_context(info_name, args, parent=parent, **extra)

    def list_commands(self, ctx):
        return sorted(COMMANDS)

    def get_command(self, ctx, name):
        if name not in COMMANDS:
            return None
        module, attr = COMMANDS[name]
        return getattr(import_module(module, __package__), attr)


def help_width() -> int:
    """Click's help width: its forced width (its test runner's) if set, else
    ``max(min(columns, 80) - 2, 50)`` with ``columns`` as
    :func:`shutil.get_terminal_size` finds it: ``$COLUMNS`` when a positive integer,
    else the terminal of standard output, else 80."""
    if click.formatting.FORCED_WIDTH is not None:
        return click.formatting.FORCED_WIDTH
    try:
        columns = int(os.environ["COLUMNS"])
    except (KeyError, ValueError):
        columns = 0
    if columns <= 0:
        try:
            columns = os.get_terminal_size(sys.__stdout__.fileno()).columns
        except (AttributeError, ValueError, OSError):
            columns = 0
        columns = columns or 80
    return max(min(columns, 80) - 2, 50)


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="thermocontact")
def cli():
    """Thermoelastic sliding contact of a conducting cylinder on a conducting half-plane."""


def _command(args):
    """The command named by the first argument, or None."""
    return cli.get_command(None, args[0]) if args else None


def _refuse_repeated_options(args):
    """An option given twice (``--lam -1 ... --lam 1``) is refused, not silently the last.

    Options declared ``multiple`` (``--only``) may repeat.
    """
    command = _command(args)
    if command is None:
        return
    names = {}
    for param in command.params:
        if isinstance(param, click.Option) and not param.multiple:
            for opt in param.opts + param.secondary_opts:
                names[opt] = param.name
    seen = {}
    for token in args[1:]:
        if token == "--":
            break
        opt = token.split("=", 1)[0]
        if opt in names:
            if names[opt] in seen:
                raise InputError(f"{opt} must be given at most once, got it twice "
                                 f"({seen[names[opt]]} and {opt})")
            seen[names[opt]] = opt


#: Python names of the library's parameters whose flag is not their click name.
_FLAG_ALIASES = {"sigma_over_delta": "--sigma", "materials": "--materials", "x": "--x",
                 "y": "--y", "start": "--from", "stop": "--to", "initial": "--start",
                 "brake_stop": "--stop",
                 "sink_distance_over_delta": "--sink-distance",
                 "T1": "--bulk-temperatures", "T2": "--bulk-temperatures"}


def _flagged(exc, args) -> str:
    """The message of a library error with the parameters it names (Python spelling,
    ``K2_over_K1``) written as the command's flags (``--K2-over-K1``)."""
    import re

    message = str(exc)
    command = _command(args)
    if command is None:
        return message
    flags = {p.name: next((o for o in p.opts if o.startswith("--")), p.opts[0])
             for p in command.params if isinstance(p, click.Option)}
    # A switch set in the library's words (dundurs=False) is the switch's own flag
    # (--no-dundurs).
    switches = {p.name: (p.opts[0], p.secondary_opts[0]) for p in command.params
                if isinstance(p, click.Option) and p.is_flag and p.secondary_opts}
    for name in getattr(exc, "parameters", ()):
        if name in switches:
            for value, flag in zip(("True", "False"), switches[name]):
                message = re.sub(rf"(?<![\w-]){re.escape(name)}={value}(?![\w-])", flag,
                                 message)
        flag = flags.get(name) or (_FLAG_ALIASES.get(name)
                                   if _FLAG_ALIASES.get(name) in flags.values() else None)
        if flag is not None:
            message = re.sub(rf"(?<![\w-]){re.escape(name)}(?![\w-])", flag, message)
    return message


def _computes(args) -> bool:
    """Whether the command line asks for work rather than a help text or the version."""
    return bool(args) and args[0] in COMMANDS and not (
        {"-h", "--help", "--version"} & set(args[: args.index("--") if "--" in args else None]))


def _nothing_to_collect_at_exit():
    """Freeze every object at the interpreter's exit (:func:`gc.freeze`, registered
    once with :mod:`atexit`), so that its last garbage collections skip them.

    For a process whose command line computes nothing (a help text, an unknown
    command): what it made holds no file or process that a collection would have to
    finalise, and the collections would walk every object of click's import, about
    6 ms of the 100 ms of ``solve --help`` (docs/convergence.md).  Work keeps the
    usual exit, and so does a caller of :func:`main` with its own ``argv``."""
    import atexit
    import gc

    atexit.unregister(gc.freeze)
    atexit.register(gc.freeze)


def main(argv=None) -> int:
    """Entry point; returns the exit status (0, or 2 for any error).  ``argv``: the
    arguments, else this process's command line (``sys.argv[1:]``)."""
    import contextlib
    import warnings

    def one_line(message, category, *args, **kwargs):
        click.echo(f"warning: {message}", err=True)

    args = sys.argv[1:] if argv is None else list(argv)
    limits = contextlib.nullcontext()
    if _computes(args):
        # The matrices here are small: one BLAS thread is faster than several
        # competing for two cores (measured: 3x on the benchmark).  Imported only
        # for work, so that a help text or the version answers at once.
        from ..execution.executors import one_blas_thread

        limits = one_blas_thread()
    elif argv is None:  # this process's own command line: its exit is ours
        _nothing_to_collect_at_exit()
    try:
        _refuse_repeated_options(args)
        with limits, warnings.catch_warnings():
            warnings.showwarning = one_line
            rc = cli.main(args=argv, prog_name="thermocontact", standalone_mode=False)
    except click.exceptions.Exit as exc:
        return exc.exit_code
    except click.ClickException as exc:
        click.echo(f"error: {exc.format_message()}", err=True)
        return 2
    except Error as exc:  # every error of the package, in one line naming the flags
        click.echo(f"error: {_flagged(exc, args)}", err=True)
        return 2
    except click.exceptions.Abort:
        click.echo("error: aborted", err=True)
        return 130
    except (ValueError, ArithmeticError) as exc:  # e.g. a non-finite number reaching json
        click.echo(f"error: {exc}", err=True)
        return 2
    # Without standalone mode click returns, rather than raises, an Exit's code.
    return rc if isinstance(rc, int) else 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
