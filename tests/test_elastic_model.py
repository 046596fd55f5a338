"""The elastic model's bookkeeping around the physics (contract section 3a): what counts
as a plank's support for its sag, planks lying on the floor, short planks, square planks,
designs without joints, and the feasibility programs' forces.  Each test states why the
expected value is what it is.
"""

from __future__ import annotations

import numpy as np
import pytest
from click.testing import CliRunner

from furncheck.check import check_design
from furncheck.cli.main import main
from furncheck.design import parse_design
from furncheck.design.model import with_model
from furncheck.geometry import analyze
from furncheck.statics import build_model

CANTILEVER = """\
furncheck: 1
name: cant
model: elastic
planks:
  - {id: base, size: [400, 400], center: [0, 0, 6]}
  - {id: post, size: [800, 400], center: [-150, 0, 412], rotation: [0, -90, 0]}
  - {id: shelf, size: [300, 300], center: [6, 0, 600]}
loads:
  - {plank: shelf, mass: 15, at: [140, 0, 606]}
"""
LIP = "  - {id: lip, size: [20, 300], center: [150, 0, 616], rotation: [0, -90, 0]}\n"
SQUARE = """\
furncheck: 1
model: elastic
planks:
  - {id: side_l, size: [400, 300], center: [-156, 0, 200], rotation: [0, -90, 0]}
  - {id: side_r, size: [400, 300], center: [156, 0, 200], rotation: [0, -90, 0]}
  - {id: shelf, size: [300, 300], center: [0, 0, 300]ROTATION}
loads:
  - {plank: shelf, mass: 20, spread: true}
"""


def _design(text: str, name: str = "d.yaml"):
    return parse_design(text, name, "yaml")


def _planks(report, case: int = 0) -> dict:
    return {p.id: p for p in report.cases[case].planks}


def test_a_lip_that_carries_nothing_is_no_support():
    """A 20 mm lip nailed on top of the cantilever shelf's free end hangs on the shelf and
    reaches the ground only through it: it does not carry the shelf, so the shelf is still
    a cantilever from the post (its joint at its end face, x = -144: span twice its 300 mm
    overhang, allowed sag 600 / 400 = 1.5 mm) and its sag changes only
    by the lip's own 0.054 kg at the tip (0.4 % of the 15 kg)."""
    plain = _planks(check_design(_design(CANTILEVER)))["shelf"]
    lipped = _planks(check_design(_design(CANTILEVER.replace("loads:\n", LIP + "loads:\n"))))
    assert lipped["shelf"].sag_allowed == pytest.approx(plain.sag_allowed, rel=1e-9)
    assert lipped["shelf"].sag_allowed == pytest.approx(2 * 300 / 400, rel=1e-3)
    assert lipped["shelf"].sag == pytest.approx(plain.sag, rel=0.01)


def test_a_post_is_not_carried_by_the_shelf_it_holds():
    """The post holds the cantilever shelf, which reaches the ground only through it: the
    post's one carrying support is its joint on the base, at its lower end (z = 12), so it
    is measured as a cantilever from there: span twice its 800 mm, allowed sag 1600 / 400
    = 4 mm (not the 588 mm between its two joints)."""
    post = _planks(check_design(_design(CANTILEVER)))["post"]
    assert post.sag_allowed == pytest.approx(2 * 800 / 400, rel=1e-3)


def test_a_plank_lying_on_the_floor_does_not_sag():
    """A 1000 mm board lying flat on the floor touches it with its whole face: the floor
    holds it everywhere, not at the four corners its contacts stand for, so it has no sag
    (and it is valid); ``range`` and ``suggest`` run on it (no nail joints) and exit 0."""
    text = "furncheck: 1\nmodel: elastic\nplanks:\n" \
        "  - {id: board, size: [1000, 300], center: [0, 0, 6]}\n"
    report = check_design(_design(text))
    assert report.valid and _planks(report)["board"].sag == 0.0


def test_range_and_suggest_run_without_joints(tmp_path):
    path = tmp_path / "board.yaml"
    path.write_text("furncheck: 1\nmodel: elastic\nplanks:\n"
                    "  - {id: board, size: [1000, 300], center: [0, 0, 6]}\n")
    runner = CliRunner()
    for command in (["range", str(path)], ["suggest", str(path)]):
        result = runner.invoke(main, command)
        assert result.exit_code == 0, result.output
        assert "Traceback" not in result.output


@pytest.mark.parametrize("size", [(1.5, 0.6), (20.0, 12.0), (30.0, 29.0)])
def test_short_planks_get_elements_of_positive_length(size):
    """A plank shorter than 8 x NODE_MERGE: its nodes merge within a tenth of its grid step,
    so no two nodes coincide and every element has a positive length; alone on the floor
    it is valid, as in the rigid model."""
    text = (f"furncheck: 1\nmodel: elastic\nplanks:\n"
            f"  - {{id: peg, size: [{size[0]}, {size[1]}], center: [0, 0, 6]}}\n")
    design = _design(text)
    model = build_model(design, analyze(design))
    assert np.all(model.beams.length > 0.0)
    assert check_design(design).valid


@pytest.mark.parametrize("gap", [0.001, float(np.nextafter(0.001, 1.0)),
                                 float(np.nextafter(0.001, 0.0)), 0.001 + 6.7e-15])
def test_attachments_a_millimetre_apart_share_a_node_whatever_their_last_bits(gap):
    """Two attachments NODE_MERGE (1 mm) apart along a 12 mm plank, inside it (one grid
    step: the merge distance is min(1 mm, 1.2 mm)), share one node, with the distance
    exactly 1 mm, one unit of the last place above or below it, or 1 mm + 6.7e-15 m (the
    largest error of the tilted bookcase-pins' positions, below); two 1.01 mm apart
    do not."""
    from furncheck.statics.elastic import _plank_nodes

    def shared(distance: float) -> bool:
        nodes = _plank_nodes(0, 0.006, [(-0.004, ("joint", 0)),
                                        (-0.004 + distance, ("contact", 1))])
        (holding,) = [set(node[1:]) for node in nodes if ("joint", 0) in node[1:]]
        return ("contact", 1) in holding

    assert shared(gap)
    assert not shared(0.00101)


def test_a_tilted_shelfs_pins_do_not_flip_from_one_hundredth_of_a_degree_to_the_next():
    """bookcase-pins with its shelf turned 8.69 to 8.72 degrees about x (the edit's
    structure has shortened pin_lb, which the shelf's back edge now bears on, to 0.88 to
    0.94 mm, so that its beam runs along its 12 mm width): two of the shelf's bearing
    corners lie 1 mm from the pin's joint along that beam, to 7e-15 m.  Its verdict and
    the pin's stress are the same at each angle: before, the two shared a node or not as
    the last bits of the turned positions fell, and the pin read 23 N/mm^2 (overstressed)
    and 0.003 N/mm^2 (valid) by turns."""
    from pathlib import Path

    from furncheck.design import load_design
    from furncheck.dofs import apply_dof, parse_dof, structure
    from furncheck.edit_check import standing_geometry

    path = Path(__file__).resolve().parent.parent / "designs" / "bookcase-pins.yaml"
    design = with_model(load_design(str(path)), "elastic")
    frame = structure(design, standing_geometry(analyze(design)))
    turn = parse_dof(design, "shelf.rx")
    seen = set()
    for degrees in (8.69, 8.70, 8.71, 8.72):
        report = check_design(apply_dof(design, frame, turn, degrees))
        pin = _planks(report)["pin_lb"]
        seen.add((report.valid, round(pin.stress, 1)))
    assert len(seen) == 1, seen


def _same_results(reports) -> None:
    """The second report's planks (sag, stress) and joints (pull) are the first's."""
    first, turned = (_planks(r) for r in reports)
    for plank in first:
        assert turned[plank].sag == pytest.approx(first[plank].sag, rel=1e-9, abs=1e-12)
        assert turned[plank].stress == pytest.approx(first[plank].stress, rel=1e-9)
    for a, b in zip(reports[0].cases[0].joints, reports[1].cases[0].joints):
        assert b.pull == pytest.approx(a.pull, rel=1e-9)


def test_a_square_shelf_turned_by_90_degrees_is_the_same_shelf():
    """A 300 x 300 shelf between two sides, described as is and turned 90 degrees about its
    normal (the same box): its beam runs between the sides both times (the side over which
    its joints are spread), so sags, stresses and joint forces agree."""
    reports = [check_design(_design(SQUARE.replace("ROTATION", rotation)))
               for rotation in ("", ", rotation: [0, 0, 90]")]
    _same_results(reports)


@pytest.mark.parametrize("turn", [90, 180, 270])
def test_a_square_shelf_nailed_by_one_edge_turned_is_the_same_shelf(turn):
    """designs/shelf-cantilever.yaml with 15 kg on its 300 x 300 shelf, nailed to the post
    by one edge: the joint's points do not say which way the shelf spans (one joint, one
    point), so its beam runs across the joint line, away from the post, however the file
    turns the shelf about its normal (it ran along the file's local x: turned 90 degrees,
    the shelf sagged 0.013 instead of 3.18 mm and the design read valid).  The same
    verdicts, sags, stresses and nail forces."""
    text = """furncheck: 1
planks:
  - {id: base, size: [400, 400], center: [0, 0, 6]}
  - {id: post, size: [800, 400], center: [-150, 0, 412], rotation: [0, -90, 0]}
  - {id: shelf, size: [300, 300], center: [6, 0, 600]ROTATION}
loads: [{plank: shelf, mass: 15, at: [0, 0, 606]}]
"""
    reports = [check_design(parse_design(text.replace("ROTATION", rotation), "s.yaml", "yaml"))
               for rotation in ("", f", rotation: [0, 0, {turn}]")]
    assert _planks(reports[0])["shelf"].sag > 1.0         # mm: the cantilever, not 0.013
    assert [v.kind for v in reports[1].violations] == [v.kind for v in reports[0].violations]
    _same_results(reports)


@pytest.mark.parametrize("turn", [90, 180, 270])
def test_a_square_board_loaded_off_centre_turned_is_the_same_board(turn, floor_at_corners):
    """A 600 x 600 board held at its four corners (``floor_at_corners``: on four narrow
    feet; the floor would hold it all over) with 40 kg at (250, 60) mm: its corners and no
    joint say nothing of which way it spans, so its beam runs along the side its load
    lies farthest out on (x, 250 mm from the centre), however the file turns it (it ran
    along the file's local x: 1.29 N/mm^2 as written, 4.09 turned 90 degrees)."""
    text = """furncheck: 1
planks: [{id: board, size: [600, 600], center: [0, 0, 6], rotation: [0, 0, TURN]}]
loads: [{plank: board, mass: 40, at: [250, 60, 12]}]
"""
    first, turned = (_planks(check_design(parse_design(text.replace("TURN", str(angle)),
                                                       "b.yaml", "yaml")))
                     for angle in (0, turn))
    assert first["board"].stress > 0.5                  # N/mm^2
    assert turned["board"].stress == pytest.approx(first["board"].stress, rel=1e-9)


def test_program_forces_balance_the_loads_in_the_elastic_model():
    """designs/l-shelf-pushed.yaml run elastic: its friction phase gives up and the
    programs decide (as in the rigid model).  Their ground forces must balance every load
    of the case, over all the model's nodes: sum = -(weight + push) to 1e-6 of the weight;
    pushed 1.6 times as hard with mu = 0.5 it slides (mu W = 10 N < 27 N), as rigid planks
    do."""
    from pathlib import Path

    text = (Path(__file__).resolve().parents[1] / "designs" / "l-shelf-pushed.yaml").read_text()
    design = with_model(_design(text), "elastic")
    case = check_design(design).cases[0]
    weight = sum(design.plank_mass(p) for p in design.planks) * 9.81
    push = np.array([9.77091957, 14.0397457, 0.0])
    total = np.sum([c.force for c in case.contacts], axis=0)
    assert case.stability == "stable"
    assert np.abs(total - np.array([-push[0], -push[1], weight])).max() <= 1e-6 * weight
    harder = text.replace("friction: 0.8568", "friction: 0.5") \
        .replace("force: [9.77091957, 14.0397457, 0.0]", "force: [15.6335, 22.4636, 0.0]")
    for model in ("elastic", "rigid"):
        pushed = with_model(_design(harder), model)
        assert check_design(pushed).cases[0].stability == "sliding", model
