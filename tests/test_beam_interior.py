"""The exact deflection and moment inside a Timoshenko element (``beams.element_interior``),
against closed forms of whole beams that one element spans."""

from __future__ import annotations

import numpy as np
import pytest

from furncheck.statics.beams import element_interior

E_I = 3000e6 * 0.3 * 0.012 ** 3 / 12.0          # N m^2: 12 mm MDF shelf, 300 mm wide
K_G_A = 5.0 / 6.0 * 800e6 * 0.3 * 0.012          # N


def test_simply_supported_uniform_load():
    """A simply supported span L under q: w(s) = q s (L^3 - 2 L s^2 + s^3) / 24 EI +
    q s (L - s) / 2 kGA, with the end
    rotations theta(0) = -theta(L) = q L^3 / 24 EI (shear does not rotate the section);
    V = dM/ds, dV/ds = q gives M(s) = -q s (L - s) / 2 in the element's convention."""
    L, q = 0.8, -150.0
    theta = q * L ** 3 / (24.0 * E_I)
    xi = np.linspace(0.0, 1.0, 9)
    w, moment = element_interior(np.array([L]), np.array([E_I]), np.array([K_G_A]),
                                 np.array([[0.0, theta, 0.0, -theta]]), np.array([q]), xi)
    s = xi * L
    expected_w = q * s * (L ** 3 - 2 * L * s ** 2 + s ** 3) / (24 * E_I) \
        + q * s * (L - s) / (2 * K_G_A)
    assert w[0] == pytest.approx(expected_w, rel=1e-9, abs=1e-15)
    assert moment[0] == pytest.approx(-q * s * (L - s) / 2.0, rel=1e-9, abs=1e-9)
    assert w[0, 4] == pytest.approx(5 * q * L ** 4 / (384 * E_I) + q * L * L / (8 * K_G_A))


def test_cantilever_tip_load():
    """A cantilever of length L with a tip force P along +w, no load along it: tip
    deflection P L^3 / 3 EI + P L / kGA, rotation P L^2 / 2 EI; inside, w(s) = P s^2 (3 L -
    s) / 6 EI + P s / kGA, and the moment falls linearly from P L at the root to 0."""
    L, P = 0.4, 20.0
    tip = P * L ** 3 / (3 * E_I) + P * L / K_G_A
    rotation = P * L ** 2 / (2 * E_I)
    xi = np.linspace(0.0, 1.0, 5)
    w, moment = element_interior(np.array([L]), np.array([E_I]), np.array([K_G_A]),
                                 np.array([[0.0, 0.0, tip, rotation]]), np.array([0.0]), xi)
    s = xi * L
    assert w[0] == pytest.approx(P * s ** 2 * (3 * L - s) / (6 * E_I) + P * s / K_G_A,
                                 rel=1e-9, abs=1e-15)
    assert np.abs(moment[0]) == pytest.approx(P * (L - s), rel=1e-9, abs=1e-9)


def test_rigid_motion_has_no_moment():
    """A rigid translation and rotation of the element (w = a + b s, theta = b) bends
    nothing: M = 0 everywhere and w stays on the line."""
    L, a, b = 0.5, 0.003, -0.02
    xi = np.linspace(0.0, 1.0, 7)
    w, moment = element_interior(np.array([L]), np.array([E_I]), np.array([K_G_A]),
                                 np.array([[a, b, a + b * L, b]]), np.array([0.0]), xi)
    assert np.abs(moment).max() < 1e-6
    assert w[0] == pytest.approx(a + b * xi * L, rel=1e-12)


@pytest.mark.parametrize("name", ["bookcase-sagging.yaml", "table.yaml", "bookshelf-20.yaml"])
def test_more_nodes_change_nothing(name, monkeypatch):
    """The elements are exact (nodal values for end loads and their own uniform load, and
    ``element_interior`` between the nodes), so a grid of 8 more nodes per plank
    (BEAM_SEGMENTS = 8) gives the same joint wrenches, sags (to the sampling of SAG_SAMPLES
    points per element, 0.12 %) and stresses as the default of none."""
    from pathlib import Path

    from furncheck import tolerances as tol
    from furncheck.design import load_design
    from furncheck.design.model import with_model
    from furncheck.geometry import analyze
    from furncheck.statics import build_model, solve_load_case

    design = with_model(load_design(str(Path(__file__).parents[1] / "designs" / name)),
                        "elastic")
    geometry = analyze(design)
    results, nodes = {}, {}
    for segments in (1, 8):
        monkeypatch.setattr(tol, "BEAM_SEGMENTS", segments)
        model = build_model(design, geometry)
        nodes[segments] = model.n_nodes
        results[segments] = [solve_load_case(model, case) for case in design.load_cases]
    assert nodes[1] < nodes[8]
    for coarse, fine in zip(results[1], results[8]):
        scale = np.abs(fine.joint_wrenches).max()
        assert np.abs(coarse.joint_wrenches - fine.joint_wrenches).max() < 1e-6 * scale
        assert coarse.planks.sag == pytest.approx(fine.planks.sag, rel=3e-3, abs=1e-7)
        assert coarse.planks.stress == pytest.approx(fine.planks.stress, rel=1e-6)


@pytest.mark.parametrize("name", ["cabinet-28", "bookshelf-18", "wall-shelf"])
def test_stacked_plank_results_are_each_models_own(name):
    """``plank_results_many`` reads several models' planks in one stacked pass (the
    sensitivity's stepped designs): the same sag, span and stress, bit for bit, as one
    ``plank_results`` call per model, whatever the models (here the design's own model at
    its solved state and at scaled states, and an edited design's model)."""
    from pathlib import Path

    from furncheck.design import load_design
    from furncheck.dofs import Blocked, OutOfReach, all_dofs, apply_dof, structure
    from furncheck.geometry import analyze
    from furncheck.statics import build_model, solve_load_case
    from furncheck.statics.bending import plank_results, plank_results_many

    design = load_design(str(Path(__file__).resolve().parents[1] / "designs" / f"{name}.yaml"))
    geometry = analyze(design)
    model = build_model(design, geometry)
    runs = []
    for case in design.load_cases:
        statics = solve_load_case(model, case)
        runs += [(model, case, statics.displacements), (model, case, 3.0 * statics.displacements)]
    frame = structure(design, geometry)
    for dof in all_dofs(design):
        try:
            edited = apply_dof(design, frame, dof, 2.0)
        except (Blocked, OutOfReach):       # a DOF that cannot move: try the next
            continue
        edited_geometry = analyze(edited)
        if edited_geometry.violations or len(edited_geometry.joints) != len(geometry.joints):
            continue
        edited_model = build_model(edited, edited_geometry)
        case = edited.load_cases[0]
        runs.append((edited_model, case, solve_load_case(edited_model, case).displacements))
        break
    holding = None
    together = plank_results_many(runs, holding)
    for (m, case, q), result in zip(runs, together):
        alone = plank_results(m, case, q, holding)
        for field in ("sag", "span", "stress"):
            assert np.array_equal(getattr(result, field), getattr(alone, field)), field


def _design_for_rates(name: str, tmp_path):
    """A catalog design by name; 'chair-upright turned 17' that design turned by 17
    degrees about z; 'generated 135' the 136th design of ``benchmarks/catalog.py``'s
    catalog (seed 16): a wall whose middle side does not bend (its sag is round-off)."""
    import sys
    from pathlib import Path

    import yaml

    from furncheck.design import load_design, parse_design
    from furncheck.design.model import with_model

    root = Path(__file__).resolve().parents[1]
    if name == "generated 135":
        sys.path.insert(0, str(root / "benchmarks"))
        from catalog import write_catalog

        paths = write_catalog(tmp_path, 136)
        return with_model(load_design(str(paths[135])), "elastic")
    if name.startswith("chair-upright turned"):
        from physics_designs import rigid_motion, to_text

        data = yaml.safe_load((root / "designs" / "chair-upright.yaml").read_text())
        turned = rigid_motion(data, float(name.rsplit(" ", 1)[1]), 0.0, 0.0)
        return parse_design(to_text(turned), "chair.yaml", "yaml")
    return load_design(str(root / "designs" / f"{name}.yaml"))


@pytest.mark.parametrize("name", ["cabinet-28", "bookshelf-18", "wall-shelf", "stool",
                                  "generated 135", "chair-upright turned 17"])
def test_plank_rates_read_at_the_design_own_points_are_the_full_reads(name, monkeypatch,
                                                                      tmp_path):
    """The sensitivity reads a stepped design's planks only where the design's own largest
    sag and stress may lie (``plank_results_where``, then ``plank_results_at``): every
    DOF's sag, span and stress rates (first load case, one-sided and central differences)
    are, bit for bit, those of reading every sample of every element of every stepped
    design (``plank_results_of``, put in its place here).  The generated wall's middle
    side and the turned chair's back do not bend (their sag is round-off, any point its
    largest): reading only the points within NEAR_LARGEST of their own largest gave 42
    of the wall's sag rates 1 to 2 % off; the band is of the design's largest.  And for
    a large change (a DOF moved 2 mm, the displacements doubled), where the largest may
    lie at another point, the stress read at the design's own points is never more than
    the full read's (a largest over fewer points)."""
    from furncheck.dofs import Blocked, OutOfReach, all_dofs, apply_dof, structure
    from furncheck.geometry import analyze
    from furncheck.sensitivity import Linearization
    from furncheck.statics import build_model, derivatives, solve_load_case
    from furncheck.statics.bending import plank_part, plank_results_of
    from furncheck.statics.bending_points import plank_results_at, plank_results_where
    from furncheck.statics.templated import built_on

    design = _design_for_rates(name, tmp_path)
    geometry = analyze(design)
    frame = structure(design, geometry)
    case = design.load_cases[0]
    dofs = all_dofs(design)

    def rates(one_sided: bool) -> list[np.ndarray]:
        sens = Linearization(design, case, geometry, frame, {},
                             one_sided=one_sided).derivatives(dofs)
        return [sens.plank_sags, sens.plank_spans, sens.plank_stresses]

    def full_reads(stepped, q, dq, where):
        return iter(plank_results_of([part for part, *_ in stepped],
                                     [q + offset * dq[:, column] for _, column, offset
                                      in stepped]))

    at_points = [rates(True), rates(False)]
    monkeypatch.setattr(derivatives, "_plank_results_batched", full_reads)
    for read, full in zip(at_points, [rates(True), rates(False)]):
        for a, b in zip(read, full):
            assert np.array_equal(a, b)

    model = build_model(design, geometry)
    statics = solve_load_case(model, case)
    base = plank_part(model, case, statics.holding)
    _, where = plank_results_where(base, statics.displacements)
    moved = 0
    for dof in dofs:
        try:
            edited = apply_dof(design, frame, dof, 2.0)
        except (Blocked, OutOfReach):
            continue
        edited_geometry = analyze(edited)
        if edited_geometry.violations or len(edited_geometry.joints) != len(geometry.joints) \
                or len(edited_geometry.contacts) != len(geometry.contacts):
            continue
        stepped = built_on(edited, edited_geometry, model)
        part = plank_part(stepped, edited.load_cases[0], statics.holding,
                          supports=(base.low, base.high))
        q = 2.0 * statics.displacements
        full = plank_results_of([part], [q])[0]
        (at,) = plank_results_at([part], [q], where)
        assert np.all(at.stress <= full.stress)
        moved += 1
    assert moved >= 3
