"""The explorer's latency in a real browser: one input changed, until the contact tab
shows the new contact (docs/explorer.md).

Run: ``python bench/bench_explorer.py [CHANGES]`` (default 100; needs Debian's
``chromium`` and ``pip install '.[test]'``).  A benchmark, not a test: it prints a
table and asserts nothing.

Each change sets one field of the contact (load, speed, radius or friction in turn, a
value not seen before, so that nothing is answered from the server's cache) and fires
its ``change`` event; the page measures, with its own clock, the time from the event
to the first frame painted after the new numbers are in the page.  The server (in
this process) times its answer to each of those requests (the solve, the view, the
JSON), so that the table splits the latency into the server's work and the rest (the
request, drawing and painting), change by change, in the same run; the server's
thread's processor time beside its wall time tells how much of it was spent waiting
for a busy machine.  Also: the time from ``thermocontact explore`` to its address, and
to the first view.
"""

from __future__ import annotations

import statistics
import subprocess
import sys
import time
from urllib.parse import urlencode

POINT = {"cylinder": "copper", "half_plane": "steel", "radius": "10mm", "load": "50kN/m",
         "speed": "2m/s", "friction": "0.2", "lam": "-1"}

#: In the page: set a field, fire its change event, and return the milliseconds until
#: the frame after the contact tab's next picture.
MEASURE = """async ([name, value]) => {
  const panel = document.getElementById('panel-contact');
  const before = Number(panel.dataset.ready);
  const f = document.querySelector(`#inputs [name="${name}"]`);
  const t0 = performance.now();
  f.value = value;
  f.dispatchEvent(new Event('change', {bubbles: true}));
  await new Promise((resolve) => {
    const obs = new MutationObserver(() => {
      if (Number(panel.dataset.ready) > before) { obs.disconnect(); resolve(); }
    });
    obs.observe(panel, {attributes: true});
  });
  await new Promise(requestAnimationFrame);
  return performance.now() - t0;
}"""


def changes(count):
    """``count`` states, each one field away from the one before, never repeated."""
    state = dict(POINT)
    out = []
    for i in range(count):
        name = ("load", "speed", "radius", "friction")[i % 4]
        k = i // 4 + 1
        value = {"load": f"{50 + 0.37 * k:.2f}kN/m", "speed": f"{2 + 0.013 * k:.3f}m/s",
                 "radius": f"{10 + 0.041 * k:.3f}mm", "friction": f"{0.2 + 0.0007 * k:.4f}"}[name]
        state = {**state, name: value}
        out.append((name, value, dict(state)))
    return out


def percentile(values, q):
    values = sorted(values)
    return values[min(len(values) - 1, int(round(q * (len(values) - 1))))]


def startup():
    """Seconds from ``thermocontact explore`` to its address printed."""
    t0 = time.perf_counter()
    proc = subprocess.Popen([sys.executable, "-m", "thermocontact", "explore"],
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    proc.stdout.readline()
    seconds = time.perf_counter() - t0
    proc.terminate()
    proc.wait()
    return seconds


def main(count=100):
    from playwright.sync_api import sync_playwright
    from thermocontact.execution.executors import one_blas_thread

    from thermocontact.explore.browser import launch, session
    from thermocontact.explore.server import Explorer, serve

    print(f"thermocontact explore: address printed after {startup():.2f} s")
    answered, cpu = [], []  # the server's milliseconds per request for a contact
    handle = Explorer.handle

    def timed(self, method, target):
        t, c = time.perf_counter(), time.thread_time()
        out = handle(self, method, target)
        if target.startswith("/api/contact"):
            answered.append(1e3 * (time.perf_counter() - t))
            cpu.append(1e3 * (time.thread_time() - c))
        return out
    Explorer.handle = timed
    one_blas_thread()  # as the command line serves it
    server = serve()
    warm, steps = changes(count + 8)[:8], changes(count + 8)[8:]
    with sync_playwright() as pw:
        browser = launch(pw)
        page = session(browser).new_page()
        t0 = time.perf_counter()
        page.goto(server.url + "?" + urlencode(POINT))
        page.wait_for_function(
            "Number(document.getElementById('panel-contact').dataset.ready) >= 1",
            timeout=120_000)
        print(f"first view (solves the first contact of the process) after "
              f"{time.perf_counter() - t0:.2f} s")
        for name, value, _ in warm:  # not counted
            page.evaluate(MEASURE, [name, value])
        latency, solve, solve_cpu = [], [], []
        for name, value, _ in steps:
            before = len(answered)
            latency.append(page.evaluate(MEASURE, [name, value]))
            solve.append(sum(answered[before:]))
            solve_cpu.append(sum(cpu[before:]))
        browser.close()
    server.shutdown()
    server.server_close()
    rows = [("in the browser: change to painted", latency),
            ("the server's answer (solve, JSON)", solve),
            ("  its processor time (its thread's)", solve_cpu)]
    print(f"\n{count} changes of one input (load, speed, radius, friction in turn), ms")
    print(f"{'':38s} {'median':>8s} {'p95':>8s} {'max':>8s}")
    for label, values in rows:
        print(f"{label:38s} {statistics.median(values):8.1f} {percentile(values, 0.95):8.1f} "
              f"{max(values):8.1f}")
    rest = [a - b for a, b in zip(latency, solve)]
    print(f"{'the rest (request, JSON, drawing)':38s} {statistics.median(rest):8.1f}")
    print(f"ratio of the medians, browser/server: "
          f"{statistics.median(latency) / statistics.median(solve):.2f}")
    print(f"changes shown within 300 ms: {sum(v <= 300 for v in latency)} of {count}")
    print("\nby the input changed, ms: median in the browser, median and p95 of the "
          "server's processor time")
    for name in ("load", "speed", "radius", "friction"):
        pick = [i for i, (n, _, _) in enumerate(steps) if n == name]
        ms = [solve_cpu[i] for i in pick]
        print(f"  {name:9s} {statistics.median([latency[i] for i in pick]):8.1f} "
              f"{statistics.median(ms):8.1f} {percentile(ms, 0.95):8.1f}")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 100)
