"""Start-up time of the command line against that of the interpreter, measured in one run.

    python bench/bench_startup.py [repeats]

Runs ``python -c pass``, ``thermocontact --version``, ``thermocontact solve --help`` and
``thermocontact --help`` in turn, ``repeats`` times each (default 21), each in a fresh
process, and prints each one's median wall time and its ratio to ``python -c pass`` (the
target of ``--version`` and ``solve --help``: at most 5), and the same of the processor
time (user + system) of the child, which another load on the machine disturbs less.
Interleaving the commands spreads such a load over all of them alike.  A benchmark, not a
test: it prints a table and asserts nothing.
"""

from __future__ import annotations

import os
import resource
import shutil
import statistics
import subprocess
import sys
import time


def script() -> str:
    """The ``thermocontact`` entry point beside this interpreter (a virtual environment's),
    else the one on the PATH."""
    here = os.path.join(os.path.dirname(sys.executable), "thermocontact")
    found = here if os.path.exists(here) else shutil.which("thermocontact")
    if found is None:
        raise SystemExit("thermocontact is not installed beside this interpreter nor on PATH")
    return found


def main(repeats: int = 21):
    exe = script()
    commands = {
        "python -c pass": [sys.executable, "-c", "pass"],
        "thermocontact --version": [exe, "--version"],
        "thermocontact solve --help": [exe, "solve", "--help"],
        "thermocontact --help": [exe, "--help"],
    }
    wall = {name: [] for name in commands}
    cpu = {name: [] for name in commands}
    for _ in range(repeats):
        for name, argv in commands.items():
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            t0 = time.perf_counter()
            subprocess.run(argv, stdout=subprocess.DEVNULL, check=True)
            wall[name].append(time.perf_counter() - t0)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu[name].append(after.ru_utime + after.ru_stime
                             - before.ru_utime - before.ru_stime)
    base_wall = statistics.median(wall["python -c pass"])
    base_cpu = statistics.median(cpu["python -c pass"])
    print(f"{'command':28s} {'wall ms':>8s} {'ratio':>6s} {'cpu ms':>8s} {'ratio':>6s}"
          f"   (medians of {repeats} runs)")
    for name in commands:
        w, c = statistics.median(wall[name]), statistics.median(cpu[name])
        print(f"{name:28s} {1e3 * w:8.1f} {w / base_wall:6.2f} {1e3 * c:8.1f} "
              f"{c / base_cpu:6.2f}")


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:2]))
