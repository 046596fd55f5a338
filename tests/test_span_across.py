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
  mm, and pinned ends, P L^3 / 48 EI + 5 w L^4 / 384 EI + P L / (4 kappa G A) = 2.84 mm.
  Either way 1.5 x sag is over L / 400 = 0.97 mm: sagging, over a 388 mm span.
* A narrow cabinet's shelf, 288 mm between its sides and 560 mm deep, 20 kg of books
  spread on it (w = 196.2 / 0.288 + 750 x 9.81 x 0.56 x 0.012 = 730.7 N/m, EI = 241.9 N
  m^2): between w L^4 / 384 EI = 0.054 mm and 5 w L^4 / 384 EI = 0.27 mm.  Along its
  depth, held at the joints' middles, it read "sags 2.33 mm at the free end of its
  280 mm overhang" (a false failure, its message said the model overstated it).
* The same top with a back panel nailed along its back edge as well (held on three
  edges) still spans across, held at its back too: it sags less than without the back,
  and still more than the allowed 0.97 mm / 1.5 (a Mindlin plate held on those three
  edges, ``benchmarks/compare_plate.py``: 0.90 mm with clamped, 2.23 mm with simply
  supported edges).
* What keeps the longer side: the top nailed all round (a front panel too: a plate held
  on four edges; the README's limits), and a seat on two 100 mm aprons along its
  1200 mm length (the aprons bend with it: a rail, not a panel).
* The rule's own cases: sides that hold less than three quarters of the top's edges
  (SPAN_ACROSS_COVER: 200 mm deep sides under the 400 mm top) leave it its length, and
  its overhang's bending along it; 300 mm sides hold it across; sides hold its edges
  straight where, bending in their plane, they give less than the top does across
  (SPAN_ACROSS_STIFFNESS), or stand on the floor along them (30 mm battens); a cleat
  nailed under its middle, or a wall at its back, changes nothing.
* Rigid motions, metres, and turning the top's description by 90 degrees change
  nothing, also for a design drawn at the rule's round numbers (sides exactly three
  quarters of the top's depth) and one hung on a wall.
"""

from __future__ import annotations

import physics_designs as pd
import pytest
import yaml

from furncheck import tolerances as tol
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
FRONT = "  - {id: front, size: [412, 550], center: [0, -206, 275], rotation: [90, 0, 0]}"

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
name: bench-on-aprons
planks:
  - {id: seat, size: [1200, 300], center: [0, 0, 444]}
  - {id: apron_f, size: [1200, 100], center: [0, 144, 388], rotation: [90, 0, 0]}
  - {id: apron_b, size: [1200, 100], center: [0, -144, 388], rotation: [90, 0, 0]}
  - {id: leg_l, size: [400, 276], center: [-550, 0, 200], rotation: [0, -90, 0]}
  - {id: leg_r, size: [400, 276], center: [550, 0, 200], rotation: [0, -90, 0]}
loads:
  - {plank: seat, mass: 80, at: [0, 0, 450]}
"""

HANGING = """furncheck: 1
name: hanging-box
walls:
  - {point: [0, 200, 0], normal: [0, -1, 0]}
planks:
  - {id: side_l, size: [200, 400], center: [-200, 0, 1100], rotation: [0, -90, 0]}
  - {id: side_r, size: [200, 400], center: [200, 0, 1100], rotation: [0, -90, 0]}
  - {id: top, size: [388, 400], center: [0, 0, 1194]}
anchors:
  - {plank: side_l, at: [-200, 200, 1180], wall: 0, capacity: 5000}
  - {plank: side_l, at: [-200, 200, 1020], wall: 0, capacity: 5000}
  - {plank: side_r, at: [200, 200, 1180], wall: 0, capacity: 5000}
  - {plank: side_r, at: [200, 200, 1020], wall: 0, capacity: 5000}
loads:
  - {plank: top, mass: 30, at: [0, 0, 1200]}
"""


def nightstand(depth: float = 400, back: bool = False, front: bool = False) -> str:
    panels = "\n".join([BACK] * back + [FRONT] * front)
    return NIGHTSTAND.replace("@D", f"{depth:g}").replace("@BACK", panels)


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
    """The nightstand's 388 x 400 top, 40 kg at its middle: sag between 0.71 and 2.84 mm
    (module docstring), over a 388 mm span: sagging.  Its shelf, loaded by nothing but
    its weight, spans across too; the sides keep their length."""
    text = nightstand()
    assert spans(text) == {"side_l": False, "side_r": False, "mid": True, "top": True}
    report, top = plank_result(text, "top")
    fixed, pinned = point_bracket(40 * G, RHO * G * 0.4 * T, 0.388, 0.4)
    assert fixed == pytest.approx(0.71e-3, abs=0.01e-3)
    assert pinned == pytest.approx(2.84e-3, abs=0.01e-3)
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


def test_a_top_with_a_back_spans_across_too_and_sags_less():
    """The top with a back panel nailed along its back edge as well: its joint lines
    across it (the back's, 388 mm) are less than 1.5 times its 388 mm side
    (SPAN_ACROSS_CROSSING), so it spans across, held at its back by the back's row: it
    sags less than the open top, and still over 0.97 / 1.5 mm (sagging)."""
    assert spans(nightstand(back=True))["top"] is True
    open_sag = plank_result(nightstand(), "top")[1].sag
    report, top = plank_result(nightstand(back=True), "top")
    assert 0.97 / 1.5 < top.sag < open_sag
    assert [(v.kind, v.where) for v in report.violations] == [("sagging", "top")]


def test_what_keeps_its_longer_side(monkeypatch):
    """A front and a back panel along both the top's short edges (four edges held, 776
    mm of lines across it: a plate; the beam along its depth, as contract 3a has it), and
    a seat nailed only along its length to two 100 mm aprons: bending in their plane
    over the 1200 mm line they give L^3 / (E t h^3) = 1.728 / (E 0.012 x 0.001), 14
    times what the 300 mm deep seat gives across its 276 mm between them, s^3 / (E w
    t^3) = 0.0210 / (E 1.2 x 1.728e-6) (SPAN_ACROSS_STIFFNESS 1): rails that bend with
    it, the composite beam.  Counted as panels (SPAN_ACROSS_STIFFNESS 20), the aprons
    would hold the seat across."""
    assert spans(nightstand(back=True, front=True))["top"] is False
    apron = 1.2 ** 3 / (0.012 * 0.1 ** 3)
    seat = 0.276 ** 3 / (1.2 * 0.012 ** 3)
    assert apron / seat == pytest.approx(14.3, abs=0.1)
    assert spans(BENCH)["seat"] is False
    monkeypatch.setattr(tol, "SPAN_ACROSS_STIFFNESS", 20.0)
    assert spans(BENCH)["seat"] is True


def with_sides(depth: float, text: str = "") -> str:
    """The nightstand with sides ``depth`` mm deep at its back (y from 200 - depth to
    200), its top and shelf 400 mm deep."""
    text = text or nightstand()
    for x in (-200, 200):
        text = text.replace(f"{{id: side_{'l' if x < 0 else 'r'}, size: [550, 400], "
                            f"center: [{x}, 0, 275]",
                            f"{{id: side_{'l' if x < 0 else 'r'}, size: [550, {depth:g}], "
                            f"center: [{x}, {200 - depth / 2:g}, 275]")
    return text


def test_sides_holding_three_quarters_of_its_edges_hold_it_across():
    """Sides 300 mm deep hold 300 of the top's 400 mm edges, three quarters
    (SPAN_ACROSS_COVER, to a millimetre): it spans across.  Sides 200 mm deep, at the
    back, hold half: it keeps its length, and its front 200 mm overhang bends along it,
    as a cantilever from the sides' front edges (the 40 kg moved to the overhang's
    middle, 100 mm out, and its weight): at least P a^2 (3 L - a) / 6 EI over the
    overhang L = 0.2 m, a = 0.1 m, EI = 3e9 x 0.388 x 0.012^3 / 12 = 167.6 N m^2,
    0.49 mm."""
    assert spans(with_sides(300))["top"] is True
    assert spans(with_sides(200))["top"] is False
    out = with_sides(200).replace("at: [0, 0, 550]", "at: [0, -100, 550]")
    assert out != with_sides(200)
    sag = plank_result(out, "top")[1].sag
    EI = E * 0.388 * T ** 3 / 12
    assert EI == pytest.approx(167.6, abs=0.1)
    assert sag * 1e-3 > 40 * G * 0.1 ** 2 * (3 * 0.2 - 0.1) / (6 * EI)


PLINTH = """furncheck: 1
name: plinth
planks:
  - {id: batten_l, size: [30, 400], center: [-200, 0, 15], rotation: [0, -90, 0]}
  - {id: batten_r, size: [30, 400], center: [200, 0, 15], rotation: [0, -90, 0]}
  - {id: top, size: [388, 400], center: [0, 0, 24]}
loads:
  - {plank: top, mass: 40, at: [0, 0, 30]}
"""


def test_battens_standing_on_the_floor_hold_a_top_across(monkeypatch):
    """A 388 x 400 top nailed between two 30 mm battens standing on the floor: bending in
    their plane over 400 mm they would give L^3 / (E t h^3) = 0.064 / (E 0.012 x 2.7e-5)
    = 197,531 / E, more than the top across its 388 mm, s^3 / (E w t^3) = 0.0584 / (E 0.4
    x 1.728e-6) = 84,507 / E: rails, but the floor holds them straight along their whole
    length (SPAN_ACROSS_STANDING): the top spans across.  Standing counted for nothing,
    it keeps its length."""
    assert 0.4 ** 3 / (0.012 * 0.03 ** 3) > 0.388 ** 3 / (0.4 * 0.012 ** 3)
    assert spans(PLINTH)["top"] is True
    monkeypatch.setattr(tol, "SPAN_ACROSS_STANDING", 10.0)
    assert spans(PLINTH)["top"] is False


def test_low_or_raised_sides_a_cleat_or_a_wall_change_nothing():
    """150 mm sides standing on the floor, or on a base board lying on it (deep enough in
    their plane: 0.064 / (E 0.012 x 0.003375) = 1,580 / E against the top's 84,507 / E),
    a 30 mm cleat nailed under the top's middle along its depth (a rail: it is left out
    of the cover, not a veto), and a wall behind the nightstand (a wall's contacts are
    not the floor's): the top spans across in each."""
    step = ("furncheck: 1\nname: step\nplanks:\n"
            "  - {id: side_l, size: [150, 400], center: [-200, 0, 75], rotation: [0, -90, 0]}\n"
            "  - {id: side_r, size: [150, 400], center: [200, 0, 75], rotation: [0, -90, 0]}\n"
            "  - {id: top, size: [388, 400], center: [0, 0, 144]}\n"
            "loads:\n  - {plank: top, mass: 40, at: [0, 0, 150]}\n")
    assert spans(step)["top"] is True
    on_board = step.replace("center: [-200, 0, 75]", "center: [-200, 0, 87]") \
        .replace("center: [200, 0, 75]", "center: [200, 0, 87]") \
        .replace("center: [0, 0, 144]", "center: [0, 0, 156]") \
        .replace("at: [0, 0, 150]", "at: [0, 0, 162]") \
        .replace("loads:", "  - {id: base, size: [500, 400], center: [0, 0, 6]}\nloads:")
    assert spans(on_board)["top"] is True
    cleat = nightstand().replace(
        "loads:", "  - {id: cleat, size: [400, 30], center: [100, 0, 523], "
                  "rotation: [90, 0, 90]}\nloads:")
    assert spans(cleat)["top"] is True
    walled = nightstand() + "walls:\n  - {point: [0, -200, 0], normal: [0, 1, 0]}\n"
    assert spans(walled)["top"] is True


@pytest.mark.parametrize("text", [nightstand(), with_sides(300), with_sides(299),
                                  with_sides(298), HANGING],
                         ids=["nightstand", "sides-three-quarters", "sides-299", "sides-298",
                              "hanging"])
@pytest.mark.parametrize("phi", [10.0, 37.0, 60.0, 90.0, -123.4])
def test_rigid_motions_and_metres_change_nothing(text, phi):
    """The nightstand, designs drawn at the rule's round numbers (sides 300 of the top's
    400 mm deep, three quarters; 299, three quarters less the millimetre to spare; 298,
    under it), and one hung on a wall by anchors (its 200 mm sides holding the top
    across), turned about the vertical and moved, and in metres: the same sag (to 1e-9
    of itself)."""
    base = plank_result(text, "top")[1].sag
    design = yaml.safe_load(text)
    moved = pd.to_text(pd.rigid_motion(design, phi, 800.0, -1700.0))
    assert plank_result(moved, "top")[1].sag == pytest.approx(base, rel=1e-9)
    metres = pd.to_text(pd.convert_units(design, "m"))
    assert plank_result(metres, "top")[1].sag * 1000 == pytest.approx(base, rel=1e-9)


def test_turning_the_top_in_the_file_changes_nothing():
    """The top described as 400 x 388 turned by 90 degrees: the same sag."""
    base = plank_result(nightstand(), "top")[1].sag
    turned_top = nightstand().replace(
        "{id: top, size: [388, 400], center: [0, 0, 544]}",
        "{id: top, size: [400, 388], center: [0, 0, 544], rotation: [0, 0, 90]}")
    assert plank_result(turned_top, "top")[1].sag == pytest.approx(base, rel=1e-9)
