"""Non-slip pads: the shop's fix for a piece that slides on its floor, pads (rubber, felt
-backed grips) under its feet that raise the friction between them and the floor.

The piece slides where the sideways load H on a grounded group exceeds mu W; it holds
with mu' >= H / W (the explanation's own estimate, ``suggest.needs``: ``friction_needed``,
the worst of its sliding cases), asked for rounded up to FRICTION_STEP.  The design's one
``friction`` is also that of its resting joints and of its walls, so the rule applies
only to a design with neither (only its feet on the floor use it), and only where
sliding is all that fails; the candidate (the design with that friction) is checked in
full.  Whether a pad gives that friction on the maker's floor is the maker's to check
(the advice says so): pads differ, and so do floors.  A friction above MAX_PAD_FRICTION is
not asked for.
"""

from __future__ import annotations

import math
from dataclasses import replace

from furncheck.plain import plain_number
from furncheck.suggest.discrete.common import Candidate, Fix, Search
from furncheck.suggest.needs import violation_needs

NON_SLIP = "non-slip pads"
"""The rule's name in ``tried.Trial`` values."""

FRICTION_STEP = 0.05
"""The friction asked of the pads is rounded up to a multiple of this."""

MAX_PAD_FRICTION = 1.0
"""The most friction the rule asks of pads: a piece that needs more (a push beyond its
weight) is not held by what goes under its feet, but by more weight or a fixing."""


def non_slip_pads(search: Search) -> Fix | None:
    """The design with the friction its feet need to stop sliding, when that is valid;
    else None (and why, in the trials)."""
    if not search.repairs(NON_SLIP, ("sliding",)):
        return None
    design = search.design
    if design.walls or design.anchors:
        search.not_applicable(NON_SLIP, "it leans on walls or is anchored")
        return None
    if any(spec.rests for spec in design.joints or ()):
        search.not_applicable(NON_SLIP, "its resting joints share the friction")
        return None
    needed = [need.values["friction_needed"]
              for need in violation_needs(design, search.geometry, search.report)
              if need.kind == "sliding" and "friction_needed" in need.values]
    if not needed:
        search.not_applicable(NON_SLIP, "no sideways load and weight known for it")
        return None
    friction = FRICTION_STEP * math.ceil(max(needed) / FRICTION_STEP)
    if friction <= design.material.friction:
        friction = design.material.friction + FRICTION_STEP
    if friction > MAX_PAD_FRICTION:
        search.not_applicable(NON_SLIP, f"it needs a friction of {plain_number(friction, 3)}, "
                              f"more than pads give (at most {plain_number(MAX_PAD_FRICTION, 3)})")
        return None
    now = plain_number(design.material.friction, 3)
    advice = (f"Fit non-slip pads under its feet that give a friction of at least "
              f"{plain_number(friction, 3)} on this floor (now {now}; check the pads on "
              "the floor itself).")
    edited = replace(design, material=replace(design.material, friction=friction))
    return search.first_valid([Candidate("pads", edited, advice, trial_rule=NON_SLIP,
                                         place=f"friction {plain_number(friction, 3)}")])
