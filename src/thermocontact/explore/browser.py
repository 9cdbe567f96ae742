"""A real browser for the explorer's tests, benchmark and screenshots: the system's
Chromium driven by Playwright, launched the one way they all use.

Nothing is downloaded: the browser is the operating system's (Debian's ``chromium``,
installed by ``apt-get``; ``THERMOCONTACT_CHROMIUM`` names another), never one that
Playwright fetches.  Playwright is a test dependency (``pip install '.[test]'``), not
one of the explorer's.
"""

from __future__ import annotations

import os
import shutil

__all__ = ["FLAGS", "chromium_path", "launch", "session"]

#: Chromium's flags: no sandbox (the tests run as root in a container), no GPU, and
#: nothing that would reach the network by itself.
FLAGS = ("--no-sandbox", "--disable-gpu", "--disable-background-networking",
         "--disable-component-update", "--disable-sync")


def chromium_path() -> str | None:
    """The system's Chromium, or None when there is none."""
    named = os.environ.get("THERMOCONTACT_CHROMIUM")
    if named:
        return named if os.path.exists(named) else None
    for name in ("chromium", "chromium-browser"):
        found = shutil.which(name)
        if found:
            return found
    return None


def launch(playwright, headless=True):
    """The system's Chromium from ``playwright`` (``sync_playwright().start()``), with
    :data:`FLAGS` and a fresh profile (Playwright makes each launch a new user-data
    folder in the temporary folder, and removes it when the browser closes).

    Returns
    -------
    playwright.sync_api.Browser
        Each ``browser.new_context()`` is a session of its own (no shared storage).
    """
    path = chromium_path()
    if path is None:
        raise RuntimeError("no chromium on this machine (apt-get install chromium)")
    return playwright.chromium.launch(executable_path=path, headless=headless,
                                      args=list(FLAGS))


def session(browser, width=1280, height=900):
    """A browser session of its own (a context: no storage shared with another).

    The page's Content-Security-Policy allows no evaluation of strings, which is how
    Playwright runs its predicates and scripts in a page: the session bypasses it (the
    page itself never evaluates a string).

    Returns
    -------
    playwright.sync_api.BrowserContext
    """
    return browser.new_context(bypass_csp=True, viewport={"width": width, "height": height})
