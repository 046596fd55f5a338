"""A thicker plank: the maker's fix for a shelf that sags or breaks, and for a joint whose
nails pull out under a moment.

In the elastic model a plank's sag goes with 1 / t^3 and its bending stress with 1 / t^2
(contract section 3a: its section is width x thickness); a nail joint's pull from the
moment about its joint line goes with 1 / t of the edge plank (contract section 3: the
nails' lever is t / 2).  So from the report, each failing plank needs its thickness times

    max over the cases of  max((sag (1 + creep) / allowed)^(1/3), (stress / strength)^(1/2))

and the edge plank of a joint whose nails pull out the thickness at which the moment about
the joint line, over the nails' lever t / 2, leaves the pull within capacity, the joint's
wrench kept (``_edge_thickness``; none when the nails shear off or the rocking moment
across the row alone pulls them out: a thicker plank helps neither).  The thickness suggested is
the next board of ``STOCK_THICKNESSES`` at or above that; if the design is still not
valid (a thicker plank is heavier, and its joints stiffer, so the loads shift), the
estimate is made again from the new report, at most ``THICKEN_TRIES`` times.

A plank grows away from the faces that hold it: a face on which another plank's end is
nailed or rests, or that lies on the floor or a wall stays where it is (a shelf on
brackets grows upward, a post with a shelf nailed to its front grows backward); with
neither face held a level plank (a shelf between two sides) grows downward, its top face
and what stands on it where they were (a shelf flush with the sides' tops stays flush),
any other toward the planks its ends are nailed to (a table's leg grows inward), else
equally both ways; with both held it grows toward a face whose planks rest on it alone
(a chair's back on its seat, which moves with it), else into the planks standing square
on one face, cut that much shorter (a cabinet's bottom into its kick board, ripped
narrower; the lower face first), else it cannot grow.  Load and anchor points on a
face that moves move with it, and those on a cut plank's cut end with that end.

The rule (``thicker_planks``) thickens every failing plank and the edge planks of the
joints that pull out, in one suggestion; ``finish`` does the same for the candidate of
another rule that fails only by planks that bend too much (a support under a shelf's far
end leaves the shelf, now simply supported, sagging a little: a thicker shelf finishes
the job).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from furncheck import tolerances as tol
from furncheck.check import check_design
from furncheck.design.model import Design, Plank
from furncheck.geometry import Geometry, Joint, analyze, interpenetrations
from furncheck.nail_groups import nail_row
from furncheck.result import DesignReport, JointResult
from furncheck.suggest.discrete.common import (
    BENDING,
    PARALLEL_COS,
    Fix,
    Search,
    amount,
    level,
    names,
    upright,
)
from furncheck.suggest.symmetry import MirrorPlane, mirror_planes
from furncheck.suggest.tried import FOUND, Trial

THICKEN_TRIES = 3
"""Thicknesses tried per suggestion (the estimate, then from the reports of the tries)."""

THICKER = "thicker board"
"""The rule's name in ``tried.Trial`` values."""

PULL_FAILING = ("non-durable",)
"""The joint violation a thicker edge plank can repair (by its pull)."""


def thicker_planks(search: Search) -> Fix | None:
    """Every failing plank and every edge plank of a joint whose nails pull out, made
    thicker (module docstring), when that makes the design valid; else None.  Tried when
    every violation is one of these (a design that also tips needs more than thicker
    boards)."""
    report = search.report
    if not search.repairs(THICKER, (*BENDING, *PULL_FAILING)):
        return None
    why: list[str] = []
    checked = _thickened(search, search.design, search.geometry, report, why)
    if checked is None:
        search.failed(THICKER, why[0] if why else "no thicker boards make it valid")
        return None
    edited, after_report, thickened = checked
    return _fix(search, edited, after_report, thickened)


def _fix(search: Search, edited: Design, report: DesignReport, thickened: dict,
         reason: str = "") -> Fix:
    """The rule's Fix: ``edited``, the design with the planks ``thickened`` ({id: (old,
    new) m}), valid by ``report``; its Trial recorded as found (with ``reason``)."""
    search.trials.append(Trial(THICKER, "", FOUND, reason, plank=names(list(thickened))))
    advice = (f"{thickness_phrase(thickened, search.design, capital=True)}"
              f"{cut_phrase(search.design, edited)}.")
    return Fix("thicker", advice, edited, report, between=tuple(thickened),
               thickened={p: new for p, (_, new) in thickened.items()})


def boards_alone(search: Search, thickened: dict, rule: str) -> Fix | None:
    """The thicker boards with which another rule's candidate was finished (``thickened``:
    {id: (old, new) m}; ``rule``: that rule's name in the reports), on the design
    without that rule's part, as this rule's fix, when that is valid (the boards the
    design has, pruned as ``_pruned`` prunes them); else None.  A heavier board holds a
    piece down as well as stiffening it: a table that slid under a shove (mu W less than
    the push) and sagged, given non-slip pads and a thicker top and legs, stood on its
    own feet with the boards alone, its weight from 124 to 237 N (mu W from 62 to 118 N
    against 110), and a maker should not be sent for pads that do nothing."""
    existing = {plank: new for plank, (_, new) in thickened.items()
                if plank in search.design.plank_index}
    if not existing:
        return None
    design, geometry = search.design, search.geometry
    grown_up = _grown_whole(search, design, geometry, existing, [])
    if grown_up is None:
        return None
    edited, after = grown_up
    search.checks += 1
    report = check_design(edited, after)
    if not report.valid:
        return None
    edited, report, current = _pruned(search, design, geometry, mirror_planes(design),
                                      existing, (edited, report))
    original = {p.id: p.thickness for p in design.planks}
    order = sorted(current, key=design.plank_index.get)
    return _fix(search, edited, report, {p: (original[p], current[p]) for p in order},
                f"the boards that finished the {rule}' candidate, without it")


def finish(search: Search, edited: Design, geometry: Geometry,
           report: DesignReport) -> tuple[Design, DesignReport, dict] | None:
    """For another rule's candidate ``edited`` (valid geometry, ``report`` its failing
    report): when every violation is a plank that sags or is overstressed, those planks
    thickened (``thicker_planks``' estimate) and the result checked; (design, report,
    {id: (old, new) thickness}) when valid, else None."""
    if any(v.kind not in BENDING for v in report.violations):
        return None
    return _thickened(search, edited, geometry, report)


def thickness_phrase(thickened: dict, design: Design, capital: bool = False) -> str:
    """'make shelf 18 mm thick (now 12 mm) and post 36 mm (now 12 mm; two 18 mm sheets
    glued face to face)' (a plank that ``design`` does not have, one a fix adds, without
    'now'; a board of two sheets, ``GLUED``, says so, at its first plank)."""
    scale, unit = design.unit_scale, design.units
    parts, said = [], set()
    for k, (plank, (old, new)) in enumerate(thickened.items()):
        notes = [f"now {amount(old / scale)} {unit}"] if plank in design.plank_index else []
        if new not in said:                 # a glued board's make-up, said once
            notes += _glued(new, design)
            said.add(new)
        parts.append(f"{plank} {amount(new / scale)} {unit}" + (" thick" if k == 0 else "")
                     + (f" ({'; '.join(notes)})" if notes else ""))
    verb = "Make" if capital else "make"
    return f"{verb} {names(parts)}"


GLUED = {0.036: 0.018, 0.044: 0.022}
"""m: the boards of STOCK_THICKNESSES made of two sheets glued face to face, and the
sheet each is made of."""


def _glued(thickness: float, design: Design) -> list[str]:
    """['two 18 mm sheets glued face to face'] for a board of GLUED, else []."""
    sheet = next((sheet for board, sheet in GLUED.items()
                  if math.isclose(thickness, board, rel_tol=tol.STOCK_MATCH)), None)
    if sheet is None:
        return []
    return [f"two {amount(sheet / design.unit_scale)} {design.units} sheets glued face to "
            "face"]


def _thickened(search: Search, design: Design, geometry: Geometry, report: DesignReport,
               why: list[str] | None = None) -> tuple[Design, DesignReport, dict] | None:
    """The tries of the module docstring, from ``design`` (whose geometry and failing
    report are given); (design, report, {id: (old, new) m}) of the first valid one, else
    None and the reason in ``why``."""
    why = [] if why is None else why
    original = {p.id: p.thickness for p in design.planks}
    current: dict[str, float] = {}
    planes = mirror_planes(design)
    wanted = _needed(design, geometry, report)
    if not wanted:
        why[:] = ["no thickness helps (a joint's nails shear off, or the moment across "
                  "its nail row alone pulls them out)"]
        return None
    stuck: set[str] = set()             # planks that cannot grow: the others alone
    for _ in range(THICKEN_TRIES):
        for plank, thickness in wanted.items():
            if plank in stuck:
                continue
            stock = _stock(thickness)
            if plank in current and (stock is None or stock <= current[plank]):
                stock = _stock(current[plank], above=True)     # at least one board up
            if stock is None:
                largest = amount(tol.STOCK_THICKNESSES[-1] / design.unit_scale)
                why[:] = [f"{plank} would need {amount(thickness / design.unit_scale)} "
                          f"{design.units}, more than the thickest board ({largest} "
                          f"{design.units})"]
                return None
            current[plank] = stock
        matched = dict(current)
        _alike(matched, planes, original, design)
        grown_up = _grown_whole(search, design, geometry, matched, why) if matched != current \
            else None
        if grown_up is not None:
            current = matched
        else:       # the images cannot take the board: the planks that need it alone
            grown_up = _grown_whole(search, design, geometry, current, why)
        if grown_up is None:
            grown_up = _without_stuck(search, design, geometry, current, stuck, why)
        if grown_up is None:
            return None
        edited, after = grown_up
        search.checks += 1
        after_report = check_design(edited, after)
        if after_report.valid:
            edited, after_report, current = _pruned(search, design, geometry, planes,
                                                    current, (edited, after_report))
            order = sorted(current, key=design.plank_index.get)
            return edited, after_report, {p: (original[p], current[p]) for p in order}
        first = after_report.violations[0]
        why[:] = [f"with {names(list(current))} thicker, {first.kind}: {first.where}: "
                  f"{first.message}"]
        if any(v.kind not in (*BENDING, *PULL_FAILING) for v in after_report.violations):
            return None
        wanted = _needed(edited, after, after_report)
        if not wanted:
            return None
    return None


def _without_stuck(search: Search, design: Design, geometry: Geometry,
                   current: dict[str, float], stuck: set[str], why: list[str]):
    """``_grown_whole`` of the thickening ``current`` less the planks that cannot grow
    on their own (each tried alone; they are taken out of ``current`` and added to
    ``stuck``, in place), where some can; else None.  A splayed coffee table's legs,
    their top ends against the top and their feet on the floor, cannot grow, but its top
    can, upward, and a 44 mm top alone holds it (the legs bowed for the thin top's
    turning ends)."""
    cannot = {plank for plank, thickness in current.items()
              if _grown_whole(search, design, geometry, {plank: thickness}, []) is None}
    if not cannot or cannot == set(current):
        return None
    for plank in cannot:
        del current[plank]
    stuck |= cannot
    return _grown_whole(search, design, geometry, current, why)


def _pruned(search: Search, design: Design, geometry: Geometry,
            planes: tuple[MirrorPlane, ...], current: dict[str, float],
            valid: tuple[Design, DesignReport]) -> tuple[Design, DesignReport, dict]:
    """The valid thickening ``current`` (``valid``: its design and report) with the planks
    it does not need left as they were: each plank (the mirror images of upright planks
    together: a table's four legs) put back to its own thickness, upright planks first,
    and kept so where the design stays valid, at most PRUNE_CHECKS full checks.  A plank
    thickened for what an earlier try showed (a bookcase's sides bowed by its sagging
    shelves) may need it no more once the planks that bent it are thicker: a maker does
    not buy 1800 mm sides of 15 mm board that 12 mm ones would do.  Nothing to try where
    one plank (or group) is thickened."""
    edited, report = valid
    group_of = {plank: {plank} for plank in current}     # mirror images of upright planks
    for plane in planes:                                   # joined, over every plane
        for a, b in plane.pairs:
            if a in current and b in current and upright(design.plank(a)) \
                    and upright(design.plank(b)) and group_of[a] is not group_of[b]:
                joined = group_of[a] | group_of[b]
                for plank in joined:
                    group_of[plank] = joined
    groups, seen = [], set()
    for plank in sorted(current, key=lambda p: (not upright(design.plank(p)),
                                                design.plank_index[p])):
        if plank not in seen:
            seen |= group_of[plank]
            groups.append(group_of[plank])
    if len(groups) < 2:
        return edited, report, current
    checks = 0
    for group in groups:
        fewer = {p: t for p, t in current.items() if p not in group}
        if checks >= PRUNE_CHECKS or not fewer:
            break
        grown_up = _grown_whole(search, design, geometry, fewer, [])
        if grown_up is None:
            continue
        checks += 1
        search.checks += 1
        trial, trial_geometry = grown_up
        trial_report = check_design(trial, trial_geometry)
        if trial_report.valid:
            current, edited, report = fewer, trial, trial_report
    return edited, report, current


PRUNE_CHECKS = 4
"""Most planks (or mirror pairs) a valid thickening tries to leave as they were
(``_pruned``: a full check each)."""


def _grown_whole(search: Search, design: Design, geometry: Geometry,
                 thicknesses: dict[str, float], why: list[str]):
    """(the design with those planks ``grown``, its geometry), or None and the reason in
    ``why`` when a plank held on both faces cannot grow, a locked DOF would change, or the
    thicker planks would cut into others or change the joints."""
    added = frozenset(design.plank_index) - frozenset(search.design.plank_index)
    edited = grown(design, geometry, thicknesses, added)
    if edited is None or not search.keeps_locks(edited):
        why[:] = ["a plank held on both faces cannot grow (nothing on either face moves "
                  "with it or can be cut shorter), or a locked DOF would change"
                  if edited is None else "it would change a locked DOF"]
        return None
    after = analyze(edited)
    if after.violations or interpenetrations(edited) or \
            {frozenset(j.planks) for j in after.joints} != \
            {frozenset(j.planks) for j in geometry.joints}:
        why[:] = ["the thicker planks would cut into others or change the joints"]
        return None
    return edited, after


def _alike(current: dict[str, float], planes: tuple[MirrorPlane, ...],
           original: dict[str, float], design: Design) -> None:
    """Mirror legs made alike (in place): where one of a pair of upright planks
    (``planes``' pairs: the four legs of a table are pairs about both planes) gets a
    thicker board, its image gets the same board, the thicker of the two (a maker cuts a
    table's legs from one board, whichever of them the push loads most).  Level planks
    are left to what each needs (a shelf over a rail may stay thinner than its image)."""
    pairs = [(a, b) for plane in planes for a, b in plane.pairs
             if upright(design.plank(a)) and upright(design.plank(b))]
    for _ in range(len(pairs) + 1):
        changed = False
        for a, b in pairs:
            if a not in current and b not in current:
                continue
            both = max(current.get(a, original.get(a, 0.0)), current.get(b, original.get(b, 0.0)))
            for plank in (a, b):
                if plank in original and current.get(plank, original[plank]) < both:
                    current[plank] = both
                    changed = True
        if not changed:
            return


def _needed(design: Design, geometry: Geometry, report: DesignReport) -> dict[str, float]:
    """m: the thickness each failing plank, and each edge plank of a joint whose nails
    pull out, needs by the estimate of the module docstring (planks in report order)."""
    factors: dict[str, float] = {}
    failing_planks = {v.where for v in report.violations if v.kind in BENDING}
    failing_joints = {v.where for v in report.violations if v.kind in PULL_FAILING}
    joints = {joint.name: joint for joint in geometry.joints}
    for case in report.cases:
        for result in case.planks or ():
            if result.id not in failing_planks:
                continue
            creep = design.material_of(design.plank(result.id)).creep
            sag = result.sag * (1.0 + creep) / result.sag_allowed if result.sag_allowed else 0.0
            stress = result.stress / result.strength if result.strength else 0.0
            factor = max(max(sag, 0.0) ** (1.0 / 3.0), max(stress, 0.0) ** 0.5)
            factors[result.id] = max(factors.get(result.id, 0.0), factor)
        for result in case.joints:
            name = "/".join(result.planks)
            if name not in failing_joints or name not in joints:
                continue
            joint = joints[name]
            needed = _edge_thickness(joint, result)
            if needed is None:
                return {}                     # shear, or the rocking moment: no thickness helps
            factors[joint.edge] = max(factors.get(joint.edge, 0.0),
                                      needed / design.plank(joint.edge).thickness)
    return {plank: design.plank(plank).thickness * factor
            for plank, factor in factors.items() if factor > 1.0}


def _edge_thickness(joint: Joint, result: JointResult) -> float | None:
    """m: the edge plank's thickness at which the joint's nails hold in this case, its
    wrench kept: with F and M in the joint frame (``nail_groups.nail_pull_shear``),

        pull(t) = (2 |M_y| / t - F_n) / n + |M_x| y_max / S <= capacity
        <=>  t >= 2 |M_y| / (n (capacity - |M_x| y_max / S) + F_n);

    None when no thickness will do (the right side is not positive, or the shear, which
    the thickness does not change, is over its capacity)."""
    if result.shear > result.shear_capacity * (1.0 + tol.CAPACITY_REL_TOL):
        return None
    sign = 1.0 if joint.planks[0] == joint.face else -1.0
    force = joint.frame.T @ (sign * np.asarray(result.force))
    moment = joint.frame.T @ (sign * np.asarray(result.moment))
    y_max, spread = (float(v[0]) for v in nail_row([joint]))
    room = joint.nails * (result.pull_capacity - abs(moment[0]) * y_max / spread) + force[2]
    if room <= 0.0:
        return None
    return 2.0 * abs(float(moment[1])) / room


def _stock(thickness: float, above: bool = False) -> float | None:
    """m: the thinnest board of STOCK_THICKNESSES at least ``thickness`` (``above``:
    thicker than it); None beyond the thickest."""
    least = thickness * (1.0 + tol.STOCK_MATCH) if above else \
        thickness * (1.0 - tol.STOCK_MATCH)
    return next((stock for stock in tol.STOCK_THICKNESSES
                 if stock > least or (not above and stock == least)), None)


def grown(design: Design, geometry: Geometry, thicknesses: dict[str, float],
          stretchable: frozenset[str] = frozenset()) -> Design | None:
    """The design with the planks of ``thicknesses`` (id -> m) that thick, each grown away
    from its held faces (module docstring); a plank held on both faces grows toward the
    side where only planks nailed to it alone rest (a chair's back on its seat), which
    move with that face, else into the planks standing square on one face, cut that much
    shorter (``_cut_side``); load and anchor points on a moved face or a cut end move with
    it.  A plank of ``stretchable`` (one the same fix adds) on whose face a grown plank's
    edge is nailed is lengthened with it, so that it still covers that edge (a back panel
    over a seat made thicker).  None when a plank cannot grow."""
    held = _held_sides(design, geometry)
    resting = _resting(geometry)
    jointed = geometry.jointed()
    planks = {p.id: p for p in design.planks}
    moves: dict[str, list] = {}                    # plank id -> how its points move
    for plank_id, thickness in thicknesses.items():
        plank = planks[plank_id]
        grow = thickness - plank.thickness
        if grow <= 0.0:
            continue
        axis = plank.rotation_matrix[:, 2]
        sides = held.get(plank_id, set())
        if len(sides) == 2:
            side = next((s for s in (1, -1) if all(
                len(set(jointed.get(leaf, ()))) == 1
                for leaf in resting.get((plank_id, s), ()))), None)
            if side is not None:
                for leaf in resting.get((plank_id, side), ()):
                    shift = axis * side * grow
                    planks[leaf] = replace(planks[leaf], center=tuple(
                        float(v) for v in planks[leaf].center_array + shift))
                    moves.setdefault(leaf, []).append(_translation(shift))
            else:       # the planks standing on one face cut shorter by the growth
                side = _cut_side(plank, resting, planks, grow)
                if side is None:
                    return None
                for leaf in resting[(plank_id, side)]:
                    planks[leaf], move = _cut(planks[leaf], axis * side, grow, design)
                    moves.setdefault(leaf, []).append(move)
        elif sides:
            side = -next(iter(sides))
        else:
            side = _free_side(design, geometry, plank, grow, planks)
            if side is None:
                return None
        centre = plank.center_array + axis * side * 0.5 * grow
        planks[plank_id] = replace(plank, thickness=float(thickness),
                                   center=tuple(float(v) for v in centre))
        moves.setdefault(plank_id, []).append(_face_shift(plank, axis, side, grow, design))
        for joint in geometry.joints:
            if joint.edge == plank_id and joint.face in stretchable:
                planks[joint.face] = _covering(planks[joint.face], planks[plank_id],
                                               axis * side)
    if not moves:
        return None

    def moved(plank_id: str, point):
        for move in moves.get(plank_id, ()):
            point = move(point)
        return point
    cases = tuple(replace(case, loads=tuple(
        replace(load, point=moved(load.plank, load.point)) if load.point is not None
        else load for load in case.loads)) for case in design.load_cases)
    anchors = tuple(replace(a, point=moved(a.plank, a.point)) for a in design.anchors)
    return replace(design, planks=tuple(planks[p.id] for p in design.planks),
                   load_cases=cases, anchors=anchors)


CUT_LEFT = 2.0
"""A plank standing on a face that grows is cut shorter only where at least this many
times the cut would be left of it along the cut (``_cut_side``)."""


def _cut_side(plank: Plank, resting: dict, planks: dict[str, Plank],
              grow: float) -> int | None:
    """The face (+1 local +z, -1 -z) of a plank held on both faces toward which it can grow
    by cutting the planks that stand on that face shorter (``_cut``: a cabinet's bottom,
    the dividers standing on it and a kick board under it, grows down into the kick
    board, ripped that much narrower): each of them standing square on it, within
    PARALLEL_COS (an in-plane axis along its normal), and at least CUT_LEFT times the
    cut long that way.  The lower face of a level plank first (its top and what stands
    on it stay), else the face with fewer planks to cut; None where neither face will
    do."""
    axis = plank.rotation_matrix[:, 2]
    order = (-1, 1) if axis[2] > 0.0 else (1, -1)
    if not level(plank):
        order = tuple(sorted((1, -1), key=lambda s: len(resting.get((plank.id, s), ()))))
    for side in order:
        leaves = resting.get((plank.id, side), ())
        if leaves and all(_fits(planks[leaf], axis * side, grow) for leaf in leaves):
            return side
    return None


def _fits(leaf: Plank, way: np.ndarray, grow: float) -> bool:
    """Whether ``leaf`` stands square along ``way`` and is long enough to be cut by
    ``grow`` (``_cut_side``)."""
    axis, _, cosine = _toward(leaf, way)
    return cosine >= PARALLEL_COS and _sizes(leaf)[axis] >= CUT_LEFT * grow / cosine


def _toward(plank: Plank, way: np.ndarray) -> tuple[int, np.ndarray, float]:
    """The plank's in-plane axis nearest ``way`` (a unit vector): its index (0: length,
    1: width), its direction turned toward ``way``, and the cosine between the two."""
    axes = plank.rotation_matrix
    axis = int(np.argmax(np.abs(axes[:, :2].T @ way)))
    cosine = float(axes[:, axis] @ way)
    return axis, axes[:, axis] * (1.0 if cosine > 0.0 else -1.0), abs(cosine)


def _sizes(plank: Plank) -> list[float]:
    return [plank.length, plank.width]


def _cut(leaf: Plank, way: np.ndarray, grow: float, design: Design):
    """(``leaf`` cut, how a point on it moves): standing on a face that moves ``grow``
    along ``way`` (a unit vector, from the face into the leaf), it is cut shorter at that
    end by what keeps its other end where it was, grow / cos along its own axis
    (``_cut_side``); a point on that end (within the design's tolerance of it) or in the
    strip cut off comes onto the new end (a load on a kick board's top edge stays on its
    edge), any other stays where it is."""
    axis, along, cosine = _toward(leaf, way)
    cut = grow / cosine
    sizes = _sizes(leaf)
    new_end = cut - 0.5 * sizes[axis]                       # along ``along``
    slack = design.tolerance + tol.ON_PLANK_EPS
    centre = leaf.center_array

    def move(point):
        short = new_end - float((np.asarray(point) - centre) @ along)
        if short <= 0.0 or short > cut + slack:
            return point
        return tuple(float(v) for v in np.asarray(point) + along * short)

    sizes[axis] -= cut
    return replace(leaf, length=sizes[0], width=sizes[1], center=tuple(
        float(v) for v in centre + along * 0.5 * cut)), move


def cut_phrase(design: Design, edited: Design) -> str:
    """'; rip kick 3 mm narrower (80 -> 77 mm) to make room': the planks of ``design``
    that ``edited`` (``design`` with planks thickened, ``grown``) has shorter or
    narrower, cut to make room for them (``_cut``), in shop words ('' where none is)."""
    scale, unit = design.unit_scale, design.units
    parts = []
    for plank in design.planks:
        if plank.id not in edited.plank_index:
            continue
        after = edited.plank(plank.id)
        for (verb, shorter), old, new in zip((("cut", "shorter"), ("rip", "narrower")),
                                             _sizes(plank), _sizes(after)):
            if new < old * (1.0 - tol.STOCK_MATCH):
                parts.append(f"{verb} {plank.id} {amount((old - new) / scale)} {unit} "
                             f"{shorter} ({amount(old / scale)} -> {amount(new / scale)} "
                             f"{unit})")
    return f"; {names(parts)} to make room" if parts else ""


def _covering(face: Plank, edge: Plank, way: np.ndarray) -> Plank:
    """``face`` lengthened along its in-plane axis nearest ``way`` (the way ``edge`` grew,
    a unit vector), its far end moved, until it reaches ``edge``'s grown face there."""
    axis, along, _ = _toward(face, way)
    sizes = _sizes(face)
    reach = float(edge.center_array @ way) + 0.5 * edge.thickness
    end = float(face.center_array @ way) + 0.5 * sizes[axis] * float(along @ way)
    short = (reach - end) / max(float(along @ way), 1e-12)
    if short <= 0.0:
        return face
    sizes[axis] += short
    return replace(face, length=sizes[0], width=sizes[1], center=tuple(
        float(v) for v in face.center_array + along * 0.5 * short))


def _resting(geometry: Geometry) -> dict[tuple[str, int], list[str]]:
    """(face plank, its side) -> the edge planks nailed on that broad face."""
    found: dict[tuple[str, int], list[str]] = {}
    for joint in geometry.joints:
        found.setdefault((joint.face, int(joint.face_side)), []).append(joint.edge)
    return found


def _free_side(design: Design, geometry: Geometry, plank: Plank, grow: float,
               planks: dict[str, Plank]) -> int | None:
    """How a plank held on neither face grows: 0 both ways, else toward +1 or -1 local
    z; the first whose new corners stay out of the floor and of the faces its ends rest
    on (a splayed leg, its ends cut square to it, cannot grow either way without
    cutting in), trying a level plank's downward side first (its top face stays: module
    docstring) and another's side toward the planks its ends are nailed to first (a
    table's leg grows inward, its outer face still flush with the top's edge: both ways
    it stuck out past the edge by half the growth); None if none does.  ``planks``: the
    planks as grown so far."""
    planes = [(np.array([0.0, 0.0, 1.0]), 0.0)]
    for joint in geometry.joints:
        if joint.edge == plank.id:
            face = planks[joint.face]
            outward = face.rotation_matrix[:, 2] * joint.face_side
            planes.append((outward, float(outward @ face.center_array) + face.half_extents[2]))
    slack = design.tolerance + tol.ON_PLANK_EPS
    axis = plank.rotation_matrix[:, 2]
    order = (0, 1, -1)
    inward = sum(float((planks[joint.face].center_array - plank.center_array) @ axis)
                 for joint in geometry.joints if joint.edge == plank.id)
    if level(plank):
        down = -1 if axis[2] > 0.0 else 1
        order = (down, 0, -down)
    elif abs(inward) > slack:
        side = 1 if inward > 0.0 else -1
        order = (side, 0, -side)
    for side in order:
        moved = replace(plank, thickness=plank.thickness + grow, center=tuple(
            float(v) for v in plank.center_array + axis * side * 0.5 * grow))
        corners = moved.corners
        old = plank.corners
        if all((corners @ n - offset).min() >= min(float((old @ n - offset).min()), 0.0) - slack
               for n, offset in planes):
            return side
    return None


def _translation(shift: np.ndarray):
    return lambda point: tuple(float(v) for v in np.asarray(point) + shift)


def _face_shift(plank: Plank, axis: np.ndarray, side: int, grow: float, design: Design):
    """How a point on ``plank`` moves when it grows by ``grow`` toward ``side`` (0: both
    ways): with its face when it lies on a face that moves, else not at all."""
    half = plank.half_extents[2]
    slack = design.tolerance + tol.ON_PLANK_EPS

    def move(point):
        height = float((np.asarray(point) - plank.center_array) @ axis)
        for face in (1, -1):
            if abs(height - face * half) <= slack and side in (0, face):
                step = grow if side else 0.5 * grow
                return tuple(float(v) for v in np.asarray(point) + axis * face * step)
        return point
    return move


def _held_sides(design: Design, geometry: Geometry) -> dict[str, set[int]]:
    """plank id -> its broad faces (+1 local +z, -1 -z) that hold: a joint's face side,
    a resting plank's, and the face a plank lying on the floor or a wall lies on."""
    held: dict[str, set[int]] = {}
    for joint in geometry.joints:
        held.setdefault(joint.face, set()).add(int(joint.face_side))
    for contact in geometry.contacts:
        if contact.on is not None and contact.frame is not None:
            face = design.plank(contact.on)
            side = 1 if float(np.asarray(contact.frame[2]) @ face.rotation_matrix[:, 2]) > 0 \
                else -1
            held.setdefault(contact.on, set()).add(side)
        elif contact.anchor is None and 0 <= contact.corner < 8:
            plank = design.plank(contact.plank)
            support = np.array([0.0, 0.0, 1.0]) if contact.wall is None else \
                np.asarray(design.walls[contact.wall].normal)
            if abs(float(plank.rotation_matrix[:, 2] @ support)) >= 0.95:
                held.setdefault(plank.id, set()).add(-1 if contact.corner < 4 else 1)
    return held
