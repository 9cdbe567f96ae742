"""One writer for tables: CSV with a provenance header, written whole."""

from __future__ import annotations

import csv
import datetime

from .._version import __version__
from .files import atomic_write

__all__ = ["write_contact_csv", "write_table"]


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


def write_contact_csv(res, path):
    """Write a physical contact's distributions (``thermocontact contact --csv``): one
    row per point of every branch, SI units.

    Parameters
    ----------
    res : PhysicalContact
        Its ``branches``, each with ``valid``, ``x``, ``pressure``,
        ``temperature_cylinder`` and ``temperature_half_plane``.
    path : str or os.PathLike
    """
    rows = ([i + 1, int(b.valid)] + [float(v) for v in row]
            for i, b in enumerate(res.branches)
            for row in zip(b.x, b.pressure, b.temperature_cylinder, b.temperature_half_plane))
    write_table(path, ["SI units; temperatures are rises above the cylinder's incoming "
                       "surface temperature"],
                ["branch", "valid", "x", "pressure", "temperature_cylinder",
                 "temperature_half_plane"], rows)
