"""The statics' faster paths give the same equilibrium as the plain ones.

(a) Designs of up to 60 planks are condensed through the planks (joint wrenches
    eliminated, h = E^-1 G q: a dense Cholesky factor of K = G^T E^-1 G); larger ones
    through the sparse mixed system.  Both solve the same linear equations, so on every
    catalog design and load case the joint wrenches and contact forces agree to 1e-7 of
    the case's weight (the mixed system's own round-off is about 1e-11 of it).
(b) ``solve_case(model, f, start)`` starts the contact active set from the contacts that
    held in another design; the unilateral contact problem has one solution, so the
    result equals the cold start's whatever the start (even every contact lifted).
(c) ``check.margin_of`` gives the same verdict as ``check_design`` and, as its margin,
    1 - the worst joint utilization of the report (or -inf for a case that is not stable).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from furncheck import tolerances
from furncheck.check import check_design, holding_states, margin_of
from furncheck.design import load_design
from furncheck.geometry import analyze
from furncheck.statics import build_model, external_forces, solve_case

CATALOG = sorted((Path(__file__).resolve().parents[1] / "designs").glob("*.yaml"))


def _solutions(design, geometry, starts=None):
    model = build_model(design, geometry)
    out = []
    for k, case in enumerate(design.load_cases):
        f = external_forces(model, case)
        statics = solve_case(model, f, None if starts is None else starts[k])
        weight = max(float(np.abs(f).sum()), 1e-12)
        out.append((statics.stability, statics.joint_wrenches, statics.contact_forces, weight))
    return out


def _assert_same(first, second, relative):
    for (stab_a, h_a, c_a, weight), (stab_b, h_b, c_b, _) in zip(first, second):
        assert stab_a == stab_b
        for a, b in ((h_a, h_b), (c_a, c_b)):
            if a is None or b is None:
                assert a is None and b is None
                continue
            assert np.abs(a - b).max(initial=0.0) <= relative * weight


@pytest.mark.parametrize("path", CATALOG, ids=lambda p: p.stem)
def test_plank_condensation_matches_the_sparse_mixed_system(path, monkeypatch):
    design = load_design(str(path))
    geometry = analyze(design)
    assert 6 * len(design.planks) <= tolerances.DENSE_PLANKS_MAX    # the catalog is small
    through_planks = _solutions(design, geometry)
    monkeypatch.setattr(tolerances, "DENSE_PLANKS_MAX", 0)
    mixed = _solutions(design, geometry)
    _assert_same(through_planks, mixed, 1e-7)


@pytest.mark.parametrize("path", CATALOG, ids=lambda p: p.stem)
def test_a_warm_start_finds_the_same_equilibrium(path):
    design = load_design(str(path))
    geometry = analyze(design)
    cold = _solutions(design, geometry)
    held = holding_states(design, geometry)
    _assert_same(cold, _solutions(design, geometry, held), 1e-9)
    lifted = tuple(None if h is None else np.zeros_like(h) for h in held)
    _assert_same(cold, _solutions(design, geometry, lifted), 1e-9)


@pytest.mark.parametrize("path", CATALOG, ids=lambda p: p.stem)
def test_margin_of_agrees_with_the_report(path):
    design = load_design(str(path))
    geometry = analyze(design)
    report = check_design(design, geometry)
    if geometry.violations:
        return                  # margin_of is for geometries without violations
    valid, margin, utilization = margin_of(design, geometry)
    assert valid == report.valid
    if any(case.stability != "stable" for case in report.cases):
        assert margin == -np.inf
        return
    worst = max((j.utilization for case in report.cases for j in case.joints), default=0.0)
    assert margin == pytest.approx(1.0 - worst, abs=1e-12)
    assert float(utilization.max(initial=0.0)) == pytest.approx(worst, abs=1e-12)
