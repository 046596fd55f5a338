"""Contact statuses that cycle (contract section 3): with friction unlimited, a contact
held sideways by its anchor can pull, and sink once lifted, so the normal phase's
statuses come back to ones already tried.  The friction phase, with friction capped at
mu N, settles such a case to an admissible equilibrium instead of leaving it to the
linear programs (which are slow, and whose forces are only the admissible ones closest to
an unsettled iterate).

The design is the catalog's 28-plank cabinet in the elastic model with its left side
turned by 1.7 degrees (a step of the ``range`` search met it): its 'lean' case cycles.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import yaml

from furncheck.design import parse_design
from furncheck.geometry import analyze
from furncheck.statics import build_model, external_forces, solve_case
from furncheck.statics import contacts as contacts_module

CABINET = Path(__file__).resolve().parents[1] / "designs" / "cabinet-28.yaml"


def _tilted_cabinet():
    tree = yaml.safe_load(CABINET.read_text())
    tree["model"] = "elastic"
    side = next(p for p in tree["planks"] if p["id"] == "side_l")
    side.update(size=[988.989351072, 385.401019364], center=[-594.0, -7.30271217233, 500.0],
                rotation=[-90.0, -88.297980757284, 90.0])
    design = parse_design(yaml.safe_dump(tree, sort_keys=False), "tilted.yaml", "yaml")
    geometry = analyze(design)
    assert not geometry.violations
    return design, build_model(design, geometry)


def test_cycling_statuses_settle_in_the_friction_phase(monkeypatch):
    """The 'lean' case's normal phase cycles both ways (all pulling contacts lifted at
    once, and one at a time), yet the case is stable without the programs, and its forces
    are an admissible equilibrium: every normal force >= 0 and every contact inside its
    cone |f_t| <= mu N (to the force tolerance), and the contact forces balance the loads,
    sum F_c + sum F = 0 and sum p_c x F_c + sum (p_n x F_n + M_n) = 0 (moments about the
    origin; p_n the node points where the loads act)."""
    design, model = _tilted_cabinet()
    case = next(c for c in design.load_cases if c.name == "lean")
    f = external_forces(model, case)
    scale = contacts_module._force_scale(model, f)
    solver = contacts_module._ActiveSet(model, f, scale)
    all_stick = np.full(len(model.contacts), contacts_module.STICK)
    for one_at_a_time in (False, True):
        found = solver.normal_phase(all_stick, one_at_a_time)
        assert found is not None and found[2] is False       # the premise: it cycles

    def no_programs(*args, **kwargs):
        raise AssertionError("the programs were asked")

    monkeypatch.setattr(contacts_module._ActiveSet, "from_programs", no_programs)
    statics = solve_case(model, f)
    assert statics.stability == "stable"
    forces = statics.contact_forces
    tolerance = 1e-9 * scale
    assert forces[:, 2].min() >= -tolerance
    assert np.all(np.hypot(forces[:, 0], forces[:, 1])
                  <= model.friction * forces[:, 2] + tolerance)
    loads = f.reshape(-1, 6)
    assert np.abs(forces.sum(axis=0) + loads[:, :3].sum(axis=0)).max() < 1e-6 * scale
    moment = np.cross(model.contact_points, forces).sum(axis=0) \
        + np.cross(model.node_points, loads[:, :3]).sum(axis=0) + loads[:, 3:].sum(axis=0)
    assert np.abs(moment).max() < 1e-6 * scale * 1.0     # N m, lever arms about 1 m


@pytest.mark.parametrize("case_name", ["default", "shove"])
def test_settled_cases_do_not_change(case_name):
    """Where the normal phase settles, nothing changed: the same stable equilibrium with
    every normal force >= 0 and the forces balancing the loads."""
    design, model = _tilted_cabinet()
    case = next(c for c in design.load_cases if c.name == case_name)
    f = external_forces(model, case)
    statics = solve_case(model, f)
    assert statics.stability == "stable"
    scale = contacts_module._force_scale(model, f)
    assert statics.contact_forces[:, 2].min() >= -1e-9 * scale
    assert np.abs(statics.contact_forces.sum(axis=0)
                  + f.reshape(-1, 6)[:, :3].sum(axis=0)).max() < 1e-6 * scale
