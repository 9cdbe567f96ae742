"""Pictures of contact sets along a path: the pressure at several loads, and the
zones' edges against the load (derivation section 14c).  Matplotlib is imported inside
the functions only."""

from __future__ import annotations

from .curves import new_figure, save_figure

__all__ = ["crossing_figure"]


def crossing_figure(record: dict, path: str) -> None:
    """One path of the crossing study: pressure against ``x/l``, and the edges against
    ``Pe_l`` (valid solid, invalid dashed), with and without interface conductance.

    Parameters
    ----------
    record : dict
        One entry of ``docs/zones/crossing_study.json``: ``profiles`` (each with
        ``label``, ``x``, ``pressure``, ``valid``) and ``histories`` (each with
        ``label`` and the continuation's ``steps``).
    path : str
        ``.png``, ``.svg`` or ``.pdf``.
    """
    fig = new_figure(figsize=(10, 4))
    left, right = fig.subplots(1, 2)
    for prof in record["profiles"]:
        style = "-" if prof["valid"] else "--"
        left.plot(prof["x"], prof["pressure"], style, label=prof["label"], lw=1.2)
    left.set_xlabel("x / l")
    left.set_ylabel("pressure p l / P")
    left.legend(fontsize=7)
    left.set_title(f"path ({record['path']}): pressure along the path", fontsize=9)
    colours = ["k", "C0", "C1", "C2", "C3", "C4", "C5", "C6"]
    for colour, hist in zip(colours, record["histories"]):
        steps = sorted(hist["steps"], key=lambda h: h["t"])
        for k in range(len(steps) - 1):
            a, b = steps[k], steps[k + 1]
            style = "-" if a["valid"] and b["valid"] else ":"
            for i in range(len(a["edges"])):
                if len(b["edges"]) == len(a["edges"]):
                    right.plot([a["pe_hertz"], b["pe_hertz"]], [a["edges"][i], b["edges"][i]],
                               style, color=colour, lw=1.0,
                               label=hist["label"] if k == 0 and i == 0 else None)
    if record.get("event"):
        right.axvline(record["event"]["pe_hertz"], color="0.6", lw=0.8)
    right.set_xlabel("Pe_l (load grows as Pe_l^2)")
    right.set_ylabel("edges x / l")
    right.legend(fontsize=7)
    right.set_title("the zones against the load (dotted: invalid)", fontsize=9)
    fig.tight_layout()
    save_figure(fig, path)
