"""The screenshots of docs/explorer.md: each tab of the explorer in Chromium.

Run from the repository: ``python docs/explorer/make_screenshots.py`` (needs Debian's
``chromium`` and ``pip install '.[test]'``; about a minute, most of it the map).
Writes ``contact.png``, ``map.png``, ``tei.png`` and ``transient.png`` beside this
script.
"""

from __future__ import annotations

import pathlib
from urllib.parse import urlencode

HERE = pathlib.Path(__file__).resolve().parent
#: Steel on cast iron (docs/maps.md), the heat into the steel: a map with an existence
#: boundary, a point below it.
STATE = {"cylinder": "steel", "half_plane": "cast-iron", "radius": "450mm",
         "load": "30kN/m", "speed": "2m/s", "friction": "0.35", "lam": "1",
         "dundurs": "false", "x": "load:1000:1000000:21:log", "y": "speed:0.1:50:21:log",
         "wavelength": "50mm", "steps": "200", "elements": "120"}
WAIT = 600_000


def main():
    from playwright.sync_api import sync_playwright

    from thermocontact.explore.browser import launch, session
    from thermocontact.explore.server import serve

    server = serve()
    with sync_playwright() as pw:
        browser = launch(pw)
        page = session(browser, height=860).new_page()

        def ready(panel):
            page.wait_for_function(
                f"Number(document.getElementById('panel-{panel}').dataset.ready) >= 1",
                timeout=WAIT)

        page.goto(server.url + "?" + urlencode(STATE))
        ready("contact")
        page.screenshot(path=HERE / "contact.png", full_page=True)
        page.click("#tab-map")
        ready("map")
        page.screenshot(path=HERE / "map.png", full_page=True)
        page.click("#tab-tei")
        ready("tei")
        page.screenshot(path=HERE / "tei.png", full_page=True)
        page.click("#tab-transient")
        page.click("#transient-run")
        ready("transient")
        page.fill("#transient-frame", "40")
        page.dispatch_event("#transient-frame", "input")
        page.screenshot(path=HERE / "transient.png", full_page=True)
        browser.close()
    server.shutdown()
    server.server_close()


if __name__ == "__main__":
    main()
