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

How a thicker plank grows (which face stays, what moves or is cut with it) is
``growth``'s.

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
from furncheck.design.model import Design
from furncheck.geometry import Geometry, Joint, analyze, interpenetrations
from furncheck.nail_groups import nail_row
from furncheck.plain import plain_number
from furncheck.result import DesignReport, JointResult
from furncheck.suggest.discrete.common import (
    BENDING,
    Fix,
    Search,
    amount,
    names,
    upright,
)
from furncheck.suggest.discrete.growth import cut_phrase, grown
from furncheck.suggest.needs import floor_friction
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
    if any(v.where.startswith("anchors[") for v in report.violations):
        search.not_applicable(THICKER, "it does not repair an overloaded wall fixing (a "
                              "thicker board only adds to the weight the fixings hold)")
        return None
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
    own feet with the boards alone, its weight from 124 to 237 N (mu W from 62 to 118.5 N
    against 110), and a maker should not be sent for pads that do nothing.  (The boards
    are those pruned with the part: a design turned off the world's axes, whose mirror
    planes ``_alike`` does not find, may keep one leg thinner than its image, too light
    without the part.)"""
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
    fix = _fix(search, *_pruned(search, design, geometry, mirror_planes(design), existing,
                                (edited, report)),
               f"the boards that finished the {rule} candidate, without it")
    held = _held_by_weight(search, fix.design)
    return fix if not held else replace(fix, advice=f"{fix.advice[:-1]}; {held}.")


def _held_by_weight(search: Search, edited: Design) -> str:
    """Words for the sliding that ``edited``'s heavier boards hold by their weight alone
    (``boards_alone``): per sliding violation of the design, the friction mu W it then
    has against the push, and how much of it is to spare ('' where none slid, or where
    what slid is held by more than the floor's friction: a part on its rests, a piece on
    a wall, ``needs.floor_friction``): a maker should know that the boards, not a fix of
    the sliding, hold the shove, and by how little."""
    sliding = [v for v in search.report.violations if v.kind == "sliding"]
    if not sliding:
        return ""
    after = analyze(edited)
    said = []
    mu = edited.material.friction
    for violation in sliding:
        if floor_friction(search.design, search.geometry, violation.where,
                          violation.case) is None:
            continue
        held = floor_friction(edited, after, violation.where, violation.case)
        if held is None:
            continue
        weight, push = held
        if push <= 0.0 or mu * weight < push:
            continue
        spare = mu * weight / push - 1.0
        said.append(f"friction then gives up to {plain_number(mu * weight, 3)} N (mu W) "
                    f"against the {plain_number(push, 3)} N push in case "
                    f"'{violation.case}', {plain_number(100.0 * spare, 2)} % to spare")
    if not said:
        return ""
    return "their weight alone also keeps it from sliding: " + "; ".join(said) + \
        " (non-slip pads would add more)"


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
            return _pruned(search, design, geometry, planes, current,
                           (edited, after_report))
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
    one plank (or group) is thickened.  (design, report, {id: (old, new) thickness}),
    in the design's plank order."""
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
        return edited, report, _pairs(design, current)
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
    return edited, report, _pairs(design, current)


def _pairs(design: Design, thicknesses: dict[str, float]) -> dict[str, tuple[float, float]]:
    """{id: (its thickness in ``design``, the new one)} of ``thicknesses``, in plank order."""
    return {p: (design.plank(p).thickness, thicknesses[p])
            for p in sorted(thicknesses, key=design.plank_index.get)}


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
