"""Against racking: aprons and stretchers between facing legs, a back panel or a diagonal
brace across their edges.

A table or a bookcase pushed sideways racks: its legs (upright planks standing on the
floor) lean like a parallelogram, and the joints at their tops take the push times the
height as a moment on a nail row whose lever is half a plank's thickness.  The
woodworker closes the parallelogram:

- an *apron* (a rail on edge between two legs whose broad faces face each other, its top
  edge under the plank they carry, nailed to both legs and to that plank) or a
  *stretcher* (the same rail lower down, nailed to the legs): the moment then goes into
  a nail row as deep as the rail, whose lever is the row's length;
- a *back panel* over the edges of the legs (and of the shelves) in one vertical plane,
  nailed to each, or a *diagonal brace*, a strap across that plane from a bottom corner
  to the opposite top corner: the push goes through the panel's or the brace's plane as
  shear on its nails.

Tried where a joint of a leg fails, or a leg bends too much, in a load case with a
sideways load (``racking_places``).  Every failing leg gets a rail to its nearest facing
leg (one suggestion with a rail per pair: a table whose two right legs' joints fail gets
an apron on each side); the panel and brace go over a plane that holds the edges of at
least two legs, failing ones among them, the plane in front of a wall first, then the
one with the most edges, then the one farthest from the loads (the back, not the front
where the books go in).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import replace

import numpy as np

from furncheck.design.model import Design, Plank
from furncheck.geometry import analyze
from furncheck.suggest.discrete.common import (
    BENDING,
    PARALLEL_COS,
    Candidate,
    Fix,
    Search,
    amount,
    board,
    facing,
    legs,
    level,
    names,
    new_id,
    size_of,
    with_planks,
)

RAIL_DEPTHS = (6.0, 8.0)
"""Depths of an apron or stretcher, in plank thicknesses (72 and 96 mm of 12 mm stock)."""

STRETCHER_HEIGHTS = (0.25, 0.5)
"""Where a stretcher's centre goes, as a fraction of the legs' height above their feet."""

BRACE_WIDTHS = (6.0, 10.0)
"""Widths of a diagonal brace tried, in plank thicknesses (72 and 120 mm of 12 mm stock):
a wider strap has more nails where it crosses an edge."""

MIN_GAP = 3.0
"""Facing legs must stand at least this many plank thicknesses apart for a rail."""

REPAIRED = ("non-durable", *BENDING)

NO_PAIR = "a failing leg has no leg whose broad face faces its own"
NO_PLANE = ("the failing legs' edges do not lie in vertical planes, each with another "
            "leg's edge")


APRON, STRETCHER, BACK_PANEL, BRACE = "apron", "stretcher", "back panel", "diagonal brace"
"""The rules' names in ``tried.Trial`` values."""


def racking_places(search: Search, rule: str) -> list[str] | None:
    """The failing legs (plank ids, in plank order) when the design racks: every violation
    is a failing joint or a bent plank, and some failing joint of a leg or bent leg is in
    a load case with a sideways load; else None (and why, recorded for ``rule``)."""
    design, report = search.design, search.report
    if not search.repairs(rule, REPAIRED):
        return None
    pushed = {case.name for case in design.load_cases
              if any(np.hypot(*load.force[:2]) > 0.0 for load in case.loads)}
    standing = legs(design, search.geometry)
    failing = set()
    for violation in report.violations:
        if violation.case not in pushed:
            continue
        failing.update(p for p in violation.where.split("/") if p in standing)
    if not failing:
        search.not_applicable(rule, "no leg's joint fails, and no leg bends, in a load case "
                              "with a sideways load (racking)")
    return [p for p in standing if p in failing] or None


def aprons(search: Search) -> Fix | None:
    """The first working aprons between each failing leg and its nearest facing leg."""
    return racking_fix(search, APRON, _apron_candidates)


def stretchers(search: Search) -> Fix | None:
    """The first working stretchers between each failing leg and its nearest facing leg."""
    return racking_fix(search, STRETCHER, _stretcher_candidates)


def back_panels(search: Search) -> Fix | None:
    """The first working back panels over the legs' edges."""
    return racking_fix(search, BACK_PANEL, _back_panel_candidates)


def braces(search: Search) -> Fix | None:
    """The first working diagonal braces across the legs' edges."""
    return racking_fix(search, BRACE, _brace_candidates)


def racking_fix(search: Search, rule: str, candidates) -> Fix | None:
    """The first working candidate of ``candidates(search, failing legs)`` for the racking
    rule ``rule`` (``racking_places``), each told as that rule's trial; None where the
    design does not rack."""
    failing = racking_places(search, rule)
    if failing is None:
        return None
    target = ",".join(failing)
    return search.first_valid(replace(candidate, trial_rule=rule, target=target)
                              for candidate in candidates(search, failing))


# --- aprons and stretchers ------------------------------------------------------------------

def _pairs(design: Design, standing: list[str], failing: list[str]) -> list[tuple[str, str]]:
    """Each failing leg with its nearest leg whose broad face faces its own (at least
    MIN_GAP thicknesses apart, overlapping both ways by a rail's size), each pair once;
    [] when a failing leg has no such partner."""
    pairs: list[tuple[str, str]] = []
    thickness = design.material.thickness
    for leg in failing:
        a = design.plank(leg)
        best = None
        for other in standing:
            if other == leg:
                continue
            seen = facing(a, design.plank(other))
            if seen is None:
                continue
            _, gap, low, high = seen
            if gap < MIN_GAP * thickness or np.any(high - low < thickness):
                continue
            if best is None or gap < best[0]:
                best = (gap, other)
        if best is None:
            return []
        pair = tuple(sorted((leg, best[1]), key=design.plank_index.get))
        if pair not in pairs:
            pairs.append(pair)
    return pairs


def _apron_candidates(search: Search, failing: list[str]) -> Iterator[Candidate]:
    """Aprons on every pair of ``_pairs``, RAIL_DEPTHS deep, each under the plank its two
    legs carry; none when a pair carries no level plank above it."""
    design = search.design
    pairs = _pairs(design, legs(design, search.geometry), failing)
    if not pairs:
        search.failed(APRON, NO_PAIR, ",".join(failing))
    thickness = design.material.thickness
    for depth in RAIL_DEPTHS if pairs else ():
        made: list[tuple[Plank, str, str, str]] = []
        for a, b in pairs:
            carried = _carried(search, a, b)
            if carried is None:
                search.failed(APRON, f"{a} and {b} carry no level plank above them",
                              ",".join(failing))
                return
            height = carried.corners[:, 2].min() - 0.5 * depth * thickness
            rail = _rail(design, a, b, height, depth * thickness, "apron", made)
            if rail is None:
                break
            made.append((rail, a, b, carried.id))
        else:
            tops = names(sorted({top for *_, top in made}, key=design.plank_index.get))
            candidate = _rail_candidate(
                design, "apron", made, pairs,
                f"on edge, the top edge under {tops}, nailed to the legs and to {tops}")
            yield replace(candidate, place=f"{_depth(depth, design)} deep, under {tops}")


def _stretcher_candidates(search: Search, failing: list[str]) -> Iterator[Candidate]:
    """Stretchers on every pair of ``_pairs``, RAIL_DEPTHS deep, at STRETCHER_HEIGHTS."""
    design = search.design
    pairs = _pairs(design, legs(design, search.geometry), failing)
    if not pairs:
        search.failed(STRETCHER, NO_PAIR, ",".join(failing))
    thickness = design.material.thickness
    for depth in RAIL_DEPTHS if pairs else ():
        for height in STRETCHER_HEIGHTS:
            made: list[tuple[Plank, str, str, str]] = []
            for a, b in pairs:
                ends = (design.plank(a).corners[:, 2], design.plank(b).corners[:, 2])
                foot = min(float(z.min()) for z in ends)
                top = max(float(z.max()) for z in ends)
                rail = _rail(design, a, b, foot + height * (top - foot), depth * thickness,
                             "stretcher", made)
                if rail is None:
                    break
                made.append((rail, a, b, ""))
            else:
                centre = made[0][0].center[2] / design.unit_scale
                candidate = _rail_candidate(
                    design, "stretcher", made, pairs,
                    f"on edge, centred {amount(centre)} {design.units} above the floor, "
                    f"nailed to the legs")
                yield replace(candidate, place=f"{_depth(depth, design)} deep, "
                              f"{amount(centre)} {design.units} up")


def _depth(depth: float, design: Design) -> str:
    """'72 mm': ``depth`` plank thicknesses in the design's unit."""
    return f"{amount(depth * design.material.thickness / design.unit_scale)} {design.units}"


def _rail_candidate(design: Design, rule: str, made: list, pairs: list,
                    where: str) -> Candidate:
    """The candidate adding the rails ``made`` ((rail, leg, leg, carried plank or ''))."""
    rails = tuple(rail for rail, *_ in made)
    joints = tuple(pair for rail, a, b, top in made
                   for pair in ((a, rail.id), (b, rail.id), *(((top, rail.id),) if top else ())))
    phrases = [f"{rail.id} ({size_of(rail, design)}) between {a} and {b}"
               for rail, a, b, _ in made]
    advice = f"Add {_noun(rule, len(made))} {names(phrases)}, {where}."
    return Candidate(rule, with_planks(design, rails), advice, rails,
                     tuple(p for pair in pairs for p in pair), joints,
                     plank=names([rail.id for rail in rails]))


def _noun(word: str, count: int) -> str:
    return word if count == 1 else f"{word}s"


def _carried(search: Search, a: str, b: str) -> Plank | None:
    """The level plank jointed to both legs, above them (a table's top), or None."""
    design = search.design
    shared = [p for p in search.neighbours[a] if p in search.neighbours[b]]
    tops = [design.plank(p) for p in shared if level(design.plank(p))]
    above = [p for p in tops if p.corners[:, 2].min() >= max(
        design.plank(a).corners[:, 2].max(), design.plank(b).corners[:, 2].max())
        - design.tolerance - 1e-9]
    return min(above, key=lambda p: p.corners[:, 2].min()) if above else None


def _rail(design: Design, a_id: str, b_id: str, height: float, depth: float, stem: str,
          made: list) -> Plank | None:
    """A rail on edge between the facing broad faces of legs a and b, its centre at world
    height ``height`` (m) and in the middle of their overlap across, ``depth`` deep; None
    when it does not fit within their overlap."""
    a, b = design.plank(a_id), design.plank(b_id)
    seen = facing(a, b)
    if seen is None:
        return None
    toward, gap, low, high = seen
    axes = a.rotation_matrix[:, :2]
    up = int(np.argmax(np.abs(axes[2])))
    if abs(float(axes[2, up])) < PARALLEL_COS:
        return None                                     # a leg turned about its normal
    across = 1 - up
    local_height = (height - a.center_array[2]) / float(axes[2, up])
    half = 0.5 * depth
    if local_height - half < low[up] - 1e-9 or local_height + half > high[up] + 1e-9:
        return None
    spot = np.zeros(2)
    spot[up] = local_height
    spot[across] = 0.5 * (low[across] + high[across])
    centre = a.center_array + axes @ spot + toward * (a.half_extents[2] + 0.5 * gap)
    face = axes[:, across]                              # horizontal, across the rail
    name = new_id(design, stem, {r.id for r, *_ in made})
    return board(name, gap, depth, design.material.thickness, centre, toward, face)


# --- back panels and braces -----------------------------------------------------------------

def _edge_planes(design: Design, standing: list[str], failing: list[str]) -> list[dict]:
    """Vertical planes holding a long narrow face of at least two legs, failing ones
    among them: {'normal': (3,) outward, 'offset': m, 'planks': ids whose narrow face lies
    in it, 'corners': (n, 3) those faces' corners, 'legs': the legs' face corners}, best
    first (module docstring)."""
    slack = design.tolerance + 1e-9
    faces = []                                          # (plank, normal, offset, corners)
    for plank in design.planks:
        for axis in (0, 1):
            for sign in (1.0, -1.0):
                outward = plank.rotation_matrix[:, axis] * sign
                if abs(float(outward[2])) > 1.0 - PARALLEL_COS:
                    continue
                local = plank.to_local(plank.corners)
                corners = plank.corners[np.isclose(local[:, axis], sign * plank.half_extents[axis])]
                faces.append((plank.id, outward, float(corners[0] @ outward), corners))
    planes = []
    for leg in failing:
        for plank_id, outward, offset, _ in faces:
            if plank_id != leg or any(np.allclose(p["normal"], outward) and
                                      abs(p["offset"] - offset) <= slack for p in planes):
                continue
            members = [(q, c) for q, n, o, c in faces
                       if n @ outward >= PARALLEL_COS and abs(o - offset) <= slack]
            if sum(1 for q, _ in members if q in standing) < 2:
                continue
            planes.append({"normal": outward, "offset": offset,
                           "planks": [q for q, _ in members],
                           "corners": np.vstack([c for _, c in members]),
                           "legs": np.vstack([c for q, c in members if q in standing])})
    load_points = [np.asarray(load.point) for case in design.load_cases for load in case.loads
                   if load.point is not None]
    centre = np.mean(load_points, axis=0) if load_points else None

    def rank(plane: dict) -> tuple:
        walled = any(float(np.asarray(w.normal) @ plane["normal"]) <= -PARALLEL_COS
                     for w in design.walls)
        far = 0.0 if centre is None else plane["offset"] - float(centre @ plane["normal"])
        return (not walled, -len(plane["planks"]), -far)
    return sorted(planes, key=rank)


def _cover(planes: list[dict], failing: list[str]) -> list[dict]:
    """Planes in their order until every failing leg's edge lies in one (each adding a
    failing leg); [] when they cannot cover them all."""
    chosen, covered = [], set()
    for plane in planes:
        new = set(plane["planks"]) & set(failing) - covered
        if new:
            chosen.append(plane)
            covered |= new
    return chosen if covered >= set(failing) else []


def _planes(search: Search, failing: list[str]) -> list[dict]:
    """The planes of ``_cover`` for the failing legs, each with 'rectangle' (holding every
    edge in it) and 'leg_rectangle' (the legs' edges only): see ``_rectangle``."""
    design = search.design
    thickness = design.material.thickness
    planes = _cover(_edge_planes(design, legs(design, search.geometry), failing), failing)
    for plane in planes:
        plane["rectangle"] = _rectangle(plane, plane["corners"], thickness)
        plane["leg_rectangle"] = _rectangle(plane, plane["legs"], thickness)
    return planes


def _back_panel_candidates(search: Search, failing: list[str]) -> Iterator[Candidate]:
    """A back panel over each plane of ``_planes`` (one suggestion)."""
    design = search.design
    planes = _planes(search, failing)
    if not planes:
        search.failed(BACK_PANEL, NO_PLANE, ",".join(failing))
        return
    made: list[Plank] = []
    for plane in planes:
        along, outward, centre, width, height = plane["rectangle"]
        name = new_id(design, "back", {p.id for p in made})
        made.append(board(name, width, height, design.material.thickness, centre, along,
                          outward))
    nailed = [tuple(plane["planks"]) for plane in planes]
    phrases = [f"{panel.id} ({size_of(panel, design)}) over the edges of {names(over)}"
               for panel, over in zip(made, nailed)]
    advice = (f"Add {_noun('back panel', len(made))} {names(phrases)}, nailed to each "
              f"plank it covers.")
    yield Candidate("back panel", with_planks(design, tuple(made)), advice, tuple(made),
                    tuple(dict.fromkeys(p for over in nailed for p in over)),
                    tuple((p, panel.id) for panel, over in zip(made, nailed) for p in over),
                    place=f"over the edges of {names([names(over) for over in nailed])}",
                    plank=names([panel.id for panel in made]))


def _brace_candidates(search: Search, failing: list[str]) -> Iterator[Candidate]:
    """Diagonal braces over each plane of ``_planes`` (BRACE_WIDTHS, both diagonals), each
    crossing the edges of at least two legs."""
    design = search.design
    thickness = design.material.thickness
    standing = legs(design, search.geometry)
    planes = _planes(search, failing)
    if not planes:
        search.failed(BRACE, NO_PLANE, ",".join(failing))
    for strap in BRACE_WIDTHS if planes else ():
        for flip in (1.0, -1.0):
            made, crossed_all = [], []
            for plane in planes:
                along, outward, centre, width, height = plane["leg_rectangle"]
                brace = _brace(design, width, height, strap * thickness, thickness, centre,
                               along * flip, outward, {b.id for b in made})
                crossed = () if brace is None else _crossed(design, brace, tuple(plane["planks"]))
                if sum(1 for p in crossed if p in standing) < 2:
                    break
                made.append(brace)
                crossed_all.append(crossed)
            else:
                phrases = [f"{brace.id} ({size_of(brace, design)}) across the edges of "
                           f"{names(crossed)}" for brace, crossed in zip(made, crossed_all)]
                advice = (f"Add {_noun('diagonal brace', len(made))} {names(phrases)}, "
                          f"from the foot of a leg to the top of the other, nailed to each "
                          f"plank it crosses.")
                yield Candidate("brace", with_planks(design, tuple(made)), advice,
                                tuple(made),
                                tuple(dict.fromkeys(p for over in crossed_all for p in over)),
                                tuple((p, brace.id) for brace, over in zip(made, crossed_all)
                                      for p in over),
                                place=f"{_depth(strap, design)} wide, "
                                      f"{'one' if flip > 0 else 'the other'} diagonal",
                                plank=names([brace.id for brace in made]))


def _rectangle(plane: dict, corners: np.ndarray, thickness: float) -> tuple:
    """(along, outward, centre, width, height): the rectangle in the plane (just outside
    it, a thickness deep) that holds ``corners``; ``along`` horizontal in it."""
    outward = plane["normal"]
    along = np.cross(np.array([0.0, 0.0, 1.0]), outward)
    along /= np.linalg.norm(along)
    s = corners @ along
    z = corners[:, 2]
    centre = outward * (plane["offset"] + 0.5 * thickness) + \
        along * 0.5 * (s.min() + s.max()) + np.array([0.0, 0.0, 0.5 * (z.min() + z.max())])
    return along, outward, centre, s.max() - s.min(), z.max() - z.min()


def _brace(design: Design, width: float, height: float, strap: float, thickness: float,
           centre: np.ndarray, along: np.ndarray, outward: np.ndarray,
           taken: set[str]) -> Plank | None:
    """A strap ``strap`` wide across the legs' width x height rectangle centred at
    ``centre`` in the plane (``along``, up), from its lower ``-along`` corner to its
    upper ``+along`` corner.  Its ends are cut square, so it reaches strap x sin(angle)
    beyond the legs' outer edges: then its whole width crosses each leg's edge (nailed
    there), its corners stay within the legs' height.  None if it does not fit."""
    angle = float(np.arctan2(height, width))
    reach = width + 2.0 * strap * np.sin(angle)
    angle = float(np.arctan2(height, reach))
    cos, sin = np.cos(angle), np.sin(angle)
    length = min((reach - strap * sin) / cos, (height - strap * cos) / sin)
    if length <= strap:
        return None
    x_axis = along * cos + np.array([0.0, 0.0, 1.0]) * sin
    return board(new_id(design, "brace", taken), length, strap, thickness, centre, x_axis,
                 outward)


def _crossed(design: Design, brace: Plank, planks: tuple[str, ...]) -> tuple[str, ...]:
    """The planks among ``planks`` whose edges the brace lies on (joints it forms)."""
    geometry = analyze(replace(with_planks(design, (brace,)), joints=None))
    return tuple(p for p in planks
                 if any(set(j.planks) == {p, brace.id} for j in geometry.joints))
