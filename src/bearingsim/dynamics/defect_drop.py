"""The drop of a ball resting on a slot's nearer edge, shared by the ring and rotor models'
geometric defect profile (:class:`bearingsim.geometry.DefectProfile`).

A ball whose centre line lies ``e`` from the edge it rests on (``e = b/2 - |x|``, ``x`` its arc
distance from the slot's centre) drops by seed VSM eq. (2) with ``b/2`` replaced by ``e``::

    d(e) = [r - sqrt(r^2 - e^2)] + sg [R - sqrt(R^2 - e^2)]

(``r`` the ball's radius, ``R`` the radius of the surface it meets, ``sg`` -1 for the concave
outer race, +1 for the convex inner race), at most the slot's depth: 0 at the edges, seed VSM's
``h_min`` at the centre.
"""

from __future__ import annotations

import math

from numba import njit

__all__ = ["edge_drop"]


@njit(cache=True, inline="always")
def edge_drop(e, rb, rr, sg, depth):
    """Drop ``d(e)`` [m] (module docstring) for ``0 < e <= b/2`` [m], ball radius ``rb`` [m],
    surface radius ``rr`` [m] and sign ``sg``, capped at ``depth`` [m]; and ``dd/de`` [-] (0 where
    the ball touches the slot's bottom)."""
    sb = math.sqrt(rb * rb - e * e)
    sr = math.sqrt(rr * rr - e * e)
    d = (rb - sb) + sg * (rr - sr)
    if d >= depth:  # the ball touches the bottom of the defect
        return depth, 0.0
    return d, e / sb + sg * e / sr
