"""More nails: the shop's first fix for a listed joint whose nails pull out or shear off
while the file gives it fewer nails than its length takes.

A listed joint's ``nails`` overrides the spacing rule (contract section 2: otherwise
max(1, floor(L / nail_spacing)) along its length L).  For every failing joint with such
a count, the force per nail goes with 1 / n for the same joint forces, so it needs about
ceil(n x the worst case's pull or shear over its capacity) nails (the explanation's own
estimate, ``suggest.needs``); a joint takes at most the spacing rule's count (nails no
closer than ``nail_spacing``).  The candidates, each checked in full (and finished with
thicker boards where it fails by bending alone, ``Search.first_valid``): every such joint
with the nails it needs (at most what it takes), its mirror images (a symmetric piece is
nailed symmetrically) with as many, then, if that is not valid, every one with all it
takes.  A
joint already at that many, or counted by the spacing rule, gets no more here (a longer
joint or a thicker edge plank does that: the continuous search and ``thicker``).
"""

from __future__ import annotations

from dataclasses import replace

from furncheck.geometry.analysis import nail_count
from furncheck.suggest.discrete.common import Candidate, Fix, Search, amount, names
from furncheck.suggest.needs import violation_needs

MORE_NAILS = "more nails"
"""The rule's name in ``tried.Trial`` values."""


def more_nails(search: Search) -> Fix | None:
    """The design with its failing listed joints given more nails, when that is valid;
    else None (and why, in the trials)."""
    if not search.repairs(MORE_NAILS, ("non-durable",)):
        return None
    design, geometry = search.design, search.geometry
    failing = {v.where for v in search.report.violations if v.kind == "non-durable"}
    orbits = _mirror_orbits(design, geometry, failing)
    joints = [joint for joint in geometry.joints if joint.name in orbits]
    if not joints:
        search.not_applicable(MORE_NAILS, "what fails holds by wall anchors, not nails")
        return None
    room = {}
    for joint in joints:
        spec = None if joint.listed is None else design.joints[joint.listed]
        most = nail_count(joint.length, design.material.nail_spacing)
        if spec is None or spec.nails is None:
            search.not_applicable(MORE_NAILS, "its nails are counted by the spacing rule "
                                  "already", joint.name)
        elif most <= spec.nails:
            search.not_applicable(MORE_NAILS, f"its {amount(joint.length / design.unit_scale)}"
                                  f" {design.units} take {most} nails at most", joint.name)
        else:
            room[joint.name] = (joint, spec, most)
    if not room:
        return None
    estimates = {need.where: need.values.get("nails_needed", 0)
                 for need in violation_needs(design, geometry, search.report)
                 if need.kind == "non-durable"}
    needed = {name: min(most, max(spec.nails + 1, estimates.get(name, 0)))
              for name, (_, spec, most) in room.items()}
    for name in needed:             # a mirror image as many as its own failing joint
        needed[name] = min(room[name][2], max(needed.get(other, 0)
                                              for other in orbits[name]))
    fix = search.first_valid([_candidate(search, room, needed)])
    full = {name: most for name, (_, _, most) in room.items()}
    if fix is None and full != needed:      # (each on its own: the fewer nails first)
        fix = search.first_valid([_candidate(search, room, full)])
    return fix


def _mirror_orbits(design, geometry, failing: set[str]) -> dict[str, set[str]]:
    """The failing joints and their mirror images (``symmetry.mirror_planes``: a stool's
    four seat/leg joints, two of which a push fails), each to the joints of its orbit:
    a maker nails a symmetric piece symmetrically, and a wriggle the other way fails the
    other two."""
    from furncheck.suggest.symmetry import mirror_planes

    by_planks = {frozenset(joint.planks): joint.name for joint in geometry.joints}
    planks_of = {joint.name: joint.planks for joint in geometry.joints}
    orbits: dict[str, set[str]] = {}
    planes = mirror_planes(design)
    for start in sorted(name for name in failing if name in planks_of):
        orbit, frontier = {start}, [start]
        while frontier:
            name = frontier.pop()
            for plane in planes:
                image = by_planks.get(frozenset(plane.partner.get(p, "") for p in
                                                planks_of[name]))
                if image is not None and image not in orbit:
                    orbit.add(image)
                    frontier.append(image)
        for name in orbit:
            orbits.setdefault(name, set()).update(orbit)
    return orbits


def _candidate(search: Search, room: dict, count: dict[str, int]) -> Candidate:
    """The design with each joint of ``room`` given ``count`` nails, and its advice."""
    design = search.design
    specs = list(design.joints)
    alike: dict[tuple, list[str]] = {}      # joints given the same, said once
    for name, (joint, spec, _) in room.items():
        specs[joint.listed] = replace(spec, nails=count[name])
        apart = amount(joint.length / count[name] / design.unit_scale)
        alike.setdefault((count[name], spec.nails, apart), []).append(name)
    parts = [f"{nails} nails into {'each of ' if len(which) > 1 else ''}{names(which)} "
             f"(now {old}), about {apart} {design.units} apart"
             for (nails, old, apart), which in alike.items()]
    advice = f"Drive {names(parts)}."
    return Candidate("nails", replace(design, joints=tuple(specs)), advice,
                     trial_rule=MORE_NAILS, target=names(list(room)),
                     place=", ".join(f"{count[name]} nails into {name}" for name in room))
