"""A continuous suggestion in a maker's words:

    Move leg_l and leg_r apart by 258 mm each (valid for 214-302 mm each).
    Lower the top of back by 79.8 mm (valid for 60-120 mm).
    Tilt leg_r 7.55 degrees about y, its top toward leg_l, its ends cut at 7.55 degrees to
    sit flat (valid for 5.04-10.1 degrees).
    Move leg_l 161 mm toward leg_r (valid for 147-176 mm); to fit, shorten rung by 161
    mm (328 -> 167 mm).

A mirror pair changed symmetrically (``suggest.symmetry``) is one phrase: apart or closer
for a move across the mirror plane, raise or lower, lengthen or shorten, tilt with their
tops apart or together.  A size change that moves a plank's top edge reads as raising or
lowering that edge (narrowing a chair's back lowers the back rest).  Every amount is a
magnitude; the verb says which way, and the interval is of that same magnitude, so the
sign of a change and of its interval never disagree.  A plank whose ends sit square on
the floor or on faces, tilted, has them cut at the angle it then makes with them
(``_bevel``): a square end would sit on one edge.  Where the upper end is where the
search stopped rather than an invalid step, the sentence says so.  Planks that the change
resizes to follow (a rung between legs moved closer, shelves between sides, legs under
a raised seat) are named after it with their new sizes (``follow_phrase``): the cut list
has them too, but a maker reads the sentence to know which boards to cut again.
"""

from __future__ import annotations

import math
import re

import numpy as np

from furncheck.design.model import Design
from furncheck.dofs import parse_dof, structure
from furncheck.edit_check import standing_geometry
from furncheck.geometry import analyze
from furncheck.plain import plain_list
from furncheck.report.cutlist import cut_number, from_to
from furncheck.report.numbers import format_number
from furncheck.suggest.cutlist import PlankEdit
from furncheck.suggest.symmetry import MirrorPlane, mirror_planes, mirrored_dof

ADVICE_DIGITS = 3
"""Significant digits of the amounts in the advice (the JSON keeps REPORT digits)."""

PARALLEL_COSINE = 0.95
"""Planks whose face normals' cosine exceeds this count as parallel."""

TOWARD_COSINE = 0.5
"""A plank is 'toward' which a move goes when the direction to its centre is within 60
degrees of the move."""

VERTICAL_COSINE = 0.7
"""A plank's axis (or the way its end moves) counts as vertical when its cosine with the
world z axis exceeds this (45 degrees)."""

TOPS_KEPT = 0.05
"""A mirror pair's tilt whose tops move across the mirror plane by at most this share of
how far they move is a tilt along the plane (both tops the same way), not apart or
together."""

PAIR_MATCH = 1e-6
"""Two DOF changes are one symmetric change when they agree to this relative amount."""

SEARCH_LIMITS = {"length": "half the design's size", "deg": "28.6 degrees"}
"""Where the line search stops (``suggest.candidates.MAX_STEP``), in words."""


def continuous_advice(dofs: tuple[str, ...], changes: tuple[float, ...],
                      units: tuple[str, ...], step: float, interval: tuple[float, float],
                      limited: bool, original: Design, edited: Design,
                      follow: str = "") -> str:
    """The suggestion as one sentence: its phrases joined by 'and', then the valid interval
    of the first phrase's amount ('valid for 157-194 mm each, the other change in
    proportion': the others scale with it; 'of the first change' read as code to a
    woodworker), then ``follow`` (``follow_phrase``)."""
    sentence, first_each, count = _changes_sentence(dofs, changes, units, original, edited)
    lead = abs(changes[0]) / step if step else 0.0
    low, high = interval
    unit = _unit(units[0])
    each = " each" if first_each else ""
    others = "" if count <= 1 else ", the other change in proportion" if count == 2 \
        else ", the other changes in proportion"
    near, far = _amount(low * lead), _amount(high * lead)
    limit = (SEARCH_LIMITS["deg" if units[0] == "deg" else "length"] if len(dofs) == 1
             else "its limit for these changes together") if limited else ""
    if near != far:
        valid = f"valid for {near}-{far} {unit}{each}{others}"
        if limited:
            valid += f"; the search stopped there, at {limit}"
    elif limited:       # valid from there on, as far as the search went: not a lone value
        valid = f"valid at {near} {unit}{each}{others}, where the search stopped, at {limit}"
    else:
        valid = f"valid for {near} {unit}{each}{others} only, to the search's resolution"
    return f"{sentence[0].upper()}{sentence[1:]} ({valid}){follow}."


def follow_phrase(edits: tuple[PlankEdit, ...], changed: set[str], unit: str,
                  said: str = "") -> str:
    """'; to fit, shorten bottom, middle and top by 604 mm each (900 -> 296 mm)': the
    planks of the cut list (``edits``) other than those the DOFs change (``changed``) whose
    length or width the change alters, those alike (the same verb, old and new size) in
    one phrase, in the cut list's order, its numbers as the cut list writes them (a
    tenth of the unit or finer: 328 -> 326.5, not 327); '' where there are none.  Planks
    whose new size ``said`` (the rest of the suggestion's words) gives already, a
    discrete fix's own cuts ('cut kick 3 mm shorter (80 -> 77 mm) to make room'), are
    left to it."""
    groups: dict[tuple[str, str, str], list[str]] = {}
    for edit in edits:
        if edit.action != "change" or edit.plank in changed or _sized(said, edit.plank):
            continue
        for field in edit.fields:
            if field.field not in ("length", "width") or field.before is None \
                    or field.after is None:
                continue
            verb = _size_verb(field.field, field.after - field.before)
            by = cut_number(abs(field.after - field.before))
            sizes = f"({from_to(field.before, field.after)} {_unit(unit)})"
            groups.setdefault((verb, by, sizes), []).append(edit.plank)
    if not groups:
        return ""
    phrases = [f"{verb} {plain_list(planks)} by {by} {_unit(unit)}"
               f"{' each' if len(planks) > 1 else ''} {sizes}"
               for (verb, by, sizes), planks in groups.items()]
    return f"; to fit, {' and '.join(phrases)}"


def _sized(text: str, plank: str) -> bool:
    """Whether ``text`` gives the plank ``plank`` a new size ('kick 3 mm narrower (80 ->
    77 mm)', ``suggest.discrete.growth.cut_phrase``)."""
    return re.search(rf"(?<![\w.-]){re.escape(plank)} [\d.,]+ \S+ "
                     r"(shorter|narrower|longer|wider) \(", text) is not None


def change_sentence(dofs: tuple[str, ...], changes: tuple[float, ...],
                    units: tuple[str, ...], original: Design, edited: Design) -> str:
    """The DOF changes as shop words joined by 'and', capitalized, without an interval
    ('Move side_l and side_r closer together by 1.31 mm each')."""
    sentence = _changes_sentence(dofs, changes, units, original, edited)[0]
    return f"{sentence[0].upper()}{sentence[1:]}"


def _changes_sentence(dofs: tuple[str, ...], changes: tuple[float, ...],
                      units: tuple[str, ...], original: Design,
                      edited: Design) -> tuple[str, bool, int]:
    """(the phrases joined by 'and', whether the first is a mirror pair's ('each'), how
    many phrases)."""
    planes = mirror_planes(original)
    geometry = analyze(original)
    held = structure(original, standing_geometry(geometry)).ends
    nailed = geometry.jointed()
    phrases, first_each = [], False
    done: set[int] = set()
    for k, name in enumerate(dofs):
        if k in done:
            continue
        pair = _pair(original, planes, dofs, changes, k, done)
        if pair is not None:
            j, plane = pair
            done.add(j)
            kind = name.rpartition(".")[2]
            if kind in ("length", "width"):     # a size: which end moves, as for one
                plank, image = name.rpartition(".")[0], dofs[j].rpartition(".")[0]
                words = [_phrase(original, edited, held, p, "{}", kind, changes[k], units[k])
                         for p in (plank, image)]
                if words[0] == words[1]:        # the same end of each (mirrored)
                    head, bracket, note = words[0].partition(" (")
                    phrases.append(head.format(f"{plank} and {image}") + " each"
                                   + bracket + note)
                else:                           # held otherwise: each its own words
                    phrases.append(f"{words[0].format(plank)} and {words[1].format(image)}")
            else:
                phrase = _pair_phrase(original, edited, plane, name, dofs[j], changes[k],
                                      units[k])
                if kind in ("rx", "ry"):
                    phrase += _bevel(original, edited, held, name.rpartition(".")[0], "their")
                phrases.append(phrase)
            first_each = first_each or k == 0
            continue
        plank = name.rpartition(".")[0]
        previous = dofs[k - 1].rpartition(".")[0] if k else None
        subject = "it" if previous == plank and k - 1 not in done else plank
        kind = name.rpartition(".")[2]
        phrase = _phrase(original, edited, held, plank, subject, kind, changes[k], units[k],
                         set(nailed.get(plank, ())))
        if kind in ("rx", "ry"):
            phrase += _bevel(original, edited, held, plank, "its")
        phrases.append(phrase)
    return " and ".join(phrases), first_each, len(phrases)


def _pair(design: Design, planes: tuple[MirrorPlane, ...], dofs: tuple[str, ...],
          changes: tuple[float, ...], k: int, done: set[int]):
    """(index of the DOF that mirrors DOF k by the mirrored amount, the plane), or None."""
    dof = parse_dof(design, dofs[k])
    for plane in planes:
        found = mirrored_dof(design, plane, dof)
        if found is None or found[0].plank == dof.plank:
            continue
        image, sign = found
        for j in range(k + 1, len(dofs)):
            if j not in done and dofs[j] == image.name and \
                    math.isclose(changes[j], sign * changes[k], rel_tol=PAIR_MATCH):
                return j, plane
    return None


def _pair_phrase(design: Design, edited: Design, plane: MirrorPlane, first: str,
                 second: str, change: float, unit: str) -> str:
    a, _, kind = first.rpartition(".")
    b = second.rpartition(".")[0]
    both = f"{a} and {b}"
    amount = f"{_amount(abs(change))} {_unit(unit)} each"
    if kind in ("x", "y", "z"):
        axis = "xyz".index(kind)
        if axis == plane.axis:
            side = design.plank(a).center[axis] - plane.offset
            apart = change * side > 0.0
            return f"move {both} {'apart' if apart else 'closer together'} by {amount}"
        if kind == "z":
            return f"{'raise' if change > 0 else 'lower'} {both} by {amount}"
        return f"move {both} {amount} {_where(design, a, axis, change)}"
    if kind == "rz":
        return f"turn {both} by {amount} about the vertical, mirrored"
    top_before = _top(design, a)
    top_after = _top(edited, a)
    if top_before is None or top_after is None:
        return f"tilt {both} by {amount}, mirrored"
    before = abs(top_before[plane.axis] - plane.offset)
    after = abs(top_after[plane.axis] - plane.offset)
    if abs(after - before) <= TOPS_KEPT * float(np.linalg.norm(top_after - top_before)):
        ahead = [_top_ahead(design, edited, p) for p in (a, b)]   # along the plane:
        if None in ahead:                                           # both one way
            way = top_after - top_before
            axis = int(np.argmax(np.abs(way[:2])))
            return f"tilt {both} by {amount}, their tops along " \
                   f"{'+' if way[axis] > 0 else '-'}{'xy'[axis]}"
        towards = ahead[0] if ahead[0] == ahead[1] else f"{ahead[0]} and {ahead[1]}"
        return f"tilt {both} by {amount}, their tops toward {towards}"
    standing = all(float(design.plank(p).corners[:, 2].min()) <= design.tolerance
                   for p in (a, b))            # feet: where they stand on the floor
    if after > before:
        return f"tilt {both} by {amount}, their tops leaning out" + (
            " (their feet in)" if standing else "")
    return f"tilt {both} by {amount}, their tops leaning in" + (
        " (their feet splayed out)" if standing else "")


def _phrase(design: Design, edited: Design, held: dict, plank: str, subject: str,
            kind: str, change: float, unit: str, nailed: set[str] = frozenset()) -> str:
    amount = f"{_amount(abs(change))} {_unit(unit)}"
    if kind == "z":
        return f"{'raise' if change > 0 else 'lower'} {subject} by {amount}"
    if kind in ("x", "y"):
        return (f"move {subject} {amount} "
                f"{_where(design, plank, 'xy'.index(kind), change, nailed)}")
    if kind in ("length", "width"):
        moved = _moved_end(design, held, plank, 0 if kind == "length" else 1)
        if moved is not None and moved[2] > VERTICAL_COSINE:
            return f"{'raise' if change > 0 else 'lower'} the top of {subject} by {amount}"
        if kind == "width" and moved is not None and moved[2] < -VERTICAL_COSINE:
            # a board hung by its top edge (a batten, an apron): its bottom edge moves; a
            # leg whose foot moves is still lengthened or shortened
            return f"{'lower' if change > 0 else 'raise'} the bottom of {subject} by {amount}"
        phrase = f"{_size_verb(kind, change)} {subject} by {amount}"
        if not _held_at(held, plank, 0 if kind == "length" else 1):
            side = "end" if kind == "length" else "edge"
            whole = len(str(int(abs(round(change)))))
            half = f"{format_number(abs(change) / 2.0, max(ADVICE_DIGITS, whole) + 1)} " \
                   f"{_unit(unit)}"              # (553 mm: 276.5 off each end, not 277)
            phrase += f" ({half} {'off' if change < 0 else 'at'} each {side})"
        return phrase
    if kind == "rz":
        turn = "counterclockwise" if change > 0 else "clockwise"
        return f"turn {subject} {amount} {turn} (seen from above)"
    how = _tilt_effect(design, edited, plank)
    return f"tilt {subject} {amount} about {kind[1]}" + (f", {how}" if how else "")


def _bevel(design: Design, edited: Design, held: dict, plank_id: str, whose: str) -> str:
    """', its ends cut at 6.5 degrees to sit flat' for a plank whose ends along its length
    sit square on the floor or on other planks' faces (``held``) and that the edit tilts
    off them by BEVEL_ANGLE or more: a square end, tilted, would touch along one edge only
    (the angle between its length and the normal of what it sits on, in ``edited``; each
    end's own where they differ, 'its end on the ground' where one end sits square: an
    end not square to what it sits on now is cut as the maker cut it); '' otherwise."""
    if plank_id not in design.plank_index or plank_id not in edited.plank_index:
        return ""
    ends = [end for end in held.get(plank_id, ()) if end.axis == 0]
    if not ends:
        return ""
    before = design.plank(plank_id).rotation_matrix[:, 0]
    after = edited.plank(plank_id).rotation_matrix[:, 0]
    square, normals, angles = [], [], []
    for end in ends:
        if _angle(before, end.normal) >= BEVEL_ANGLE:       # not square to it now: its
            continue                                        # cut is the maker's own
        normal = end.normal if end.on is None or end.on not in edited.plank_index else \
            edited.plank(end.on).rotation_matrix[:, 2]
        square.append(end)
        normals.append(normal)
        angles.append(_angle(after, normal))
    ends = square
    if not ends or max(angles) < BEVEL_ANGLE:
        return ""
    if len(ends) == 1:
        return f", {whose} end on {ends[0].support} cut at {_amount(angles[0])} degrees to " \
               "sit flat"
    if max(angles) - min(angles) < BEVEL_ANGLE:
        edges = _edge_length(edited, plank_id, normals[0], max(angles))
        return f", {whose} ends cut at {_amount(max(angles))} degrees to sit flat " \
               f"({format_number(edges / edited.unit_scale, 4)} {edited.units} along " \
               f"{whose} edges)"
    said = [f"on {end.support} at {_amount(angle)}" for end, angle in zip(ends, angles)]
    return f", {whose} ends cut to sit flat ({', '.join(said)} degrees)"


def _edge_length(design: Design, plank_id: str, normal: np.ndarray, angle: float) -> float:
    """m: how long a plank whose ends are cut parallel at ``angle`` degrees is along its
    edges, the ends' planes those square ones met at its corners: its length L (the
    model's box, whose square ends touch what it sits on at a corner) plus its extent e
    across it in the tilt's plane times tan(angle): the ends' planes lie that much
    apart along each edge (L cos a + e sin a = the height it spans = its edges x cos a)."""
    plank = design.plank(plank_id)
    axes = plank.rotation_matrix
    across = np.asarray(normal, dtype=float) - float(np.asarray(normal) @ axes[:, 0]) * axes[:, 0]
    size = float(np.linalg.norm(across))
    extent = 0.0 if size == 0.0 else \
        (abs(float(across @ axes[:, 1])) * plank.width
         + abs(float(across @ axes[:, 2])) * plank.thickness) / size
    return plank.length + extent * math.tan(math.radians(angle))


def _angle(axis: np.ndarray, normal: np.ndarray) -> float:
    """Degrees between a plank's length ``axis`` and the line of a face's ``normal``."""
    cosine = min(abs(float(axis @ normal)) / float(np.linalg.norm(normal)), 1.0)
    return math.degrees(math.acos(cosine))


BEVEL_ANGLE = 0.5
"""Degrees: an end within this of square to what it sits on needs no cut (``_bevel``)."""


def _size_verb(kind: str, change: float) -> str:
    if kind == "length":
        return "lengthen" if change > 0 else "shorten"
    return "widen" if change > 0 else "narrow"


def _where(design: Design, plank: str, axis: int, change: float,
           nailed: set[str] = frozenset()) -> str:
    sign = 1.0 if change > 0 else -1.0
    ahead = _toward(design, plank, _unit_vector(axis, sign), nailed)
    behind = _toward(design, plank, _unit_vector(axis, -sign), nailed)
    if ahead:
        return f"toward {ahead}"
    if behind:
        return f"away from {behind}"
    return f"along {'+' if change > 0 else '-'}{'xyz'[axis]}"


def _unit_vector(axis: int, sign: float) -> np.ndarray:
    vector = np.zeros(3)
    vector[axis] = sign
    return vector


def _toward(design: Design, plank_id: str, way: np.ndarray,
            nailed: set[str] = frozenset()) -> str | None:
    """The plank ahead of a move of ``plank_id`` the (unit, world) ``way``: among the others
    whose centre lies within 60 degrees of it, a parallel one (the other leg of a pair)
    before the rest, then one it is not ``nailed`` to (a splayed leg moved in under its
    seat goes toward the leg opposite, not 'toward seat', which it hangs from), then the
    nearest."""
    moved = design.plank(plank_id)
    normal = moved.rotation_matrix[:, 2]
    best, best_key = None, None
    for plank in design.planks:
        offset = plank.center_array - moved.center_array
        distance = float(np.linalg.norm(offset))
        if plank.id == plank_id or distance == 0 or \
                float(offset @ way) < TOWARD_COSINE * distance:
            continue
        parallel = abs(float(plank.rotation_matrix[:, 2] @ normal)) > PARALLEL_COSINE
        key = (not parallel, plank.id in nailed, distance)
        if best_key is None or key < best_key:
            best, best_key = plank.id, key
    return best


def _moved_end(design: Design, held: dict, plank_id: str, axis: int) -> np.ndarray | None:
    """The outward unit direction (world) of the plank's end that a size change along
    local ``axis`` moves: the end opposite the one held by a joint or the ground (as
    ``dofs.apply_dof`` does it); None when neither is held (both ends move alike)."""
    ends = [end for end in held.get(plank_id, ()) if end.axis == axis]
    if len(ends) != 1:
        return None
    return -ends[0].sign * design.plank(plank_id).rotation_matrix[:, axis]


def _held_at(held: dict, plank_id: str, axis: int) -> bool:
    """Whether a joint or the ground holds an end of the plank along local ``axis`` (where
    none does, a size change along it moves both ends alike, as ``dofs.apply_dof``
    makes it)."""
    return any(end.axis == axis for end in held.get(plank_id, ()))


def _top(design: Design, plank_id: str, side: int = 0) -> np.ndarray | None:
    """The centre of the plank's higher end along its length (``side`` 1: the middle of
    its higher long edge, along its width; None if that way lies flat)."""
    if plank_id not in design.plank_index:
        return None
    plank = design.plank(plank_id)
    axis = plank.rotation_matrix[:, side]
    if abs(float(axis[2])) < 1e-9:
        return None
    end = 0.5 * (plank.width if side else plank.length) * (axis if axis[2] > 0 else -axis)
    return plank.center_array + end


def _top_ahead(design: Design, edited: Design, plank_id: str, side: int = 0) -> str | None:
    """The plank toward which an upright plank's top (``side`` 1: a plank on edge, its top
    edge) moves in ``edited`` (``_toward``), or None (it lies flat, its top stays, or no
    plank is that way)."""
    if abs(float(design.plank(plank_id).rotation_matrix[2, side])) <= VERTICAL_COSINE:
        return None
    before, after = _top(design, plank_id, side), _top(edited, plank_id, side)
    if before is None or after is None:
        return None
    way = after - before
    way[2] = 0.0
    if float(np.linalg.norm(way)) <= 1e-12:
        return None
    return _toward(design, plank_id, way / float(np.linalg.norm(way)))


def _tilt_effect(design: Design, edited: Design, plank_id: str) -> str:
    """What a tilt does, for the phrase: where an upright plank's top goes ('its top toward
    leg_l'), where the top edge of one on edge goes as it turns about its length (a back
    rest: 'its top edge toward seat'), or which end of a lying one rises."""
    plank = design.plank(plank_id)
    length_axis = plank.rotation_matrix[:, 0]
    if abs(float(length_axis[2])) > VERTICAL_COSINE:
        ahead = _top_ahead(design, edited, plank_id)
        return f"its top toward {ahead}" if ahead else ""
    if plank_id not in edited.plank_index:
        return ""
    turned = edited.plank(plank_id).rotation_matrix[:, 0]
    rising = turned[2] - length_axis[2]
    if abs(float(rising)) <= 1e-12:     # turned about its level length: on edge (a back
        if abs(float(plank.rotation_matrix[2, 1])) > VERTICAL_COSINE:       # rest), its
            ahead = _top_ahead(design, edited, plank_id, side=1)           # top edge moves
            return f"its top edge toward {ahead}" if ahead else ""
        return ""
    end = length_axis if rising > 0 else -length_axis
    ahead = _toward(design, plank_id, end / float(np.linalg.norm(end)))
    return f"raising its end toward {ahead}" if ahead else ""


def _amount(value: float) -> str:
    """ADVICE_DIGITS significant digits, but whole units at least (1250 mm, not 1.25e+03)."""
    whole = len(str(int(abs(round(value)))))
    return format_number(value, max(ADVICE_DIGITS, whole))


def _unit(unit: str) -> str:
    return "degrees" if unit == "deg" else unit
