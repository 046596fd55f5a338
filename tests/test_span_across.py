"""A plank nailed along both its longer edges to panels spans across its width
(elastic model, ``statics.elastic._spans_across``; contract 3a's beam runs along the
longer side, and this is its one exception).  Hand checks (12 mm MDF, E = 3000 N/mm^2,
G = 800 N/mm^2, 750 kg/m^3, creep 0.5, sag limit span / 400):

* A nightstand's top, 388 mm between its sides and 400 mm deep (deeper than wide, as
  nightstands often are), 40 kg at its middle.  Along its 400 mm depth the beam is held
  all along by the sides' nail rows and read no bending at all (the design passed); the
  same top 380 mm deep read 2.14 mm.  Across, it spans L = 0.388 m, section 400 x 12
  (EI = 3e9 x 0.4 x 0.012^3 / 12 = 172.8 N m^2, kappa G A = 5/6 x 0.8e9 x 0.0048 =
  3.2e6 N), P = 392.4 N and its weight w = 750 x 9.81 x 0.4 x 0.012 = 35.3 N/m: its sag
  lies between fixed ends, P L^3 / 192 EI + w L^4 / 384 EI + P L / (8 kappa G A) = 0.71
  mm, and pinned ends, P L^3 / 48 EI + 5 w L^4 / 384 EI + P L / (4 kappa G A) = 2.83 mm.
  Either way 1.5 x sag is over L / 400 = 0.97 mm: sagging, over a 388 mm span.
* A narrow cabinet's shelf, 288 mm between its sides and 560 mm deep, 20 kg of books
  spread on it (w = 196.2 / 0.288 + 750 x 9.81 x 0.56 x 0.012 = 730.7 N/m, EI = 241.9 N
  m^2): between w L^4 / 384 EI = 0.054 mm and 5 w L^4 / 384 EI = 0.27 mm.  Along its
  depth, held at the joints' middles, it read "sags 2.33 mm at the free end of its
  280 mm overhang" (a false failure, its message said the model overstated it).
* What keeps the longer side: the same top with a back panel nailed along its whole
  back edge (held on three edges; the README's limits), and a seat on two 100 mm
  aprons along its 1200 mm length (the aprons bend with it: a rail, not a panel).
* Rigid motions and turning the top's description by 90 degrees change nothing.
"""

from __future__ import annotations

import math

import pytest

from furncheck.check import check_design
from furncheck.design import parse_design
from furncheck.geometry import analyze
from furncheck.statics.beams import along_width
from furncheck.statics.elastic import build_elastic_model

G = 9.81
E, G_SHEAR, RHO, T = 3.0e9, 0.8e9, 750.0, 0.012

NIGHTSTAND = """furncheck: 1
name: nightstand
planks:
  - {id: side_l, size: [550, @D], center: [-200, 0, 275], rotation: [0, -90, 0]}
  - {id: side_r, size: [550, @D], center: [200, 0, 275], rotation: [0, -90, 0]}
  - {id: mid, size: [388, @D], center: [0, 0, 300]}
  - {id: top, size: [388, @D], center: [0, 0, 544]}
@BACK
loads:
  - {plank: top, mass: 40, at: [0, 0, 550]}
"""

BACK = "  - {id: back, size: [412, 550], center: [0, 206, 275], rotation: [90, 0, 0]}"

NARROW = """furncheck: 1
name: narrow-cabinet
planks:
  - {id: side_l, size: [900, 560], center: [-150, 0, 450], rotation: [0, -90, 0]}
  - {id: side_r, size: [900, 560], center: [150, 0, 450], rotation: [0, -90, 0]}
  - {id: bottom, size: [288, 560], center: [0, 0, 56]}
  - {id: shelf, size: [288, 560], center: [0, 0, 450]}
  - {id: top, size: [288, 560], center: [0, 0, 894]}
loads:
  - {plank: shelf, mass: 20, spread: true}
"""

BENCH = """furncheck: 1
name: bench-aprons
planks:
  - {id: seat, size: [1200, 350], center: [0, 0, 444]}
  - {id: leg_l, size: [438, 350], center: [-500, 0, 219], rotation: [0, -90, 0]}
  - {id: leg_r, size: [438, 350], center: [500, 0, 219], rotation: [0, -90, 0]}
  - {id: apron_f, size: [988, 100], center: [0, 169, 388], rotation: [90, 0, 0]}
  - {id: apron_b, size: [988, 100], center: [0, -169, 388], rotation: [90, 0, 0]}
loads:
  - {plank: seat, mass: 80, at: [0, 0, 450]}
"""


def nightstand(depth: float = 400, back: bool = False) -> str:
    return NIGHTSTAND.replace("@D", f"{depth:g}").replace("@BACK", BACK if back else "")


def spans(text: str) -> dict[str, bool]:
    """Per plank of the elastic model: whether its beam runs along its shorter side."""
    design = parse_design(text, "design.yaml", "yaml")
    model = build_elastic_model(design, analyze(design))
    return {design.planks[k].id: crosswise != along_width(design.planks[k])
            for k, crosswise in zip(model.planks, model.beams.crosswise)}


def plank_result(text: str, plank: str):
    report = check_design(parse_design(text, "design.yaml", "yaml"))
    (case,) = report.cases
    return report, next(p for p in case.planks if p.id == plank)


def point_bracket(P: float, w: float, L: float, width: float) -> tuple[float, float]:
    """m: the sag of a beam of span L, section width x T, under a central point load P and
    its weight w (N/m), fixed ends and pinned ends, bending and shear (kappa = 5/6)."""
    EI = E * width * T ** 3 / 12
    kGA = 5 / 6 * G_SHEAR * width * T
    fixed = P * L ** 3 / (192 * EI) + w * L ** 4 / (384 * EI) + P * L / (8 * kGA)
    pinned = P * L ** 3 / (48 * EI) + 5 * w * L ** 4 / (384 * EI) + P * L / (4 * kGA)
    return fixed, pinned


def test_a_deep_top_between_its_sides_spans_across_and_sags():
    """The nightstand's 388 x 400 top, 40 kg at its middle: sag between 0.71 and 2.83 mm
    (module docstring), over a 388 mm span: sagging.  Its shelf, loaded by nothing but
    its weight, spans across too; the sides keep their length."""
    text = nightstand()
    assert spans(text) == {"side_l": False, "side_r": False, "mid": True, "top": True}
    report, top = plank_result(text, "top")
    fixed, pinned = point_bracket(40 * G, RHO * G * 0.4 * T, 0.388, 0.4)
    assert fixed == pytest.approx(0.71e-3, abs=0.01e-3)
    assert pinned == pytest.approx(2.83e-3, abs=0.01e-3)
    assert fixed < top.sag * 1e-3 < pinned       # the report's lengths are in mm
    (sagging,) = report.violations
    assert (sagging.kind, sagging.where) == ("sagging", "top")
    assert "over a 388 mm span" in sagging.message
    assert top.sag_allowed == pytest.approx(388 / 400)


def test_a_top_as_deep_as_it_is_wide_or_less_reads_the_same():
    """The same top 380 mm deep (its longer side is its span: contract 3a as written) sags
    within the 400 mm top's bracket scaled to its section; the two differ by what the
    section's width gives, about 400 / 380 for the point load (its weight per metre
    scales with the width too, and its sag does not)."""
    deep = plank_result(nightstand(400), "top")[1].sag
    shallow = plank_result(nightstand(380), "top")[1].sag
    assert spans(nightstand(380))["top"] is False     # its longer side already spans
    fixed, pinned = point_bracket(40 * G, RHO * G * 0.38 * T, 0.388, 0.38)
    assert fixed < shallow * 1e-3 < pinned
    assert shallow / deep == pytest.approx(400 / 380, rel=0.02)


def test_a_narrow_cabinet_shelf_spans_its_288_mm_and_holds():
    """The narrow cabinet's 288 x 560 shelf with 20 kg of books: between 0.054 and 0.27 mm
    (module docstring), and the design is valid (it read a 2.33 mm overhang before)."""
    report, shelf = plank_result(NARROW, "shelf")
    w = 20 * G / 0.288 + RHO * G * 0.56 * T
    EI = E * 0.56 * T ** 3 / 12
    assert w == pytest.approx(730.7, abs=0.1) and EI == pytest.approx(241.9, abs=0.1)
    fixed, pinned = w * 0.288 ** 4 / (384 * EI), 5 * w * 0.288 ** 4 / (384 * EI)
    assert fixed == pytest.approx(0.054e-3, abs=0.001e-3)
    assert pinned == pytest.approx(0.27e-3, abs=0.01e-3)
    assert fixed < shelf.sag * 1e-3 < pinned + w * 0.288 ** 2 / (8 * 5 / 6 * G_SHEAR * 0.56 * T)
    assert report.valid


def test_what_keeps_its_longer_side():
    """A back panel along the top's whole back edge (three edges held: the beam along its
    depth, held along its length and at its end, is kept), and a seat nailed along its
    length to 100 mm aprons (rails that bend with it over 988 mm: the composite beam)."""
    assert spans(nightstand(back=True))["top"] is False
    assert not any(spans(BENCH).values())


@pytest.mark.parametrize("turn", [90.0, -123.4])
def test_turning_the_design_or_the_top_changes_nothing(turn):
    """The whole nightstand turned about the vertical, and its top described as 400 x 388
    turned by 90 degrees: the same sag (to 1e-9 of itself)."""
    base = plank_result(nightstand(), "top")[1].sag
    turned_top = nightstand().replace(
        "{id: top, size: [388, 400], center: [0, 0, 544]}",
        "{id: top, size: [400, 388], center: [0, 0, 544], rotation: [0, 0, 90]}")
    assert plank_result(turned_top, "top")[1].sag == pytest.approx(base, rel=1e-9)
    c, s = math.cos(math.radians(turn)), math.sin(math.radians(turn))
    lines = []
    for line in nightstand().splitlines():
        if "center: [" in line or "at: [" in line:
            key = "center: [" if "center: [" in line else "at: ["
            head, rest = line.split(key)
            numbers, tail = rest.split("]", 1)
            x, y, z = (float(v) for v in numbers.split(","))
            moved = f"{c * x - s * y:.12g}, {s * x + c * y:.12g}, {z:g}"
            line = f"{head}{key}{moved}]{tail}"
            if "rotation: [" in line:
                line = line.replace("rotation: [0, -90, 0]", f"rotation: [0, -90, {turn:g}]")
            elif key == "center: [":
                line = line.replace("}", f", rotation: [0, 0, {turn:g}]}}")
        lines.append(line)
    moved_sag = plank_result("\n".join(lines) + "\n", "top")[1].sag
    assert moved_sag == pytest.approx(base, rel=1e-9)
