"""One writer for tables: CSV with a provenance header, written whole."""

from __future__ import annotations

import csv
import datetime

from .._version import __version__
from .files import atomic_write

__all__ = ["write_table"]


def provenance(*lines: str) -> list[str]:
    """The first header lines of every file: package, version, date, then ``lines``."""
    return [f"thermocontact {__version__}, {datetime.date.today().isoformat()}", *lines]


def write_table(path, header, columns, rows):
    """Write a CSV table atomically.

    Parameters
    ----------
    path : str or os.PathLike
    header : sequence of str
        Lines after the provenance line, each written as ``# line``.
    columns : sequence of str
        The column names (the first uncommented row).
    rows : iterable of sequences
        Values; floats are written with 12 significant digits.
    """
    with atomic_write(path, "w", newline="") as fh:
        for line in provenance(*header):
            fh.write(f"# {line}\n")
        w = csv.writer(fh)
        w.writerow(columns)
        for row in rows:
            w.writerow([f"{v:.12g}" if isinstance(v, float) else v for v in row])
