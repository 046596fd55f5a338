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
that case's push (within 45 degrees), wider than it is thick (and carries no load at a
point, which would have to move with it): those legs, and their mirror images that are
legs too (a maker turns all four legs of a table whose two far ones fail), turned about
their length through their centres, then (a second candidate) each moved along the
push so that its outer edge stays where its outer face was, flush with what it carries
as a maker sets a leg at a corner.  Each candidate is checked in full like every other
(joints kept, no plank cut into another); one that then fails only by bending is
finished with thicker boards (``common.Search.first_valid``).
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import replace

import numpy as np

from furncheck.design.model import Design, Plank
from furncheck.dofs import euler_degrees
from furncheck.suggest.discrete.common import (
    Candidate,
    Fix,
    Search,
    amount,
    legs,
    names,
    normal,
)
from furncheck.suggest.discrete.racking import racking_places
from furncheck.suggest.symmetry import mirror_planes

TURNED = "quarter turn"
"""The rule's name in ``tried.Trial`` values."""

SQUARE_TO_PUSH = math.cos(math.radians(45.0))
"""A leg's broad face is square to a push where the cosine between its normal and the
push's horizontal direction is at least this."""


def quarter_turns(search: Search) -> Fix | None:
    """The failing legs turned a quarter turn about their length (module docstring), when
    that (finished with thicker boards where only bending is left) is valid; else None."""
    failing = racking_places(search, TURNED)
    if failing is None:
        return None
    target = ",".join(failing)
    return search.first_valid(replace(candidate, trial_rule=TURNED, target=target)
                              for candidate in _candidates(search, failing))


def _candidates(search: Search, failing: list[str]) -> Iterator[Candidate]:
    """The legs of ``failing`` square to the push they fail under, turned through their
    centres, then turned and moved to keep their outer edges where their outer faces
    were."""
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
        loaded = any(load.plank == leg and load.point is not None
                     for case in design.load_cases for load in case.loads)
        if push is not None and not loaded \
                and abs(float(normal(plank)[:2] @ push)) >= SQUARE_TO_PUSH \
                and plank.width > plank.thickness * (1.0 + 1e-9):
            turning.append((leg, push))
    if not turning:
        search.failed(TURNED, "no failing leg is pushed square to its broad face and wider "
                      "than it is thick, without a load at a point on it", ",".join(failing))
        return
    turned_legs = [leg for leg, _ in turning]
    width = {amount(design.plank(leg).width / design.unit_scale) for leg in turned_legs}
    thick = {amount(design.plank(leg).thickness / design.unit_scale) for leg in turned_legs}
    their = "its" if len(turned_legs) == 1 else "their"
    meets = (f"so that the push meets {their} {width.pop()} {design.units} width, not "
             f"{their} {thick.pop()} {design.units} thickness" if len(width) == len(thick) == 1
             else "so that the push meets their width, not their thickness")
    for flush in (False, True):
        turned = {leg: _turned(design, design.plank(leg), push, flush) for leg, push in turning}
        edited = replace(design, planks=tuple(turned.get(p.id, p) for p in design.planks))
        one = len(turned_legs) == 1
        where = (f"{'its' if one else 'each with its'} outer edge where its outer face was"
                 if flush else f"{'centred' if one else 'each centred'} where it stood")
        advice = (f"Turn {names(turned_legs)} a quarter turn about {their} length, {meets} "
                  f"({where}).")
        yield Candidate("turn", edited, advice,
                        place="turned, outer edges kept" if flush else "turned in place",
                        plank=names(turned_legs))


def _push(design: Design, search: Search, leg: str) -> np.ndarray | None:
    """(2,) the horizontal direction (unit) of the sideways loads' sum in the first load
    case where the leg's joint fails or it bends, among those with a sideways load; None
    where there is none."""
    cases = {case.name: case for case in design.load_cases}
    for violation in search.report.violations:
        if leg not in violation.where.split("/"):
            continue
        case = cases.get(violation.case)
        if case is None:
            continue
        total = np.sum([load.force[:2] for load in case.loads], axis=0) if case.loads \
            else np.zeros(2)
        size = float(np.hypot(*total))
        if size > 0.0:
            return np.asarray(total, dtype=float) / size
    return None


def _turned(design: Design, plank: Plank, push: np.ndarray, flush: bool) -> Plank:
    """``plank`` turned a quarter turn about its length (its local axis nearest the
    vertical, through its centre); with ``flush``, also moved along ``push`` so that its
    extent away from the design's middle ends where it did."""
    rotation = plank.rotation_matrix
    along = int(np.argmax(np.abs(rotation[2, :2])))           # its length: local x or y
    axis = rotation[:, along]
    turn = _about(axis, math.pi / 2.0)
    new_rotation = turn @ rotation
    centre = plank.center_array.copy()
    if flush:
        direction = np.array([push[0], push[1], 0.0])
        middle = np.mean([p.center_array for p in design.planks], axis=0)
        side = 1.0 if float((centre - middle) @ direction) >= 0.0 else -1.0
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


def _about(axis: np.ndarray, angle: float) -> np.ndarray:
    """The rotation by ``angle`` (rad) about the unit ``axis`` (Rodrigues' formula)."""
    x, y, z = axis / np.linalg.norm(axis)
    k = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    return np.eye(3) + math.sin(angle) * k + (1.0 - math.cos(angle)) * (k @ k)
