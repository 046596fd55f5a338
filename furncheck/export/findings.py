"""What the pictures and meshes show of a report: each plank's utilization, the load case
that governs, the joints and contacts that fail, and what a suggestion changed.

Values in, values out (no drawing): the views, the force-space plot and the meshes read
the same findings, so a plank has one colour everywhere.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

from furncheck import tolerances as tol
from furncheck.design.model import Design, Plank
from furncheck.result import CaseResult, ContactResult, DesignReport, JointResult

DURABILITY_COUNTS = ("stable", "sliding")
"""Stabilities of a case whose joint and anchor forces count (``validity.evaluate_case``):
a case that topples shows its joints as if bolted down, and those raise nothing."""

SAME_PLACE = 1e-9
"""m (or degrees, for rotations): a plank whose centre, rotation and sizes differ by no
more than this after a suggestion is unchanged."""


@dataclass(frozen=True)
class FailingContact:
    """A ground or wall contact that fails in a load case.

    contact : its result (point in the file's unit)
    reason  : 'lifts' (it would have to pull: normal force < 0) or 'slides' (the friction
              it needs exceeds mu N)
    demand  : friction needed over mu N ('slides'), or the pull in N ('lifts')
    """

    contact: ContactResult
    reason: str
    demand: float


def plank_utilization(report: DesignReport, planks: tuple[Plank, ...] | list[Plank]
                      ) -> dict[str, float | None]:
    """``utilization_of`` the plank ids (a copy: callers may change it)."""
    return dict(utilization_of(report, tuple(plank.id for plank in planks)))


@lru_cache(maxsize=64)
def utilization_of(report: DesignReport, plank_ids: tuple[str, ...]
                   ) -> dict[str, float | None]:
    """Per plank id, its largest utilization over all load cases: its own sag and stress
    (elastic model) and the joints and anchors it takes part in, in cases where they count
    (``DURABILITY_COUNTS``: not the as-if-bolted forces of a case that topples).  None
    when no case counts (the design does not stand as drawn, or topples in every case:
    grey, as the scale says for "not computed").  A plank named by a geometric violation,
    or whose contacts lift or slide, is at least at the scale's failing end (1.5)."""
    used: dict[str, float | None] = {plank_id: None for plank_id in plank_ids}

    def raise_to(plank_id: str, value: float) -> None:
        if plank_id in used:
            current = used[plank_id]
            used[plank_id] = value if current is None else max(current, value)

    counted = [case for case in report.cases if case.stability in DURABILITY_COUNTS]
    for case in counted:        # a toppling case's forces are as if bolted down: not counted
        for plank_id in used:
            raise_to(plank_id, 0.0)
        for plank in case.planks or ():
            raise_to(plank.id, plank.utilization)
        for joint in case.joints:
            for plank_id in joint.planks:
                raise_to(plank_id, joint.utilization)
        for anchor in case.anchors:
            raise_to(anchor.plank, anchor.utilization)
    for violation in report.violations:
        if violation.kind in UTILIZED:
            continue            # counted through their utilization above
        for plank_id in violation.where.replace("/", ",").split(","):
            raise_to(plank_id, 1.5)
    return used


UTILIZED = ("non-durable", "sagging", "overstressed")
"""Violation kinds whose planks' utilization is a number of a report; the others
(toppling, sliding, a design that does not stand as drawn) are drawn at the scale's
failing end."""


def kinds_without_utilization(report: DesignReport) -> set[str]:
    """The report's violation kinds that no utilization measures (``UTILIZED``: lift-off,
    sliding, disconnected ...), which a page names where it would show a percentage."""
    return {v.kind for v in report.violations if v.kind not in UTILIZED}


def case_severity(case: CaseResult) -> float:
    """How bad a case is, for choosing the one a view shows: inf when it is not stable,
    else its largest utilization of a joint, anchor or plank."""
    if case.stability != "stable":
        return math.inf
    values = [joint.utilization for joint in case.joints]
    values += [anchor.utilization for anchor in case.anchors]
    values += [plank.utilization for plank in case.planks or ()]
    return max(values, default=0.0)


def governing_case(report: DesignReport) -> CaseResult | None:
    """The case a view draws: the first that is not stable, else the one with the largest
    utilization (the first on ties); None for a report without cases."""
    best = None
    for case in report.cases:
        if best is None or case_severity(case) > case_severity(best):
            best = case
    return best


def failing_joints(report: DesignReport) -> list[tuple[JointResult, str]]:
    """Every joint past its capacity in a case where that counts, once, at its worst
    case: [(joint, case name)], worst first."""
    worst: dict[tuple[str, ...], tuple[JointResult, str]] = {}
    for case in report.cases:
        if case.stability not in DURABILITY_COUNTS:
            continue
        for joint in case.joints:
            if joint.durable:
                continue
            key = tuple(sorted(joint.planks))
            if key not in worst or joint.utilization > worst[key][0].utilization:
                worst[key] = (joint, case.name)
    return sorted(worst.values(), key=lambda item: -item[0].utilization)


def tangential(contact: ContactResult) -> float:
    """N: the friction force of a contact (its force across its surface's normal)."""
    fx, fy, fz = contact.force
    return math.sqrt(max(fx * fx + fy * fy + fz * fz - contact.pressing ** 2, 0.0))


def friction_demand(contact: ContactResult, friction: float) -> float:
    """Friction needed over what the contact can give, |T| / (mu N); inf for a contact
    that would have to pull (N < 0) or that meets no friction (mu = 0) and is pushed
    across, 0 for one carrying nothing."""
    normal = contact.pressing
    if normal < 0.0:
        return math.inf
    if normal == 0.0 or friction <= 0.0:
        return 0.0 if tangential(contact) == 0.0 else math.inf
    return tangential(contact) / (friction * normal)


def failing_contacts(case: CaseResult, friction: float) -> list[FailingContact]:
    """The contacts of an unstable case that lift (normal force < 0 in the held-down
    state the report shows) or slide (friction needed beyond mu N), worst first; none in
    a stable case."""
    if case.stability not in ("lift-off", "sliding"):
        return []
    found = []
    for contact in case.contacts:
        if contact.pressing < 0.0:
            found.append(FailingContact(contact, "lifts", -contact.pressing))
        elif case.stability == "sliding":
            demand = friction_demand(contact, friction)
            if demand > 1.0 + tol.CAPACITY_REL_TOL:
                found.append(FailingContact(contact, "slides", demand))
    return sorted(found, key=lambda item: (item.reason != "lifts", -item.demand))


def changed_planks(before: Design, after: Design) -> dict[str, str]:
    """Planks of ``after`` that differ from ``before``: plank id -> 'changed' (moved,
    turned, resized, thickness or material) or 'added' (not in ``before``), in
    ``after``'s order."""
    old = {plank.id: plank for plank in before.planks}
    marks = {}
    for plank in after.planks:
        if plank.id not in old:
            marks[plank.id] = "added"
        elif not _same_plank(old[plank.id], plank):
            marks[plank.id] = "changed"
    return marks


def _same_plank(one: Plank, other: Plank) -> bool:
    numbers = [(one.length, other.length), (one.width, other.width),
               (one.thickness, other.thickness), *zip(one.center, other.center),
               *zip(one.rotation, other.rotation)]
    return all(abs(a - b) <= SAME_PLACE for a, b in numbers) and one.material == other.material
