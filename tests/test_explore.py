"""The explorer without a browser: its adapter against the public calls, its errors,
its server's routes and its command (the browser's tests: test_explore_browser.py)."""

from __future__ import annotations

import json
import os
import shlex
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request

import numpy as np
import pytest

import thermocontact as tc
from thermocontact.cli.main import main
from thermocontact.explore import adapter
from thermocontact.explore.server import Explorer, is_loopback
from conftest import contact_keywords as kwargs

#: The README's contact, as the page's fields hold it.
POINT = {"cylinder": "copper", "half_plane": "steel", "radius": "10mm", "load": "50kN/m",
         "speed": "2m/s", "friction": "0.2", "lam": "-1"}
#: The same with the bulk temperatures instead of lam.
HOT = {**{k: v for k, v in POINT.items() if k != "lam"},
       "bulk_temperatures": "80C,20C", "sink_distance": "2mm"}


def record_at(record, key):
    return adapter.record_value(record, key)


@pytest.fixture(scope="module")
def views():
    return {name: (state, adapter.contact_view(state), tc.contact(**kwargs(state)).to_dict())
            for name, state in (("lam", POINT), ("hot", HOT))}


@pytest.mark.parametrize("name", ["lam", "hot"])
def test_every_number_shown_is_the_records(views, name):
    """Each number carries its record key and the repr of that record value."""
    state, view, record = views[name]
    keys = [n["key"] for n in view["numbers"]]
    assert len(keys) == len(set(keys)) >= 15
    for n in view["numbers"]:
        assert n["value"] == repr(record_at(record, n["key"])), n["key"]
    if name == "hot":
        assert "peak_temperatures[0]" in keys and "lam_error" in keys
    assert view["verdicts"]["valid"]["value"] == repr(record["valid"])
    assert view["verdicts"]["applicable"]["reasons"] == record["applicability_reasons"]


def test_a_moving_half_plane_shows_its_temperatures():
    state = {**POINT, "speed2": "0.5m/s"}
    view = adapter.contact_view(state)
    record = tc.contact(**kwargs(state)).to_dict()
    shown = {n["key"]: n["value"] for n in view["numbers"]}
    for key in ("half_plane_incoming_temperature", "flash_temperature_half_plane"):
        assert shown[f"branches[0].{key}"] == repr(record["branches"][0][key])


def test_hertz_pressure_for_comparison(views):
    """The dashed Hertz curve: its peak is the record's Hertz peak pressure and it
    carries the load (Simpson's rule on the cosine points: a few parts in 1e4)."""
    _, view, record = views["lam"]
    x, p = (np.array(view["curves"][k]) for k in ("hertz_x", "hertz_pressure"))
    assert p.max() == pytest.approx(record["hertz_peak_pressure"], rel=1e-12)
    assert x[0] == pytest.approx(-record["hertz_half_width"], rel=1e-12)
    from scipy.integrate import simpson

    assert simpson(p, x=x) == pytest.approx(50e3, rel=1e-3)


def test_absolute_temperatures_with_bulk_temperatures(views):
    """With the bulk temperatures the surfaces' curves are absolute: the record's bulk
    temperature plus the rise (the same arrays as the branch's)."""
    _, view, record = views["hot"]
    res = tc.contact(**kwargs(HOT))
    curve = np.array(view["curves"]["temperature_cylinder"], dtype=float)
    rise = res.primary.temperature_cylinder
    assert np.array_equal(np.isnan(curve), np.isnan(rise))
    assert np.allclose(curve - record["inputs"]["bulk_temperatures"][0], rise, rtol=0,
                       atol=1e-12 * np.nanmax(curve), equal_nan=True)
    assert np.nanmax(curve) <= record["peak_temperatures"][0] * (1 + 1e-12)


def test_a_load_no_patch_carries():
    """No branch: the numbers of the branch shown as absent (None), the message why."""
    view = adapter.contact_view({"cylinder": "steel", "half_plane": "cast-iron",
                                 "radius": "450mm", "load": "1e9N/m", "speed": "20m/s",
                                 "friction": "0.35", "lam": "1", "dundurs": "false"})
    shown = {n["key"]: n["value"] for n in view["numbers"]}
    assert shown["half_width"] == shown["flash_temperature"] == "None"
    assert float(shown["hertz_half_width"]) > 0
    assert view["verdicts"]["valid"]["value"] == "False" and view["verdicts"]["branches"] == 0
    assert view["verdicts"]["message"].startswith("no half-width carries this load")
    assert "x" not in view["curves"] and view["curves"]["hertz_pressure"]


def test_a_map_at_bulk_temperatures_has_no_curves():
    """Each point of such a map is its own contact: no boundary curves to draw."""
    import xarray as xr

    ds = xr.Dataset({k: (("speed", "load"), v) for k, v in (
        ("valid", [[1, 0]]), ("applicable", [[1, 0]]), ("branches", [[1, 1]]))},
                    coords={"load": [1e4, 2e4], "speed": [1.0]},
                    attrs={"x": "load:1e4:2e4:2:log", "y": "speed:1:1:1"})
    ds["reason"] = (("speed", "load"), [["valid", "invalid single patch"]])
    view = adapter.map_view(ds)
    assert view["verdict"] == [[3, 1]] and view["boundary_x"] == []


BAD = [("cylinder", "nosuch"), ("half_plane", "E=1"), ("half_plane", ""),
       ("radius", "abc"), ("radius", "0"), ("load", "abc"), ("load", "-5kN/m"),
       ("speed", "2kg"), ("speed", "1e999"), ("speed2", "x"), ("friction", "abc"),
       ("friction", "-1"), ("lam", "abc"), ("lam", "inf"), ("lam", ""),
       ("dundurs", "maybe")]


@pytest.mark.parametrize("name, text", BAD)
def test_bad_input_is_named_next_to_its_field(name, text):
    with pytest.raises(adapter.UserError) as info:
        adapter.contact_view({**POINT, name: text})
    assert name in info.value.fields
    assert "\n" not in info.value.fields[name] and "Traceback" not in info.value.message


@pytest.mark.parametrize("name, text", [("bulk_temperatures", "abc"),
                                        ("sink_distance", "abc"),
                                        ("layer_thickness", "1kg")])
def test_bad_temperatures_are_named(name, text):
    with pytest.raises(adapter.UserError) as info:
        adapter.contact_view({**HOT, name: text})
    assert name in info.value.fields


@pytest.mark.parametrize("kind, name, text", [
    ("map", "x", "abc"), ("map", "y", "load:1:10:5:log"), ("map", "x", "lam:0:1:5"),
    ("transient", "duration", "abc"), ("transient", "steps", "1.5"),
    ("transient", "elements", "x"), ("transient", "elements", "3"),
    ("transient", "bulk_temperatures", "80C,20C")])
def test_bad_input_of_a_job_is_named_before_it_starts(kind, name, text):
    state = {**POINT, name: text}
    if name == "bulk_temperatures":
        state = {**HOT}
    with pytest.raises(adapter.UserError) as info:
        adapter.job_key(kind, state)
    assert name in info.value.fields or name == "bulk_temperatures" and info.value.fields


def test_tei_view_is_the_tei_call():
    view = adapter.tei_view({**POINT, "wavelength": "20mm"})
    res = tc.tei("copper", "steel", 0.2, "20mm", speed=2.0).to_dict()
    for n in view["numbers"]:
        assert n["value"] == repr(record_at(res, n["key"])), n["key"]
    curve = view["curves"]
    i = len(curve["wavelength"]) // 2
    assert curve["wavelength"][i] == pytest.approx(0.02, rel=1e-12)
    assert curve["critical_speed"][i] == pytest.approx(res["critical_speed"], rel=1e-12)
    with pytest.raises(adapter.UserError) as info:
        adapter.tei_view({**POINT, "wavelength": "1km2"})
    assert "wavelength" in info.value.fields


def test_python_code_gives_the_same_record():
    code = adapter.code_for(POINT)["python"]
    scope = {}
    exec(code.replace("tc.contact(", "result = tc.contact("), scope)
    assert scope["result"].to_dict() == tc.contact(**kwargs(POINT)).to_dict()


@pytest.mark.parametrize("state, tab", [(POINT, "contact"), (HOT, "contact"),
                                        ({**POINT, "wavelength": "20mm"}, "tei")])
def test_command_gives_the_same_record(capsys, state, tab):
    """The command shown, run, prints the record the page shows."""
    command = adapter.code_for(state, tab)["command"]
    assert main(shlex.split(command)[1:] + ["--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    if tab == "contact":
        expected = tc.contact(**kwargs(state)).to_dict()
    else:
        expected = tc.tei("copper", "steel", 0.2, "20mm", speed=2.0).to_dict()
    printed.pop("version", None), expected.pop("version", None)
    assert printed == json.loads(json.dumps(expected))


def test_map_code_and_spec_are_one_map():
    """The map's Python call and the page's map are the same specification."""
    state = {**POINT, "x": "load:10000:200000:3:log", "y": "speed:0.5:8:3:log"}
    spec = adapter.map_spec_of(state)
    python = adapter.code_for(state, "map")["python"]
    call = python.split("\n")[1].replace("tc.operating_map(", "tc.map_spec(")
    assert eval(call, {"tc": tc}).manifest() == spec.manifest()
    assert "--x load:10000.0:200000.0:3:log" in adapter.code_for(state, "map")["command"]


def test_transient_duration_unit_is_the_runs():
    """An empty duration is TRANSIENT_UNITS l^2/kappa2, the run's own unit."""
    kw = adapter.transient_call(POINT)
    _, attrs = tc.contact_transient_spec(**kw)
    assert attrs["duration_s"] == pytest.approx(adapter.TRANSIENT_UNITS * attrs["time_unit_s"],
                                                rel=1e-3)


def test_query_strings_are_read_strictly():
    assert adapter.parse_state({"load": ["5kN/m"], "other": ["x"]}) == {"load": "5kN/m"}
    for query in ({"load": ["1", "2"]}, {"radius": ["1" * 500]}):
        with pytest.raises(adapter.UserError):
            adapter.parse_state(query)


@pytest.fixture(scope="module")
def app():
    app = Explorer()
    yield app
    app.close()
    assert not os.path.exists(app.folder)


def answer(app, method, target):
    status, kind, body, headers = app.handle(method, target)
    return status, (json.loads(body) if kind == "application/json" else body), headers


def test_server_routes(app):
    status, body, _ = answer(app, "GET", "/api/contact?" + "&".join(
        f"{k}={v}" for k, v in POINT.items()))
    assert status == 200 and body["numbers"]
    status, body, _ = answer(app, "GET", "/api/contact?load=abc")
    assert status == 400 and "load" in body["error"]["fields"]
    status, body, headers = answer(app, "GET", "/download/point.csv?load=50kN/m")
    assert status == 200 and body.startswith(b"# thermocontact") and b"pressure" in body
    assert headers["Content-Disposition"].endswith('"point.csv"')
    status, body, _ = answer(app, "GET", "/download/point.json")
    assert body["inputs"]["load"] == 50e3
    for target in ("/download/map.nc?job=../../etc/passwd", "/api/jobs/nosuch",
                   "/etc/passwd", "/download/x.nc"):
        assert answer(app, "GET", target)[0] == 404
    assert answer(app, "GET", "/api/contact?" + "x" * 9000)[0] == 414
    assert os.listdir(app.folder) == []  # the CSV was made there and removed


def test_an_unexpected_error_is_one_line(app, monkeypatch):
    def broken(state):
        raise ZeroDivisionError("float division by zero")
    monkeypatch.setattr(adapter, "contact_view", broken)
    status, body, _ = answer(app, "GET", "/api/contact")
    assert status == 500
    assert body["error"]["message"] == ("the computation failed (ZeroDivisionError: float "
                                        "division by zero)")


def test_jobs_run_cancel_and_share(app):
    """A transient run in its own process with progress; the same request joins it; a
    cancel by one of two sessions leaves it running, by the last ends it."""
    state = "&".join(f"{k}={v}" for k, v in POINT.items())
    small = f"/api/jobs?kind=transient&{state}&steps=20&elements=64"
    job = answer(app, "POST", small)[1]["job"]
    assert answer(app, "POST", small)[1]["job"] == job
    for _ in range(600):
        report = answer(app, "GET", f"/api/jobs/{job}")[1]
        if report["status"] not in ("queued", "running"):
            break
        time.sleep(0.1)
    assert report["status"] == "done", report
    assert report["done"] == report["total"] == 20
    assert len(report["view"]["time"]) == 21
    status, body, _ = answer(app, "GET", f"/download/transient.nc?job={job}")
    assert status == 200 and body[:3] in (b"CDF", b"\x89HD")
    assert answer(app, "GET", f"/download/map.nc?job={job}")[0] == 404
    long = f"/api/jobs?kind=transient&{state}&steps=5000&elements=400"
    job = answer(app, "POST", long)[1]["job"]
    assert answer(app, "POST", long)[1]["job"] == job
    answer(app, "POST", f"/api/jobs/{job}/cancel")
    assert answer(app, "GET", f"/api/jobs/{job}")[1]["status"] in ("queued", "running")
    answer(app, "POST", f"/api/jobs/{job}/cancel")
    assert answer(app, "GET", f"/api/jobs/{job}")[1]["status"] == "cancelled"
    for path, _, names in os.walk(app.folder):
        assert os.path.realpath(path).startswith(os.path.realpath(tempfile.gettempdir()))


def test_jobs_are_bounded(tmp_path):
    """No more jobs waiting or computing than the server keeps: the next is refused in
    one line, and none starts a process before its turn."""
    from thermocontact.explore.jobs import Jobs

    jobs = Jobs(str(tmp_path), running=0, kept=2)  # none may compute: all wait
    try:
        ids = [jobs.start("transient", {}, key) for key in ("a", "b")]
        assert jobs.start("transient", {}, "a") == ids[0]  # the same: shared
        with pytest.raises(adapter.UserError, match="2 maps and runs to compute"):
            jobs.start("transient", {}, "c")
        assert [jobs.report(i)["status"] for i in ids] == ["queued", "queued"]
        assert jobs.cancel(ids[1]) and jobs.report(ids[1])["status"] == "cancelled"
        jobs.start("transient", {}, "c")
    finally:
        jobs.close()


def test_loopback_only_by_name():
    assert all(map(is_loopback, ("127.0.0.1", "127.0.0.2", "::1", "[::1]", "localhost")))
    assert not any(map(is_loopback, ("0.0.0.0", "192.0.2.1", "example.org", "")))


def test_explore_refuses_a_bad_port(capsys):
    assert main(["explore", "--port", "70000"]) == 2
    assert "--port must be 0" in capsys.readouterr().err


def test_explore_warns_off_loopback(capsys, monkeypatch):
    from thermocontact.explore import server

    def cannot(host, port):
        raise OSError(99, "Cannot assign requested address")
    monkeypatch.setattr(server, "serve", cannot)
    assert main(["explore", "--host", "192.0.2.1", "--port", "8123"]) == 2
    err = capsys.readouterr().err
    assert "warning: --host 192.0.2.1 is not loopback" in err
    assert "error: cannot listen on 192.0.2.1:8123 (Cannot assign requested address)" in err


def test_explore_prints_its_address_and_serves(tmp_path):
    """The command, as a user runs it: its address on loopback, the page there; ended,
    it leaves nothing in the temporary folder."""
    proc = subprocess.Popen([sys.executable, "-m", "thermocontact", "explore"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            env={**os.environ, "TMPDIR": str(tmp_path)})
    try:
        line = proc.stdout.readline()
        assert line.startswith("thermocontact explore: http://127.0.0.1:"), line
        url = line.split()[2]
        with urllib.request.urlopen(url, timeout=30) as page:
            assert b"thermocontact explore" in page.read()
            assert page.headers["Content-Security-Policy"].startswith("default-src 'self'")
        # Addressed by another name (a page elsewhere rebinding its name to loopback):
        # refused.
        other = urllib.request.Request(url, headers={"Host": "example.org"})
        with pytest.raises(urllib.error.HTTPError) as refused:
            urllib.request.urlopen(other, timeout=30)
        assert refused.value.code == 421
        with urllib.request.urlopen(url + "api/setup", timeout=30) as setup:
            assert "copper" in json.load(setup)["names"]
        assert [p.name for p in tmp_path.iterdir()][0].startswith("thermocontact-explore-")
    finally:
        proc.terminate()
        proc.wait(timeout=30)
    assert proc.returncode == 0 and "stopped" in proc.stderr.read()
    assert not [p for p in tmp_path.iterdir() if p.name.startswith("thermocontact-explore-")]
