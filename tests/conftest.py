"""Shared test helpers: the stored independent references (tests/data/make_*.py)."""

import json
import pathlib
from functools import lru_cache

from threadpoolctl import threadpool_limits

# The matrices are small: one BLAS thread, as the command line and every map worker
# use (several threads competing for two cores made the suite three times slower).
threadpool_limits(1)


#: Seconds the slowest files take on one of two busy cores (measured late on 2026-11-28;
#: rough, and only their order matters).  Under ``--dist loadfile`` the workers take
#: the files in the order collected (:func:`pytest_collection_modifyitems`): these first,
#: longest first, then the rest by their number of tests, so that the short files fill
#: in at the end and the two workers finish together.  xdist's own order, by the number
#: of tests alone, left the browser's nine tests (36 s) and the figures' nine (19 s)
#: for last, one worker running them while the other waited.
SLOW_FILES = {
    "test_explore_browser.py": 36, "test_maps.py": 30, "test_tei_layers.py": 24,
    "test_zones.py": 22, "test_operating_maps.py": 21, "test_reproduce.py": 20,
    "test_examples.py": 16, "test_rolling_sliding.py": 14, "test_stability.py": 14,
    "test_tei_layer_reference.py": 13, "test_solver.py": 12,
    "test_contact_set_closures.py": 11, "test_cli.py": 11, "test_boundaries.py": 10,
    "test_plotting.py": 10,
}


def pytest_configure(config):
    # The files in the order collected, not sorted again by their number of tests.
    if getattr(config.option, "loadscopereorder", False):
        config.option.loadscopereorder = False


def pytest_collection_modifyitems(items):
    """The slowest files first (:data:`SLOW_FILES`), then the others by their number of
    tests; each file's tests in their own order."""
    count = {}
    for item in items:
        count[item.path] = count.get(item.path, 0) + 1
    items.sort(key=lambda item: (-SLOW_FILES.get(item.path.name, 0), -count[item.path]))


#: The stored references and the scripts that make them.
DATA = pathlib.Path(__file__).parent / "data"


@lru_cache(maxsize=None)
def references() -> dict:
    """The values written by ``python tests/data/make_references.py``."""
    return json.loads((DATA / "references.json").read_text())


def data_script(name):
    """The script ``tests/data/<name>.py`` that makes a stored reference, as a module (its
    cases and its independent computation, shared with the test that reads what it
    stored)."""
    import importlib.util

    spec = importlib.util.spec_from_file_location(name, DATA / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def contact_keywords(state) -> dict:
    """``thermocontact.contact``'s keyword arguments for an explorer page's state, as a
    user writes them (independently of the page's own translation): the contact's fields
    only, friction and lam as numbers, dundurs as a flag, the bulk temperatures as
    ``closure=BulkTemperatures(T1, T2, sink_distance=..., layer_thickness=...)``."""
    import thermocontact as tc
    from thermocontact.explore.adapter import POINT, TEMPERATURES

    kw = {k: v for k, v in state.items() if k in POINT and k not in TEMPERATURES}
    for k in ("friction", "lam"):
        if k in kw:
            kw[k] = float(kw[k])
    if "dundurs" in kw:
        kw["dundurs"] = kw["dundurs"].lower() in ("true", "1", "yes")
    if "bulk_temperatures" in state:
        sinks = {k: state[k] for k in TEMPERATURES[1:] if k in state}
        kw["closure"] = tc.BulkTemperatures(*state["bulk_temperatures"].split(","), **sinks)
    return kw


def assert_ulps(got, want, ulps=4, scale="max", equal_nan=False, err_msg=""):
    """Assert that two computations of the same numbers agree to a few units in the last
    place.

    Two computational paths that apply the same formulas to the same numbers (a point
    alone and in an array, a block of columns and the whole, a stack of systems and each
    system, a geometry moved and one built afresh) agree to the last bit on some CPUs
    only: NumPy evaluates transcendental functions and the remainders of arrays with
    vector units whose last bit depends on the CPU and on the element's place in the
    array, and BLAS kernels with the memory's alignment.  The difference is then a few
    roundings of the operations that make each number.  ``scale="max"`` measures them in
    ulps of the largest magnitude in ``want`` (for numbers that are sums with
    cancellation, whose small entries are rounding noise of the large ones); ``"each"``
    in ulps of each entry (for values of a function at points).  Non-finite entries must
    be equal (NaN equal to NaN with ``equal_nan``).  Bitwise equality is for the same path
    run twice, and is asserted with ``np.array_equal``.
    """
    import numpy as np

    got, want = np.asarray(got), np.asarray(want)
    assert got.shape == want.shape, f"{err_msg} shapes {got.shape} != {want.shape}"
    finite = np.isfinite(got) & np.isfinite(want)
    same_nonfinite = np.array_equal(got[~finite], want[~finite], equal_nan=equal_nan)
    assert same_nonfinite, f"{err_msg} non-finite entries differ"
    if not finite.any():
        return
    g, w = got[finite], want[finite]
    magnitude = np.maximum(np.abs(g), np.abs(w)).astype(float)
    if scale == "max":
        magnitude = np.full_like(magnitude, magnitude.max())
    elif scale != "each":
        raise ValueError(f"scale must be 'max' or 'each', got {scale!r}")
    bound = ulps * np.spacing(magnitude)
    worst = np.max(np.abs(g - w) - bound)
    assert worst <= 0.0, (f"{err_msg} differ by more than {ulps} ulps: largest excess "
                          f"{worst:.3g} (max |difference| {np.max(np.abs(g - w)):.3g})")


def assert_same_result(got, want, rtol=1e-11, path="result"):
    """Assert that two computations of one result agree: every float (and float array)
    field to ``rtol`` of its largest magnitude, every other field (flags, counts,
    statuses, texts) exactly, nested results, records, lists and dicts entry by entry.

    For a result made along two computational paths (a grid line solved together and
    its points one by one, a stack of systems and each system): the same operations,
    whose last bits differ between CPUs (:func:`assert_ulps`), amplified at most by the
    condition number of the systems solved (rcond > 1e-4 in the cases tested, so
    1e-11 leaves room for a few ulps).  A result compared with itself after a round
    trip (pickle, a file, a resumed run) is compared with ``==``: to the last bit.
    """
    import dataclasses

    import numpy as np

    if dataclasses.is_dataclass(got) and not isinstance(got, type):
        assert type(got) is type(want), f"{path}: {type(got).__name__} != {type(want).__name__}"
        for f in dataclasses.fields(got):
            assert_same_result(getattr(got, f.name), getattr(want, f.name), rtol,
                               f"{path}.{f.name}")
        return
    if isinstance(got, dict):
        assert isinstance(want, dict) and got.keys() == want.keys(), f"{path}: keys differ"
        for k in got:
            assert_same_result(got[k], want[k], rtol, f"{path}[{k!r}]")
        return
    if isinstance(got, (list, tuple)) and not (got and isinstance(got[0], (float, np.floating))):
        assert type(got) is type(want) and len(got) == len(want), f"{path}: lengths differ"
        for i, (a, b) in enumerate(zip(got, want)):
            assert_same_result(a, b, rtol, f"{path}[{i}]")
        return
    a, b = np.asarray(got), np.asarray(want)
    if a.dtype.kind in "fc" and b.dtype.kind in "fc":
        assert a.shape == b.shape, f"{path}: shapes {a.shape} != {b.shape}"
        finite = np.isfinite(a) & np.isfinite(b)
        assert np.array_equal(a[~finite], b[~finite], equal_nan=True), f"{path}: non-finite differ"
        if finite.any():
            scale = np.max(np.abs(b[finite]))
            worst = np.max(np.abs(a[finite] - b[finite]))
            assert worst <= rtol * scale, f"{path}: differs by {worst:.3g} (scale {scale:.3g})"
        return
    if a.dtype.kind == "O" or b.dtype.kind == "O":
        assert got == want, f"{path}: {got!r} != {want!r}"
        return
    assert np.array_equal(a, b), f"{path}: {got!r} != {want!r}"
