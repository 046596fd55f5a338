"""Legs given a quarter turn: the shop's fix for legs that rack across their thickness.

A leg cut from a board stands with its broad face one way; pushed square to that face it
bends across its thickness t and its nail row at the top has a lever of t / 2, while
along its face it is its width w deep: the same board turned a quarter turn about its
length is (w / t)^3 times stiffer against the push (sag goes with 1 / I, I = b h^3 / 12)
and its nails' lever grows with it.  A table's 60 x 12 mm legs pushed along the table's
length bow 29.5 mm; turned, they carry the push on their 60 mm depth.  No part is added
and no board bought: the maker cuts the same legs and nails them on turned.

Tried where the design racks (``racking.racking_places``: a leg's joint fails or a leg
bends in a load case with a sideways load) and a failing leg's broad face is square to
that case's push (within 45 degrees), wider than it is thick and at most LEG_WIDTH
times (a leg, not a panel): those legs, and their mirror images that are legs too (a
maker turns all four legs of a table whose two far ones fail), turned about their
length, each moved along the push and across it so that its outer edges stay where its
outer faces were (set in its corner as before), then (a second candidate) turned in
place, each candidate only where no turned leg reaches past the plan of what it carries
(turned in place, a leg flush with the top's end would stand past it); where both are
finished with as much board, the first is kept.  Load and anchor points on a leg turn
with it.  Each candidate is checked in full like every other (joints kept, no plank cut
into another); one that then fails only by bending is finished with thicker boards
(``common.Search.first_valid``).
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import replace

import numpy as np

from furncheck.design.model import Design, Plank
from furncheck.dofs import axis_rotation, euler_degrees, with_planks_carried
from furncheck.geometry import Geometry
from furncheck.suggest.discrete.common import (
    Candidate,
    Fix,
    Search,
    amount,
    legs,
    names,
    normal,
)
from furncheck.suggest.discrete.racking import racking_fix
from furncheck.suggest.symmetry import mirror_planes

TURNED = "quarter turn"
"""The rule's name in ``tried.Trial`` values."""

SQUARE_TO_PUSH = math.cos(math.radians(45.0))
"""A leg's broad face is square to a push where the cosine between its normal and the
push's horizontal direction is at least this (less SHAPE_ROUNDOFF: 45 degrees is in)."""

LEG_WIDTH = 8.0
"""A leg is turned where it is at most this many times as wide as it is thick (96 mm of
12 mm stock): a leg or a post, not a panel (a side table's 400 mm end panel turned stands
on a 12 mm fin, past the top's ends)."""

SHAPE_ROUNDOFF = 1e-9
"""Relative round-off spared where a leg's width is compared with its thickness and its
face with the push (a square leg is not turned; a push at exactly 45 degrees counts)."""


def quarter_turns(search: Search) -> Fix | None:
    """The failing legs turned a quarter turn about their length (module docstring), when
    that (finished with thicker boards where only bending is left) is valid; else None."""
    return racking_fix(search, TURNED, _candidates)


def _candidates(search: Search, failing: list[str]) -> Iterator[Candidate]:
    """The legs of ``failing`` square to the push they fail under, and their mirror images,
    turned and moved to keep their outer edges where their outer faces were, then turned
    through their centres; the advice says what the turn gives up (against a push across
    the one it fails under, the legs are then their thickness deep)."""
    design = search.design
    standing = set(legs(design, search.geometry))
    images = list(failing)                  # and their mirror images, turned alike
    for plane in mirror_planes(design):
        for leg in list(images):
            image = plane.partner.get(leg)
            if image in standing and image not in images:
                images.append(image)
    pushes = {leg: _push(design, search, leg) for leg in failing}
    turning = []
    for leg in sorted(images, key=design.plank_index.get):
        push = pushes.get(leg)
        if push is None:                    # an image: the push its failing leg takes
            push = next((pushes[other] for other in failing if pushes[other] is not None),
                        None)
        plank = design.plank(leg)
        across = _across(plank)
        if push is not None \
                and abs(float(normal(plank)[:2] @ push)) >= SQUARE_TO_PUSH - SHAPE_ROUNDOFF \
                and plank.thickness * (1.0 + SHAPE_ROUNDOFF) < across \
                <= LEG_WIDTH * plank.thickness * (1.0 + SHAPE_ROUNDOFF):
            turning.append((leg, push))
    if not turning:
        search.failed(TURNED, f"no failing leg is pushed square to its broad face, wider "
                      f"than it is thick and at most {LEG_WIDTH:g} times (a leg, not a "
                      f"panel)", ",".join(failing))
        return
    turned_legs = [leg for leg, _ in turning]
    width = {amount(_across(design.plank(leg)) / design.unit_scale) for leg in turned_legs}
    thick = {amount(design.plank(leg).thickness / design.unit_scale) for leg in turned_legs}
    their = "its" if len(turned_legs) == 1 else "their"
    one = len(turned_legs) == 1
    if len(width) == len(thick) == 1:
        wide, deep = f"{width.pop()} {design.units}", f"{thick.pop()} {design.units}"
        meets = f"so that the push meets {their} {wide} width, not {their} {deep} thickness"
        trade = (f"; against a push across that one {'it is' if one else 'they are'} then "
                 f"{deep} deep")
    else:
        meets, trade = "so that the push meets their width, not their thickness", ""
    for flush in (True, False):
        edited = _with_turned(design, dict(turning), flush)
        clear = _clear_of(design, edited, search.geometry, turned_legs)
        if clear:
            search.failed(TURNED, f"{'outer edges kept' if flush else 'in place'}: "
                          f"{clear} would reach past what it carries", ",".join(failing))
            continue
        where = (f"{'its' if one else 'each with its'} outer edges where its outer faces "
                 f"were" if flush else f"{'centred' if one else 'each centred'} where it "
                 f"stood")
        advice = (f"Turn {names(turned_legs)} a quarter turn about {their} length, {meets} "
                  f"({where}{trade}).")
        yield Candidate("turn", edited, advice,
                        place="turned, outer edges kept" if flush else "turned in place",
                        plank=names(turned_legs), preferred=flush)


def _clear_of(design: Design, edited: Design, geometry: Geometry, turned: list[str]) -> str:
    """The first turned leg (id) that reaches further past the outline of what it carries
    (the planks jointed to it above its middle: a table's top, each in its own frame) in
    ``edited`` than it did in ``design``, beyond the design's tolerance; '' where none
    does (turned in place, a leg flush with a top's end would stand 24 mm past it; one
    that stood proud of the top as drawn may stand as proud)."""
    partners = geometry.jointed()
    for leg in turned:
        carried = [p for p in partners.get(leg, ())
                   if design.plank(p).center[2] > design.plank(leg).center[2]]
        if not carried:
            continue
        if _overreach(edited, leg, carried) > _overreach(design, leg, carried) \
                + design.tolerance:
            return leg
    return ""


def _overreach(design: Design, leg: str, carried: list[str]) -> float:
    """m: how far the leg's corners reach past the outlines of the ``carried`` planks, in
    the plane of each (a corner counts under the plank it is least past)."""
    corners = design.plank(leg).corners
    past = []
    for plank_id in carried:
        plank = design.plank(plank_id)
        local = plank.to_local(corners)[:, :2]
        halves = np.array([plank.length, plank.width]) / 2.0
        past.append(np.clip(np.abs(local) - halves, 0.0, None).max(axis=1))
    return float(np.min(past, axis=0).max())


def _across(plank: Plank) -> float:
    """m: the leg's size across its length (its local axis nearest the vertical)."""
    return (plank.length, plank.width)[1 - _length_axis(plank)]


def _length_axis(plank: Plank) -> int:
    """0 or 1: the leg's local axis along its length, the one nearest the vertical."""
    return int(np.argmax(np.abs(plank.rotation_matrix[2, :2])))


def _push(design: Design, search: Search, leg: str) -> np.ndarray | None:
    """(2,) the horizontal direction (unit) of the sideways loads' sum in the first load
    case where the leg's joint fails or it bends, among those with a sideways load; None
    where there is none."""
    cases = {case.name: case for case in design.load_cases}
    for violation in search.report.violations:
        if leg not in violation.where.split("/"):
            continue
        case = cases.get(violation.case)
        if case is None or not case.loads:
            continue
        total = np.sum([load.force[:2] for load in case.loads], axis=0)
        size = float(np.hypot(*total))
        if size > 0.0:
            return np.asarray(total, dtype=float) / size
    return None


def _with_turned(design: Design, pushes: dict[str, np.ndarray], flush: bool) -> Design:
    """The design with each leg of ``pushes`` (id -> the push's direction) turned
    (``_turned``), the load and anchor points on it carried with it
    (``dofs.with_planks_carried``)."""
    turned = {leg: _turned(design, design.plank(leg), push, flush)
              for leg, push in pushes.items()}
    return with_planks_carried(design, tuple(turned.get(p.id, p) for p in design.planks))


def _turned(design: Design, plank: Plank, push: np.ndarray, flush: bool) -> Plank:
    """``plank`` turned a quarter turn about its length (its own axis, through its
    centre); with ``flush``, also moved along ``push`` and across it so that its extent
    away from the middle of the design's bounding box ends where it did, each way (a
    table's leg set in its corner as before; not along a way in which it stands at the
    middle, within the design's tolerance: a six-legged table's middle legs)."""
    rotation = plank.rotation_matrix
    new_rotation = rotation @ axis_rotation(_length_axis(plank), math.pi / 2.0)
    centre = plank.center_array.copy()
    if flush:                       # along the push, then across it
        corners = np.vstack([p.corners for p in design.planks])
        middle = 0.5 * (corners.min(axis=0) + corners.max(axis=0))
        for direction in (np.array([push[0], push[1], 0.0]),
                          np.array([-push[1], push[0], 0.0])):
            offset = float((centre - middle) @ direction)
            if abs(offset) <= design.tolerance:     # a middle leg: no outer side
                continue
            side = 1.0 if offset > 0.0 else -1.0
            before = _reach(rotation, plank, direction * side)
            after = _reach(new_rotation, plank, direction * side)
            centre = centre + direction * side * (before - after)
    angles = euler_degrees(new_rotation, plank.rotation)
    return replace(plank, rotation=tuple(float(a) for a in angles),
                   center=tuple(float(v) for v in centre))


def _reach(rotation: np.ndarray, plank: Plank, direction: np.ndarray) -> float:
    """m: how far the plank reaches from its centre along ``direction`` (unit), turned by
    ``rotation``: its half sizes times the local axes' components along it."""
    halves = np.array([plank.length, plank.width, plank.thickness]) / 2.0
    return float(np.abs(rotation.T @ direction) @ halves)
