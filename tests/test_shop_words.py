"""Continuous advice in a maker's words (``report.shop_words``), on edits made by hand.

The stool (designs/stool.yaml): legs at x = -170 and +170 mm, their length along z
(rotation [0, -90, 0] maps local x to world +z), nailed under the seat and standing on the
floor.  The chair (designs/chair-upright.yaml): its back stands on the seat, its length
along z, its bottom end nailed to the seat and its top free.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from furncheck.design import load_design
from furncheck.design.model import with_model
from furncheck.dofs import apply_dof, parse_dof, structure
from furncheck.edit_check import standing_geometry
from furncheck.geometry import analyze
from furncheck.report.shop_words import continuous_advice

CATALOG = Path(__file__).resolve().parents[1] / "designs"


def edited(design, changes: dict[str, float]):
    frame = structure(design, standing_geometry(analyze(design)))
    for name, change in changes.items():
        design = apply_dof(design, frame, parse_dof(design, name), change)
    return design


def advise(design, changes: dict[str, float], interval=(0.9, 1.2), limited=False) -> str:
    """The advice for ``changes`` made at step 1 (so the quoted interval is the interval
    times the first change's magnitude)."""
    units = tuple("deg" if name.rpartition(".")[2] in ("rx", "ry", "rz") else "mm"
                  for name in changes)
    return continuous_advice(tuple(changes), tuple(changes.values()), units, 1.0, interval,
                             limited, design, edited(design, changes))


def test_a_mirror_pair_moves_apart_or_closer_together():
    """leg_l -20 mm and leg_r +20 mm along x, the mirror plane x = 0 between them: apart,
    20 mm each; the other way round: closer together.  The interval 0.9-1.2 of the step is
    18-24 mm of each leg's move."""
    stool = with_model(load_design(str(CATALOG / "stool.yaml")), "rigid")
    assert advise(stool, {"leg_l.x": -20.0, "leg_r.x": 20.0}) == \
        "Move leg_l and leg_r apart by 20 mm each (valid for 18-24 mm each)."
    assert advise(stool, {"leg_l.x": 20.0, "leg_r.x": -20.0}) == \
        "Move leg_l and leg_r closer together by 20 mm each (valid for 18-24 mm each)."


def test_a_combined_change_quotes_its_first_amount_the_others_in_proportion():
    """Two phrases, the legs apart by 20 mm each and the seat 30 mm higher: the interval
    (0.9-1.2 of the step) is the first phrase's, 18-24 mm each, and the other change
    scales with it, as the words say (a woodworker read 'of the first change' as code);
    a combined change valid up to the search's limit names that limit as the limit for
    the changes together (the limit of one change alone: half the design's size)."""
    stool = with_model(load_design(str(CATALOG / "stool.yaml")), "rigid")
    assert advise(stool, {"leg_l.x": -20.0, "leg_r.x": 20.0, "seat.z": 30.0}) == (
        "Move leg_l and leg_r apart by 20 mm each and raise seat by 30 mm (valid for "
        "18-24 mm each, the other change in proportion).")
    assert advise(stool, {"leg_l.x": -20.0, "leg_r.x": 20.0, "seat.z": 30.0},
                  limited=True).startswith(
        "Move leg_l and leg_r apart by 20 mm each and raise seat by 30 mm (valid for "
        "18-24 mm each, the other change in proportion; the search stopped there, at its "
        "limit for these changes together)")
    assert advise(stool, {"seat.z": 30.0}, limited=True).startswith(
        "Raise seat by 30 mm (valid for 27-36 mm; the search stopped there, at half the "
        "design's size)")


def test_a_tilt_says_where_the_top_goes_and_quotes_magnitudes():
    """leg_r turned -7.55 degrees about y: its top (local x = world +z) turns toward -x,
    toward leg_l; the amount and the interval (5.04-10.1 degrees: 0.667 and 1.333 of the
    step) are magnitudes, no minus sign.  The leg stands on the floor and under the seat,
    so a maker cuts its ends at the tilt's angle to sit flat, and the advice says so, with
    the length along its edges that spans the 438 mm from the floor to the seat tilted:
    438 / cos 7.55 = 441.8 mm."""
    stool = with_model(load_design(str(CATALOG / "stool.yaml")), "rigid")
    text = advise(stool, {"leg_r.ry": -7.55}, interval=(5.04 / 7.55, 10.1 / 7.55))
    assert text == ("Tilt leg_r 7.55 degrees about y, its top toward leg_l, its ends cut at "
                    "7.55 degrees to sit flat (441.8 mm along its edges) (valid for "
                    "5.04-10.1 degrees).")


def test_a_shorter_back_rest_is_its_top_lowered():
    """The chair's back shortened by 79.8 mm: its bottom end is nailed to the seat, so its
    top comes down: 'lower the top of back', not 'shorten back'.  Its seat shortened (no
    end held: both ends move) stays 'shorten'."""
    stool = with_model(load_design(str(CATALOG / "stool.yaml")), "rigid")
    assert advise(stool, {"leg_l.width": 20.0, "leg_r.width": 20.0}).startswith(
        "Widen leg_l and leg_r by 20 mm each (10 mm at each edge) (")
    chair = with_model(load_design(str(CATALOG / "chair-upright.yaml")), "rigid")
    assert advise(chair, {"back.length": -79.8}) == \
        "Lower the top of back by 79.8 mm (valid for 71.8-95.8 mm)."
    assert advise(chair, {"back.length": 20.0}).startswith("Raise the top of back by 20 mm")


def test_a_board_hung_from_its_top_edge_grows_at_its_bottom():
    """The coat rack's back board (900 x 150, flat on the wall, its width along z) has the
    hat shelf nailed onto its top edge: a wider board keeps that edge and reaches further
    down, 'lower the bottom of back', not 'widen back'; a narrower one raises its
    bottom.  A leg nailed under a seat is still shortened ('raise the bottom of leg_m'
    would not be a maker's words)."""
    from shop_designs import COAT_RACK

    from furncheck.design import parse_design

    rack = with_model(parse_design(COAT_RACK.format(right=1620), "coat-rack.yaml", "yaml"),
                      "rigid")
    assert advise(rack, {"back.width": 50.0}).startswith("Lower the bottom of back by 50 mm")
    assert advise(rack, {"back.width": -30.0}).startswith("Raise the bottom of back by 30 mm")
    bench = with_model(load_design(str(CATALOG / "bench-long-leg.yaml")), "rigid")
    assert advise(bench, {"leg_m.length": -2.0}).startswith("Shorten leg_m by 2 mm")


def test_the_search_limit_is_said():
    """An interval whose upper end is the search limit says where the search stopped."""
    stool = with_model(load_design(str(CATALOG / "stool.yaml")), "rigid")
    assert advise(stool, {"seat.z": 30.0}, limited=True) == (
        "Raise seat by 30 mm (valid for 27-36 mm; the search stopped there, at half the "
        "design's size).")


def test_an_interval_that_is_the_search_limit_alone_is_not_a_lone_value():
    """Valid from the step found to the search limit, which round alike: 'valid at 30 mm,
    where the search stopped', not 'valid for 30 mm only, to the search's resolution;
    the search stopped there' (a woodworker read the two as contradicting)."""
    stool = with_model(load_design(str(CATALOG / "stool.yaml")), "rigid")
    assert advise(stool, {"seat.z": 30.0}, interval=(1.0, 1.0001), limited=True) == (
        "Raise seat by 30 mm (valid at 30 mm, where the search stopped, at half the "
        "design's size).")
    assert advise(stool, {"seat.z": 30.0}, interval=(1.0, 1.0001)) == \
        "Raise seat by 30 mm (valid for 30 mm only, to the search's resolution)."


def test_a_mirror_pair_tilted_along_its_plane_names_where_the_tops_go():
    """The stool's legs (mirrored about x = 0, their length along +z) both tilted 5
    degrees about x: R_x(5) turns +z toward -y, so their tops move along -y, the same
    way, neither apart nor together across the plane; with no plank that way the advice
    names the axis ('their tops toward leg_l and leg_r'-like where planks lie there)."""
    stool = with_model(load_design(str(CATALOG / "stool.yaml")), "rigid")
    assert advise(stool, {"leg_l.rx": 5.0, "leg_r.rx": 5.0}) == \
        "Tilt leg_l and leg_r by 5 degrees each, their tops along -y, their ends cut at 5 " \
        "degrees to sit flat (439.7 mm along their edges) (valid for 4.5-6 degrees each)."



@pytest.mark.parametrize(("turn", "words"), [
    (5.0, "their tops leaning in (their feet splayed out)"),
    (-5.0, "their tops leaning out (their feet in)")])
def test_a_mirror_pair_tilted_across_its_plane_says_which_way_they_lean(turn, words):
    """The stool's legs (leg_l at x = -170, leg_r at +170, turned (0, -90, 0): their
    length along +z) tilted by 5 degrees each across their mirror plane x = 0: turning
    leg_r about y by -5 degrees brings its top toward the plane, so the tops lean in and
    the feet splay out (a woodworker read 'their tops together' as the tops touching);
    the other way the tops lean out."""
    stool = with_model(load_design(str(CATALOG / "stool.yaml")), "rigid")
    text = advise(stool, {"leg_l.ry": turn, "leg_r.ry": -turn})
    assert text.startswith(f"Tilt leg_l and leg_r by 5 degrees each, {words}, "), text


def test_planks_that_do_not_stand_on_the_floor_have_no_feet():
    """The stool's legs tilted across their plane as above, the stool drawn 200 mm above
    the floor (a wall unit's brackets, say): their tops lean in, and no feet are named."""
    from furncheck.design.load import parse_design

    text = (CATALOG / "stool.yaml").read_text()
    for z in ("444", "219", "150", "450"):
        text = text.replace(f", {z}]", f", {int(z) + 200}]")
    raised = with_model(parse_design(text, "raised.yaml", "yaml"), "rigid")
    assert min(float(p.corners[:, 2].min()) for p in raised.planks) > 0.19
    advice = advise(raised, {"leg_l.ry": 5.0, "leg_r.ry": -5.0})
    assert advice.startswith("Tilt leg_l and leg_r by 5 degrees each, their tops leaning "
                             "in, "), advice
    assert "feet" not in advice


def test_a_leg_moved_in_under_its_seat_goes_toward_the_leg_opposite():
    """A splayed leg (its top nailed under the seat's edge) moved 50 mm along -x: the seat's
    centre lies 54 degrees off that way (within the 60 of 'toward') and nearer than the
    leg opposite (straight ahead), but the leg hangs from the seat, so 'toward seat' says
    nothing: the move goes toward leg_mm (the legs are not parallel, each splayed 10
    degrees the other way)."""
    from shop_designs import SPLAYED_STOOL

    from furncheck.design.load import parse_design

    stool = parse_design(SPLAYED_STOOL, "splayed.yaml", "yaml")
    assert advise(stool, {"leg_pm.x": -50.0}) == \
        "Move leg_pm 50 mm toward leg_mm (valid for 45-60 mm)."


BENCH_WITH_BACK = """\
furncheck: 1
name: hall-bench
material: {thickness: 18}
planks:
  - {id: side_l, size: [450, 350], center: [-491, 0, 225], rotation: [0, -90, 0]}
  - {id: side_r, size: [450, 350], center: [491, 0, 225], rotation: [0, -90, 0]}
  - {id: seat, size: [1000, 350], center: [0, 0, 459]}
  - {id: back, size: [1000, 400], center: [0, -166, 668], rotation: [90, 0, 0]}
"""


def test_a_back_rest_on_edge_tilted_says_where_its_top_edge_goes():
    """A bench's back rest stands on edge on the seat's rear (length along x, width up,
    at y = -166 mm behind the seat's middle): turned about x, its length stays level, so
    'which end rises' says nothing (turned about y, it does); its top edge moves, toward
    the seat (-5.5 degrees about x: the top edge, above the axis, goes to +y) or away
    from it (nothing is there: no phrase), as a woodworker's trial asked."""
    from furncheck.design import parse_design

    bench = with_model(parse_design(BENCH_WITH_BACK, "bench.yaml", "yaml"), "rigid")
    assert advise(bench, {"back.rx": -5.5}, interval=(1.0, 2.0)) == \
        "Tilt back 5.5 degrees about x, its top edge toward seat (valid for 5.5-11 degrees)."
    assert advise(bench, {"back.rx": 5.5}, interval=(1.0, 2.0)) == \
        "Tilt back 5.5 degrees about x (valid for 5.5-11 degrees)."
    # turned about y its length rises at one end: that end is what the advice names
    assert advise(bench, {"back.ry": 4.0}, interval=(1.0, 2.0)) == \
        "Tilt back 4 degrees about y, raising its end toward side_l (valid for 4-8 degrees)."


def test_a_mirror_pair_hung_by_their_top_edges_grows_at_their_bottoms():
    """The wall shelf's two cleats (a mirror pair about x = 0) carry the shelf on their
    top edges: widened together, they keep those edges and reach further down, 'lower
    the bottom of cleat_l and cleat_r ... each' (the pair's words were 'widen', as if both
    edges moved; the same rule a single board has)."""
    shelf = with_model(load_design(str(CATALOG / "wall-shelf.yaml")), "rigid")
    assert advise(shelf, {"cleat_l.width": 230.0, "cleat_r.width": 230.0}) == \
        "Lower the bottom of cleat_l and cleat_r by 230 mm each (valid for 207-276 mm each)."


def test_an_end_cut_is_asked_only_of_ends_that_sit_square_now():
    """The cut is the angle the tilted plank's length makes with the normal of what each
    end sits on, asked only where the ends sit square now: a leg already drawn 10 degrees
    off upright has ends the model takes as they are (tilted 5 more, or back upright, no
    cut is named), while the stool's upright leg tilted 5 degrees about x has both ends,
    on the floor and under the seat, cut at 5 degrees, 438 / cos 5 = 439.7 mm along its
    edges."""
    stool = with_model(load_design(str(CATALOG / "stool.yaml")), "rigid")
    tilted = edited(stool, {"leg_r.ry": -10.0})
    for change in (-5.0, 10.0):
        assert "cut" not in advise(tilted, {"leg_r.ry": change}), change
    assert advise(stool, {"leg_r.rx": 5.0}) == (
        "Tilt leg_r 5 degrees about x, its ends cut at 5 degrees to sit flat (439.7 mm along "
        "its edges) (valid for 4.5-6 degrees).")


def test_a_board_cut_shorter_at_both_ends_says_how_much_comes_off_each():
    """The tipping bench's seat (1200 mm, its legs nailed under it, neither end held):
    its length change keeps its centre, so 546 mm shorter is 273 mm off each end, and a
    maker must know which: the advice says so; widened by 490 mm, 245 mm at each edge.
    The chair's back, nailed to the seat by its bottom end, grows at its top only: no
    such note (its phrase says it raises its top)."""
    bench = with_model(load_design(str(CATALOG / "bench-tips.yaml")), "rigid")
    assert advise(bench, {"seat.length": -546.0}) == \
        "Shorten seat by 546 mm (273 mm off each end) (valid for 491-655 mm)."
    assert advise(bench, {"seat.length": -553.0}).startswith(
        "Shorten seat by 553 mm (276.5 mm off each end) (")          # not 277
    assert advise(bench, {"seat.width": 490.0}).startswith(
        "Widen seat by 490 mm (245 mm at each edge) (valid for")
    stool = with_model(load_design(str(CATALOG / "stool.yaml")), "rigid")
    assert advise(stool, {"leg_l.width": 20.0, "leg_r.width": 20.0}).startswith(
        "Widen leg_l and leg_r by 20 mm each (10 mm at each edge) (")
    chair = with_model(load_design(str(CATALOG / "chair-upright.yaml")), "rigid")
    assert advise(chair, {"back.length": 10.0}).startswith("Raise the top of back by 10 mm (")


def test_planks_resized_to_follow_are_named_with_their_new_sizes():
    """The stool's rung runs between its legs (328 mm, nailed to both): moving leg_l 40 mm
    toward leg_r shortens the rung by the same 40 mm (328 -> 288 mm), moving both legs
    apart by 25 mm each lengthens it by 50 mm (378 mm); the sentence names it after the
    interval, as the cut list has it.  A plank the DOFs change themselves, or whose new
    size the rest of the suggestion's words give already (a discrete fix's own cuts), is
    not named again; one only thickened there is."""
    from furncheck.report.shop_words import follow_phrase
    from furncheck.suggest.cutlist import plank_edits

    stool = with_model(load_design(str(CATALOG / "stool.yaml")), "rigid")
    closer = edited(stool, {"leg_l.x": 40.0})
    edits = plank_edits(stool, closer)
    assert continuous_advice(("leg_l.x",), (40.0,), ("mm",), 1.0, (0.9, 1.2), False, stool,
                             closer, follow_phrase(edits, {"leg_l"}, "mm")) == \
        "Move leg_l 40 mm toward leg_r (valid for 36-48 mm); to fit, shorten rung by 40 mm " \
        "(328 -> 288 mm)."
    apart = plank_edits(stool, edited(stool, {"leg_l.x": -25.0, "leg_r.x": 25.0}))
    assert follow_phrase(apart, {"leg_l", "leg_r"}, "mm") == \
        "; to fit, lengthen rung by 50 mm (328 -> 378 mm)"
    assert follow_phrase(apart, {"leg_l", "leg_r", "rung"}, "mm") == ""
    nudged = plank_edits(stool, edited(stool, {"leg_l.x": 1.5}))        # as the cut list
    assert follow_phrase(nudged, {"leg_l"}, "mm") == \
        "; to fit, shorten rung by 1.5 mm (328 -> 326.5 mm)"
    said = "make seat 22 mm thick (now 12 mm); cut {} 3 mm shorter (328 -> 325 mm) to make room"
    assert follow_phrase(apart, {"leg_l", "leg_r"}, "mm", said.format("rung")) == ""
    assert follow_phrase(apart, {"leg_l", "leg_r"}, "mm", said.format("rung_b")) != ""
    assert follow_phrase(apart, {"leg_l", "leg_r"}, "mm", "make rung 22 mm thick") != ""
