"""Command line: a thin shell over the public calls of :mod:`thermocontact.api`.

Each command is one call; its ``--json`` output is that call's result's ``to_dict()``
and a map's file is the call's dataset.
"""

from .main import cli, main

__all__ = ["cli", "main"]
