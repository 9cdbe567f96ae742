"""Peak memory and wall time of one graded solve at fixed n, each in a fresh process.

    python bench/memory.py [n ...]

Prints, per n, the peak resident set size (``ru_maxrss`` of the child) and the wall
time of ``thermocontact.solve(5, 0.2, 10, lam=-1, n=n)`` (levels n/4, n/2 and n, the
validity checks included), and the resident size of the interpreter with the package
and its dependencies imported but nothing solved, for comparison.
"""

from __future__ import annotations

import json
import subprocess
import sys

CHILD = """
import json, resource, sys, time
import thermocontact
n = int(sys.argv[1])
t0 = time.perf_counter()
if n:
    thermocontact.solve(5, 0.2, 10, lam=-1, n=n)
else:
    import numpy, scipy.linalg, scipy.special  # noqa: F401  (the baseline)
print(json.dumps({"seconds": time.perf_counter() - t0,
                  "peak_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}))
"""


def main(ns):
    print(f"{'n':>6s} {'peak MB':>9s} {'seconds':>9s}")
    for n in [0] + ns:
        out = subprocess.run([sys.executable, "-c", CHILD, str(n)], capture_output=True,
                             text=True, check=True)
        rec = json.loads(out.stdout)
        label = "import" if n == 0 else str(n)
        print(f"{label:>6s} {rec['peak_mb']:9.0f} {rec['seconds']:9.2f}")


if __name__ == "__main__":
    main([int(a) for a in sys.argv[1:]] or [32, 128, 256, 512, 1024])
