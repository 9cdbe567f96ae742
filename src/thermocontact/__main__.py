"""``thermocontact`` and ``python -m thermocontact``: the command line, interruptible.

The command line's modules are imported inside :func:`main`, so that an interrupt
while NumPy and SciPy load ends the command with one line and status 130, never a
traceback.  ``--version`` alone is answered before click is imported.
"""

import sys


def main(argv=None) -> int:
    """Run the command line; return its exit status."""
    args = sys.argv[1:] if argv is None else list(argv)
    if args == ["--version"]:
        # click's wording, as the command group's own --version (tested equal).
        from ._version import __version__

        sys.stdout.write(f"thermocontact, version {__version__}\n")
        return 0
    try:
        from .cli import main as cli_main

        return cli_main(None if argv is None else args)
    except KeyboardInterrupt:
        sys.stderr.write("error: interrupted\n")
        return 130


if __name__ == "__main__":
    sys.exit(main())
