"""Durability and stability verdicts (contract section 3, paper sections 5.1 and 6.2):
each case's results and violations from its statics.

A joint is durable iff its worst nail's pull <= nail_pull / safety_factor and shear <=
nail_shear / safety_factor (``nail_groups``: the per-nail forces from the joint's
wrench).  Stability comes from the statics: 'lift-off' and 'sliding' cases.
"""

from __future__ import annotations

import numpy as np

from furncheck import tolerances as tol
from furncheck.design.model import Design, LoadCase, Material
from furncheck.geometry import Geometry, Joint
from furncheck.nail_groups import (
    NailForces,
    joint_utilization,
    nail_pull_shear,
    part_rows,
    worst_part_forces,
)
from furncheck.plain import article, distinguishing_digits, plain_compared, plain_number
from furncheck.result import (
    AnchorResult,
    CaseResult,
    ContactResult,
    JointResult,
    LoadResult,
    PlankResult,
    Violation,
)
from furncheck.statics import CaseStatics, StaticsModel
from furncheck.statics.beams import beam_frame, beam_length_width


def evaluate_case(design: Design, geometry: Geometry, model: StaticsModel, case: LoadCase,
                  statics: CaseStatics) -> tuple[CaseResult, list[Violation]]:
    """Turn one case's statics into its CaseResult and violations.

    A case that topples ('lift-off') reports its joints as if the design were bolted down;
    those wrenches are shown but raise no 'non-durable' violation: the toppling comes first.
    """
    scale = design.unit_scale
    joints, violations = [], []
    pull_cap = design.material.nail_pull / design.safety_factor
    shear_cap = design.material.nail_shear / design.safety_factor
    if statics.joint_wrenches is not None:
        model_joints = [geometry.joints[j] for j in model.joints]
        pulls, shears = nail_pull_shear(model_joints, statics.joint_wrenches)
        if statics.part_wrenches is not None:   # the worst nail of the row's parts too
            part_pulls, part_shears = worst_part_forces(
                model, part_rows(geometry, model), statics.part_wrenches)
            pulls, shears = np.maximum(pulls, part_pulls), np.maximum(shears, part_shears)
        for joint, wrench, pull, shear in zip(model_joints, statics.joint_wrenches.tolist(),
                                              pulls.tolist(), shears.tolist()):
            nails = NailForces(pull, shear, pull_cap, shear_cap)
            joints.append(JointResult(
                planks=joint.planks, point=_tuple(joint.point / scale), nails=joint.nails,
                force=tuple(wrench[:3]), moment=tuple(wrench[3:]), pull=pull, shear=shear,
                pull_capacity=pull_cap, shear_capacity=shear_cap,
                utilization=nails.utilization, durable=nails.durable))
            if not nails.durable and statics.stability in ("stable", "sliding"):
                violations.append(Violation("non-durable", joint.name, case.name,
                                            _durability_message(nails, design),
                                            _joint_line(design, joint)))
    contacts, anchors = [], []
    if statics.contact_forces is not None:
        held = model.corner_forces(statics.contact_forces)     # the stations shared out
        points = (model.contact_points[:model.n_corners] / scale).tolist()
        forces = model.world_forces(held).tolist()
        normals = held[:, 2].tolist()
        for row, (point, force) in enumerate(zip(points, forces)):
            contact = geometry.contacts[model.contacts[row]]
            if contact.anchor is None:
                contacts.append(ContactResult(contact.plank, tuple(point), tuple(force),
                                              contact.wall, normals[row], contact.on))
                continue
            held = _anchor_held(design, contact.anchor, point, force)
            anchors.append(held)
            if held.utilization > 1.0 + tol.CAPACITY_REL_TOL \
                    and statics.stability in ("stable", "sliding"):
                size, capacity = plain_compared(held.size, held.capacity)
                parts = _anchor_parts(design, contact.wall, force)
                violations.append(Violation(
                    "non-durable", f"anchors[{contact.anchor}]", case.name,
                    f"anchor of {contact.plank} to wall {contact.wall} holds {size} N"
                    + (f" ({parts})" if parts else "") + f", more than its {capacity} N"
                    + _factor_note(design),
                    design.line_of(f"anchors[{contact.anchor}]")))
    planks = None
    if statics.planks is not None:
        planks = []
        bending = plank_bending(design, model, statics.planks)
        for k, (sag, allowed, stress, strength, used) in enumerate(zip(*bending)):
            plank = design.planks[model.planks[k]]
            planks.append(PlankResult(plank.id, sag / scale, allowed / scale, stress / 1e6,
                                      strength / 1e6, used))
            if statics.stability not in ("stable", "sliding"):
                continue
            material = design.material_of(plank)
            final = sag * (1.0 + material.creep)
            key = f"planks[{model.planks[k]}]"      # its line looked up only for a violation
            if final > allowed * (1.0 + tol.CAPACITY_REL_TOL):
                overhang = statics.planks.overhang is not None and \
                    bool(statics.planks.overhang[k])
                crosswise = model.beams.crosswise[k]
                sideways = _upright(plank, crosswise) or (
                    statics.planks.sideways is not None and statics.planks.sideways(k))
                violations.append(Violation("sagging", plank.id, case.name, _sag_message(
                    design, material, sag, allowed, statics.planks.span[k], sideways,
                    overhang)
                    + (_held_along(geometry, model, plank, crosswise) if overhang else "")
                    + _rests_along(geometry, plank, crosswise),
                    design.line_of(key)))
            if stress > strength * (1.0 + tol.CAPACITY_REL_TOL):
                violations.append(Violation("overstressed", plank.id, case.name,
                                            _stress_message(design, stress, strength),
                                            design.line_of(key)))
        planks = tuple(planks)
    stable = statics.stability == "stable"
    if not stable:
        kind = "sliding" if statics.stability == "sliding" else "lift-off"
        where = ",".join(statics.culprits) or ",".join(design.planks[i].id for i in model.planks)
        detail = statics.detail
        failing = [j for j in joints if not j.durable]
        if kind == "lift-off" and failing:      # no violation of their own: told here
            worst = max(failing, key=lambda j: j.utilization)
            more = f" and {len(failing) - 1} more joint{'s' if len(failing) > 2 else ''}" \
                if len(failing) > 1 else ""
            held = "so held" if "held down" in detail else "held down"
            detail += (f"; {held}, joint {'/'.join(worst.planks)}{more} would fail too "
                       f"({_durability_message(_nails_of(worst), design)})")
        violations.append(Violation(kind, where, case.name, detail,
                                    design.line_of(_case_key(design, case))))
    durable = all(j.durable for j in joints) \
        and all(a.utilization <= 1.0 + tol.CAPACITY_REL_TOL for a in anchors)
    result = CaseResult(case.name, durable, stable, tuple(joints), tuple(contacts),
                        statics.stability, planks, case_loads(design, case), tuple(anchors))
    return result, violations


def anchor_capacity(design: Design, index: int) -> float:
    """N: what anchor ``index`` may hold, its capacity / safety factor."""
    return design.anchors[index].capacity / design.safety_factor


def _anchor_held(design: Design, index: int, point: list[float],
                 force: list[float]) -> AnchorResult:
    """An anchor's result for the wall's force on its plank (N, world) at ``point`` (file
    unit: where it holds, ``geometry.model.anchor_tie``)."""
    anchor = design.anchors[index]
    size = float(np.linalg.norm(force))
    capacity = anchor_capacity(design, index)
    return AnchorResult(anchor.plank, anchor.wall, tuple(point), tuple(force), size,
                        capacity, size / capacity, index)


def _anchor_parts(design: Design, wall: int, force: list[float]) -> str:
    """What an anchor's force (the wall's on its plank, N, world) is made of, in a
    fixer's words: its pull out of the wall (or push into it), what it holds up (or down)
    and its shear along the wall, the parts of at least ANCHOR_PART of the whole ('a pull of
    91.99 N out of the wall, 136.4 N holding it up, 162.4 N along the wall'; '' for none):
    a large part along the wall comes from the planks' bending between fixings, not from a
    load."""
    normal = np.asarray(design.walls[wall].normal, dtype=float)
    force = np.asarray(force, dtype=float)
    out = float(-(force @ normal))          # > 0: the wall pulls the plank in
    up = float(force[2])
    along = force - (force @ normal) * normal
    along[2] = 0.0
    sideways = float(np.linalg.norm(along))
    least = tol.ANCHOR_PART * float(np.linalg.norm(force))
    parts = []
    if abs(out) >= least and abs(out) > 0.0:
        parts.append(f"a {'pull' if out > 0 else 'push'} of {plain_number(abs(out))} N "
                     f"{'out of' if out > 0 else 'into'} the wall")
    if abs(up) >= least and abs(up) > 0.0:
        parts.append(f"{plain_number(abs(up))} N holding it {'up' if up > 0 else 'down'}")
    if sideways >= least and sideways > 0.0:
        parts.append(f"{plain_number(sideways)} N along the wall")
    return ", ".join(parts)


def anchor_utilization(design: Design, geometry: Geometry, model: StaticsModel,
                       statics: CaseStatics) -> float:
    """The case's largest anchor utilization, |force| / (capacity / safety factor) (0
    without anchors)."""
    if model.contact_anchored is None or statics.contact_forces is None:
        return 0.0
    worst = 0.0
    for row in np.flatnonzero(model.contact_anchored):
        index = geometry.contacts[model.contacts[row]].anchor
        size = float(np.linalg.norm(statics.contact_forces[row]))
        worst = max(worst, size / anchor_capacity(design, index))
    return worst


def _factor_note(design: Design) -> str:
    return "" if design.safety_factor == 1.0 else \
        f" (capacity / safety factor {plain_number(design.safety_factor, 6)})"


def case_loads(design: Design, case: LoadCase) -> tuple[LoadResult, ...]:
    """The loads acting in ``case`` as the file gives them (mass or force, ``at`` in the
    file unit), each with the case it was included from."""
    scale = design.unit_scale
    return tuple(
        LoadResult(plank=load.plank, mass=load.mass,
                   force=None if load.mass is not None else tuple(load.force),
                   at=None if load.point is None else tuple(c / scale for c in load.point),
                   spread=load.spread,
                   origin=None if case.origin(i) == case.name else case.origin(i))
        for i, load in enumerate(case.loads))


def plank_bending(design: Design, model: StaticsModel, planks) -> tuple[np.ndarray, ...]:
    """Per local plank of an elastic model's case (``elastic.PlankStatics``): sag (m),
    allowed sag span / sag_limit (m), stress (Pa), strength bending_strength /
    safety_factor (Pa) and utilization max(sag (1 + creep) / allowed, stress / strength),
    each plank with its own material (``Design.material_of``)."""
    sag_limit, creep, strength = plank_limits(design, model)
    sag_used, stress_used = bending_use(planks.sag, planks.span, planks.stress, sag_limit,
                                        creep, strength)
    return planks.sag, planks.span / sag_limit, planks.stress, strength, \
        np.maximum(sag_used, stress_used)


def bending_use(sag, span, stress, sag_limit, creep, strength) -> tuple:
    """(sag use, stress use) of planks (arrays) or of one plank (numbers, as 0-d arrays):
    sag (1 + creep) over the allowed span / sag_limit (0 without a span), and stress over
    strength (bending_strength / safety_factor, ``plank_limits``)."""
    allowed = np.asarray(span, dtype=float) / sag_limit
    final = np.asarray(sag, dtype=float) * (1.0 + creep)
    sag_used = np.divide(final, allowed, out=np.zeros_like(final), where=allowed > 0.0)
    return sag_used, np.asarray(stress, dtype=float) / strength


def plank_limits(design: Design, model: StaticsModel) -> tuple[np.ndarray, ...]:
    """Per local plank of the model, from its material: sag_limit, creep and strength
    bending_strength / safety_factor (Pa), each (nP,) (kept in ``model.plank_cache``)."""
    cached = model.plank_cache.get("limits")
    if cached is None:
        materials = [design.material_of(design.planks[i]) for i in model.planks]
        limits = np.array([(m.sag_limit, m.creep, m.bending_strength) for m in materials],
                          dtype=float).reshape(-1, 3)
        cached = (limits[:, 0], limits[:, 1], limits[:, 2] / design.safety_factor)
        model.plank_cache["limits"] = cached
    return cached


def _upright(plank, crosswise: bool) -> bool:
    """Whether the plank's beam (``crosswise``: along its local y, as the elastic model
    laid it, ``StaticsModel.beams``) stands more upright than level: its bending is then
    a bow sideways (a leg, a side), not a sag."""
    return abs(float(beam_frame(plank, crosswise)[2, 0])) > tol.UPRIGHT_SINE


def bows_sideways(violation: Violation) -> bool:
    """Whether a ``sagging`` violation's plank bows sideways (``_sag_message``: a leg, a
    side, or a level plank bent across rather than down), not sags under its load."""
    return violation.kind == "sagging" and violation.message.startswith("bows ")


def _sag_message(design: Design, material: Material, sag: float, allowed: float,
                 span: float, upright: bool = False, overhang: bool = False) -> str:
    """The ``sagging`` violation's words; an upright plank's (a leg, a side: ``_upright``)
    and one bent across rather than down (a rail pushed sideways: ``PlankStatics.
    sideways``) say it bows sideways, as a woodworker would, with the same numbers; an
    overhang's
    (a cantilever's free end) name the overhang, whose span is twice it (contract 3a)."""
    unit, scale = design.units, design.unit_scale
    creep = material.creep
    digits = distinguishing_digits(sag * (1 + creep) / scale, allowed / scale, 3)
    shown = f"{plain_number(sag / scale, digits)} {unit}"
    if overhang:
        bends = (f"{'bows' if upright else 'sags'} {shown}{' sideways' if upright else ''} "
                 f"at the free end of its {plain_number(0.5 * span / scale)} {unit} overhang "
                 f"(a span of {plain_number(span / scale)} {unit}), ")
    elif upright:
        bends = (f"bows {shown} sideways between supports {plain_number(span / scale)} "
                 f"{unit} apart, ")
    else:
        across = plain_number(span / scale)
        bends = f"sags {shown} over {article(across)} {across} {unit} span, "
    return (bends +
            f"{plain_number(sag * (1 + creep) / scale, digits)} {unit} with creep "
            f"(x {plain_number(1 + creep, 6)}); allowed {plain_number(allowed / scale, digits)} "
            f"{unit} (span / {plain_number(material.sag_limit, 6)})")


ALONG_COSINE = 0.9
"""A joint line within about 25 degrees of a plank's beam axis runs along it."""

ALONG_SHARE = 0.5
"""... and a joint along at least this share of the beam's length holds it along it."""


def _held_along(geometry: Geometry, model, plank, crosswise: bool) -> str:
    """A note for the overhang's sag of a plank nailed along its beam (its longer side: a
    shelf nailed by its back edge, a top on a rail by its edge), which the one-beam model
    holds at the joint's middle only, its halves overhangs, where the joint is left whole
    (a wide board held near its edge: ``elastic.joint_part_counts``; README, "Elastic
    planks"): what it reads is an overstatement.  '' for any other plank."""
    axis = beam_frame(plank, crosswise)[:, 0]
    length = beam_length_width(plank, crosswise)[0]
    parts = model.plank_cache.get("joint_part_counts")
    if model.plank_cache.get("plates") is not None and \
            model.planks.index(model.design.plank_index[plank.id]) in \
            model.plank_cache.get("whole_rows_hung", ()):
        return ""                       # its plate, hung on the row, is what it reads
    for row, j in enumerate(model.joints):
        joint = geometry.joints[j]
        if parts is not None and parts[row] > 1:
            continue                    # held along its row
        if plank.id in joint.planks and joint.length >= ALONG_SHARE * length and \
                abs(float(joint.frame[:, 1] @ axis)) >= ALONG_COSINE:
            other = joint.face if joint.edge == plank.id else joint.edge
            return (f" (it is nailed along its length to {other}, which the model holds "
                    f"at the joint's middle only: this overstates its sag)")
    return ""


def _rests_along(geometry: Geometry, plank, crosswise: bool) -> str:
    """A note for the sag of a plank that a resting joint holds along its beam (a loose
    seat lying on a rail along its length, or the rail under it), whose contacts are the
    corners of the planks' touching region (contract section 2): the model holds the
    plank at the region's ends only, so what it reads between them is an overstatement
    (README, "Elastic planks").  '' for any other plank."""
    axis = beam_frame(plank, crosswise)[:, 0]
    length = beam_length_width(plank, crosswise)[0]
    corners: dict[int, list] = {}
    for contact in geometry.contacts:
        if contact.on is not None and plank.id in (contact.plank, contact.on):
            corners.setdefault(contact.rest, []).append(contact)
    for held in corners.values():
        along = np.array([c.point for c in held], dtype=float) @ axis
        if float(along.max() - along.min()) >= ALONG_SHARE * length:
            upper, lower = held[0].resting
            if upper == plank.id:
                return (f" (it rests along its length on {lower}, which the model holds "
                        "at the rest's corners only: this overstates its sag)")
            return (f" ({upper} rests on it along its length, which the model holds at the "
                    "rest's corners only: this overstates its sag)")
    return ""


def _stress_message(design: Design, stress: float, strength: float) -> str:
    factor = ("" if design.safety_factor == 1.0
              else f" (strength / safety factor {plain_number(design.safety_factor, 6)})")
    stress_shown, strength_shown = plain_compared(stress / 1e6, strength / 1e6, 3)
    return (f"bending stress {stress_shown} N/mm^2 exceeds its strength "
            f"{strength_shown} N/mm^2{factor}")


def case_holds(design: Design, geometry: Geometry, model: StaticsModel,
               statics: CaseStatics) -> bool:
    """Whether a case has no violation: ``not evaluate_case(...)[1]`` without building its
    result (for searches that only need the verdict).  A case holds iff it is stable and
    every joint is durable (a sliding case is a violation whatever its joints do)."""
    return case_margin(design, geometry, model, statics)[1]


def case_margin(design: Design, geometry: Geometry, model: StaticsModel,
                statics: CaseStatics) -> tuple[float, bool]:
    """(smallest 1 - utilization of the case's joints and, elastic model, planks (1.0
    without either; -inf when the case is not stable), whether the case holds), without
    building its result."""
    if statics.stability != "stable":
        return -np.inf, False
    margin, holds = 1.0, True
    if statics.joint_wrenches is not None and model.joints:
        utilization, held = joint_utilization(design, geometry, model, statics.joint_wrenches,
                                              parts=statics.part_wrenches)
        margin, holds = 1.0 - float(utilization.max()), bool(np.all(held))
    used = max(worst_plank_utilization(design, model, statics),
               anchor_utilization(design, geometry, model, statics))
    return min(margin, 1.0 - used), holds and used <= 1.0 + tol.CAPACITY_REL_TOL


def worst_plank_utilization(design: Design, model: StaticsModel,
                            statics: CaseStatics) -> float:
    """The case's largest plank utilization (``plank_bending``; 0 without plank results:
    the rigid model)."""
    if statics.planks is None:
        return 0.0
    return float(plank_bending(design, model, statics.planks)[4].max(initial=0.0))


def _nails_of(joint: JointResult) -> NailForces:
    return NailForces(joint.pull, joint.shear, joint.pull_capacity, joint.shear_capacity)


def _durability_message(nails: NailForces, design: Design) -> str:
    parts = []
    factor = ("" if design.safety_factor == 1.0
              else f" (capacity / safety factor {plain_number(design.safety_factor, 6)})")
    if nails.pull > nails.pull_capacity:
        parts.append("pull {} N per nail exceeds {} N".format(
            *plain_compared(nails.pull, nails.pull_capacity)))
    if nails.shear > nails.shear_capacity:
        parts.append("shear {} N per nail exceeds {} N".format(
            *plain_compared(nails.shear, nails.shear_capacity)))
    return "; ".join(parts) + factor


def _joint_line(design: Design, joint: Joint) -> int | None:
    """Source line of a listed joint, or of the edge plank of a detected one."""
    if joint.key:
        return design.line_of(joint.key)
    return design.line_of(f"planks[{design.plank_index[joint.edge]}]")


def _case_key(design: Design, case: LoadCase) -> str:
    return "loads" if case.name == "default" and "loads" in design.lines \
        else f"load_cases.{case.name}"


def _tuple(values: np.ndarray) -> tuple[float, float, float]:
    return tuple(np.asarray(values, dtype=float).tolist())
