"""The moving body's surface displacement and slope by Maysel's route, computed once
and stored.

Run ``python tests/data/make_maysel_references.py`` to regenerate
``tests/data/maysel_references.json`` (about ten seconds).  For each parameter set and
position of ``test_moving_distortion_maysel`` in ``tests/test_green_functions.py``, the
displacement and its slope by Maysel's reciprocal theorem with the moving source's
temperature superposed in time (nested adaptive quadratures,
``maysel_moving_distortion`` there): the reference of claim (c) by the real-space
route, which depends on nothing in the package.
"""

from __future__ import annotations

import json
import pathlib
import sys

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE / "maysel_references.json"
#: The positions ``u = v x / (2 kappa)`` of the test.
U = (-5.0, -0.5, 0.5, 2.0, 8.0)


def reference(module, params, u):
    """``(w, dw/dx)`` at ``u`` for ``params`` by ``module.maysel_moving_distortion``."""
    Q, K, kappa, v, alpha, nu = params
    x = 2 * kappa * u / v
    return (module.maysel_moving_distortion(x, Q, K, kappa, v, alpha, nu),
            module.maysel_moving_distortion(x, Q, K, kappa, v, alpha, nu, derivative=True))


def main():
    sys.path.insert(0, str(HERE.parent))
    import test_green_functions as module
    from thermocontact.io.files import atomic_write

    out = []
    for params in module.PARAMS:
        for u in U:
            w, s = reference(module, params, u)
            out.append({"params": list(params), "u": u, "w": w, "slope": s})
            print(params, u, w, s)
    with atomic_write(OUT, "w") as fh:
        json.dump({"cases": out}, fh, indent=1)


if __name__ == "__main__":
    main()
