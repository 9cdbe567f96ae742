"""The explorer in a real browser: Debian's Chromium driven by Playwright.

What a person sees is read from the page (each number's ``data-value``) and compared
with the public calls; inputs are typed, the map clicked, links reopened, bad input
given in fields and in the URL, and twenty sessions opened at once.  One browser and
one server for the module; the map is a small one, started when the module starts
and joined by its test.
"""

from __future__ import annotations

import json
import os
import urllib.request
from urllib.parse import parse_qsl, urlencode, urlsplit

import pytest

import thermocontact as tc
from thermocontact.explore.browser import chromium_path, launch, session
from conftest import contact_keywords as kwargs

sync_api = pytest.importorskip("playwright.sync_api",
                               reason="playwright is not installed (pip install '.[test]')")

if chromium_path() is None:
    if os.environ.get("CI"):  # .ci/run installs it: its absence there is a failure
        raise RuntimeError("no chromium: .ci/run must install it (apt-get install chromium)")
    pytestmark = pytest.mark.skip(reason="no chromium on this machine (apt-get install "
                                         "chromium; .ci/run installs it)")

POINT = {"cylinder": "copper", "half_plane": "steel", "radius": "10mm", "load": "50kN/m",
         "speed": "2m/s", "friction": "0.2", "lam": "-1"}
#: A small map around the point (its test joins the job started with the module).
MAP = {"x": "load:30000:80000:3:log", "y": "speed:1:4:3:log"}
#: Seconds a view may take to appear (the machine may be busy).
WAIT = 60_000


@pytest.fixture(scope="module")
def server():
    from thermocontact.explore.server import serve

    srv = serve()
    # The map's job starts now, in its own process, while the other tests run.
    request = urllib.request.Request(srv.url + "api/jobs?" + urlencode(
        {**POINT, **MAP, "kind": "map"}), method="POST")
    with urllib.request.urlopen(request) as answer:
        assert "job" in json.load(answer)
    yield srv
    srv.shutdown()
    srv.server_close()


@pytest.fixture(scope="module")
def browser():
    pw = sync_api.sync_playwright().start()
    b = launch(pw)
    yield b
    b.close()
    pw.stop()


class Session:
    """One browser session (a context of its own) on the explorer, with the errors its
    page reports."""

    def __init__(self, browser, server, query=None, wait=True):
        self.context = session(browser)
        self.page = self.context.new_page()
        self.errors = []
        self.page.on("pageerror", lambda e: self.errors.append(str(e)))
        # A refused input is answered 400, which the browser's console logs: not an
        # error of the page.
        self.page.on("console", lambda m: m.type == "error" and "status of 400" not in m.text
                     and self.errors.append(m.text))
        self.page.goto(server.url + ("?" + urlencode(query) if query else ""),
                       wait_until="commit" if not wait else "load")
        if wait:
            self.ready("contact", 1)

    def ready(self, panel, count):
        """Wait until the panel has been drawn ``count`` times."""
        self.page.wait_for_function(
            f"Number(document.getElementById('panel-{panel}').dataset.ready) >= {count}",
            timeout=WAIT)

    def count(self, panel):
        return int(self.page.get_attribute(f"#panel-{panel}", "data-ready") or 0)

    def shown(self, panel):
        """``{record key: data-value}`` of every number the panel shows."""
        pairs = self.page.eval_on_selector_all(
            f"#panel-{panel} [data-quantity]",
            "els => els.map(e => [e.dataset.quantity, e.dataset.value])")
        return dict(pairs)

    def type(self, name, text):
        """Type into a field of the contact and press Enter; wait for the answer to it
        (a new picture or an error)."""
        sent = int(self.page.get_attribute("#panel-contact", "data-sent") or 0)
        self.page.fill(f"#f-{name}", text)
        self.page.press(f"#f-{name}", "Enter")
        self.page.wait_for_function(
            f"(p => Number(p.dataset.sent) > {sent} && p.dataset.answered === p.dataset.sent)"
            f"(document.getElementById('panel-contact'))", timeout=WAIT)

    def state(self):
        return dict(parse_qsl(urlsplit(self.page.url).query))

    def close(self):
        self.context.close()


def at(record, key):
    from thermocontact.explore.adapter import record_value

    return record_value(record, key)


def assert_shown_is(shown, record):
    """Every number shown equals the record's to 1e-9 (its repr: to the last digit)."""
    assert len(shown) >= 15
    for key, value in shown.items():
        expected = at(record, key)
        if isinstance(expected, float):
            assert float(value) == pytest.approx(expected, rel=1e-9, abs=1e-300), key
        else:
            assert value == repr(expected), key


def test_numbers_shown_are_the_librarys(browser, server):
    s = Session(browser, server, POINT)
    assert_shown_is(s.shown("contact"), tc.contact(**kwargs(POINT)).to_dict())
    # The URL holds the state in tc.contact's keywords: the same record again.
    state = s.state()
    assert state == POINT
    assert tc.contact(**kwargs(state)).to_dict()["flash_temperature"] == float(
        s.shown("contact")["flash_temperature"])
    # The code shown is the call.
    assert s.page.inner_text("#code-python").endswith(
        "tc.contact('copper', 'steel', radius='10mm', load='50kN/m', speed='2m/s', "
        "friction=0.2, lam=-1.0)")
    assert s.errors == []
    s.close()


def test_a_change_updates_the_views_and_the_url(browser, server):
    s = Session(browser, server, POINT)
    s.type("load", "80kN/m")
    state = {**POINT, "load": "80kN/m"}
    assert s.state() == state
    assert_shown_is(s.shown("contact"), tc.contact(**kwargs(state)).to_dict())
    # The link reopens the same view, in a session of its own.
    again = Session(browser, server, s.state())
    assert again.shown("contact") == s.shown("contact")
    again.close()
    # Bulk temperatures instead of lam: absolute temperatures, lam an output.
    s.page.check("input[name=closure][value=temperatures]")
    s.page.fill("#f-sink_distance", "2mm")
    s.type("bulk_temperatures", "80C,20C")
    hot = {k: v for k, v in state.items() if k != "lam"}
    hot.update(bulk_temperatures="80C,20C", sink_distance="2mm")
    assert s.state() == hot
    shown = s.shown("contact")
    assert "peak_temperatures[0]" in shown
    assert_shown_is(shown, tc.contact(**kwargs(hot)).to_dict())
    assert s.errors == []
    s.close()


#: Bad text in each field of the contact, and values out of range.
BAD = [("radius", "abc"), ("load", "-5kN/m"), ("speed", "2kg"), ("speed2", "x"),
       ("cylinder", "E=1"), ("half_plane", "nosuch"), ("friction", "abc"), ("lam", "inf")]


def test_bad_input_named_and_last_picture_kept(browser, server):
    s = Session(browser, server, POINT)
    good = s.shown("contact")
    for name, text in BAD:
        s.type(name, text)
        message = s.page.inner_text(f"[data-error-for={name}]")
        assert name in message and "Traceback" not in s.page.content(), name
        assert s.page.get_attribute(f"#f-{name}", "aria-invalid") == "true"
        assert s.shown("contact") == good
        assert s.page.get_attribute("#panel-contact", "data-stale") == "1"
        s.type(name, POINT.get(name, "0"))
        assert s.page.inner_text(f"[data-error-for={name}]") == ""
        assert s.shown("contact") == good
    assert s.errors == []
    s.close()


def test_bad_input_in_the_tabs_fields(browser, server):
    """The map's axes, the TEI's wavelength, the transient's fields: each bad one named
    next to it."""
    s = Session(browser, server, {**POINT, **MAP, "tab": "tei"})
    s.ready("tei", 1)
    for tab, name, text in (("tei", "wavelength", "abc"), ("map", "x", "load:1:abc:3"),
                            ("map", "y", "lam:0:1:3"), ("transient", "steps", "1.5"),
                            ("transient", "elements", "x"), ("transient", "duration", "1kg")):
        s.page.click(f"#tab-{tab}")
        s.page.fill(f"#f-{name}", text)
        s.page.press(f"#f-{name}", "Enter")
        s.page.wait_for_function(
            f"document.querySelector('[data-error-for={name}]').textContent !== ''",
            timeout=WAIT)
        assert name in s.page.inner_text(f"[data-error-for={name}]")
        assert "Traceback" not in s.page.content()
        s.page.fill(f"#f-{name}", {**MAP, "wavelength": "50mm", "steps": "200",
                                   "elements": "120", "duration": ""}[name])
        s.page.press(f"#f-{name}", "Enter")
    assert s.errors == []
    s.close()


def test_bad_input_in_the_url(browser, server):
    s = Session(browser, server, {**POINT, "load": "abc", "unknown": "1"}, wait=False)
    s.page.wait_for_function("document.body.dataset.started === '1'", timeout=WAIT)
    assert "load" in s.page.inner_text("[data-error-for=load]")
    assert s.shown("contact") == {} and "Traceback" not in s.page.content()
    s.type("load", "50kN/m")
    assert_shown_is(s.shown("contact"), tc.contact(**kwargs(POINT)).to_dict())
    s.close()


def test_map_click_moves_the_point(browser, server):
    s = Session(browser, server, {**POINT, **MAP, "tab": "map"})
    s.ready("map", 1)
    assert s.page.locator("#plot-map rect").count() == 9
    assert not s.page.is_hidden("#download-map")
    before = s.count("contact")
    box = s.page.locator("#plot-map rect").nth(2).bounding_box()  # the lowest row's last
    s.page.mouse.click(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    s.ready("contact", before + 1)
    state = s.state()
    assert state["load"] != POINT["load"] and state["speed"] != POINT["speed"]
    assert_shown_is(s.shown("contact"), tc.contact(**kwargs(state)).to_dict())
    # The point moved on the map to where it was clicked.
    marker = s.page.locator("#plot-map circle.marker").bounding_box()
    assert abs(marker["x"] + marker["width"] / 2 - (box["x"] + box["width"] / 2)) < 2
    assert "thermocontact map --cylinder copper" in s.page.inner_text("#code-command")
    href = s.page.get_attribute("#download-map", "href")
    with urllib.request.urlopen(server.url.rstrip("/") + href) as answer:
        assert answer.read(3) in (b"CDF", b"\x89HD")
    assert s.errors == []
    s.close()


def test_tei_tab(browser, server):
    s = Session(browser, server, {**POINT, "wavelength": "20mm", "tab": "tei"})
    s.ready("tei", 1)
    record = tc.tei("copper", "steel", 0.2, "20mm", speed=2.0).to_dict()
    shown = {k: v for k, v in s.shown("tei").items() if k != "stable_at_all_speeds"}
    for key, value in shown.items():
        assert float(value) == pytest.approx(at(record, key), rel=1e-9), key
    assert s.page.locator("#plot-tei path.series").count() == 1
    s.close()


def test_transient_tab_runs_and_plays(browser, server):
    s = Session(browser, server, {**POINT, "tab": "transient", "steps": "20",
                                  "elements": "64", "duration": "1ms"})
    s.page.click("#transient-run")
    s.ready("transient", 1)
    assert s.page.get_attribute("#transient-time", "data-value") == "0.0"
    s.page.click("#transient-play")
    s.page.wait_for_function("document.getElementById('transient-frame').value === '20'",
                             timeout=WAIT)
    assert float(s.page.get_attribute("#transient-time", "data-value")) == pytest.approx(
        1e-3, rel=1e-12)
    assert "--transient --duration 1ms --steps 20 --elements 64" in s.page.inner_text(
        "#code-command")
    assert s.errors == []
    s.close()


def test_twenty_sessions_at_once(browser, server):
    """Twenty sessions, each its own load, opened at once (twenty frames of one page,
    each a document with its own state and requests): each shows its own contact (the
    half-width grows with the load; every fifth compared with the library), and none
    an error."""
    loads = [f"{30 + 2 * i}kN/m" for i in range(20)]
    s = Session(browser, server, POINT)
    frames = "".join(f'<iframe src="{server.url}?{urlencode({**POINT, "load": load})}" '
                     f'width="300" height="200"></iframe>' for load in loads)
    s.page.evaluate("html => { document.body.innerHTML = html; }", frames)
    widths = []
    for i, (frame, load) in enumerate(zip(s.page.frames[1:], loads)):
        frame.wait_for_function(
            "Number(document.getElementById('panel-contact').dataset.ready) >= 1",
            timeout=WAIT)
        shown = dict(frame.eval_on_selector_all(
            "#panel-contact [data-quantity]",
            "els => els.map(e => [e.dataset.quantity, e.dataset.value])"))
        widths.append(float(shown["half_width"]))
        if i % 5 == 0:
            expected = tc.contact(**kwargs({**POINT, "load": load})).to_dict()
            for key in ("half_width", "flash_temperature", "peak_pressure"):
                assert float(shown[key]) == pytest.approx(expected[key], rel=1e-9), key
        assert dict(parse_qsl(urlsplit(frame.url).query))["load"] == load
        assert frame.evaluate("document.getElementById('general').textContent") == ""
    assert all(a < b for a, b in zip(widths, widths[1:]))
    assert len(s.page.frames) == 21 and s.errors == []
    s.close()
