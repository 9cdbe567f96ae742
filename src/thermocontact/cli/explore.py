"""``thermocontact explore``: the explorer in the browser (:mod:`thermocontact.explore`)."""

from __future__ import annotations

import signal

import click

__all__ = ["explore_cmd"]


@click.command("explore")
@click.option("--host", default="127.0.0.1", show_default=True,
              help="Address to listen on. Anything but loopback (127.0.0.1, ::1, "
                   "localhost) lets other machines use the explorer and its processors: a "
                   "warning says so.")
@click.option("--port", type=int, default=0,
              help="Port to listen on, 1 to 65535 [default: a free port].")
def explore_cmd(host, port):
    """Serve the explorer: a page in the browser over the contact, its map, its TEI and
    its transient. Prints its address and serves until interrupted (Ctrl-C)."""
    import threading

    from ..problem.validation import InputError

    if not 0 <= port <= 65535:
        raise InputError(f"--port must be 0 (a free port) to 65535, got {port}")
    from ..explore.server import is_loopback, serve

    if not is_loopback(host):
        click.echo(f"warning: --host {host} is not loopback: other machines can reach the "
                   f"explorer and run computations on this one", err=True)
    try:
        server = serve(host, port)
    except OSError as exc:
        raise InputError(f"cannot listen on {host}:{port} ({exc.strerror or exc})") from None
    click.echo(f"thermocontact explore: {server.url} (Ctrl-C to stop)")
    # A termination ends the server as an interrupt does: its processes and its
    # temporary folder go with it.
    signal.signal(signal.SIGTERM, _stop)
    try:
        threading.Event().wait()
    except (KeyboardInterrupt, SystemExit):
        click.echo("stopped", err=True)
    finally:
        server.shutdown()
        server.server_close()


def _stop(signum, frame):
    raise SystemExit(0)
