"""The explorer in the browser (``thermocontact explore``): a page over the public
calls, served on this machine.

Modules: :mod:`.adapter`, every call into the library (and the only one);
:mod:`.jobs`, maps and transient runs in background processes; :mod:`.server`, the
HTTP server and its routes; ``static/``, the page (HTML, CSS, JavaScript).
"""
