"""The margins behind suggestions and their rates, against hand calculations, and the
line search's regula falsi.

Each test runs in the default (elastic) model unless it names one."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from furncheck.check import check_design
from furncheck.design import load_design
from furncheck.design.model import with_model
from furncheck.dofs import all_dofs, design_size, structure
from furncheck.edit_check import standing_geometry
from furncheck.geometry import analyze
from furncheck.suggest.edits import Editor
from furncheck.suggest.line_search import _boundary
from furncheck.suggest.margins import Margins

CATALOG = Path(__file__).resolve().parents[1] / "designs"
G = 9.81


def margins_of(name: str, model: str | None = None) -> Margins:
    design = with_model(load_design(str(CATALOG / name)), model)
    geometry = analyze(design)
    report = check_design(design, geometry)
    editor = Editor(design, geometry, structure(design, standing_geometry(geometry)))
    return Margins(design, geometry, report, editor, all_dofs(design))


def rate(margins: Margins, margin, dof_name: str) -> float:
    return float(margin.rates[[d.name for d in margins.dofs].index(dof_name)])


@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_cantilever_pull_margin_and_its_rate_by_hand(model):
    """shelf-cantilever-overloaded: M(L) = 294.3 N x 0.75 L + (750 x 0.3 x 0.012 L kg) g
    x L / 2 at L = 0.4 m is 90.4 N m; pull = 2 M / t / 15 = 1004.5 N, margin 1 - pull/700.
    dM/dL = 220.7 + 26.49 L = 231.3 N m per m, so the margin falls by 2 dM/dL / t / 15 /
    700 = 3.67 per m of shelf length: per scaled unit (the design's size, 0.812 m) 2.98.
    Statics alone fixes the shelf's joint: the same in both models."""
    margins = margins_of("shelf-cantilever-overloaded.yaml", model)
    pull = next(m for m in margins.violated if m.where == "post/shelf")
    load_arm, per_m = 294.3 * 0.75, 750 * 0.3 * 0.012 * G
    moment = load_arm * 0.4 + per_m * 0.4 ** 2 / 2
    assert pull.value == pytest.approx(1 - 2 * moment / 0.012 / 15 / 700, rel=2e-3)
    slope = 2 * (load_arm + per_m * 0.4) / 0.012 / 15 / 700
    size = design_size(margins.design) / 1000
    assert size == pytest.approx(0.812)
    assert rate(margins, pull, "shelf.length") == pytest.approx(-slope * size, rel=2e-3)


def test_sliding_margin_and_its_rate_by_hand():
    """table-slides, case shove: W = 12.6 kg g = 124 N, H = 110 N, mu = 0.5: the margin
    (mu W - H) / W = -0.387.  Widening the 1000 mm top by dw adds 750 x 1.0 x 0.012 dw kg:
    d margin / dw = mu x 88.29 N/m / W, per scaled unit times the size (1.0 m)."""
    margins = margins_of("table-slides.yaml")
    sliding = [m for m in margins.violated if m.restores == "stability"]
    assert len(sliding) == 1 and sliding[0].case == "shove"
    design = margins.design
    weight = sum(design.plank_mass(p) for p in design.planks) * G
    assert sliding[0].value == pytest.approx((0.5 * weight - 110) / weight, rel=1e-6)
    size = design_size(design) / 1000
    expected = 0.5 * 750 * 1.0 * 0.012 * G / weight * size
    assert rate(margins, sliding[0], "top.width") == pytest.approx(expected, rel=1e-4)


def test_penetration_margin_is_depth_against_tolerance():
    """bench-long-leg: the middle leg's corners are 2 mm below the floor, tolerance
    0.5 mm: margin (0.5 - 2) / size.  The sunk leg does not count as standing, so its
    length is free: shortening it raises its corners one for one (rate -1 per scaled unit
    of length), and raising the seat lifts it along (+1)."""
    margins = margins_of("bench-long-leg.yaml")
    (sunk,) = margins.violated
    size = design_size(margins.design)
    assert sunk.restores == "geometry" and sunk.where == "leg_m"
    assert sunk.value == pytest.approx((0.5 - 2.0) / size, rel=1e-9)
    assert rate(margins, sunk, "leg_m.length") == pytest.approx(-1.0, rel=1e-6)
    assert rate(margins, sunk, "seat.z") == pytest.approx(1.0, rel=1e-6)


def test_regula_falsi_needs_fewer_checks_than_bisection():
    """A margin linear in the step, zero at 0.3: the boundary is found to the resolution
    (below the valid end: 1e-4 of it) in a few evaluations (bisection of [0, 1] to 3e-5
    would need 16); above the valid end the resolution is absolute (1e-3)."""
    calls = []

    def margin(step: float) -> float:
        calls.append(step)
        return (step - 0.3) * 2.0

    low, _ = _boundary(margin, (1.0, margin(1.0)), (0.0, margin(0.0)), 1e-4)
    assert 0.3 <= low <= 0.3 + 1e-4
    assert len(calls) - 2 <= 8

    calls.clear()
    high, _ = _boundary(lambda s: 1.0 if s < 0.6 else -math.inf, (0.0, 1.0),
                        (1.0, -math.inf), 1e-3)
    assert 0.599 <= high < 0.6


@pytest.mark.parametrize("name, dof, model", [
    ("shelf-cantilever-overloaded.yaml", "shelf.length", "rigid"),
    ("bench-tips.yaml", "leg_r.x", "rigid"),
    ("shelf-cantilever-overloaded.yaml", "shelf.width", "rigid"),
    ("bench-tips.yaml", "leg_r.x", "elastic"),
    ("shelf-cantilever-overloaded.yaml", "shelf.length", "elastic")])
def test_margin_at_agrees_with_the_full_report(name, dof, model):
    """The line search's lean margin equals utilization_margin(check_design(...)) of the moved
    design, valid and invalid steps alike, in each model."""
    import numpy as np

    from furncheck.dofs import parse_dof
    from furncheck.suggest.edits import utilization_margin

    margins = margins_of(name, model)
    editor, design = margins.editor, margins.design
    dofs = (parse_dof(design, dof),)
    for step in (-0.3, -0.15, -0.05, 0.05, 0.15, 0.3):
        lean = editor.margin_at(dofs, np.array([1.0]), step)
        moved = editor.moved(dofs, editor.changes(dofs, np.array([1.0]), step))
        geometry = editor.keeps(moved)
        full = -math.inf if geometry is None else utilization_margin(check_design(moved, geometry))
        assert lean == pytest.approx(full, abs=1e-12) or lean == full == -math.inf
