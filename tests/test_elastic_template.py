"""A model built on a template (``build_elastic_model(..., template=...)``, the
sensitivity's stepped designs) is the model a fresh build gives when nothing moved: the
template's node layout, frames and topology caches stand for what the keys would give."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from furncheck.design import load_design
from furncheck.design.model import with_model
from furncheck.geometry import analyze
from furncheck.statics import external_forces, solve_case
from furncheck.statics.elastic import build_elastic_model

DESIGNS = Path(__file__).resolve().parents[1] / "designs"


@pytest.mark.parametrize("name", ["cabinet-28.yaml", "table.yaml", "bookcase-sagging.yaml",
                                  "shelf-cantilever.yaml"])
def test_a_template_of_the_same_design_changes_nothing(name):
    """Every array of the model (node places, beams, joint blocks and springs, contact
    maps, nodal weights, load nodes) is the same, bit for bit, and so is each case's
    solution."""
    design = with_model(load_design(str(DESIGNS / name)), "elastic")
    geometry = analyze(design)
    fresh = build_elastic_model(design, geometry)
    again = build_elastic_model(design, geometry, template=fresh)
    for field in ("node_plank", "node_points", "joint_nodes", "joint_blocks",
                  "joint_stiffness", "contact_maps", "contact_node", "contact_plank",
                  "nodal_weight"):
        assert np.array_equal(getattr(fresh, field), getattr(again, field)), field
    for field in ("nodes", "length", "frames", "local_stiffness", "node_s"):
        assert np.array_equal(getattr(fresh.beams, field), getattr(again.beams, field)), field
    assert fresh.load_nodes == again.load_nodes
    for case in design.load_cases:
        a = solve_case(fresh, external_forces(fresh, case))
        b = solve_case(again, external_forces(again, case))
        assert np.array_equal(a.joint_wrenches, b.joint_wrenches)
