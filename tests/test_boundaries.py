"""Changes of validity along one parameter: located to 1e-9, checked against Barber's
limiting width, bisection of plain solves and the sweeps of the figures."""

import json

import numpy as np
import pytest
from scipy.optimize import bisect

from thermocontact import solve
from thermocontact.cli import main
from thermocontact.physics.reference_solutions import barber_insulated
from thermocontact.studies.boundaries import follow

#: Barber's limiting width of the insulated, non-distorting cylinder (derivation §9).
BARBER = 0.578886941848794


def test_barber_limit_approached_at_first_order():
    """Along fHPe with lam = -1, k2/k1 = 1, delta1/delta2 = 0, the load ratio vanishes at
    fHPe* whose distance from Barber's 0.5788869418... falls tenfold per decade of
    K2/K1 (observed 2.5662e-5, 2.5661e-6, 2.5661e-7 at 1e4, 1e5, 1e6; ratios within
    1e-3 of 10), the first-order approach of derivation §9; the reference itself is
    the independent Galerkin solution's zero (checked here to 1e-12)."""
    assert abs(barber_insulated(BARBER).load_ratio) < 1e-12
    gaps = []
    for K in (1e4, 1e5, 1e6):
        path = follow(dict(pe=5, K2_over_K1=K, k2_over_k1=1, delta1_over_delta2=0, lam=-1.0),
                      "fhpe", 0.3, 0.9)
        (e,) = [e for e in path.events if e.inequality == "load"]
        assert e.edge is None and e.valid_before and not e.valid_after
        gaps.append(e.at - BARBER)
    ratios = np.array(gaps[:-1]) / np.array(gaps[1:])
    assert np.all(np.abs(ratios - 10) < 1e-2), ratios
    assert 0 < gaps[-1] < 1e-6


def test_events_against_bisection_of_plain_solves():
    """Fig. 4 (Pe = 5, K2/K1 = 10, lam = 1) along fHPe: the gap margin turns negative just
    outside the leading edge at 0.66536213..., equal to bisection of the gap margin of
    plain solves at the path's n to 1e-9 relative; then the pressure margin at the
    leading edge."""
    path = follow(dict(pe=5, K2_over_K1=10, lam=1.0), "fhpe", 0.0, 2.0)
    gap, pressure = path.events[:2]
    assert (gap.inequality, gap.edge, gap.valid_before, gap.valid_after) == \
        ("gap", "leading", True, False)
    assert pressure.inequality == "pressure" and pressure.edge == "leading"
    root = bisect(lambda f: solve(5, f, 10, lam=1.0, n=path.n).validity.gap_margin,
                  0.6, 0.7, xtol=1e-13)
    assert abs(gap.at - root) < 1e-9 * root


def test_along_an_assembly_parameter_and_lam():
    """Along lam (Fig. 5, fHPe = 0.3) the gap boundary (3.5656185) equals the one the
    figures' sweep locates at the same n to 1e-9 relative; along Pe (fHPe = 0.9) the
    pressure and gap events (Pe = 27.5, 33.5) agree with plain solves 1e-6 either side."""
    from thermocontact.studies.sweeps import sweep

    path = follow(dict(pe=5, fhpe=0.3, K2_over_K1=10), "lam", -1.0, 5.0)
    e = path.events[0]
    curve = sweep("fig5", dict(pe=5, fhpe=0.3, K2_over_K1=10), "lam", np.linspace(3, 4, 3),
                  n=path.n, xtol=1e-12)
    assert e.inequality == "gap" and abs(e.at - curve.boundaries[0].at) < 1e-9 * e.at
    path = follow(dict(fhpe=0.9, K2_over_K1=10, lam=1.0), "pe", 0.5, 50.0)
    assert [e.inequality for e in path.events] == ["pressure", "gap"]
    for e in path.events:
        for x, valid in ((e.at * (1 - 1e-6), e.valid_before), (e.at * (1 + 1e-6), e.valid_after)):
            assert solve(x, 0.9, 10, lam=1.0, n=path.n).valid == valid


def test_boundary_command(capsys):
    assert main(["boundary", "--along", "fhpe", "--from", "0", "--to", "2", "--pe", "5",
                 "--K2-over-K1", "10", "--lam", "1", "--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    assert {"at", "inequality", "edge", "valid_before", "valid_after"} <= rec["events"][0].keys()
    assert abs(rec["events"][0]["at"] - 0.66536213) < 1e-8


@pytest.mark.parametrize("args, words", [
    (["--along", "bogus", "--pe", "5", "--K2-over-K1", "10", "--lam", "1"],
     "--along must be one of"),
    (["--along", "fhpe", "--pe", "5", "--lam", "1"], "--K2-over-K1 must be given"),
    (["--along", "fhpe", "--pe", "5", "--K2-over-K1", "10"], "give exactly one closure: --lam"),
    (["--along", "fhpe", "--pe", "5", "--K2-over-K1", "10", "--lam", "1", "--to", "0"],
     "--to must differ from --from"),
])
def test_boundary_bad_input(args, words, capsys):
    """One line naming what to change, exit status 2."""
    base = ["boundary", "--from", "0"] + ([] if "--to" in args else ["--to", "1"])
    assert main(base + args) == 2
    err = capsys.readouterr().err
    assert words in err and len(err.strip().splitlines()) == 1


def test_physical_paths_meet_at_one_pe_hertz(capsys):
    """Along the load (API) and along the speed (command line) the steel/cast-iron
    contact (lam = 1) passes the edge-layer event at one Pe_H (D26: load and
    speed enter only through v sqrt(P)): v* = v0 sqrt(P*/P0) to 1e-8 at the same n;
    each event carries its discretisation error estimate (against n/2)."""
    from thermocontact.problem.materials import get_material
    from thermocontact.studies.physical_contact import PhysicalProblem, follow_along

    prob = PhysicalProblem(get_material("steel"), get_material("cast-iron"), 0.45, 1e5, 1.0,
                           0.35, 1.0, dundurs=False)  # where the event was located
    path = follow_along(prob, "load", 3.9e5, 3.97e5, n=32, points=3)
    assert path.fixed["dundurs"] is False  # recorded with the path
    (e,) = [e for e in path.events if e.inequality == "edge"]
    assert e.edge == "leading" and not e.valid_after
    assert 0 < e.error_estimate < 0.01 * e.at
    assert main(["boundary", "--along", "speed", "--from", "1.975", "--to", "1.99", "--cylinder",
                 "steel", "--half-plane", "cast-iron", "--radius", "450mm", "--load",
                 "100kN/m", "--friction", "0.35", "--lam", "1", "-n", "32", "--no-dundurs",
                 "--json"]) == 0
    (v,) = [v for v in json.loads(capsys.readouterr().out)["events"]
            if v["inequality"] == "edge"]
    assert abs(v["at"] / np.sqrt(e.at / 1e5) - 1) < 1e-8


@pytest.mark.parametrize("args, words", [
    (["--along", "load", "--from", "1e3", "--to", "1e4", "--cylinder", "steel",
      "--half-plane", "cast-iron", "--radius", "0.45", "--friction", "0.3", "--lam", "1"],
     "--speed must be given"),
    (["--along", "load", "--from", "1e3", "--to", "1e4", "--radius", "0.45"],
     "--cylinder must be given"),
    (["--along", "fhpe", "--from", "0", "--to", "1", "--pe", "5", "--K2-over-K1", "10",
      "--lam", "1", "--load", "1e4"], "--load belongs to a physical path"),
    (["--along", "load", "--from", "-1", "--to", "1e4", "--cylinder", "steel",
      "--half-plane", "cast-iron", "--radius", "0.45", "--speed", "1", "--friction", "0.3",
      "--lam", "1"], "load must be > 0"),
])
def test_bad_physical_paths_refused(args, words, capsys):
    assert main(["boundary"] + args) == 2
    err = capsys.readouterr().err
    assert words in err and len(err.strip().splitlines()) == 1


def test_slowly_converging_events_are_located_again_with_more_unknowns():
    """delta1/delta2 = 0.8: the margins converge algebraically (the edge logarithm), so
    an event's estimate against n/2 can exceed event_rtol at the path's n (64 here);
    each event is then located again with doubled n, and equals the event of the
    whole path run at that n to 1e-9, with an estimate below event_rtol."""
    kw = dict(pe=5, K2_over_K1=10, delta1_over_delta2=0.8, lam=1.0)
    auto = follow(kw, "fhpe", 0.3, 1.2, points=9, event_rtol=1e-3)
    assert auto.event_n > auto.n
    fixed = follow(kw, "fhpe", 0.3, 1.2, points=9, n=auto.event_n)
    assert [e.inequality for e in auto.events] == [e.inequality for e in fixed.events]
    for a, b in zip(auto.events, fixed.events):
        assert abs(a.at / b.at - 1) < 1e-9
        assert a.error_estimate < 1e-3 * a.at


def test_where_solutions_end_is_resolved_and_the_events_before_it_found():
    """Along fHPe to 1e300 (Pe = 5, K2/K1 = 10, lam = -1) the first samples past 0 have
    no solution: the load event (0.64) is still found, equal to the one of the path
    ending at 2 at the same n, and the last solution is located where a plain solve
    still succeeds and one 1e-6 past it fails (or the path's samples say so)."""
    fixed = dict(pe=5, K2_over_K1=10, lam=-1.0)
    far = follow(fixed, "fhpe", 0.0, 1e300, n=16, points=9)
    near = follow(fixed, "fhpe", 0.0, 2.0, n=16, points=9)
    (load,) = [e for e in far.events if e.inequality == "load"]
    assert abs(load.at - near.events[0].at) < 1e-9 * load.at
    (end,) = [e for e in far.events if e.inequality == "solution_ends"]
    assert end.at > load.at and not end.valid_after and end.changes_validity is False
    solve(5, end.at, 10, lam=-1.0, n=16)
    with pytest.raises(Exception):
        solve(5, end.at * (1 + 1e-6), 10, lam=-1.0, n=16)
    # Backwards: the first solution, then the load event the other way round.
    back = follow(fixed, "fhpe", 1e300, 0.0, n=16, points=9)
    assert [e.inequality for e in back.events] == ["solution_begins", "load"]
    assert abs(back.events[0].at - end.at) < 1e-9 * end.at


def test_events_chain_and_say_whether_validity_changes():
    """Along lam over +-1e6 (Pe = 5, fHPe = 0.2, K2/K1 = 10): each event starts from the
    validity the previous one left; the pressure margin's sign change at 6.46, where
    the gap already fails, is an event that does not change validity, as plain solves
    either side confirm."""
    path = follow(dict(pe=5, fhpe=0.2, K2_over_K1=10), "lam", -1e6, 1e6, n=32)
    assert [e.inequality for e in path.events] == ["load", "gap", "pressure"]
    for prev, e in zip(path.events[:-1], path.events[1:]):
        assert e.valid_before == prev.valid_after
    for e in path.events:
        for x, valid in ((e.at - 1e-6, e.valid_before), (e.at + 1e-6, e.valid_after)):
            assert solve(5, 0.2, 10, lam=x, n=32).valid == valid
    assert [e.changes_validity for e in path.events] == [True, True, False]
    assert path.to_dict()["events"][2]["changes_validity"] is False


def test_solutions_narrower_than_the_samples_spacing_are_found():
    """With sigma/Delta = 0 solutions exist only for fHPe > 0: along fHPe to 1e30 no
    evenly spaced sample solves; sampled again in asinh, the path finds where they
    begin and the load event, equal to that of the path ending at 2 at the same n."""
    fixed = dict(pe=5, K2_over_K1=10, sigma_over_delta=0.0)
    far = follow(fixed, "fhpe", 0.0, 1e30, n=16, points=9)
    near = follow(fixed, "fhpe", 0.0, 2.0, n=16, points=9)
    assert far.events[0].inequality == "solution_begins" and far.events[0].valid_after
    far_load = [e for e in far.events if e.inequality == "load"][0]
    near_load = [e for e in near.events if e.inequality == "load"][0]
    assert abs(far_load.at - near_load.at) < 1e-9 * near_load.at
    assert not far_load.valid_after
    assert [e.inequality for e in near.events].count("solution_begins") == 1


def test_an_event_is_estimated_within_its_own_stretch_of_the_path():
    """The estimate re-locates an event at n/2 only between the samples that bound it
    and the next events of its margin: another event's sign change on a long path is
    not taken for it."""
    from types import SimpleNamespace

    from thermocontact.studies.boundaries import Event, estimate_events

    def at(n, x):
        # At n the gap margin changes sign at 1 and at 60; at n/2 only at 60.2.
        gap = (x - 1.0) * (60.0 - x) if n == 32 else 60.2 - x
        margins = {"pressure": 1.0, "gap": gap, "edge": 1.0}
        return SimpleNamespace(load_ratio=1.0, valid=gap >= 0,
                               validity=SimpleNamespace(margins=lambda: margins))

    events = [Event(1.0, "gap", "leading", False, True, 1.0),
              Event(60.0, "gap", "leading", True, False, 1.0)]
    samples = np.linspace(0.0, 1000.0, 21)  # brackets (0, 50) and (50, 100)

    def xtol(a, b):
        return 1e-12 * max(1.0, abs(a), abs(b))

    def estimates(**kw):
        out, n = estimate_events(at, events, 32, 0.0, 1000.0, xtol, event_rtol=None, **kw)
        assert n == 32
        return [e.error_estimate for e in out]

    first, second = estimates(samples=samples)
    assert first is None and second == pytest.approx(0.2, rel=1e-9)
    # Without the samples the first took the second's sign change: 59.2.
    assert estimates()[0] == pytest.approx(59.2, rel=1e-9)


def test_the_point_past_an_event_is_brents_own(monkeypatch):
    """The validity after an event is read from Brent's own point nearest the root on
    the far side of the sign change (the root itself when there): no solve past it.
    Against a solve 10 xtol past each root (the reading before), the same events, roots
    and validity after, the margins' positions within 1e-8, with a solve fewer per
    event."""
    import thermocontact.studies.boundaries as bd

    calls = []
    solve_at = bd.Model.solve_at

    def counting(self, *args, **kwargs):
        calls.append(args)
        return solve_at(self, *args, **kwargs)
    monkeypatch.setattr(bd.Model, "solve_at", counting)
    kw = dict(pe=5, fhpe=0.2, K2_over_K1=10)
    path = follow(kw, "lam", -1e6, 1e6, n=32)
    own = len(calls)
    monkeypatch.setattr(bd, "_just_past", lambda *args: None)
    calls.clear()
    again = follow(kw, "lam", -1e6, 1e6, n=32)
    assert own == len(calls) - 2
    assert len(path.events) == len(again.events) == 3
    for e, f in zip(path.events, again.events):
        assert (e.at, e.inequality, e.edge, e.valid_before, e.valid_after) == \
            (f.at, f.inequality, f.edge, f.valid_before, f.valid_after)
        assert (e.position is None) == (f.position is None)
        if e.position is not None:
            assert abs(e.position - f.position) <= 1e-8 * abs(f.position)
