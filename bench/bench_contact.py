"""Wall time of the docs' `contact` examples against one `solve` process at the same point.

Run: ``python bench/bench_contact.py [REPEATS]`` (default 5).  A benchmark, not a
test: it prints a table and asserts nothing.  Each example's command (from
docs/examples, with and without its ``--plot``) and the dimensionless ``solve`` at
the half-width it finds run as whole processes, interleaved so that a drifting
machine affects all alike; the table gives the median of each and the ratio of
``contact`` to ``solve``.
"""

from __future__ import annotations

import pathlib
import re
import shlex
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

DOCS = pathlib.Path(__file__).resolve().parent.parent / "docs" / "examples"


def example_command(name):
    text = (DOCS / name).read_text()
    console = re.search(r"```console\n(.*?)```", text, re.S).group(1)
    return shlex.split(console.replace("\\\n", " ").strip()[2:])


def solve_command(contact_args):
    """``thermocontact solve`` at the primary branch's dimensionless point."""
    from thermocontact.problem.materials import get_material
    from thermocontact.problem.units import parse_quantity
    from thermocontact.studies.physical_contact import PhysicalProblem, contact

    opts = dict(zip(contact_args[2::2], contact_args[3::2]))
    prob = PhysicalProblem(get_material(opts["--cylinder"]), get_material(opts["--half-plane"]),
                           parse_quantity(opts["--radius"], "m", "radius"),
                           parse_quantity(opts["--load"], "N/m", "load"),
                           parse_quantity(opts["--speed"], "m/s", "speed"),
                           float(opts["--friction"]), float(opts["--lam"]))
    dim = prob.to_dimensionless(contact(prob).primary.half_width)
    cmd = ["thermocontact", "solve"]
    for key, value in dim.items():
        cmd += ["--" + key.replace("_", "-"), repr(float(value))]
    return cmd


def wall(cmd, cwd):
    t0 = time.perf_counter()
    subprocess.run(cmd, cwd=cwd, capture_output=True, check=True)
    return time.perf_counter() - t0


def main(repeats=5):
    if shutil.which("thermocontact") is None:
        sys.exit("thermocontact is not on PATH: install the package first")
    print(f"medians of {repeats} runs (s)")
    print(f"{'example':22s} {'contact':>8s} {'no plot':>8s} {'solve':>8s} {'ratio':>6s} "
          f"{'no plot':>8s}")
    with tempfile.TemporaryDirectory() as tmp:
        for name in ("brake_block.md", "electrical_contact.md"):
            cmd = example_command(name)
            bare = [a for a in cmd if a != "--plot" and not a.endswith(".png")]
            solve = solve_command(cmd)
            times = {"contact": [], "bare": [], "solve": []}
            for _ in range(repeats):
                times["contact"].append(wall(cmd, tmp))
                times["bare"].append(wall(bare, tmp))
                times["solve"].append(wall(solve, tmp))
            m = {k: statistics.median(v) for k, v in times.items()}
            print(f"{name[:-3]:22s} {m['contact']:8.2f} {m['bare']:8.2f} {m['solve']:8.2f} "
                  f"{m['contact'] / m['solve']:6.2f} {m['bare'] / m['solve']:8.2f}")


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:]))
