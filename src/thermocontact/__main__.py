"""``thermocontact`` and ``python -m thermocontact``: the command line, interruptible.

The command line's modules are imported inside :func:`main`, so that an interrupt
while NumPy and SciPy load ends the command with one line and status 130, never a
traceback.
"""

import sys


def main(argv=None) -> int:
    """Run the command line; return its exit status."""
    try:
        from .cli import main as cli_main

        return cli_main(argv)
    except KeyboardInterrupt:
        sys.stderr.write("error: interrupted\n")
        return 130


if __name__ == "__main__":
    sys.exit(main())
