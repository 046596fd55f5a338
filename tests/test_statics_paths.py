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
    1 - the worst joint or plank utilization of the report (or -inf for a case that is not
    stable); with any load case solved first and the cases stopping at the first that
    fails (``first``, for the range search's probes), the same verdict, a valid design's
    margin and utilization unchanged, an invalid one's stopping at a case the report
    names in a violation, its margin that of the cases solved (not below the full one).
    It is defined only for geometries without violations: catalog designs with a
    geometric violation are skipped, with their kinds as the reason.
(d) A contact state's condensed matrix is factored once (Cholesky, LU when it is not
    positive definite) and solved as a plain LU solve would.
(e) ``solve_case(model, f, near=...)`` starts the friction phase of an edit where the
    design's case settled (``statics.LineStarts``, for range's and suggest's probes): the
    same verdict, forces within the iterations' tolerances, fewer Newton steps.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from furncheck import tolerances
from furncheck.check import case_statics, check_design, margin_of
from furncheck.design import load_design
from furncheck.geometry import analyze
from furncheck.statics import build_model, external_forces, solve_case
from furncheck.statics.anchored import _anchored_stiffness, _Factored, anchored_system
from furncheck.statics.condense import _accurate
from furncheck.statics.lapack import cholesky as _cholesky

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
    """Started from the contacts that held (or from none holding), the contact iterations
    reach the equilibrium of a start from every contact holding: the same verdict, and
    forces within ten force tolerances (FORCE_REL_TOL of the loads: the iterations stop
    once the out-of-balance force and the friction caps' mismatch are within one, so two
    paths may end a few apart; the cabinet's differ by 2.5 of them)."""
    design = load_design(str(path))
    geometry = analyze(design)
    cold = _solutions(design, geometry)
    held = tuple(statics.holding for statics in case_statics(design, geometry))
    close = 10 * tolerances.FORCE_REL_TOL
    _assert_same(cold, _solutions(design, geometry, held), close)
    lifted = tuple(None if h is None else np.zeros_like(h) for h in held)
    _assert_same(cold, _solutions(design, geometry, lifted), close)


@pytest.mark.parametrize("path", CATALOG, ids=lambda p: p.stem)
def test_margin_of_agrees_with_the_report(path):
    design = load_design(str(path))
    geometry = analyze(design)
    if geometry.violations:
        kinds = ", ".join(sorted({v.kind for v in geometry.violations}))
        pytest.skip(f"geometric violations ({kinds}): margin_of is only defined for "
                    "geometries without them")
    report = check_design(design, geometry)
    valid, margin, utilization, _ = margin_of(design, geometry)
    assert valid == report.valid
    for first in range(len(design.load_cases)):     # a case first, stopping at a failure
        ordered = margin_of(design, geometry, first=first)
        assert ordered.valid == valid
        if valid:
            assert (ordered.margin, ordered.utilization.tobytes()) == \
                (margin, utilization.tobytes())
        else:       # the case it stopped at has a violation in the report
            assert design.load_cases[ordered.case].name in {v.case for v in report.violations}
            assert ordered.margin >= margin
    if any(case.stability != "stable" for case in report.cases):
        assert margin == -np.inf
        return
    worst = max((j.utilization for case in report.cases for j in case.joints), default=0.0)
    bent = max((p.utilization for case in report.cases for p in case.planks or ()),
               default=0.0)
    held = max((a.utilization for case in report.cases for a in case.anchors), default=0.0)
    assert margin == pytest.approx(1.0 - max(worst, bent, held), abs=1e-12)
    assert float(utilization.max(initial=0.0)) == pytest.approx(worst, abs=1e-12)


def test_a_factored_system_solves_as_lu_does():
    """``_Factored``: a symmetric positive definite matrix is solved through its Cholesky
    factor, an indefinite one by LU (no factor), a singular one not at all; the solutions
    equal numpy's LU solve to round-off."""
    rng = np.random.default_rng(7)
    basis = rng.normal(size=(12, 12))
    rhs = rng.normal(size=(12, 3))
    positive = basis @ basis.T + 12.0 * np.eye(12)
    indefinite = positive - 40.0 * np.eye(12)
    for matrix, chol in ((positive, True), (indefinite, False)):
        system = _Factored(matrix, _cholesky(matrix))
        assert (system.factor is not None) == chol
        expected = np.linalg.solve(matrix, rhs)
        assert np.abs(system.solve(rhs) - expected).max() <= 1e-10 * np.abs(expected).max()
    singular = np.zeros((3, 3))
    assert _Factored(singular, _cholesky(singular)).solve(np.ones(3)) is None


@pytest.mark.parametrize("name", ["cabinet-28", "stool", "bench-tips"])
def test_a_contact_state_is_factored_once_and_solves_its_matrix(name):
    """``anchored_system`` keeps one factored S0 + K_c per model and contact state: asked
    again for the same state it returns the same object, and its solve has the backward
    error of a fresh LU solve of the condensed matrix (``_accurate``: residual below 1e-10
    of |A| |x| + |b|); the two agree to 1e-8 relative (the matrix's condition, contact
    springs against joints, is about 1e7)."""
    design = load_design(str(CATALOG[0].parent / f"{name}.yaml"))
    model = build_model(design, analyze(design))
    holding = np.ones(len(model.contacts), dtype=bool)
    holding[::3] = False
    for state in (np.ones_like(holding), holding):
        system = anchored_system(model, state)
        assert anchored_system(model, state.copy()) is system
        rhs = model.condensation.load(external_forces(model, design.load_cases[0]))[1]
        matrix = _anchored_stiffness(model, state)
        expected, found = np.linalg.solve(matrix, rhs), system.solve(rhs)
        assert _accurate(matrix, found, rhs) and _accurate(matrix, expected, rhs)
        assert np.abs(found - expected).max() <= 1e-8 * np.abs(expected).max()


NEAR_DESIGNS = ("cabinet-28.yaml", "bookshelf-20.yaml", "table.yaml")
"""Catalog designs whose cases go through the friction phase (in the elastic model)."""

NEAR_CLOSE = 2e-7
"""Forces of a case solved from a near start and from its own, apart by at most this of
the loads' weight: both stop once the friction caps agree with mu N to a force tolerance
(FORCE_REL_TOL of the loads), and where many corners slip the equilibrium moves more than
their caps (the elastic cabinet's edits below: up to 6.3e-8; every fifth DOF of every
catalog design edited by 0.5 and -2 mm from the design: up to 5.6e-8, its 'lean' case
with the cap raised 0.5 mm).  A range's probes, started from other probes further along,
end up to 1.5e-6 apart (chair-tilted, rigid; ``contacts._ActiveSet._near_start``): only
a margin within that of zero can read otherwise."""


def _edits(design, geometry, count=6, steps=(0.5, -2.0)):
    """Some edits of ``design``: every DOF of a few spread over its DOFs, changed by each
    step (mm, or degrees), that keep a geometry without violations."""
    from furncheck.dofs import Blocked, OutOfReach, all_dofs, apply_dof, structure
    from furncheck.edit_check import standing_geometry

    frame = structure(design, standing_geometry(geometry))
    dofs = all_dofs(design)
    for dof in dofs[::max(1, len(dofs) // count)]:
        for step in steps:
            try:
                edited = apply_dof(design, frame, dof, step)
            except (Blocked, OutOfReach):
                continue
            edited_geometry = analyze(edited)
            if not edited_geometry.violations:
                yield step, edited, edited_geometry


def _friction_steps(monkeypatch) -> list[int]:
    """A counter of the friction phase's Newton steps (each factors its Hessian once)."""
    from furncheck.statics import friction

    count = [0]
    factored = friction._FrictionEnergy._factored_hessian

    def counted(self, x):
        count[0] += 1
        return factored(self, x)

    monkeypatch.setattr(friction._FrictionEnergy, "_factored_hessian", counted)
    return count


@pytest.mark.parametrize("model", ["rigid", "elastic"])
@pytest.mark.parametrize("name", NEAR_DESIGNS)
def test_a_near_start_finds_the_same_equilibrium(name, model, monkeypatch):
    """(e) An edit's cases solved from the design's cases (``solve_case``'s ``near``: the
    friction phase starts from their caps and grounded displacements, as range and
    suggest probes start) reach the verdict and, within NEAR_CLOSE of the loads' weight,
    the forces of a solve from the edit's own normal phase; in the elastic model in at
    most two thirds of the friction phase's Newton steps (cabinet 258 against 715,
    bookshelf 49 / 136, table 53 / 90)."""
    from furncheck.design.model import with_model

    steps = _friction_steps(monkeypatch)
    design = with_model(load_design(str(CATALOG[0].parent / name)), model)
    geometry = analyze(design)
    near = case_statics(design, geometry)
    cold_steps = near_steps = 0
    for _, edited, edited_geometry in _edits(design, geometry):
        edited_model = build_model(edited, edited_geometry)
        for k, case in enumerate(edited.load_cases):
            f = external_forces(edited_model, case)
            steps[0] = 0
            cold = solve_case(edited_model, f)
            cold_steps, steps[0] = cold_steps + steps[0], 0
            warm = solve_case(edited_model, f, near=near[k])
            near_steps += steps[0]
            weight = max(float(np.abs(f).sum()), 1e-12)
            _assert_same([(cold.stability, cold.joint_wrenches, cold.contact_forces, weight)],
                         [(warm.stability, warm.joint_wrenches, warm.contact_forces, weight)],
                         NEAR_CLOSE)
    if model == "elastic":
        assert cold_steps > 0
        assert 3 * near_steps <= 2 * cold_steps, (near_steps, cold_steps)


def test_line_starts_take_the_nearest_step_on_its_side():
    """``LineStarts.near``: per case, the nearest step checked (the first of equally near
    ones), the design's own case where it is as near or nearer (so never a step on the
    other side of the design), and nothing from a step whose case did not settle."""
    from furncheck.statics import CaseStatics, LineStarts

    def settled(tag: float) -> CaseStatics:
        return CaseStatics("stable", None, np.full((1, 3), tag), holding=np.ones(1, bool),
                           ground=np.full(6, tag))

    line = LineStarts((settled(0.0), settled(0.0)))
    line.keep(4.0, {0: settled(4.0), 1: CaseStatics("sliding", None, None)})
    line.keep(-1.0, {0: settled(-1.0), 1: settled(-1.0)})
    line.keep(3.0, {0: settled(3.0)})
    tags = lambda step: [float(s.ground[0]) for s in line.near(step)]   # noqa: E731
    assert tags(3.6) == [4.0, 0.0]      # case 1 did not settle at 4: the design's
    assert tags(3.5) == [4.0, 0.0]      # 4 and 3 equally near: the first kept
    assert tags(2.0) == [3.0, 0.0]
    assert tags(1.5) == [0.0, 0.0]      # the design as near as 3: the design
    assert tags(0.4) == [0.0, 0.0]      # the design, nearer than any step beyond it
    assert tags(-0.6) == [-1.0, -1.0]
    assert line.near(2.0)[0].joint_wrenches is None     # kept slim


def test_a_near_start_that_finds_no_minimum_falls_back_to_its_own(monkeypatch):
    """(e) A near start from which the friction phase finds no minimum: the iterations
    start again from the case's own normal phase, to the verdict and forces of a cold
    solve, and the near start is not tried again.  bookcase-pins (elastic), its shelf
    turned 4 degrees about x (a probe of the range of ``shelf.rx``; some corners slip, so
    a friction phase runs), 'push' case (20 N at the top), solved from a near case whose
    contacts carry no normal force: its caps mu N are 0, and without friction nothing
    holds the push, so the capped energy falls without bound along the sliding motion
    (Phi of ``friction._FrictionEnergy``).  The range search meets such near starts on
    its own (probes of this DOF near 8.6 degrees), but at probes where the last bits of
    the sums decide whether the iterations settle from the near start; a near case
    without friction fails for a reason that does not depend on them.  Without the
    fallback the probe's forces came from the linear programs (``solve_case``: the
    admissible forces nearest the elastic solution), not from the contact law."""
    from dataclasses import replace

    from furncheck.design.model import with_model
    from furncheck.dofs import apply_dof, parse_dof, structure
    from furncheck.edit_check import standing_geometry
    from furncheck.statics import contacts

    design = with_model(load_design(str(CATALOG[0].parent / "bookcase-pins.yaml")),
                        "elastic")
    frame = structure(design, standing_geometry(analyze(design)))
    probe = apply_dof(design, frame, parse_dof(design, "shelf.rx"), 4.0)
    model = build_model(probe, analyze(probe))
    (push,) = [k for k, case in enumerate(probe.load_cases) if case.name == "push"]
    f = external_forces(model, probe.load_cases[push])
    settled = []
    settle = contacts._ActiveSet._settle

    def recorded(self, ground, caps):
        found = settle(self, ground, caps)
        settled.append(found is not None)
        return found

    monkeypatch.setattr(contacts._ActiveSet, "_settle", recorded)
    cold = solve_case(model, f)
    assert cold.stability == "stable" and settled == [True]
    frictionless = replace(cold, contact_forces=np.zeros_like(cold.contact_forces))
    settled.clear()
    warm = solve_case(model, f, near=frictionless)
    assert settled == [False, True]         # no minimum from the near start; its own
    weight = float(np.abs(f).sum())
    _assert_same([(cold.stability, cold.joint_wrenches, cold.contact_forces, weight)],
                 [(warm.stability, warm.joint_wrenches, warm.contact_forces, weight)],
                 NEAR_CLOSE)
