"""Stronger fixings: the shop's fix for a wall fixing (an ``anchors`` entry) that holds
more than its rating, as more nails are for a joint whose nails pull out.

An anchor's force does not depend on its rating (its spring is the same: README
"Anchors"), so every failing anchor needs a rating of at least the force it holds in its
worst case times the safety factor (the explanation's own estimate, ``suggest.needs``),
rounded up to RATING_STEP; the candidate, checked in full (and finished with thicker
boards where it fails by bending alone, ``Search.first_valid``), gives each such anchor
that rating.  Where other violations remain (a joint whose nails fail as well), the rule
does not apply: it repairs fixings alone.
"""

from __future__ import annotations

import math
from dataclasses import replace

from furncheck.plain import plain_number
from furncheck.suggest.discrete.common import Candidate, Fix, Search, names
from furncheck.suggest.needs import violation_needs

STRONGER_FIXINGS = "stronger fixings"
"""The rule's name in ``tried.Trial`` values."""

RATING_STEP = 50.0
"""N: the rating asked for is rounded up to a multiple of this (fixings are sold by
rated loads in round figures)."""


def stronger_fixings(search: Search) -> Fix | None:
    """The design with its failing wall fixings rated for what they hold, when that is
    valid; else None (and why, in the trials)."""
    if not search.repairs(STRONGER_FIXINGS, ("non-durable",)):
        return None
    design = search.design
    failing = sorted({v.where for v in search.report.violations if v.kind == "non-durable"
                      and v.where.startswith("anchors[")}, key=_index)
    joints = [v.where for v in search.report.violations if v.kind == "non-durable"
              and not v.where.startswith("anchors[")]
    if not failing:
        search.not_applicable(STRONGER_FIXINGS, "no wall fixing holds more than its rating")
        return None
    if joints:
        search.not_applicable(STRONGER_FIXINGS, f"{names(sorted(set(joints)))} fail too")
        return None
    needed = {need.where: need.values["rating_needed"]
              for need in violation_needs(design, search.geometry, search.report)
              if need.where in failing and "rating_needed" in need.values}
    if set(needed) != set(failing):
        search.not_applicable(STRONGER_FIXINGS, "no force known for every failing fixing")
        return None
    return search.first_valid([_candidate(search, {where: RATING_STEP * math.ceil(
        force / RATING_STEP) for where, force in needed.items()})])


def _index(where: str) -> int:
    return int(where[len("anchors["):-1])


def _candidate(search: Search, ratings: dict[str, float]) -> Candidate:
    """The design with each anchor of ``ratings`` given that rating (N), and its advice."""
    design = search.design
    anchors = list(design.anchors)
    by_rating: dict[tuple[float, float], list[str]] = {}
    for where, rating in ratings.items():
        index = _index(where)
        by_rating.setdefault((rating, anchors[index].capacity), []).append(where)
        anchors[index] = replace(anchors[index], capacity=rating)
    parts = [f"{names(which)} rated at least {plain_number(rating, 6)} N (now "
             f"{plain_number(old, 6)} N)"
             for (rating, old), which in by_rating.items()]
    advice = f"Use wall fixings for {names(parts)}."
    return Candidate("fixings", replace(design, anchors=tuple(anchors)), advice,
                     trial_rule=STRONGER_FIXINGS, target=names(list(ratings)),
                     place=", ".join(f"{where} rated {plain_number(r, 6)} N"
                                     for where, r in ratings.items()))

