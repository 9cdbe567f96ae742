"""The explorer's web server: the page, its JSON, its downloads (``thermocontact explore``).

A threaded HTTP server of the standard library (one thread per request, so twenty
sessions are served at once).  The server keeps no session: every request carries the
whole state of its page (the query string, whose keys are the keyword names of
:func:`thermocontact.contact`), so each browser tab has its own state by construction
and a link reopens the same view.  The only state held here is the background jobs
(:class:`~.jobs.Jobs`), known by ids too long to guess.

Routes
------
``GET /``                        the page (and ``/explorer.js``, ``/explorer.css``)
``GET /api/contact?<state>``     the contact tab's view, or the errors by field
``GET /api/tei?<state>``         the TEI tab's view
``GET /api/code?<state>&tab=``   the command and the Python call of a tab
``GET /api/setup``               the fields, their defaults, the library's materials
``POST /api/jobs?kind=&<state>`` start a map or a transient run (or join the same one)
``GET /api/jobs/<id>``           its status, progress and, once done, its view
``POST /api/jobs/<id>/cancel``   cancel it
``GET /download/point.json?<state>``, ``/download/point.csv?<state>``: the point
``GET /download/<kind>.nc?job=<id>``: a finished job's dataset

Errors reach the page as JSON ``{"error": {"message", "fields"}}`` with a message
next to each field it names, never a traceback (that goes to the server's standard
error).  Files are written only under one temporary folder, removed when the server
stops; nothing a client sends is used as a path.
"""

from __future__ import annotations

import atexit
import ipaddress
import json
import shutil
import sys
import tempfile
import threading
import traceback
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from importlib.resources import files
from urllib.parse import parse_qs, urlsplit

from . import adapter
from .jobs import Jobs

__all__ = ["Explorer", "is_loopback", "serve"]

#: The page's files, read once from the package.
STATIC = {"/": ("index.html", "text/html; charset=utf-8"),
          "/explorer.js": ("explorer.js", "text/javascript; charset=utf-8"),
          "/explorer.css": ("explorer.css", "text/css; charset=utf-8")}
#: The longest query string taken.
MAX_QUERY = 8192
#: The longest request body read (the requests have none worth reading).
MAX_BODY = 8192


def is_loopback(host: str) -> bool:
    """Whether ``host`` names this machine only (127.0.0.0/8, ::1, localhost)."""
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host.strip("[]")).is_loopback
    except ValueError:
        return False


class Explorer:
    """The application: routes a request to the adapter or the jobs, and answers.

    Parameters
    ----------
    running : int
        Background jobs computing at once.
    """

    def __init__(self, running=2):
        self.folder = tempfile.mkdtemp(prefix="thermocontact-explore-")
        self.jobs = Jobs(self.folder, running=running)
        atexit.register(self.close)  # the folder goes even if nobody closes the server
        package = files(__package__) / "static"
        self.static = {route: ((package / name).read_bytes(), kind)
                       for route, (name, kind) in STATIC.items()}

    def close(self):
        """End the jobs' processes and remove the temporary folder (again: nothing)."""
        self.jobs.close()
        shutil.rmtree(self.folder, ignore_errors=True)

    def warm(self):
        """Solve the default contact once (the first solve pays for imports and caches)."""
        try:
            adapter.contact_view({})
        except Exception:  # pragma: no cover - a warm-up only
            pass

    def handle(self, method, target):
        """``(status, content type, body, extra headers)`` for one request."""
        parts = urlsplit(target)
        if len(parts.query) > MAX_QUERY:
            return self._error(414, adapter.UserError(
                f"the query is longer than {MAX_QUERY} characters"))
        path = parts.path
        query = parse_qs(parts.query, keep_blank_values=True)
        if method == "GET" and path == "/favicon.ico":
            return 204, "image/x-icon", b"", {}
        if method == "GET" and path in self.static:
            body, kind = self.static[path]
            return 200, kind, body, {}
        try:
            return self._route(method, path, query)
        except (adapter.UserError, *adapter.EXPECTED) as exc:
            return self._error(400, adapter.explain(exc))
        except Exception as exc:  # never a traceback in the page: it goes to stderr
            traceback.print_exc(file=sys.stderr)
            return self._error(500, adapter.explain(exc))

    def _route(self, method, path, query):
        if method == "GET" and path == "/api/setup":
            return self._json(adapter.setup())
        if method == "GET" and path in ("/api/contact", "/api/tei", "/api/code",
                                        "/download/point.json", "/download/point.csv"):
            state = adapter.parse_state(query)
            if path == "/api/contact":
                return self._json(adapter.contact_view(state))
            if path == "/api/tei":
                return self._json(adapter.tei_view(state))
            if path == "/api/code":
                return self._json(adapter.code_for(state, state.get("tab", "contact")))
            if path == "/download/point.json":
                return self._file(adapter.contact_record(state).encode(),
                                  "application/json", "point.json")
            return self._file(adapter.contact_csv(state, self.folder), "text/csv",
                              "point.csv")
        if method == "POST" and path == "/api/jobs":
            kind = (query.get("kind") or [""])[0]
            state = adapter.parse_state(query)
            key = adapter.job_key(kind, state)
            return self._json({"job": self.jobs.start(kind, state, key)})
        if path.startswith("/api/jobs/"):
            job_id, _, action = path[len("/api/jobs/"):].partition("/")
            if method == "GET" and not action:
                report = self.jobs.report(job_id)
                if report is not None:
                    return self._json(report)
            elif method == "POST" and action == "cancel":
                if self.jobs.cancel(job_id):
                    return self._json({"cancelled": job_id})
            return self._error(404, adapter.UserError("no such job (finished long ago, or "
                                                      "the server was restarted)"))
        if method == "GET" and path in ("/download/map.nc", "/download/transient.nc"):
            kind = path[len("/download/"):-len(".nc")]
            found = self.jobs.file((query.get("job") or [""])[0], kind)
            if found is None:
                return self._error(404, adapter.UserError(f"no finished {kind} of that job"))
            with open(found, "rb") as fh:
                return self._file(fh.read(), "application/x-netcdf", f"{kind}.nc")
        return self._error(404, adapter.UserError(f"no page {path}"))

    @staticmethod
    def _json(content, status=200):
        return (status, "application/json",
                json.dumps(content, allow_nan=False).encode(), {"Cache-Control": "no-store"})

    def _error(self, status, exc):
        return self._json({"error": exc.to_dict()}, status)

    @staticmethod
    def _file(body, kind, name):
        return 200, kind, body, {"Content-Disposition": f'attachment; filename="{name}"'}


class Handler(BaseHTTPRequestHandler):
    """Hands each request to the server's :class:`Explorer`."""

    server_version = "thermocontact-explore"
    protocol_version = "HTTP/1.1"
    # Small answers on a kept-alive connection: sent at once, not held back by Nagle's
    # algorithm for the browser's delayed acknowledgement (40 ms each).
    disable_nagle_algorithm = True

    def _answer(self, method):
        length = int(self.headers.get("Content-Length") or 0)
        if length:
            self.rfile.read(min(length, MAX_BODY))
        if not self.server.host_allowed(self.headers.get("Host", "")):
            status, kind, body, extra = self.server.app._error(
                421, adapter.UserError("this server answers to its own address only"))
        else:
            status, kind, body, extra = self.server.app.handle(method, self.path)
        self.send_response(status)
        self.send_header("Content-Type", kind)
        self.send_header("Content-Length", str(len(body)))
        self.send_header("X-Content-Type-Options", "nosniff")
        # The page loads nothing from elsewhere, and only pages of this server frame it.
        self.send_header("Content-Security-Policy",
                         "default-src 'self'; frame-ancestors 'self'")
        for name, value in extra.items():
            self.send_header(name, value)
        self.end_headers()
        self.wfile.write(body)

    def do_GET(self):  # noqa: N802 - the standard library's name
        self._answer("GET")

    def do_POST(self):  # noqa: N802
        self._answer("POST")

    def log_message(self, format, *args):  # the page's requests are not news
        pass


class Server(ThreadingHTTPServer):
    """The HTTP server, its :class:`Explorer`, and which ``Host`` headers it answers."""

    daemon_threads = True

    def __init__(self, address, app):
        self.app = app
        super().__init__(address, Handler)

    @property
    def url(self) -> str:
        host, port = self.server_address[:2]
        return f"http://{host}:{port}/"

    def host_allowed(self, header: str) -> bool:
        """On loopback, only requests addressed to this machine by name or number (a
        page elsewhere cannot reach the server through a name it controls)."""
        host = self.server_address[0]
        if not is_loopback(host):
            return True
        name = header.rsplit(":", 1)[0] if not header.endswith("]") else header
        return is_loopback(name.strip("[]")) or name == host

    def handle_error(self, request, client_address):
        """A page that went away mid-answer (its request aborted by a newer one) is not
        an error; anything else is told on standard error."""
        if isinstance(sys.exc_info()[1], ConnectionError):
            return
        super().handle_error(request, client_address)

    def server_close(self):
        super().server_close()
        self.app.close()


def serve(host="127.0.0.1", port=0, running=2) -> Server:
    """The explorer's server, bound and serving in a thread of its own; stop it with
    ``server.shutdown(); server.server_close()``.

    Parameters
    ----------
    host : str
        The address to listen on (loopback by default).
    port : int
        0 for a free port.
    running : int
        Background jobs computing at once.

    Returns
    -------
    Server
        Its ``url`` is the page's address.
    """
    app = Explorer(running=running)
    try:
        server = Server((host, port), app)
    except OSError:
        app.close()
        raise
    threading.Thread(target=server.serve_forever, daemon=True, name="explore").start()
    threading.Thread(target=app.warm, daemon=True, name="explore-warm").start()
    return server
