"""The shop's score that ranks suggestions (``suggest.score``), by hand.

Designs in millimetres; the score's relative changes: a size change over the old size, a
move over the design's size (its largest bounding-box edge), a turn in radians, an added
plank 1; plus PLANK_COST = 0.05 per plank touched.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from shop_designs import WALL_SHELF_LONG

from furncheck.design.load import parse_design
from furncheck.design.model import with_model
from furncheck.geometry import analyze
from furncheck.suggest.cutlist import plank_edits
from furncheck.suggest.score import ShopScore, shop_score
from furncheck.suggest.symmetry import mirror_planes

CATALOG = Path(__file__).resolve().parents[1] / "designs"
STOOL = (CATALOG / "stool.yaml").read_text()

SHELF = """
furncheck: 1
name: shelf
units: mm
planks:
  - {id: side_l, size: [900, 300], center: [-906, 0, 450], rotation: [0, -90, 0]}
  - {id: side_r, size: [900, 300], center: [906, 0, 450], rotation: [0, -90, 0]}
  - {id: shelf, size: [1800, 300], center: [0, 0, 456]}
"""


def score_of(before_text: str, after_text: str, model: str | None = None) -> ShopScore:
    before = parse_design(before_text, "a.yaml", "yaml")
    after = parse_design(after_text, "b.yaml", "yaml")
    if model is not None:
        before, after = with_model(before, model), with_model(after, model)
    return shop_score(before, analyze(before), mirror_planes(before), after,
                      plank_edits(before, after))


def test_relative_change_and_planks_touched():
    """The stool's size is its height, 450 mm (seat 400 mm long, legs' outer faces at
    +-176 mm, 300 mm deep).  Its rung shortened from 328 to 246 mm (-25 %) and raised
    45 mm: its largest relative change is 0.25 (45 / 450 = 0.1 is smaller); one plank:
    cost 0.25 + 0.05 = 0.3.  The rung, across the mirror plane, stays symmetric."""
    after = STOOL.replace("{id: rung, size: [328, 80], center: [0, 0, 150]",
                          "{id: rung, size: [246, 80], center: [0, 0, 195]")
    score = score_of(STOOL, after)
    assert score.touched == 1
    assert score.cost == pytest.approx(0.25 + 0.05)
    assert score.implausible == () and score.broken == 0


def test_a_turn_counts_in_radians_and_an_added_plank_as_one():
    """The rung turned 9 degrees about x: pi / 20 = 0.157 + 0.05; a brace added: 1 + 0.05."""
    turned = STOOL.replace("rotation: [90, 0, 0]}", "rotation: [99, 0, 0]}")
    assert score_of(STOOL, turned).cost == pytest.approx(math.pi / 20 + 0.05)
    added = STOOL.replace("loads:", "  - {id: brace, size: [300, 80], center: [0, 100, 150], "
                                    "rotation: [90, 0, 0]}\nloads:", 1)
    assert score_of(STOOL, added).cost == pytest.approx(1.05)


def test_a_plank_longer_than_a_stock_board_is_implausible():
    """The 1800 mm shelf lengthened to 2500 mm (with the sides moved out) no longer fits a
    2440 x 1220 mm sheet; at 2400 mm it still does."""
    long = SHELF.replace("[1800, 300]", "[2500, 300]").replace("-906", "-1256") \
        .replace("[906", "[1256")
    fits = SHELF.replace("[1800, 300]", "[2400, 300]").replace("-906", "-1206") \
        .replace("[906", "[1206")
    assert score_of(SHELF, long).implausible == ("shelf is larger than a stock board",)
    assert score_of(SHELF, fits).implausible == ()


def test_a_plank_already_too_long_may_change():
    """A 2500 mm shelf (too long for one sheet already) lengthened to 2600 mm: the
    proportion was the maker's, nothing implausible is added."""
    long = SHELF.replace("[1800, 300]", "[2500, 300]").replace("-906", "-1256") \
        .replace("[906", "[1256")
    longer = SHELF.replace("[1800, 300]", "[2600, 300]").replace("-906", "-1306") \
        .replace("[906", "[1306")
    assert score_of(long, longer).implausible == ()


def test_a_leg_wider_than_the_seat_it_holds_is_implausible():
    """The stool's leg_l widened from 300 mm to 594 mm under the seat, 300 mm wide along
    y (the leg's end face runs along y): 594 > 300 + 0.5 mm.  Widened to 300.4 mm it is
    still within the tolerance.  (At 594 mm its width also passes its 438 mm length, so
    the elastic model's beam would run across it: the second reason.)"""
    wide = STOOL.replace("{id: leg_l, size: [438, 300]", "{id: leg_l, size: [438, 594]")
    slight = STOOL.replace("{id: leg_l, size: [438, 300]", "{id: leg_l, size: [438, 300.4]")
    assert score_of(STOOL, wide).implausible == (
        "leg_l is wider than seat, which it is nailed to",
        "leg_l is 438 x 594 mm now, and the elastic model turns the beam with it (one beam "
        "along the longer side, or across between panels nailed along both edges), so the "
        "fix may be the model's")
    assert score_of(STOOL, slight).implausible == ()


def test_a_leg_moved_off_the_seat_it_holds_is_implausible():
    """The stool's leg_l (its 300 mm wide end nailed under the seat, 300 mm deep along y)
    moved 90 mm along y: its end spans -60 .. 240 mm against the seat's -150 .. 150, so
    90 mm of it, 30 %, hangs past the seat's edge (over HANG_SHARE, a quarter); moved
    60 mm, 20 %, it does not count."""
    leg = "{id: leg_l, size: [438, 300], center: [-170, 0, 219]"
    moved = STOOL.replace(leg, "{id: leg_l, size: [438, 300], center: [-170, 90, 219]")
    less = STOOL.replace(leg, "{id: leg_l, size: [438, 300], center: [-170, 60, 219]")
    assert score_of(STOOL, moved).implausible == (
        "leg_l hangs 30 % of its end past the edge of seat, which it is nailed to",)
    assert score_of(STOOL, less).implausible == ()


def test_an_end_that_already_hung_past_may_move():
    """leg_l drawn with 150 mm of its end (50 %) past the seat's edge, moved 50 mm further
    (67 %): the maker drew it hanging (a shelf's back edge on a narrow back slat), so
    nothing implausible is added.  (The stool without its rung, whose end the moved leg
    would leave.)"""
    leg = "{id: leg_l, size: [438, 300], center: [-170, 0, 219]"
    bare = "\n".join(line for line in STOOL.splitlines() if "id: rung" not in line)
    drawn = bare.replace(leg, "{id: leg_l, size: [438, 300], center: [-170, 150, 219]")
    further = bare.replace(leg, "{id: leg_l, size: [438, 300], center: [-170, 200, 219]")
    assert score_of(drawn, further).implausible == ()


TWO_BOARDS = """
furncheck: 1
name: two boards
units: mm
planks:
  - {{id: top_l, size: [500, 600], center: [-250, 0, 706]}}
  - {{id: top_r, size: [500, 600], center: [250, 0, 706]}}
  - {{id: leg, size: [700, 300], center: [{x}, 0, 350], rotation: [0, -90, 90]}}
"""


def test_an_end_under_the_seam_of_two_boards_is_covered_by_both():
    """A 300 mm wide leg, turned 90 degrees about z so that its end's long side runs
    along x, under a top of two 500 mm boards meeting at x = 0, moved from x = -100 to
    0: half its end under each board, none of it in the air (each board alone would
    leave half of it hanging), so the hang rule adds nothing.  (top_l, held by the leg
    alone, overhangs it by 350 of its 500 mm now, 70 %, where it did by 250, 50 %: an
    overhang past a third that grows, which the overhang rule names.)"""
    before = TWO_BOARDS.format(x=-100)
    after = TWO_BOARDS.format(x=0)
    assert score_of(before, after).implausible == (
        "top_l overhangs its supports by 70 % of its length (it was 50 %)",)


ONE_TOP = """
furncheck: 1
name: one top
units: mm
planks:
  - {{id: top, size: [1000, 600], center: [0, 0, 706]}}
  - {{id: leg, size: [700, 300], center: [{x}, {y}, 350], rotation: [0, -90, 45]}}
"""


def test_an_end_turned_in_the_face_plane_is_clipped_to_the_outline():
    """The leg turned 45 degrees about z: its 300 mm end runs along (-0.707, 0.707) from
    its centre, under a 1000 x 600 top (edges at x = +-500, y = +-300).  Centred at
    (440, 100), it reaches x = 500 after 60 / 0.707 = 84.9 mm toward -s: 65.1 mm, 22 %,
    hangs past; centred at (470, 150), after 42.4 mm: 107.6 mm, 36 % (over a quarter),
    implausible (less the design's 0.5 mm tolerance: 35.6 %).  The top's outline
    projected on the end's direction (its 1131 mm shadow, centred where the top is)
    covers both ends whole: it would have read 0.  (The top, on this one leg, also
    overhangs it by more than a third, more than it did: the overhang rule's reason,
    left out here.)"""
    base = ONE_TOP.format(x=0, y=0)
    near = ONE_TOP.format(x=440, y=100)
    past = ONE_TOP.format(x=470, y=150)

    def hanging(after):
        return tuple(r for r in score_of(base, after).implausible if " hangs " in r)

    assert hanging(near) == ()
    assert hanging(past) == (
        "leg hangs 36 % of its end past the edge of top, which it is nailed to",)


def test_a_plank_resized_past_square_is_implausible_in_the_elastic_model():
    """The stool's 400 x 300 mm seat on two 60 mm wide legs, widened to 420 mm: its longer
    side is now its width, and the elastic model's one beam per plank (contract 3a: along
    the longer side) turns with it, so whatever the edit repairs may be the turn's doing;
    the rigid model has no beam, and a seat widened to 390 mm (still longer than wide) is
    no turn.  On the catalog stool's 300 mm wide legs the seat spans across between them
    past the square while their nail lines cover three quarters of its edges
    (``elastic._spans_across``): no turn at 401 mm, a turn at 420 mm."""
    narrow = STOOL.replace("size: [438, 300]", "size: [438, 60]")
    seat = "{id: seat, size: [400, 300]"
    wider = narrow.replace(seat, "{id: seat, size: [400, 420]")
    still = narrow.replace(seat, "{id: seat, size: [400, 390]")
    reason = ("seat is 400 x 420 mm now, and the elastic model turns the beam with it (one "
              "beam along the longer side, or across between panels nailed along both "
              "edges), so the fix may be the model's")
    assert reason in score_of(narrow, wider).implausible
    assert not any("longer side" in r for r in score_of(narrow, still).implausible)
    rigid = score_of(narrow, wider, model="rigid").implausible
    assert not any("longer side" in r for r in rigid)
    # on the catalog stool's 300 mm legs, panels, a seat 401 mm wide spans across between
    # them (their lines cover 300 of its 401 mm edges, over SPAN_ACROSS_COVER): no turn;
    # 420 mm wide (300 of 420) it keeps its longer side, and turns
    assert 0.300 / 0.401 >= 0.75 - 0.001 / 0.401 > 0.300 / 0.420
    across = score_of(STOOL, STOOL.replace(seat, "{id: seat, size: [400, 401]"))
    assert not any("turns the beam" in r for r in across.implausible)
    turned = score_of(STOOL, STOOL.replace(seat, "{id: seat, size: [400, 420]"))
    assert any(r.startswith("seat is 400 x 420 mm now, and the elastic model turns")
               for r in turned.implausible)


def test_a_beam_turned_by_another_planks_edit_is_named_where_it_is_held_all_along():
    """designs/nightstand-deep.yaml with a back panel: its 388 x 400 top spans across
    between its 400 mm deep sides (``elastic._spans_across``: one short edge nailed
    too).  A front panel added nails it all round: its beam turns to its 400 mm depth,
    held all along by the sides' rows, and reads almost none of its bending (a plate
    held on four edges): the edit's fix may be the model's, and the reason names the top
    (and the shelf, which the front holds too) although neither is changed.  Sides cut
    to 250 mm deep (holding 250 of the 400 mm edges, under SPAN_ACROSS_COVER) turn the
    top's beam back to its depth too, where the sides' rows hold it along 250 mm and it
    reads little of its bending: the same reason.  Two panels added along a table's long
    sides turn its top across, between them, where the shop's top bends too (no
    reason)."""
    nightstand = (CATALOG / "nightstand-deep.yaml").read_text()
    back = "  - {id: back, size: [412, 550], center: [0, 206, 275], rotation: [90, 0, 0]}\n"
    front = "  - {id: front, size: [412, 550], center: [0, -206, 275], rotation: [90, 0, 0]}\n"
    with_back = nightstand.replace("loads:", back + "loads:")
    all_round = with_back.replace("loads:", front + "loads:")
    reason = ("the elastic model turns the beam of shelf and top with the edit (one beam "
              "along the longer side, or across between panels nailed along both edges), "
              "so the fix may be the model's")
    assert reason in score_of(with_back, all_round).implausible
    sides = "size: [550, 400], center: [{x}, 0, 275]"
    cut = with_back
    for x in (-200, 200):
        cut = cut.replace(sides.format(x=x), f"size: [550, 250], center: [{x}, 75, 275]")
    assert cut != with_back
    assert reason in score_of(with_back, cut).implausible
    table = (CATALOG / "table-racking.yaml").read_text()
    panels = ("  - {id: back-1, size: [1000, 712], center: [0, 306, 356], rotation: [90, 0, 0]}\n"
              "  - {id: back-2, size: [1000, 712], center: [0, -306, 356], "
              "rotation: [90, 0, 0]}\n")
    boxed = table.replace("loads:", panels + "loads:", 1)
    assert boxed != table
    assert not any("turns the beam" in r for r in score_of(table, boxed).implausible)


def test_the_ranking_key_is_lexicographic():
    """Plausible before implausible, then the symmetry kept, then the smaller cost."""
    cheap_odd = ShopScore(("leg_l is wider than seat, which it is nailed to",), 0, 0.1, 1)
    asymmetric = ShopScore((), 1, 0.2, 1)
    symmetric = ShopScore((), 0, 0.9, 3)
    cheaper = ShopScore((), 0, 0.5, 1)
    ranked = sorted([cheap_odd, asymmetric, symmetric, cheaper], key=ShopScore.key)
    assert ranked == [cheaper, symmetric, asymmetric, cheap_odd]


BENCH = """
furncheck: 1
name: bench
units: mm
planks:
  - {{id: seat, size: [900, 300], center: [0, 0, 456], thickness: 25}}
  - {{id: leg_l, size: [443.5, 300], center: [{left}, 0, 221.75], rotation: [0, 90, 0]}}
  - {{id: leg_r, size: [443.5, 300], center: [{right}, 0, 221.75], rotation: [0, 90, 0]}}
"""


@pytest.mark.parametrize("left, right, flagged", [
    (-200, 200, False),         # 450 - 206 = 244 mm past the legs: 27 % of 900
    (-113, 113, True),          # 450 - 119 = 331 mm: 36.8 %, over a third
    (-380, 40, True),           # right end 450 - 46 = 404 mm: 44.9 %
])
def test_a_seat_overhanging_its_legs_by_over_a_third_is_implausible(left, right, flagged):
    """A 900 mm bench seat on 12 mm legs at x = -+380 (they reach 386 mm out: 64 mm, 7 %
    of its length, past them at each end).  Legs moved in so that the seat reaches past
    the outer face of a leg by more than OVERHANG_SHARE = 1/3 of its length at one end
    read as implausible (whoever sits on that end tips it), however valid; the seat's
    depth (300 mm, the legs' width) stays covered."""
    from furncheck.suggest.score import OVERHANG_SHARE

    assert OVERHANG_SHARE == pytest.approx(1 / 3)
    before = BENCH.format(left=-380, right=380)
    score = score_of(before, BENCH.format(left=left, right=right))
    reasons = [r for r in score.implausible if "overhangs" in r]
    assert bool(reasons) is flagged
    if flagged:
        reach = 450 - min(abs(left), abs(right)) - 6
        assert reasons == [f"seat overhangs its supports by {round(100 * reach / 900)} % "
                           f"of its length"]


@pytest.mark.parametrize("legs, past", [
    (370, None),            # 24 mm past the legs' faces: 18.8 N m < W d = 27.5 N m
    (300, 94),              # 16 % overhang, under the rule's third: 73.8 > 22.4 N m
    (200, 194),             # 27 %: 152.2 > 15.1 N m
])
def test_a_seat_whose_end_load_tips_the_bench_is_implausible(legs, past):
    """The 900 x 300 x 25 mm bench seat with 80 kg on it (P = 784.8 N), its legs 443.5 x
    300 x 12 mm at x = -+legs: the planks weigh 5.06 + 2 x 1.20 = 7.46 kg, W = 73.2 N at
    x = 0.  The load moved to the seat's end, 50 mm in from it (x = 400: ISO 7172's
    vertical force), tips the bench about the outer face of the leg under that end, x =
    legs + 6 mm, where P a > W d (a = 400 - legs - 6, d = legs + 6): legs at -+380, the
    input, a = 14 mm: 11.0 N m against 28.2 N m, it stands; at -+370 it still does; at
    -+300 and -+200 it tips, which the one-third overhang rule does not see (16 % and
    27 %), and the change reads implausible.  Without the load there is no such reason."""
    before = BENCH.format(left=-380, right=380) + LOADED
    after = BENCH.format(left=-legs, right=legs)
    found = [r for r in score_of(before, after + LOADED).implausible if "tips it over" in r]
    expected = [] if past is None else [
        f"the 80 kg on seat, moved to its end ({past} mm past what the piece stands on), "
        "tips it over: its own 7.46 kg cannot hold it back (before the change it could)"]
    assert found == expected
    assert not [r for r in score_of(BENCH.format(left=-380, right=380), after).implausible
                if "tips it over" in r]


def test_the_tipping_words_are_a_mirror_images_words():
    """Legs moved from -+380 to -200 and +150: both ends tip the bench (194 and 244 mm
    past the legs' faces); the words name the farther, 244 mm, and so do the mirror
    image's (legs at -150 and +200), where the first end found was named before."""
    before = BENCH.format(left=-380, right=380) + LOADED
    words = [[r for r in score_of(before, BENCH.format(left=left, right=right)
                                  + LOADED).implausible if "tips it over" in r]
             for left, right in ((-200, 150), (-150, 200))]
    assert words[0] == words[1] == [
        "the 80 kg on seat, moved to its end (244 mm past what the piece stands on), tips "
        "it over: its own 7.46 kg cannot hold it back (before the change it could)"]


def test_an_end_load_that_tipped_the_input_already_is_not_flagged():
    """The same bench with its legs at -+200 as the input (its end load tips it already:
    the maker drew it so, and the load cases decide) and moved to -+150: no new
    tipping reason."""
    before = BENCH.format(left=-200, right=200) + LOADED
    score = score_of(before, BENCH.format(left=-150, right=150) + LOADED)
    assert not [r for r in score.implausible if "tips it over" in r]


LOADED = "loads:\n  - {plank: seat, mass: 80, at: [0, 0, 468.5]}\n"


def test_an_overhang_that_barely_grows_is_no_new_overhang():
    """Legs at -+154 under the 900 mm seat leave 450 - 160 = 290 mm, 32.2 %, past them;
    moved 11 mm in (-+143: 301 mm, 33.4 %) the seat crosses a third but grows its
    overhang by 1.2 % of its length, less than OVERHANG_GROWTH = 5 %: not implausible;
    60 mm in (-+94: 350 mm, 38.9 %, 6.7 % more) is."""
    before = BENCH.format(left=-154, right=154)
    small = score_of(before, BENCH.format(left=-143, right=143))
    large = score_of(before, BENCH.format(left=-94, right=94))
    assert not [r for r in small.implausible if "overhangs" in r]
    assert [r for r in large.implausible if "overhangs" in r] == [
        "seat overhangs its supports by 39 % of its length"]


def test_a_chair_seat_across_its_depth_and_an_overhang_already_there():
    """The chair's seat, 400 mm long and 420 mm wide (deep), on sides 400 mm wide at
    y = -+204 (12 mm thick): the sides moved 165 mm in each (y = -+39) leave 210 - 45 =
    165 mm, 39 % of its width, past them: implausible.  A cantilever shelf (held at one
    end: its overhang is the design) may grow: the rule flags only overhangs the input did
    not have."""
    chair = (CATALOG / "chair-upright.yaml").read_text()
    moved = chair.replace("center: [0, -204, 219]", "center: [0, -39, 219]").replace(
        "center: [0, 204, 219]", "center: [0, 39, 219]")
    assert moved != chair
    assert "seat overhangs its supports by 39 % of its width" in score_of(chair,
                                                                          moved).implausible
    cantilever = (CATALOG / "shelf-cantilever.yaml").read_text()
    longer = cantilever.replace("{id: shelf, size: [300, 300], center: [6, 0, 600]}",
                                "{id: shelf, size: [400, 300], center: [56, 0, 600]}")
    assert longer != cantilever
    assert not [r for r in score_of(cantilever, longer).implausible if "overhangs" in r]


SEAT = """
furncheck: 1
name: seat
units: mm
planks:
  - {{id: seat, size: [400, 300], center: [0, 0, {z}]}}
  - {{id: leg_l, size: [{h}, 300], center: [-194, 0, {c}], rotation: [0, -90, 0]}}
  - {{id: leg_r, size: [{h}, 300], center: [194, 0, {c}], rotation: [0, -90, 0]}}
loads:
  - {{plank: seat, mass: 80}}
"""


def seat_at(top: float) -> str:
    """SEAT with its top face ``top`` mm above the floor (12 mm seat on two legs)."""
    height = top - 12.0
    return SEAT.format(z=top - 6.0, h=height, c=height / 2)


@pytest.mark.parametrize("lowered, flagged", [(60.0, False), (85.0, False), (100.0, True),
                                               (200.0, True)])
def test_a_loaded_seat_raised_or_lowered_by_over_a_fifth_is_implausible(lowered, flagged):
    """A seat 450 mm above the floor on two legs, 80 kg on it, lowered with its legs by
    60 mm (to 390 mm: 13 %) or 85 mm (to 365 mm: 18.9 %) is still a seat; by 100 mm (to
    350 mm: 22.2 %, more than HEIGHT_SHARE = 20 %: a bar stool cut from 750 to 581 mm is
    lowered as much) or 200 mm (44 %) it is another piece, and reads as implausible
    however valid (a chair's seat lowered from 450 to 80 mm stood, and ranked with the
    rest; a desk lowered by 33 % passed the third this share was)."""
    from furncheck.suggest.score import HEIGHT_SHARE

    assert HEIGHT_SHARE == pytest.approx(0.2)
    score = score_of(seat_at(450.0), seat_at(450.0 - lowered))
    reasons = [r for r in score.implausible if "above the floor" in r]
    assert reasons == ([f"seat ends {round(450 - lowered)} mm above the floor (it was "
                        f"450 mm: another piece)"] if flagged else [])


def test_a_loaded_board_on_the_floor_may_grow_thicker():
    """A board lying on the floor with a load on it, thickened upward from 12 to 22 mm:
    its top rises from 12 to 22 mm, which is no other piece (the height rule reads only
    the highest loaded level planks clear of the floor)."""
    board = """
furncheck: 1
name: board
units: mm
planks:
  - {{id: base, size: [1600, 300], center: [0, 0, {z}], thickness: {t}}}
loads:
  - {{plank: base, mass: 200, spread: true}}
"""
    score = score_of(board.format(z=6, t=12), board.format(z=11, t=22))
    assert not score.implausible


def test_planks_alike_are_named_together():
    """A shelf unit's two shelves (582 x 300 mm, books on each) both cut to 199 mm by the
    sides moving in: one reason naming both, not one per shelf (a bookshelf of ten such
    shelves read twenty lines).  Their beams do not turn past square: nailed along both
    their 300 mm edges to the sides, they span between them either way
    (``elastic._spans_across``)."""
    unit = """
furncheck: 1
name: two shelves
planks:
  - {id: side_l, size: [900, 300], center: [-297, 0, 450], rotation: [0, -90, 0]}
  - {id: side_r, size: [900, 300], center: [297, 0, 450], rotation: [0, -90, 0]}
  - {id: shelf_a, size: [582, 300], center: [0, 0, 300]}
  - {id: shelf_b, size: [582, 300], center: [0, 0, 600]}
loads:
  - {plank: shelf_a, mass: 10, spread: true}
  - {plank: shelf_b, mass: 10, spread: true}
"""
    narrow = unit.replace("[-297,", "[-105.5,").replace("[297,", "[105.5,") \
        .replace("[582, 300]", "[199, 300]")
    assert score_of(unit, narrow).implausible == (
        "shelf_a and shelf_b are cut to 199 mm of their 582 mm length under their loads",)


def test_a_loaded_top_cut_to_a_strip_is_implausible_a_pushed_leg_narrowed_is_not():
    """A plant stand's 400 mm top with a 25 kg pot, cut to 160 mm (less than half its
    length, SHRINK_SHARE): implausible; to 220 mm: not.  A leg that a push loads, narrowed
    to less than half, is judged by the other rules alone (it is not what the load stands
    on, and its unloaded mirror leg would not be flagged either)."""
    stand = """
furncheck: 1
name: stand
planks:
  - {id: base, size: [300, 300], center: [0, 0, 6]}
  - {id: post, size: [782, 200], center: [0, 0, 403], rotation: [0, -90, 0]}
  - {id: top, size: [400, 400], center: [0, 0, 800]}
loads:
  - {plank: top, mass: 25, at: [0, 0, 806]}
  - {plank: post, force: [10, 0, 0], at: [0, 0, 400]}
"""
    cut = stand.replace("{id: top, size: [400, 400]", "{id: top, size: [160, 400]")
    fine = stand.replace("{id: top, size: [400, 400]", "{id: top, size: [220, 400]")
    thin = stand.replace("{id: post, size: [782, 200]", "{id: post, size: [782, 80]")
    assert "top is cut to 160 mm of its 400 mm length under its load" in \
        score_of(stand, cut).implausible
    assert not any("cut to" in r for r in score_of(stand, fine).implausible)
    assert not any("cut to" in r for r in score_of(stand, thin).implausible)


@pytest.mark.parametrize("tilt, flagged", [(4.0, False), (10.5, True)])
def test_a_loaded_top_tilted_out_of_level_is_implausible(tilt, flagged):
    """A woodworker's wall desk: its top, loaded, turned 10.5 degrees about y (what
    stands on it slides off: implausible, beyond TILT_LIMIT = 5 degrees); by 4 degrees,
    about what a chair's seat slopes back, it is not.  The slope is the angle between
    its broad face and level."""
    from furncheck.suggest.score import TILT_LIMIT

    assert TILT_LIMIT == 5.0
    desk = """
furncheck: 1
name: desk
planks:
  - {{id: side_l, size: [700, 500], center: [-394, 0, 350], rotation: [0, -90, 0]}}
  - {{id: side_r, size: [700, 500], center: [394, 0, 350], rotation: [0, -90, 0]}}
  - {{id: top, size: [800, 500], center: [0, 0, 706], rotation: [0, {tilt}, 0]}}
loads:
  - {{plank: top, mass: 10, spread: true}}
"""
    reasons = [r for r in score_of(desk.format(tilt=0), desk.format(tilt=tilt)).implausible
               if "slope" in r]
    assert reasons == ([f"top slopes {tilt:g} degrees under its load: what stands on it "
                        f"slides off"] if flagged else [])
    # a top drawn sloping (a drafting table's, 8 degrees) may slope further
    assert not [r for r in score_of(desk.format(tilt=8), desk.format(tilt=8.5)).implausible
                if "slope" in r]


def test_a_push_carried_down_with_its_plank_is_implausible():
    """A woodworker's narrow bookcase: a child's 50 N pull at the top (1800 mm up).
    Lowering the top by 261 mm carries the pull down with it (loads ride with their
    plank), and the case then holds only because the lever shrank: 50 N x 1.539 m against
    the 1.8 m the child still reaches on the sides' tops.  Beyond PUSH_DROP_SHARE (10 %)
    of its height below the piece's top that reads as implausible; a 100 mm drop (5.6 %)
    does not, nor does a mass (a load that stands where it is put) carried down, nor the
    pull on a top that stays the highest part of a piece cut down whole."""
    from furncheck.suggest.score import PUSH_DROP_SHARE

    assert PUSH_DROP_SHARE == 0.1
    unit = """
furncheck: 1
name: bookcase
material: {{thickness: 18}}
planks:
  - {{id: side_l, size: [1800, 250], center: [-191, 0, 900], rotation: [0, -90, 0]}}
  - {{id: side_r, size: [1800, 250], center: [191, 0, 900], rotation: [0, -90, 0]}}
  - {{id: top, size: [364, 250], center: [0, 0, {z}]}}
loads:
  - {{plank: top, force: [0, 50, 0], at: [0, 125, {at}]}}
  - {{plank: top, mass: 5, at: [0, 0, {at}]}}
"""
    before = unit.format(z=1791, at=1800)
    low = score_of(before, unit.format(z=1530, at=1539)).implausible
    assert [r for r in low if "push" in r] == [
        "the 50 N push on top moves 261 mm lower with it (case 'default'): it may hold only "
        "because the push moved"]
    # a push given without 'at' acts at its plank's centre: the same
    centred = unit.replace("force: [0, 50, 0], at: [0, 125, {at}]", "force: [0, 50, 0]")
    assert [r for r in score_of(centred.format(z=1791, at=1800),
                                centred.format(z=1530, at=1539)).implausible
            if "push" in r] == ["the 50 N push on top moves 261 mm lower with it (case "
                                "'default'): it may hold only because the push moved"]
    assert not [r for r in score_of(before, unit.format(z=1691, at=1700)).implausible
                if "push" in r]
    # the whole piece cut down, the top still its highest part: the pull goes down with
    # it, as a sitter with a lowered seat (a stool's push on its seat)
    lower = unit.replace("[1800, 250], center: [-191, 0, 900]", "[1539, 250], center: "
                         "[-191, 0, 769.5]").replace("[1800, 250], center: [191, 0, 900]",
                                                     "[1539, 250], center: [191, 0, 769.5]")
    assert not [r for r in score_of(before, lower.format(z=1530, at=1539)).implausible
                if "push" in r]


def test_an_upright_plank_turned_in_plan_is_implausible():
    """A stool's leg turned 8.5 degrees about the vertical (out of square with the seat,
    a woodworker's trial: a brace holds the same push square) reads as implausible,
    beyond TURN_LIMIT = 5 degrees; tilted 4 degrees in its own plane, or across it, it is
    not turned in plan; a level seat turned in plan is left to the other rules."""
    from furncheck.suggest.score import TURN_LIMIT

    assert TURN_LIMIT == 5.0
    turned = STOOL.replace("rotation: [0, -90, 0]}", "rotation: [0, -90, 8.5]}", 1)
    assert turned != STOOL
    reasons = score_of(STOOL, turned).implausible
    assert [r for r in reasons if "in plan" in r] == [
        "leg_l is turned 8.5 degrees in plan, out of square with the piece"]
    tilted = STOOL.replace("rotation: [0, -90, 0]}", "rotation: [0, -86, 0]}", 1)
    across = STOOL.replace("rotation: [0, -90, 0]}", "rotation: [4, -90, 0]}", 1)
    seat = STOOL.replace("{id: seat, size: [400, 300], center: [0, 0, 444]}",
                         "{id: seat, size: [400, 300], center: [0, 0, 444], "
                         "rotation: [0, 0, 9]}")
    assert seat != STOOL
    for edited in (tilted, across, seat):
        assert not [r for r in score_of(STOOL, edited).implausible if "in plan" in r]


def test_a_reclined_slat_rolled_is_not_turned_in_plan():
    """A magazine rack's slat leans back 40 degrees (a reviewer's case): rolled 15
    degrees about y, its long edge turns 0.77 degrees in plan and its face normal's
    horizontal part 6.6; the rule reads only planks standing square (a leg, a side)."""
    from furncheck.dofs import apply_dof, parse_dof, structure
    from furncheck.edit_check import standing_geometry

    design = parse_design((CATALOG / "magazine-rack.yaml").read_text(), "rack.yaml", "yaml")
    geometry = analyze(design)
    edited = apply_dof(design, structure(design, standing_geometry(geometry)),
                       parse_dof(design, "slat_a.ry"), 15.0)
    score = shop_score(design, geometry, mirror_planes(design), edited,
                       plank_edits(design, edited))
    assert not [r for r in score.implausible if "in plan" in r]


SUPPORT = "  - {id: support-1, size: [1460, 250], center: [0, 125, 730], rotation: [0, 90, 0]}\n"
CLEAT = "  - {id: cleat_m, size: [150, 120], center: [0, 6, 1400], rotation: [90, 0, 0]}\n"


def test_a_wall_shelf_stood_on_the_floor_is_implausible():
    """A shelf hung on a wall by two screwed cleats, nothing near the floor: a 1.46 m
    panel added under it, standing on the floor, makes a floor unit, another piece (a
    maker adds a cleat or a stronger fixing); a third cleat screwed to the wall does not
    read so, nor does a panel added to a piece that stood on the floor already."""
    with_support = WALL_SHELF_LONG.replace("anchors:", SUPPORT + "anchors:")
    assert score_of(WALL_SHELF_LONG, with_support).implausible == (
        "support-1 stands on the floor under a piece that hangs on the wall: a floor unit, "
        "another piece",)
    assert score_of(WALL_SHELF_LONG, WALL_SHELF_LONG.replace("anchors:", CLEAT + "anchors:")
                    ).implausible == ()
    standing = WALL_SHELF_LONG.replace("  - {id: shelf,", "  - {id: post, size: [1460, 250], "
                                  "center: [-600, 125, 730], rotation: [0, 90, 0]}\n"
                                  "  - {id: shelf,")
    assert score_of(standing, standing.replace("anchors:", SUPPORT + "anchors:")
                    ).implausible == ()
