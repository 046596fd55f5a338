"""The margins of one solved load case, kind by kind (``margins``' module docstring says
what each measures): per joint its nails' pull and shear (``durability_margins``), per
plank of an elastic model its sag and stress (``bending_margins``), per ground contact of
a case that topples its normal force (``toppling_margins``) or of one that slides by a
wall its friction cone (``cone_margins``), and per anchor its force
(``anchor_margins``); each with its rates over the free DOFs from the force
sensitivity (eq. 6).  ``Margin`` is what they give.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from furncheck.design.model import Design
from furncheck.geometry.model import nails_listed
from furncheck.nail_groups import nail_pull_shear
from furncheck.sensitivity import Linearization, Sensitivity
from furncheck.statics import external_forces
from furncheck.tolerances import GRAVITY
from furncheck.validity import anchor_capacity, plank_limits

NAIL_FORCE_STEP = 1e-6
"""Step (N, N m per unit rate) of the difference that turns wrench rates into pull and
shear rates (both are piecewise linear in the wrench)."""


@dataclass(frozen=True)
class Margin:
    """One validity margin (see the module docstring).

    restores : 'durability', 'stability', 'geometry', 'stiffness' (sag) or 'strength'
               (bending stress) (the contract's ``restores``)
    where    : joint 'a/b', plank id or component, for messages
    case     : load case name, None for geometry and for a leg drawn short (it restores
               every case that topples: ``Margins._standing``)
    value    : dimensionless, >= 0 where the design passes
    rates    : (n_free,) d value / d DOF, scaled DOF units, in ``Margins.dofs`` order
    target   : the value a direction aims at for a violated margin
    """

    restores: str
    where: str
    case: str | None
    value: float
    rates: np.ndarray
    target: float



def durability_margins(linear: Linearization, sens: Sensitivity,
                scales: np.ndarray) -> list[Margin]:
    """Per joint: 1 - pull / capacity and 1 - shear / capacity, with rates.

    Pull and shear are per nail, and the nail count follows the joint's length in whole
    nails; its smooth trend (forces per nail ~ 1 / length) is added to the rates, so that
    widening a plank at a failing joint reads as the help it is.
    """
    design = linear.design
    joints = [linear.geometry.joints[j] for j in linear.model.joints]
    if not joints:
        return []
    wrenches = linear.joint_wrenches
    pull_cap = design.material.nail_pull / design.safety_factor
    shear_cap = design.material.nail_shear / design.safety_factor
    pull, shear = nail_pull_shear(joints, wrenches)
    n = len(scales)
    stepped = wrenches[None] + NAIL_FORCE_STEP * sens.joint_wrenches              # (n, nJ, 6)
    p, s = nail_pull_shear(joints * n, stepped.reshape(-1, 6))
    pull_rates = (p.reshape(n, -1) - pull) / NAIL_FORCE_STEP                       # (n, nJ)
    shear_rates = (s.reshape(n, -1) - shear) / NAIL_FORCE_STEP
    counted = np.array([0.0 if nails_listed(design, joint) else 1.0 / joint.length
                        for joint in joints])
    relative = sens.joint_lengths * counted                                        # dL / L
    pull_rates = ((pull_rates - pull * relative) * scales[:, None]).T              # (nJ, n)
    shear_rates = ((shear_rates - shear * relative) * scales[:, None]).T
    margins = []
    for k, joint in enumerate(joints):
        margins.append(Margin("durability", joint.name, linear.case.name,
                              1.0 - pull[k] / pull_cap, -pull_rates[k] / pull_cap, 0.0))
        margins.append(Margin("durability", joint.name, linear.case.name,
                              1.0 - shear[k] / shear_cap, -shear_rates[k] / shear_cap, 0.0))
    return margins


def bending_margins(linear: Linearization, sens: Sensitivity, scales: np.ndarray) -> list[Margin]:
    """Per plank of an elastic model: 1 - sag (1 + creep) sag_limit / span ('stiffness')
    and 1 - stress / strength ('strength'), with rates from the sag, span and stress
    rates (none in the rigid model)."""
    planks = linear.statics.planks
    if planks is None or sens.plank_sags is None or not sens.plank_sags.shape[1]:
        return []
    design, model = linear.design, linear.model
    sag_limits, creeps, strengths = plank_limits(design, model)
    margins = []
    for k in range(len(planks.sag)):
        plank_id = design.planks[model.planks[k]].id
        factor = (1.0 + float(creeps[k])) * float(sag_limits[k])
        strength = float(strengths[k])
        sag, span = float(planks.sag[k]), float(planks.span[k])
        if span > 0.0:
            rates = -factor * (sens.plank_sags[:, k] * span - sag * sens.plank_spans[:, k]) \
                / (span * span)
            margins.append(Margin("stiffness", plank_id, linear.case.name,
                                  1.0 - factor * sag / span, rates * scales, 0.0))
        margins.append(Margin("strength", plank_id, linear.case.name,
                              1.0 - float(planks.stress[k]) / strength,
                              -sens.plank_stresses[:, k] * scales / strength, 0.0))
    return margins


def toppling_margins(linear: Linearization, force_rates: np.ndarray,
              scales: np.ndarray) -> list[Margin]:
    """Per contact of the bolted state (not an anchor's tie, which may pull): normal
    force / the case's weight (the sum of the normal forces; with walls or anchors, which
    share the loads with the ground, the loads' size)."""
    forces = linear.contact_forces
    weight = _load_scale(linear) if linear.model.contact_frames is not None \
        or linear.model.contact_anchored is not None else max(float(forces[:, 2].sum()), 1e-12)
    rates = force_rates[:, :, 2].T * scales / weight                     # (nK, n)
    planks = linear.design.planks
    model = linear.model
    ties = model.contact_anchored
    return [Margin("stability", planks[model.planks[model.contact_plank[k]]].id,
                   linear.case.name, float(forces[k, 2] / weight), rates[k], 0.0)
            for k in range(len(forces)) if ties is None or not ties[k]]


def _load_scale(linear: Linearization) -> float:
    """N: the size of the case's applied loads (the sum of the ground's and the walls'
    normal forces would be no scale for a design leaning on walls: they cancel)."""
    forces = external_forces(linear.model, linear.case).reshape(-1, 6)[:, :3]
    return max(float(np.sqrt((forces * forces).sum(axis=1)).sum()), 1e-12)


def cone_margins(linear: Linearization, force_rates: np.ndarray,
           scales: np.ndarray) -> list[Margin]:
    """Per contact of the bolted state of a case that slides while leaning on walls (not
    an anchor's tie): (mu N - |F_t|) / the loads' size, with rates."""
    model, forces, mu = linear.model, linear.contact_forces, linear.design.material.friction
    weight = _load_scale(linear)
    ties = model.contact_anchored
    planks = linear.design.planks
    margins = []
    for k in range(len(forces)):
        if ties is not None and ties[k]:
            continue
        tangential = forces[k, :2]
        size = max(float(np.hypot(*tangential)), 1e-12)
        rates = (mu * force_rates[:, k, 2] - force_rates[:, k, :2] @ tangential / size) \
            * scales / weight
        margins.append(Margin("stability", planks[model.planks[model.contact_plank[k]]].id,
                              linear.case.name, float(mu * forces[k, 2] - size) / weight,
                              rates, 0.0))
    return margins


def anchor_margins(linear: Linearization, force_rates: np.ndarray,
             scales: np.ndarray) -> list[Margin]:
    """Per anchor: 1 - |F| / capacity (capacity / safety factor), with rates
    -(F . dF) / (|F| capacity) from the contact force rates (n, nK, 3)."""
    model, design = linear.model, linear.design
    if model.contact_anchored is None:
        return []
    margins = []
    for k in np.flatnonzero(model.contact_anchored):
        index = linear.geometry.contacts[model.contacts[k]].anchor
        capacity = anchor_capacity(design, index)
        force = linear.contact_forces[k]
        size = max(float(np.linalg.norm(force)), 1e-12)
        rates = -(force_rates[:, k, :] @ force) * scales / (size * capacity)
        margins.append(Margin("durability", f"anchors[{index}]", linear.case.name,
                              1.0 - size / capacity, rates, 0.0))
    return margins


def component_loads(design: Design, components: list[list[int]], case_name: str) -> np.ndarray:
    """(n_components, 3) N: the planks' weight and the case's loads on each component."""
    case = next(c for c in design.load_cases if c.name == case_name)
    per_plank = np.zeros((len(design.planks), 3))
    for i, plank in enumerate(design.planks):
        per_plank[i, 2] -= design.plank_mass(plank) * GRAVITY
    for load in case.loads:
        per_plank[design.plank_index[load.plank]] += load.force
    return np.array([per_plank[component].sum(axis=0) for component in components])
