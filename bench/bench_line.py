"""The cost of one grid line of the benchmark map, in CPU time or in instructions.

Run: ``python bench/bench_line.py [LINES]`` (default 10): LINES lines of the 200 x 200
map of ``bench_map.py --against-lu`` (fHPe 0-0.8 along each line, Pe 0.5-100 log
across, K2/K1 = 10, lambda = 1, tolerance 1e-6), spread over the map, solved in this
process with one BLAS thread after a first line that warms the tables; prints the CPU
time per line.  A benchmark, not a test: it asserts nothing.

``python bench/bench_line.py --gc [LINES]`` (default 30) times the garbage collector's
share of the lines, as a pool's worker runs them (its start frozen, ``gc.freeze``) and
with nothing frozen: the processor time of its collections per line, and of the lines.

``python bench/bench_line.py --instructions [LINES]`` (default 3) counts the machine
instructions of those lines under valgrind's callgrind tool (when installed),
collected only inside the lines' loop.  On a shared machine, whose speed here drifts by
10-40 % within minutes, the count is the measure that repeats to a few parts in
10 000: a change that saves instructions in the lines saves their time on a quiet
machine (memory traffic aside).
"""

from __future__ import annotations

import functools
import re
import shutil
import subprocess
import sys
import time

COUNT = 200


def tasks(lines):
    from thermocontact.studies.maps import MapSpec, parse_axis

    spec = MapSpec(parse_axis("--x", f"fhpe:0:0.8:{COUNT}"),
                   parse_axis("--y", f"pe:0.5:100:{COUNT}:log"),
                   {"K2_over_K1": 10.0, "lam": 1.0}, tol=1e-6)
    every = spec.tasks()
    step = max(1, len(every) // lines)
    return every[0], every[7::step][:lines]


def run(lines):
    """Solve the lines; the loop runs inside ``functools.reduce``, the C function on
    which callgrind switches its collection on and off."""
    from thermocontact.execution.executors import one_blas_thread

    from thermocontact.studies.maps import evaluate_chunk

    first, chosen = tasks(lines)
    with one_blas_thread():
        evaluate_chunk(first)
        t0 = time.process_time()
        functools.reduce(lambda _, task: evaluate_chunk(task), chosen, None)
        return (time.process_time() - t0) / len(chosen)


def instructions(lines):
    if shutil.which("valgrind") is None:
        sys.exit("valgrind is not installed: no instruction count")
    out = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null",
                          "--collect-atstart=no", "--toggle-collect=functools_reduce",
                          sys.executable, __file__, "--in-valgrind", str(lines)],
                         capture_output=True, text=True)
    found = re.search(r"Collected : (\d+)", out.stderr)
    if found is None:
        sys.exit("callgrind reported no count:\n" + out.stderr[-2000:])
    return int(found.group(1)) / lines


def collections(lines):
    """``(collector's ms per line, line's ms)`` with the start frozen, then without."""
    import gc

    from thermocontact.execution.executors import one_blas_thread

    from thermocontact.numerics.cache import clear_caches
    from thermocontact.studies.maps import evaluate_chunk

    spent = [0.0, 0.0]

    def timer(phase, info):
        if phase == "start":
            spent[1] = time.process_time()
        else:
            spent[0] += time.process_time() - spent[1]
    first, chosen = tasks(lines)
    out = []
    gc.callbacks.append(timer)
    try:
        with one_blas_thread():
            for frozen in (True, False):
                clear_caches()
                if frozen:
                    gc.freeze()  # as the pool's worker initialiser does
                evaluate_chunk(first)
                spent[0] = 0.0
                t0 = time.process_time()
                for task in chosen:
                    evaluate_chunk(task)
                out.append((1e3 * spent[0] / len(chosen),
                            1e3 * (time.process_time() - t0) / len(chosen)))
                gc.unfreeze()
    finally:
        gc.callbacks.remove(timer)
    return out


if __name__ == "__main__":
    args = sys.argv[1:]
    if args[:1] == ["--in-valgrind"]:
        run(int(args[1]))
    elif args[:1] == ["--gc"]:
        lines = int(args[1]) if len(args) > 1 else 30
        for label, (collector, line) in zip(("start frozen", "nothing frozen"),
                                            collections(lines)):
            print(f"{label}: collector {collector:.2f} ms of {line:.1f} ms CPU per line "
                  f"({lines} lines)")
    elif args[:1] == ["--instructions"]:
        lines = int(args[1]) if len(args) > 1 else 3
        print(f"{instructions(lines) / 1e9:.4f} G instructions per line ({lines} lines)")
    else:
        lines = int(args[0]) if args else 10
        print(f"{1e3 * run(lines):.1f} ms CPU per line ({lines} lines)")
