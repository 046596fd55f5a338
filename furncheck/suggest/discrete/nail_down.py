"""Nailing a loose part down: the shop's fix for a top, shelf or block that lies on its
supports without nails (``type: rests``, contract section 2) and lifts off them or slides
on them.

A resting joint holds only by pressing and by friction; the same touching region nailed
is a nail joint (an end face of one plank on the face of the other).  The candidates nail
every resting joint that a lift-off or sliding violation names (both of its planks among
the violation's), and those of the same loose part with them (a top on two frames is
nailed to both), with FEW_NAILS each, then with as many as each length takes by the
spacing rule, each checked in full: the nails must hold what the rests could not (a top
tipped by a sitter at its front edge pulls its back nails).  A part resting on pins
(planks under PIN_SIZE) is not nailed: a nail would split them.
"""

from __future__ import annotations

from dataclasses import replace

from furncheck.geometry import analyze
from furncheck.suggest.discrete.common import Candidate, Fix, Search, names

NAIL_DOWN = "nail down"
"""The rule's name in ``tried.Trial`` values."""


def nail_down(search: Search) -> Fix | None:
    """The design with the failing resting joints nailed, when that is valid; else None
    (and why, in the trials)."""
    if not search.repairs(NAIL_DOWN, ("lift-off", "sliding")):
        return None
    design, geometry = search.design, search.geometry
    specs = list(design.joints or ())
    named = [set(v.where.split(",")) for v in search.report.violations
             if v.kind in ("lift-off", "sliding")]
    failing = {k for k, spec in enumerate(specs) if spec.rests
               and any(set(spec.planks) <= planks for planks in named)}
    if not failing:
        search.not_applicable(NAIL_DOWN, "no resting joint fails: what lifts or slides "
                                         "stands on the floor" if any(
                                             spec.rests for spec in specs)
                              else "it has no resting joints")
        return None
    loose = {_loose_plank(geometry, k) for k in failing}
    failing |= {k for k, spec in enumerate(specs) if spec.rests
                and _loose_plank(geometry, k) in loose}
    pins = sorted({_onto(geometry, k) for k in failing if _is_pin(design, _onto(geometry, k))})
    if pins:
        search.not_applicable(NAIL_DOWN, f"{names(sorted(loose))} rests on "
                              f"{names(pins)}: pins, which a nail would split")
        return None
    joints = [f"{specs[k].planks[0]}/{specs[k].planks[1]}" for k in sorted(failing)]
    candidates = [_candidate(design, geometry, specs, failing, count, joints)
                  for count in (FEW_NAILS, None)]
    return search.first_valid(candidates)


def _candidate(design, geometry, specs: list, failing: set[int], count: int | None,
               joints: list[str]) -> Candidate:
    """The design with the ``failing`` resting joints nailed, each with ``count`` nails
    (None: as many as its length takes by the spacing rule), and its advice."""
    specs = list(specs)
    for k in failing:
        specs[k] = replace(specs[k], rests=False,
                           nails=count if count is not None else specs[k].nails)
    nailed = replace(design, joints=tuple(specs))
    found = {frozenset(joint.planks): joint.nails for joint in analyze(nailed).joints}
    counts = {k: found.get(frozenset(specs[k].planks), 0) for k in failing}
    return Candidate("nails", nailed, _advice(geometry, sorted(failing), counts),
                     new_joints=tuple(specs[k].planks for k in sorted(failing)),
                     trial_rule=NAIL_DOWN, target=names(joints),
                     place=f"{len(failing)} resting joints nailed"
                           + (f", {count} nails each" if count is not None else ""))


FEW_NAILS = 2
"""Nails per resting joint the rule tries first (two screws or nails through a top into
its frame hold what a sitter at its edge asks of them), before as many as the joint's
length takes."""

PIN_SIZE = 0.06
"""m: a plank whose length and width are both below this is a pin or a small block, into
which a nail would split it (a shelf on pins is not nailed down)."""


def _is_pin(design, plank_id: str) -> bool:
    plank = design.plank(plank_id)
    return max(plank.length, plank.width) < PIN_SIZE


def _advice(geometry, joints: list[int], counts: dict[int, int]) -> str:
    """'Nail top to end_l and end_r, 30 nails into each (its resting joints made nail
    joints).'; with several loose planks, or counts that differ, each plank with what it
    is nailed to: 'Nail top_a to end_l (30 nails) and divider (29), and top_b to divider
    (29) and end_r (30) (their resting joints made nail joints).'"""
    by_plank: dict[str, list[int]] = {}
    for k in joints:
        by_plank.setdefault(_loose_plank(geometry, k), []).append(k)
    made = ("its resting joint made a nail joint" if len(joints) == 1 else
            f"{'its' if len(by_plank) == 1 else 'their'} resting joints made nail joints")
    if len(by_plank) == 1 and len({counts[k] for k in joints}) == 1:
        plank, count = next(iter(by_plank)), counts[joints[0]]
        each = f", {count} nail{'s' if count != 1 else ''} into " \
            f"{'each' if len(joints) > 1 else 'it'}"
        return f"Nail {plank} to {names([_onto(geometry, k) for k in joints])}{each} ({made})."
    phrases = []
    for p, (plank, rests) in enumerate(by_plank.items()):
        said = [f"{_onto(geometry, k)} ({counts[k]}"
                + (f" nail{'s' if counts[k] != 1 else ''})" if p == 0 and n == 0 else ")")
                for n, k in enumerate(rests)]
        phrases.append(f"{plank} to {names(said)}")
    return f"Nail {', and '.join(phrases)} ({made})."


def _loose_plank(geometry, joint: int) -> str:
    """The plank that lies on the other at resting joint ``joint`` (``Contact.resting``)."""
    return next((c.resting[0] for c in geometry.contacts if c.rest == joint), "")


def _onto(geometry, joint: int) -> str:
    """The plank the loose one lies on at resting joint ``joint``."""
    return next((c.resting[1] for c in geometry.contacts if c.rest == joint), "")
