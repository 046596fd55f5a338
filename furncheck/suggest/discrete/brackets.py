"""Under a wall shelf: a pair of brackets (the shop's fix for a shelf that hangs on a rail,
a cleat or a back board screwed to a wall, and sags, breaks or pulls its nails out).

A level plank i whose nail joint with a plank k runs along i's longer side, k lying face
to a wall of the design (within WALL_ANCHOR_REACH of it) and reaching below i, gets two
brackets: boards on edge under i, square to the wall, as deep as i reaches out past k's
face and as tall as k reaches below i (at most as tall as they are deep), nailed to i
above and to k behind.  They go beside k's fixings where two of them lie under i (each
screw then pulls close behind a bracket, its head left clear), else BRACKET_INSET of i's
length in from its ends.  Tried where i sags or is overstressed, or a joint of i fails
(the brackets take the shelf's moment off the row's nails).  Not for an overloaded
fixing: brackets that end at k's bottom edge leave the lever between the screws and k's
foot, where the wall pushes, as it was (the catalog's wall-shelf-rail: the rule says
so).
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design
from furncheck.suggest.discrete.common import (
    PARALLEL_COS,
    Candidate,
    Fix,
    Search,
    board,
    level,
    new_id,
    point_of,
    size_of,
    upright,
    with_planks,
)

REPAIRED = ("sagging", "overstressed", "non-durable")

BRACKET = "wall bracket"
"""The rule's name in ``tried.Trial`` values."""

BRACKET_INSET = 1.0 / 6.0
"""Brackets not under fixings go this share of the shelf's length in from its ends (a
900 mm shelf: 150 mm; the overhangs past them a quarter of the span between)."""

BRACKET_CLEARANCE = 0.03
"""m: from a fixing's centre to the face of a bracket set beside it (room for the screw's
head and a driver's bit)."""

ALONG_COS = 0.9
"""A joint line within about 25 degrees of the shelf's longer side runs along it."""


def wall_brackets(search: Search) -> Fix | None:
    """The first working pair of brackets (see the module docstring)."""
    design = search.design
    if not design.walls:
        search.not_applicable(BRACKET, "the design stands by no wall")
        return None
    if not search.repairs(BRACKET, REPAIRED):
        return None
    return search.first_valid(_candidates(search))


def _candidates(search: Search) -> Iterator[Candidate]:
    """Brackets under each shelf that a violation names (a plank, a joint's level plank),
    in the report's order, on each plank it hangs on by a wall, at each place
    (``_places``)."""
    design = search.design
    shelves: dict[str, None] = {}
    for violation in search.report.violations:
        if violation.where.startswith("anchors["):
            continue
        shelves.update((p, None) for p in violation.where.split("/", 1)
                       if p in design.plank_index and level(design.plank(p)))
    tried = 0
    for i in shelves:
        for k in search.neighbours.get(i, ()):
            hung = _hung_on(design, search, i, k)
            if hung is None:
                continue
            for places, words in _places(design, i, k, hung):
                tried += 1
                yield _candidate(design, i, k, hung, places, words)
    fixings = any(v.where.startswith("anchors[") for v in search.report.violations)
    if not shelves and fixings:
        search.not_applicable(BRACKET, "it does not relieve a wall fixing (brackets that "
                              "end at the foot of the plank they stand against leave its "
                              "screws' lever as it is)")
    elif not tried:
        search.not_applicable(BRACKET, "no failing level plank hangs along its length on a "
                              "plank lying face to a wall and reaching below it")


def _hung_on(design: Design, search: Search, i: str, k: str):
    """(along, out, front, reach, underside, bottom) where the level plank ``i`` is nailed
    along its longer side to plank ``k`` lying face to a wall: i's longer axis, laid level
    (along the wall), the wall's normal (out of it), how far k's front face and i's front
    edge lie out from the wall, i's underside and k's bottom (m, heights); None where
    not, or where the brackets would be shorter than two plank thicknesses either way."""
    shelf, back = design.plank(i), design.plank(k)
    if not upright(back):
        return None
    joint = next((j for j in search.geometry.joints if set(j.planks) == {i, k}), None)
    if joint is None:
        return None
    axis = shelf.rotation_matrix[:, 0 if shelf.length >= shelf.width else 1]
    along = np.array([axis[0], axis[1], 0.0])
    if np.linalg.norm(along) <= 0.5 or abs(float(joint.frame[:, 1] @ axis)) < ALONG_COS:
        return None
    along /= np.linalg.norm(along)
    slack = design.tolerance + tol.ON_PLANK_EPS
    for wall in design.walls:
        out = np.asarray(wall.normal, dtype=float)
        distances = wall.distance(back.corners)
        if abs(float(back.rotation_matrix[:, 2] @ out)) < PARALLEL_COS \
                or not -slack <= float(distances.min()) <= tol.WALL_ANCHOR_REACH \
                or abs(float(out @ along)) > 1.0 - PARALLEL_COS or abs(out[2]) > 1e-9:
            continue                    # (a wall that is not upright: no brackets)
        side = along - float(along @ out) * out         # along the wall, exactly
        front = float(distances.max())
        reach = float(wall.distance(shelf.corners).max())
        underside = float(shelf.corners[:, 2].min())
        bottom = float(back.corners[:, 2].min())
        least = 2.0 * design.material.thickness
        if reach - front >= least and underside - bottom >= least:
            return side / np.linalg.norm(side), out, front, reach, underside, bottom, wall
    return None


def _places(design: Design, i: str, k: str, hung) -> list[tuple[float, float]]:
    """Where along the shelf (m, along its longer axis from the origin, each to a whole
    unit of the design) the two brackets go, and in words: beside the two outermost
    fixings of ``k`` that lie under the shelf, BRACKET_CLEARANCE from each screw to the
    bracket's face, toward the shelf's middle (a bracket over a screw hides its head: it
    could be neither driven nor reached), then BRACKET_INSET of its length in from its
    ends; each pair once."""
    along = hung[0]
    shelf = design.plank(i)
    thickness, scale = design.material.thickness, design.unit_scale
    length = max(shelf.length, shelf.width)
    centre = float(shelf.center_array @ along)
    half = 0.5 * length - thickness
    places = []
    under = sorted(float(np.asarray(a.point) @ along) for a in design.anchors
                   if a.plank == k and abs(float(np.asarray(a.point) @ along) - centre) < half)
    beside = BRACKET_CLEARANCE + 0.5 * thickness
    if len(under) >= 2 and under[-1] - under[0] > 2.0 * (beside + thickness):
        places.append(((under[0] + beside, under[-1] - beside), "beside its fixings"))
    inset = (centre - length * (0.5 - BRACKET_INSET), centre + length * (0.5 - BRACKET_INSET))
    places.append((inset, "a sixth in from its ends"))
    rounded = []
    for pair, words in places:
        pair = tuple(round(v / scale) * scale for v in pair)
        if all(max(abs(a - b) for a, b in zip(pair, other)) > design.tolerance
               for other, _ in rounded):
            rounded.append((pair, words))
    return rounded


def _candidate(design: Design, i: str, k: str, hung, places, words: str) -> Candidate:
    """The design with a bracket at each of ``places`` (``_hung_on``'s ``hung``; ``words``:
    where, for the reports)."""
    along, out, front, reach, underside, bottom, wall = hung
    depth = reach - front
    height = min(underside - bottom, depth)
    thickness = design.material.thickness
    base = np.asarray(wall.point, dtype=float)
    taken: set[str] = set()
    made = []
    for place in places:
        name = new_id(design, "bracket", taken)
        taken.add(name)
        centre = along * place + out * (float(base @ out) + front + 0.5 * depth)
        centre[2] = underside - 0.5 * height            # (along and out are level)
        made.append(board(name, depth, height, thickness, centre, out, along))
    first, second = made
    advice = (f"Add {first.id} and {second.id} ({size_of(first, design)}), brackets on "
              f"edge under {i}, square to the wall, at {point_of(first.center, design)} and "
              f"{point_of(second.center, design)}, each nailed to {i} and to {k}.")
    return Candidate("bracket", with_planks(design, tuple(made)), advice, tuple(made),
                     (i, k), tuple((end, p.id) for p in made for end in (i, k)),
                     BRACKET, i, f"under {i}, on {k}, {words}", f"{first.id} and {second.id}")

