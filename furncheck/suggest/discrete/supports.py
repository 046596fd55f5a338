"""The paper's discrete suggestion (section 6.5): add a support plank.

When a joint is not durable, a support is added between two nearly parallel planks P_i
and P_j that a third plank P_k joins, where the failing joint is P_k's joint with one of
them -- a shelf nailed to a post gets a support standing on the base, a chair's seat a
post down to the stretcher.  Under a level P_i the floor serves as P_j too: a leg under a
ledge nailed to the outside of a bookcase.  The support stands across the gap between the
faces of P_i and P_j that face each other, its ends nailed to both (it becomes the edge
plank of two new joints; on the floor it just stands), its broad face turned toward P_k.
Candidate places are the far side of the overlap of P_i and P_j from P_k (a triangle with
the joint that fails: the woodworker's bracket) and its middle.  A plank that sags or is
overstressed (elastic model) is P_i itself: the support goes under the middle of its
overlap with a parallel plank P_j that shares a neighbour P_k with it (a divider between
a sagging shelf and the shelf below), or the floor.  Each candidate design is checked in
full -- valid in every case, the new plank joined to P_i and P_j only, no plank cutting
another -- and only working supports are suggested; a candidate that does not come near
every failing joint and plank (one joint from the planks it is nailed to, ``_reach``) is
not built at all.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import replace

import numpy as np

from furncheck.design.model import Design, Plank
from furncheck.suggest.discrete.common import (
    BENDING,
    PARALLEL_COS,
    Candidate,
    Fix,
    Search,
    amount,
    board,
    level,
    names,
    new_id,
    parallel,
    point_of,
    size_of,
    with_planks,
)

PLACES = (("far", 1.0), ("middle", 0.0))
"""Candidate places across the overlap, away from P_k: its far edge (1) and middle (0)."""

MIN_OVERLAP = 3.0
"""The overlap of P_i and P_j must be at least this many plank thicknesses wide (in
both directions) to hold a support."""

REPAIRED = ("non-durable", "sagging", "overstressed")
"""The violations a support plank can repair."""

SUPPORT = "support plank"
"""The name of the support-plank rule in ``tried.Trial`` values."""

STIFFENER = "stiffening rail"
"""The name of the stiffening-rail rule in ``tried.Trial`` values."""

_PLACE_WORDS = {"far": "at the far side", "middle": "in the middle"}
"""``PLACES`` in a Trial's reason."""

STIFFENER_DEPTHS = (4.0, 6.0, 8.0)
"""Depths of a stiffening rail tried under a bent plank, in plank thicknesses (48, 72 and
96 mm for 12 mm stock): the shallowest that works is suggested.  Under a plank nearer the
floor than a depth, that depth is not tried (its rail would cut into the floor); the
plank's height above the floor is tried instead, a rail standing on the floor, where it
is at least MIN_STIFFENER_DEPTH deep."""

MIN_STIFFENER_DEPTH = 2.0
"""The shallowest rail tried, in plank thicknesses: a rail that fits under a plank near
the floor (a bookcase's raised bottom) only this deep or less is no rail."""


def stiffener_depths(thickness: float, clearance: float, tolerance: float) -> list[float]:
    """m: the depths of the rails tried under a plank whose underside is ``clearance`` above
    the floor (STIFFENER_DEPTHS, those that fit within the tolerance, then the clearance
    itself where a deeper one did not fit and it is at least MIN_STIFFENER_DEPTH deep)."""
    depths = [depth * thickness for depth in STIFFENER_DEPTHS]
    fitting = [depth for depth in depths if depth <= clearance + tolerance]
    if len(fitting) < len(depths) and clearance >= MIN_STIFFENER_DEPTH * thickness \
            and not any(abs(depth - clearance) <= tolerance for depth in fitting):
        fitting.append(clearance)
    return fitting


def support_planks(search: Search) -> Fix | None:
    """The first working support plank or stiffening rail (``support_candidates``)."""
    return search.first_valid(support_candidates(search))


def support_candidates(search: Search) -> Iterator[Candidate]:
    """Support planks and stiffening rails for the non-durable joints and the sagging or
    overstressed planks of the report (see the module docstring), in the order tried:
    failing joints and planks as reported, then P_k, P_i, P_j, places."""
    design, report = search.design, search.report
    if not search.repairs(SUPPORT, REPAIRED):
        return
    neighbours = search.neighbours
    tried: set[tuple] = set()
    before = len(search.trials)
    built = False
    failing = dict.fromkeys(_place(design, v.where) for v in report.violations)
    reaches = _reach(failing, neighbours)
    for where in failing:
        if "/" in where:                                 # a joint k/i: brackets and posts
            pair = where.split("/", 1)
            placements = [(k, i, PLACES) for k, i in (pair, pair[::-1])]
        else:                                            # a bent plank i
            if (where, "stiffener") not in tried:
                tried.add((where, "stiffener"))
                yield from _stiffeners(search, where, neighbours[where], reaches, tried)
            placements = [(k, where, PLACES[1:]) for k in neighbours[where]]
        out_of_reach = []
        for k, i, places in placements:
            partners = [j for j in neighbours[k]
                        if j != i and parallel(design.plank(i), design.plank(j))]
            if level(design.plank(i)):
                partners.append(None)                    # the floor, under a level plank
            for j in partners:
                for place, position in places:
                    key = (*sorted((i, j or "")), position)
                    if key in tried:
                        continue
                    if not reaches({i, j}):
                        out_of_reach.append(f"{i} and {j or 'the floor'}")
                        continue
                    tried.add(key)
                    plank_i, plank_k = design.plank(i), design.plank(k)
                    away = (plank_k.center_array - plank_i.center_array) @ \
                        plank_i.rotation_matrix[:, :2]               # where k stands
                    between = f"between {i} and {j or 'the floor'} {_PLACE_WORDS[place]}"
                    candidate = support_candidate(search, away, i, j, position)
                    if candidate is None:
                        search.failed(SUPPORT, f"{between}: no room (a gap no wider than a "
                                      f"plank, or an overlap narrower than {MIN_OVERLAP:g} "
                                      f"plank thicknesses)", where)
                        continue
                    built = True
                    yield replace(candidate, target=where, place=between)
        if out_of_reach:
            search.failed(SUPPORT, f"one between {_listed(sorted(set(out_of_reach)))} would "
                          f"not come near every failing joint and plank", where)
    if not built and not any(t.rule == SUPPORT for t in search.trials[before:]):
        search.not_applicable(SUPPORT, "no support fits: no two parallel planks to stand "
                              "one between, and no failing level plank over the floor")


def _listed(items: list[str], most: int = 3) -> str:
    """'a, b, c' or 'a, b, c and 2 more'."""
    head = ", ".join(items[:most])
    return head if len(items) <= most else f"{head} and {len(items) - most} more"


def _reach(failing, neighbours: dict[str, list[str]]) -> Callable[[set], bool]:
    """Whether an added plank nailed to ``ends`` (a set of plank ids) comes near every
    failing place (``failing``: violations' ``where``, a joint 'a/b' or a plank): each
    failing joint and plank is one of ``ends`` or jointed to one (``neighbours``).  A
    support relieves what it is nailed to and the planks those carry (a support under a
    cantilevered shelf unloads its post too, a leg under a table top its legs), not a
    shelf two joints away; so a candidate that does not come near every failing place is
    not built and checked (a bookcase whose shelves all sag gets no support tried, at
    once instead of after a full check of each)."""
    joints = [set(where.split("/", 1)) for where in failing if "/" in where]
    planks = [{where} for where in failing if "/" not in where]

    def reaches(ends: set) -> bool:
        near = set(ends)
        for end in ends:
            near.update(neighbours.get(end, ()))
        return all(place & near for place in (*joints, *planks))
    return reaches


def _place(design: Design, where: str) -> str:
    """A violation's place as the discrete fixes take it: a joint k/i, a plank i, and for
    an anchor over its capacity (``anchors[n]``) the plank it holds (a support under that
    plank takes load off the anchor)."""
    if where.startswith("anchors["):
        return design.anchors[int(where[len("anchors["):-1])].plank
    return where


def _stiffeners(search: Search, i: str, neighbours: list[str],
                reaches: Callable[[set], bool], tried: set | None = None
                ) -> Iterator[Candidate]:
    """Rails on edge under one long edge of the level plank i (a shelf's front lip), or
    under its middle, between the two parallel planks that hold i's ends (the ends of its
    beam, else, on a shelf deeper than it is wide, its other two), nailed to i and to
    both: the woodworker's fix for a sagging shelf.  (A lip at one edge carries that
    edge; the beam model's shelf, whose section does not bend across its width, then
    twists about its axis: where that is too much, the rail under the middle does it.)
    ``stiffener_depths`` deep, the shallowest first; at each depth, first, where parallel
    planks hold i between its ends too (a bench's middle trestle), a rail under its
    middle in each bay between them (``_rails_per_bay``: a rail from end to end would cut
    into them), then a rail under the middle of i and of every failing plank alike to i
    (``_alike_failing``: a bookcase's identical shelves get one rail each, not a rail
    under one and thicker boards for the rest), then the three places under i.  None (and the reason
    recorded) when i is not level, is not held at both ends by parallel planks, or a rail
    would not reach every failing place (``reaches``, see ``_reach``).  ``tried``: the
    rule's keys of what it built, where the rails under each alike plank are kept too,
    so that each alike plank's turn does not build them again."""
    design = search.design
    shelf = design.plank(i)
    if not level(shelf):
        search.not_applicable(STIFFENER, f"{i} is not level", i)
        return
    span = _rail_span(design, shelf, neighbours)
    if span is None:
        search.not_applicable(STIFFENER, f"{i} is not held at both ends by parallel planks",
                              i)
        return
    low, high = span[1], span[2]
    if not reaches({i, low.id, high.id}):
        search.failed(STIFFENER, f"a rail under {i} would not come near every failing joint "
                      f"and plank", i)
        return
    thickness = design.material.thickness
    depths = stiffener_depths(thickness, float(shelf.corners[:, 2].min()), design.tolerance)
    if not depths:
        search.not_applicable(STIFFENER, f"{i} is too near the floor for a rail under it", i)
        return
    name = new_id(design, "rail")
    nailed = (i, low.id, high.id)
    others = _alike_failing(search, shelf)
    bays = _bays(design, shelf, span, neighbours)
    for rail_depth in depths:
        if bays:                        # a plank held between its ends too: a rail a bay
            yield _rails_per_bay(design, shelf, span, bays, rail_depth, thickness)
        group = _rails_under_each(design, shelf, span, others, rail_depth, thickness)
        key = ("rails under each", group and group.between, rail_depth)
        if group is not None and (tried is None or key not in tried):
            if tried is not None:       # (each alike plank, in its own pass, makes it too)
                tried.add(key)
            yield replace(group, target=i)
        for side, edge, where in ((-1.0, 1.0, "under one long edge"),
                                  (1.0, 1.0, "under the other long edge"),
                                  (1.0, 0.0, "under the middle")):
            rail = _rail(shelf, span, rail_depth, thickness, side, edge, name)
            advice = (f"Add {name} ({size_of(rail, design)}) on edge under {i}, from "
                      f"{low.id} to {high.id}, centred at {point_of(rail.center, design)}, "
                      f"nailed to all three.")
            place = (f"{amount(rail_depth / design.unit_scale)} {design.units} deep, from "
                     f"{low.id} to {high.id}, {where}")
            yield Candidate("rail", with_planks(design, (rail,)), advice, (rail,), nailed,
                            tuple((end, name) for end in nailed), STIFFENER, i, place, name)


def _rail_span(design: Design, shelf: Plank, neighbours: list[str]):
    """(frame, low, high, start, stop, width) of a rail under the level ``shelf``: its
    beam's frame (axis, across, normal), the parallel planks (among ``neighbours``) that
    hold its ends, nearest on each side along the beam (else along its other axis, a
    shelf deeper than it is wide), where the rail starts and stops along the axis from
    the shelf's centre (m, between their faces), and the shelf's width across the axis;
    None where no two parallel planks hold its ends."""
    from furncheck.statics.beams import along_width, beam_frame, beam_length_width

    for crosswise in (along_width(shelf), not along_width(shelf)):
        frame = beam_frame(shelf, crosswise)        # its beam's axis first, then across it
        axis = frame[:, 0]
        ends = []
        for k in neighbours:
            other = design.plank(k)
            if abs(float(other.rotation_matrix[:, 2] @ axis)) >= PARALLEL_COS:
                ends.append((float((other.center_array - shelf.center_array) @ axis), other))
        below = [e for e in ends if e[0] < 0]
        above = [e for e in ends if e[0] > 0]
        if below and above:
            (s_low, low), (s_high, high) = max(below, key=lambda e: e[0]), \
                min(above, key=lambda e: e[0])
            return (frame, low, high, s_low + low.half_extents[2],
                    s_high - high.half_extents[2], beam_length_width(shelf, crosswise)[1])
    return None


def _bays(design: Design, shelf: Plank, span, neighbours: list[str]) -> list[tuple]:
    """The bays of the level ``shelf`` between the planks that hold its ends (``span``,
    ``_rail_span``) where parallel planks among ``neighbours`` hold it between them too
    (a bench's middle trestle, a shelf's divider): the spans (``_rail_span``'s shape) from
    each holding plank's face to the next's, in order along the axis; [] where none
    stands between the ends."""
    frame, low, high, start, stop, width = span
    axis = frame[:, 0]
    middle = sorted((float((other.center_array - shelf.center_array) @ axis), other)
                    for other in (design.plank(k) for k in neighbours)
                    if other.id not in (low.id, high.id)
                    and abs(float(other.rotation_matrix[:, 2] @ axis)) >= PARALLEL_COS)
    inside = [(at, other) for at, other in middle
              if start + other.half_extents[2] < at < stop - other.half_extents[2]]
    if not inside:
        return []
    bays, first, begin = [], low, start
    for at, other in inside:
        bays.append((frame, first, other, begin, at - other.half_extents[2], width))
        first, begin = other, at + other.half_extents[2]
    bays.append((frame, first, high, begin, stop, width))
    return bays


def _rails_per_bay(design: Design, shelf: Plank, span, bays: list[tuple], depth: float,
                   thickness: float) -> Candidate:
    """Rails ``depth`` deep on edge under the middle of ``shelf``, one in each of its
    ``bays`` (``_bays``), each nailed to the shelf and the two planks at its bay's ends:
    a woodworker's rail per bay under a bench seat on three trestles, where one rail from
    end to end would cut into the middle one."""
    rails, joints, taken = [], [], set()
    for bay in bays:
        name = new_id(design, "rail", taken)
        taken.add(name)
        rails.append(_rail(shelf, bay, depth, thickness, 1.0, 0.0, name))
        joints += [(end, name) for end in (shelf.id, bay[1].id, bay[2].id)]
    sizes = [size_of(rail, design) for rail in rails]
    size = sizes[0] if len(set(sizes)) == 1 else ", ".join(sizes)
    ends = ", ".join(f"{bay[1].id} to {bay[2].id}" for bay in bays)
    advice = (f"Add {_run(rails)} ({size}), one on edge under the middle of {shelf.id} in "
              f"each bay ({ends}), each nailed to {shelf.id} and the two planks at its "
              f"bay's ends.")
    place = (f"{amount(depth / design.unit_scale)} {design.units} deep, under the middle of "
             f"{shelf.id}, one in each bay")
    nailed = tuple(dict.fromkeys((shelf.id, *(p.id for bay in bays for p in bay[1:3]))))
    return Candidate("rail", with_planks(design, tuple(rails)), advice, tuple(rails),
                     nailed, tuple(joints), STIFFENER, shelf.id, place, _run(rails))


def _rail(shelf: Plank, span, depth: float, thickness: float, side: float, edge: float,
          name: str) -> Plank:
    """The rail ``name``, ``depth`` deep and ``thickness`` thick, on edge under ``shelf``
    along ``span`` (``_rail_span``): under the long edge on ``side`` (``edge`` 1) or
    under the middle (``edge`` 0).  Under an edge that overhangs the planks holding the
    shelf's ends (a desk's top 25 mm past its end panels, front and back), the rail is
    set back flush with the nearer of their edges, where it meets both: under the very
    edge it met neither, and the rule offered only the rail under the middle.  Only on
    that edge's side of the shelf's middle, and where the rail then lies on both (a
    table's front legs, holding its top's ends, would set the rail meant for the back
    edge under the front one: it stays under the back edge, and meets neither)."""
    frame, low, high, start, stop, width = span
    axis, across = frame[:, 0], frame[:, 1] * side
    down = -frame[:, 2] if frame[2, 2] > 0 else frame[:, 2]
    offset = 0.5 * width - 0.5 * thickness
    if edge:
        reach = [(end.corners - shelf.center_array) @ across for end in (low, high)]
        flush = min(float(r.max()) for r in reach) - 0.5 * thickness
        if 0.0 < flush < offset and flush >= max(float(r.min()) for r in reach) \
                + 0.5 * thickness:
            offset = flush
    centre = (shelf.center_array + axis * 0.5 * (start + stop)
              + across * edge * offset
              + down * (shelf.half_extents[2] + 0.5 * depth))
    return board(name, stop - start, depth, thickness, centre, axis, across)


def _alike_failing(search: Search, shelf: Plank) -> list[tuple[Plank, tuple]]:
    """The other planks that sag or break in the report and are alike to ``shelf``: level,
    of its length, width and thickness (to the design's tolerance), each with its rail's
    span (``_rail_span``), in the design's order; [] where any of them has no span (each
    rail's room above the floor is ``_rails_under_each``'s, depth by depth)."""
    design, tolerance = search.design, search.design.tolerance
    failing = {v.where for v in search.report.violations if v.kind in BENDING}
    found = []
    for plank in design.planks:
        if plank.id == shelf.id or plank.id not in failing or not level(plank):
            continue
        if max(abs(plank.length - shelf.length), abs(plank.width - shelf.width),
               abs(plank.thickness - shelf.thickness)) > tolerance:
            continue
        span = _rail_span(design, plank, search.neighbours[plank.id])
        if span is None:
            return []
        found.append((plank, span))
    return found


def _rails_under_each(design: Design, shelf: Plank, span, others, depth: float,
                      thickness: float) -> Candidate | None:
    """The candidate of a rail ``depth`` deep under the middle of ``shelf`` and of each of
    ``others`` (``_alike_failing``), each nailed to its plank and the two that hold its
    ends; None without others, or where one of them has no room for it above the floor
    (within the design's tolerance)."""
    if not others:
        return None
    rails, joints, taken = [], [], set()
    group = sorted(((shelf, span), *others), key=lambda item: design.plank_index[item[0].id])
    for plank, plank_span in group:
        if float(plank.corners[:, 2].min()) < depth - design.tolerance:
            return None
        name = new_id(design, "rail", taken)
        taken.add(name)
        rails.append(_rail(plank, plank_span, depth, thickness, 1.0, 0.0, name))
        joints += [(end, name) for end in (plank.id, plank_span[1].id, plank_span[2].id)]
    shelves = [plank.id for plank, _ in group]
    ends = {(plank_span[1].id, plank_span[2].id) for _, plank_span in group}
    between = (f"each from {span[1].id} to {span[2].id}" if len(ends) == 1 else
               "each between the two planks that hold its shelf's ends")
    advice = (f"Add {_run(rails)} ({size_of(rails[0], design)}), one on "
              f"edge under the middle of each of {names(shelves)}, {between}, nailed to all "
              f"three.")
    place = (f"{amount(depth / design.unit_scale)} {design.units} deep, under the middle of "
             f"each of {names(shelves)}")
    return Candidate("rail", with_planks(design, tuple(rails)), advice, tuple(rails),
                     tuple(shelves), tuple(joints), STIFFENER, shelf.id, place, _run(rails))


def _run(rails: list[Plank]) -> str:
    """The rails' names: 'rail-1 to rail-8' where they are numbered one after another,
    else listed."""
    numbers = [rail.id.rpartition("-")[2] for rail in rails]
    if len(rails) > 2 and all(n.isdigit() for n in numbers) and \
            [int(n) for n in numbers] == list(range(int(numbers[0]), int(numbers[0]) + len(rails))):
        return f"{rails[0].id} to {rails[-1].id}"
    return names([rail.id for rail in rails])


def support_candidate(search: Search, away: np.ndarray, i: str, j: str | None,
                      position: float, rule: str = "support",
                      trial_rule: str = "support plank") -> Candidate | None:
    """A support between i and j (None: the floor) at ``position`` (1 far side, 0
    middle) of their overlap, on the side of i opposite to ``away`` ((2,) in i's local
    x-y: where the plank k it is to relieve stands); None when it does not fit."""
    design = search.design
    other = None if j is None else design.plank(j)
    plank = _support(design, away, design.plank(i), other, position)
    if plank is None:
        return None
    ends = (i,) if j is None else (i, j)
    size, centre = size_of(plank, design), point_of(plank.center, design)
    if j is None:
        advice = (f"Add {plank.id} ({size}) under {i}, standing on the floor, centred at "
                  f"{centre}, nailed to {i}.")
    else:
        advice = (f"Add {plank.id} ({size}) between {i} and {j}, centred at {centre}, nailed "
                  f"to both.")
    return Candidate(rule, with_planks(design, (plank,)), advice, (plank,),
                     (i, j or "the floor"), tuple((end, plank.id) for end in ends),
                     trial_rule, plank=plank.id)


def _support(design: Design, away: np.ndarray, i: Plank, j: Plank | None,
             position: float) -> Plank | None:
    """The support plank between the facing broad faces of i and j, or between i's
    underside and the floor (j None); None if they do not face each other over an
    overlap wide enough."""
    normal = i.rotation_matrix[:, 2]
    if j is None:
        normal = -normal if normal[2] > 0 else normal                 # down, to the floor
        gap = float(i.corners[:, 2].min())
    else:
        offset = float((j.center_array - i.center_array) @ normal)
        if offset < 0:
            normal, offset = -normal, -offset
        gap = offset - i.half_extents[2] - j.half_extents[2]
    thickness = design.material.thickness
    if gap <= thickness:
        return None
    axes = i.rotation_matrix[:, :2]                                   # in-plane x, y of i
    low, high = -i.half_extents[:2], i.half_extents[:2].copy()
    if j is not None:
        corners_j = (j.corners - i.center_array) @ axes               # j seen in i's plane
        low = np.maximum(low, corners_j.min(axis=0))
        high = np.minimum(high, corners_j.max(axis=0))
    if np.any(high - low < MIN_OVERLAP * thickness):
        return None
    along = int(np.argmax(np.abs(away)))                              # axis away from k
    sign = -1.0 if away[along] > 0 else 1.0
    middle = 0.5 * (low + high)
    half_span = 0.5 * (high[along] - low[along]) - 0.5 * thickness
    spot = middle.copy()
    spot[along] += sign * position * half_span
    across = 1 - along
    width = float(high[across] - low[across])
    centre = i.center_array + axes @ spot + normal * (i.half_extents[2] + 0.5 * gap)
    x_axis = normal                                                   # its length spans the gap
    z_axis = axes[:, along] * sign                                    # its face looks at k
    return board(new_id(design, "support"), gap, width, thickness, centre, x_axis, z_axis)
