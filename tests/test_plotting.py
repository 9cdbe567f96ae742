"""Plot functions draw a result on the Axes they are given and return it; figure
writers leave no pyplot figure open."""

import matplotlib

matplotlib.use("Agg")  # the tests' choice; the package never chooses a backend

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from thermocontact import solve  # noqa: E402
from thermocontact.plotting.curves import plot_curve, plot_distributions  # noqa: E402
from thermocontact.studies.sweeps import sweep  # noqa: E402


def test_plot_functions_use_and_return_the_given_axes():
    fig, (a1, a2) = plt.subplots(2, 1)
    sol = solve(5, 0.2, 10, lam=-1)
    got = plot_distributions(sol, (a1, a2))
    assert got == (a1, a2)
    line = a1.get_lines()[0]
    assert np.array_equal(line.get_xdata(), sol.s) and np.array_equal(line.get_ydata(), sol.pressure)
    curve = sweep("c", dict(pe=5, K2_over_K1=10, lam=-1.0), "fhpe", np.linspace(0, 0.3, 4), n=16)
    _, ax = plt.subplots()
    assert plot_curve(curve, "load_ratio", ax=ax) is ax
    plt.close("all")


def test_figure_writers_leave_no_pyplot_figure(tmp_path):
    from thermocontact.plotting.curves import distributions_figure

    plt.close("all")
    distributions_figure([solve(5, 0.2, 10, lam=-1)], str(tmp_path / "d"), "t")
    assert plt.get_fignums() == []
    assert (tmp_path / "d.png").read_bytes()[:4] == b"\x89PNG"


def test_crossing_figure_draws_profiles_and_edges(tmp_path):
    """The crossing study's picture from its record: a PNG, no pyplot figure left open."""
    from thermocontact.plotting.zones import crossing_figure
    from thermocontact.studies.contact_sets import find_contact_set
    res = find_contact_set(2.0, 0.3, 10.0, lam=1.0, n=12)
    sol = res.solution
    x, p = sol.pressure_samples(21)
    record = {"path": "t", "event": None,
              "profiles": [{"label": "one", "x": x.tolist(), "pressure": p.tolist(),
                            "valid": True}],
              "histories": [{"label": "perfect", "steps": res.history}]}
    out = tmp_path / "crossing.png"
    crossing_figure(record, str(out))
    assert out.stat().st_size > 1000 and len(res.history) >= 2
    assert plt.get_fignums() == []


def test_map_outlines_where_a_contact_set_holds():
    """An operating map with contact sets: where one is valid is outlined (dashed) and
    points of several zones are marked; where one holds everywhere the legend says so;
    a map without them draws none of it."""
    import xarray as xr

    from thermocontact.plotting.maps import plot_map

    dims, shape = ("load", "speed"), (3, 4)
    held = np.array([[1, 1, 1, 0], [1, 1, 0, 0], [1, 0, 0, 0]])
    base = {"load_ratio": (dims, np.linspace(0.2, 1, 12).reshape(shape)),
            "valid": (dims, held), "status": (dims, np.full(shape, "solved"))}
    zones = {"zones_status": (dims, np.where(held == 1, "solved", "no steady solution")),
             "zones_valid": (dims, held), "zones_count": (dims, 1 + (held == 1) * np.eye(3, 4,
                                                                                       dtype=int))}
    coords = {"load": [1e4, 2e4, 3e4], "speed": [1.0, 2.0, 3.0, 4.0]}
    _, ax = plt.subplots()
    plot_map(xr.Dataset({**base, **zones}, coords=coords), ax=ax)
    labels = ax.get_legend_handles_labels()[1]
    assert "a valid contact set exists inside" in labels and "several zones" in labels
    marks = [ln for ln in ax.get_lines() if ln.get_label() == "several zones"][0]
    assert sorted(marks.get_xdata()) == [1.0, 2.0]  # the diagonal where held
    _, ax = plt.subplots()
    plot_map(xr.Dataset(base, coords=coords), ax=ax)
    assert ax.get_legend() is None
    everywhere = {"zones_status": (dims, np.full(shape, "solved")),
                  "zones_valid": (dims, np.ones(shape, int)),
                  "zones_count": (dims, np.ones(shape, int))}
    _, ax = plt.subplots()
    plot_map(xr.Dataset({**base, **everywhere}, coords=coords), ax=ax)
    assert "a valid contact set exists at every point" in ax.get_legend_handles_labels()[1]
    plt.close("all")


def test_contact_picture_text_fits_in_the_figure(tmp_path, monkeypatch):
    """The picture of `contact --plot` keeps its labels, title and legend inside the
    figure, for a branch with lambda given and one with lambda from bulk temperatures
    (the longest title)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    import thermocontact as tc
    from thermocontact.plotting import curves

    drawn = []
    monkeypatch.setattr(curves, "save_figure", lambda fig, path, written=None: drawn.append(fig))
    kw = dict(cylinder="copper", half_plane="steel", radius="50mm", load="5kN/m", speed=10,
              friction=0.3)
    for closure in ({"lam": 0}, {"closure": tc.BulkTemperatures("60C", "40C", sink_distance="5mm")}):
        curves.contact_figure(tc.contact(**kw, **closure), str(tmp_path / "c.png"))
    for fig in drawn:
        renderer = FigureCanvasAgg(fig).get_renderer()
        fig.draw(renderer)
        # Everything drawn (tick labels, axis labels, title, legend), in inches.
        ink, page = fig.get_tightbbox(renderer), fig.bbox_inches
        assert (ink.x0 >= page.x0 and ink.x1 <= page.x1 and ink.y0 >= page.y0
                and ink.y1 <= page.y1), (ink, page)
