"""The active set of contact elements, in one place: how the next set follows from a
solution's violations, and when a cycle of sets has settled (derivation section 14b).

The steady elements (the contact sets' second method) and both steps of the transient
run solve on a set of elements in contact and change it where the pressure is tensile
or the gap negative.  Near an edge that lies inside an element the set may cycle: an
element is tensile in contact and interpenetrates out of it.  Such a cycle has settled
when every element it toggles is within :data:`SETTLED_WITHIN` elements of an end of the
zones that all its sets share: the edges are then known to that many elements.
"""

from __future__ import annotations

import numpy as np

__all__ = ["SETTLED_WITHIN", "chattering", "next_set"]

#: A cycle of sets has settled when every element it toggles lies within this many
#: elements of an end of the zones its sets share (two elements, from the end's
#: position between elements).
SETTLED_WITHIN = 2.5


def next_set(active, p, gap, tension, overlap, seen, one_at_a_time):
    """The next active set: every change at once until that revisits a set, then the
    worst violation alone (the most tensile element out, else the most interpenetrating
    in).

    Parameters
    ----------
    active : ndarray of bool
    p, gap : ndarray
        The solution on ``active``.
    tension, overlap : ndarray of bool
        The violations: elements in contact with tensile pressure, out of it with a
        negative gap.
    seen : container
        The sets (``active.tobytes()``) tried before.
    one_at_a_time : bool
        Whether the worst violation alone is changed from now on.

    Returns
    -------
    new, one_at_a_time, cycled
        ``cycled`` when ``new`` was seen before.
    """
    if not one_at_a_time:
        new = (active & ~tension) | overlap
        if new.tobytes() not in seen:
            return new, False, False
    new = active.copy()
    if tension.any():
        new[int(np.argmin(np.where(active, p, np.inf)))] = False
    else:
        new[int(np.argmin(np.where(active, np.inf, gap)))] = True
    return new, True, new.tobytes() in seen


def chattering(states):
    """The elements a cycle of active ``states`` toggles, where it has settled (every
    one within :data:`SETTLED_WITHIN` elements of an end of the zones all the states
    share); None where it has not."""
    every = np.logical_and.reduce(states)
    toggled = np.flatnonzero(np.logical_or.reduce(states) & ~every)
    ends = np.flatnonzero(np.diff(np.concatenate([[0], every.astype(int), [0]])))
    if not (toggled.size and ends.size):
        return None
    distance = np.min(np.abs(toggled[:, None] - ends[None, :] + 0.5), axis=1)
    return toggled if np.all(distance <= SETTLED_WITHIN) else None
