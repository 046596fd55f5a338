"""Near misses (contract section 2, issue 14): planks that come close to touching but do
not are reported with their gap, never silently left out, and a design that does not
stand as drawn gets no statics (no toppling with absurd forces).

The stool of ``designs/stool.yaml``: seat underside at z = 438 mm, legs 438 mm tall from
the floor, tolerance 0.5 mm, so the near-miss band is 20 x 0.5 = 10 mm.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from furncheck import tolerances as tol
from furncheck.check import check_design
from furncheck.design import load_design, parse_design
from furncheck.geometry import analyze

ROOT = Path(__file__).resolve().parents[1]
STOOL = (ROOT / "designs" / "stool.yaml").read_text()
LEG_L = "{id: leg_l, size: [438, 300], center: [-170, 0, 219]"


def stool_with_leg_l(length: float, centre_z: float, text: str = STOOL) -> str:
    """The stool with leg_l (vertical, its length along world z) of ``length`` centred
    at ``centre_z``: it spans centre_z -+ length / 2."""
    assert LEG_L in text
    return text.replace(LEG_L, f"{{id: leg_l, size: [{length}, 300], "
                               f"center: [-170, 0, {centre_z}]")


def parsed(text: str, name: str = "test.yaml"):
    return parse_design(text, name, "yaml")


def cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "furncheck.cli.main", *args],
                          capture_output=True, text=True, cwd=ROOT, check=False)


def test_the_band_is_twenty_tolerances():
    assert tol.NEAR_MISS_FACTOR == 20.0


@pytest.mark.parametrize("model", ["elastic", "rigid"])
def test_a_stool_leg_4_mm_short_reads_as_a_gap_and_a_hover_through_the_cli(tmp_path, model):
    """Issue 14: leg_l 430 mm long at z = 219 spans 4 .. 434 mm: 4 mm short of the seat
    (438) and 4 mm above the floor.  It still hangs on the rung, so the planks form one
    grounded group; the old report had it topple ('the ground would have to pull
    1.121e+04 N' three times).  Now: the gap and the hover, exit 1, no statics."""
    path = tmp_path / "stool-short.yaml"
    path.write_text(stool_with_leg_l(430, 219))
    run = cli("validate", str(path), "--model", model)
    assert run.returncode == 1, run.stderr
    lines = run.stdout.splitlines()
    assert lines[0].endswith("INVALID, 2 violations")
    assert lines[1].startswith("  disconnected: seat/leg_l: 4 mm gap between the end of "
                               "leg_l and the face of seat")
    assert lines[2].startswith("  floating: leg_l: 4 mm above the floor")
    assert "lift-off" not in run.stdout and "would have to pull" not in run.stdout
    assert "per nail" not in run.stdout
    document = json.loads(cli("validate", str(path), "--model", model,
                              "--format", "json").stdout)
    report = document["reports"][0]
    assert [(v["kind"], v["where"], v["case"]) for v in report["violations"]] == \
        [("disconnected", "seat/leg_l", None), ("floating", "leg_l", None)]
    assert [c["name"] for c in report["cases"]] == ["default", "perch", "rock"]
    assert all(c["joints"] == [] and c["contacts"] == [] and c.get("planks", []) == []
               for c in report["cases"])              # the statics were not run
    assert all(("planks" in c) == (model == "elastic") and not c["durable"]
               and not c["stable"] for c in report["cases"])   # the schema's keys


def test_the_gap_is_measured_not_assumed():
    """Same leg 6 mm short at the top only (length 432 from the floor): one gap of 6 mm,
    no hover; the NearMiss value is the gap in metres."""
    geometry = analyze(parsed(stool_with_leg_l(432, 216)))
    assert [(m.planks, round(m.distance, 9)) for m in geometry.near_misses] == \
        [(("seat", "leg_l"), 0.006)]
    assert not geometry.stands
    assert [v.message.split(":")[0] for v in geometry.violations] == \
        ["6 mm gap between the end of leg_l and the face of seat"]


def test_a_plank_4_mm_above_the_floor():
    """leg_l 434 mm long at z = 221 spans 4 .. 438: its joint with the seat is whole, its
    foot 4 mm up while leg_r stands: ``floating`` leg_l with its height, nothing else."""
    design = parsed(stool_with_leg_l(434, 221))
    report = check_design(design)
    assert [(v.kind, v.where) for v in report.violations] == [("floating", "leg_l")]
    assert report.violations[0].message.startswith("4 mm above the floor")
    assert report.valid is False and all(not c.joints for c in report.cases)
    assert {c.stability for c in report.cases} == {"not solved"}


def test_an_overlap_of_three_tolerances():
    """leg_l 439.5 mm long at z = 219.75 spans 0 .. 439.5: it cuts 1.5 mm (3 x 0.5 mm)
    into the seat's underside, too deep for a joint: ``disconnected`` with the overlap."""
    report = check_design(parsed(stool_with_leg_l(439.5, 219.75)))
    assert [(v.kind, v.where) for v in report.violations] == [("disconnected", "seat/leg_l")]
    assert report.violations[0].message.startswith(
        "1.5 mm overlap: the end of leg_l cuts into the face of seat")


def test_the_band_ends_at_twenty_tolerances():
    """A gap of exactly 20 x 0.5 = 10 mm (leg 428 mm from the floor) is a near miss."""
    report = check_design(parsed(stool_with_leg_l(428, 214)))
    assert [(v.kind, v.where) for v in report.violations] == [("disconnected", "seat/leg_l")]
    assert report.violations[0].message.startswith("10 mm gap")


@pytest.mark.parametrize(("length", "gap"), [(427.9, 10.1), (425.5, 12.5)])
def test_beyond_the_band_the_planks_are_apart_and_the_design_is_checked_as_built(length,
                                                                                  gap):
    """A gap of 10.1 mm or 25 x 0.5 = 12.5 mm is taken as meant: no near miss.  leg_l then
    stands on the floor and holds the rung only; the seat hangs on leg_r alone, a
    cantilever of ~170 mm carrying 80 kg, whose 15 nails cannot hold it (rigid model:
    M ~ 785 N x 0.17 m = 133 N m, pull ~ 2 M / t / 15 = 1480 N > 700 N).  The statics run
    and say so."""
    design = parsed(stool_with_leg_l(length, length / 2))
    geometry = analyze(design)
    assert geometry.near_misses == () and geometry.stands
    report = check_design(design)
    kinds = {(v.kind, v.where) for v in report.violations}
    assert ("non-durable", "seat/leg_r") in kinds
    assert not any(v.kind in ("disconnected", "floating") for v in report.violations)
    assert all(c.joints for c in report.cases)


def test_listed_joints_have_no_near_misses_of_unlisted_pairs():
    """A file that lists its joints says which planks are joined: with seat/leg_l left
    out of the list the 4 mm gap is no near miss (the leg is still 4 mm above the floor,
    a ground near miss in any design)."""
    text = stool_with_leg_l(430, 219) + (
        "joints:\n  - [seat, leg_r]\n  - [leg_l, rung]\n  - [leg_r, rung]\n")
    geometry = analyze(parsed(text))
    assert [m.planks for m in geometry.near_misses] == [("leg_l",)]


CARCASS = """\
furncheck: 1
name: carcass
planks:
  - {id: side_l, size: [600, 300], center: [-206, 0, 300], rotation: [0, -90, 0]}
  - {id: side_r, size: [600, 300], center: [206, 0, 300], rotation: [0, -90, 0]}
  - {id: top, size: [424, 300], center: [0, 0, 606]}
  - {id: bottom, size: [400, 300], center: [0, 0, 11]}
  - {id: shelf_a, size: [400, 200], center: [0, -50, 300]}
  - {id: shelf_b, size: [400, 300], center: [0, 0, 317]}
  - {id: divider, size: [272, 80], center: [0, 100, 153], rotation: [0, -90, 0]}
"""


def test_no_false_near_misses_in_a_carcass():
    """A carcass whose bottom lies flat 5 mm above the floor (z 5 .. 17) between two sides
    standing on it, two shelves 5 mm apart face to face (294 .. 306 and 311 .. 323), and
    a divider standing on the bottom whose top end (z 289) is 5 mm under shelf_a's level
    but beside it (divider at y 60 .. 140, shelf_a at y -150 .. 50): nothing is a near
    miss, and the carcass is valid in the rigid model."""
    design = parsed(CARCASS)
    geometry = analyze(design)
    assert geometry.near_misses == () and geometry.violations == ()
    assert check_design(parsed(CARCASS + "model: rigid\n")).valid


def test_the_same_divider_under_a_full_width_shelf_is_a_near_miss():
    """The control of the test above: shelf_a full width (y -150 .. 150) is over the
    divider's top end, 5 mm above it: a missed joint shelf_a/divider."""
    text = CARCASS.replace("{id: shelf_a, size: [400, 200], center: [0, -50, 300]}",
                           "{id: shelf_a, size: [400, 300], center: [0, 0, 300]}")
    geometry = analyze(parsed(text))
    assert [(m.planks, round(m.distance, 9)) for m in geometry.near_misses] == \
        [(("shelf_a", "divider"), 0.005)]


def test_a_near_miss_on_a_plank_jointed_elsewhere_is_still_reported():
    """shelf_b 3 mm short of side_r (size 397 from side_l's face at x = -200) stays nailed
    to side_l: the joint the maker meant is missing, so the gap is reported and the
    statics (a cantilevered shelf) are not run."""
    text = CARCASS.replace("{id: shelf_b, size: [400, 300], center: [0, 0, 317]}",
                           "{id: shelf_b, size: [397, 300], center: [-1.5, 0, 317]}")
    report = check_design(parsed(text))
    assert [(v.kind, v.where) for v in report.violations] == [("disconnected", "side_r/shelf_b")]
    assert report.violations[0].message.startswith("3 mm gap")
    assert all(not c.joints for c in report.cases)


def test_a_floating_plank_stops_the_statics_of_the_whole_design():
    """A shelf hovering 20 mm under the top, joined to nothing (beyond the band: no near
    miss): ``disconnected`` and ``floating``, and no case is solved."""
    text = CARCASS + "  - {id: loose, size: [300, 200], center: [0, 0, 574]}\n"
    report = check_design(parsed(text))
    assert [(v.kind, v.where) for v in report.violations] == \
        [("disconnected", "loose"), ("floating", "loose")]
    assert all(not c.joints and not c.contacts for c in report.cases)


def test_near_misses_in_metres_and_without_tolerance():
    """A file in metres reports its gap in metres (tolerance 0.0005 m: the same band);
    with tolerance 0 there is no band."""
    metres = """\
furncheck: 1
units: m
tolerance: 0.0005
planks:
  - {id: seat, size: [0.4, 0.3], center: [0, 0, 0.444]}
  - {id: leg_l, size: [0.43, 0.3], center: [-0.17, 0, 0.219], rotation: [0, -90, 0]}
  - {id: leg_r, size: [0.438, 0.3], center: [0.17, 0, 0.219], rotation: [0, -90, 0]}
  - {id: rung, size: [0.328, 0.08], center: [0, 0, 0.15], rotation: [90, 0, 0]}
"""
    report = check_design(parsed(metres))
    assert [(v.where, v.message.split(" between")[0].split(":")[0])
            for v in report.violations] == [("seat/leg_l", "0.004 m gap"),
                                            ("leg_l", "0.004 m above the floor")]
    exact = parsed(stool_with_leg_l(430, 219) + "tolerance: 0\n")
    assert analyze(exact).near_misses == ()


def test_an_edit_that_keeps_the_joints_but_misses_the_floor_is_analyzed_in_full():
    """The stool's rung (on edge, 80 mm tall, z 110 .. 190) lowered to z = 45 keeps both
    of its joints and every ground contact, but its lower edge hovers 5 mm above the
    floor: the batched edit check (``EditedTables``) must not take the design's geometry
    for it, and gives what ``analyze`` gives."""
    from furncheck.geometry.edits import EditedTables

    design = load_design(str(ROOT / "designs" / "stool.yaml"))
    geometry = analyze(design)
    edited = parsed(STOOL.replace("{id: rung, size: [328, 80], center: [0, 0, 150]",
                                  "{id: rung, size: [328, 80], center: [0, 0, 45]"),
                    str(ROOT / "designs" / "stool.yaml"))
    tables = EditedTables(design, geometry, [edited])
    found = tables.geometries()[0]
    assert tables.kept == [False]
    assert [(v.kind, v.where) for v in found.violations] == [("floating", "rung")]
    assert found.violations == analyze(edited).violations


def test_no_catalog_design_has_a_near_miss():
    """The catalog's verdicts do not change: none of its designs misses a joint or a
    ground contact narrowly."""
    for path in sorted((ROOT / "designs").glob("*.yaml")):
        assert analyze(load_design(str(path))).near_misses == (), path.name


def test_suggest_closes_the_near_misses_of_the_short_stool(tmp_path):
    """Rigid model (the stool is valid there once whole): leg_l 4 mm short at both ends
    wants 8 mm more length (each end within the 0.5 mm tolerance: 7 to 9 mm); the
    suggestion may add the missed joint seat/leg_l and stand the leg on the floor, and
    every suggestion's written design validates (``--out``, through the CLI)."""
    from furncheck.check import check_file
    from furncheck.design.model import with_model
    from furncheck.suggest import suggest_design

    result = suggest_design(with_model(parsed(stool_with_leg_l(430, 219)), "rigid"))
    lengthen = next(s for s in result.suggestions if s.dofs == ("leg_l.length",))
    assert 7.0 <= lengthen.changes[0] <= 9.0
    path = tmp_path / "stool-short.yaml"
    path.write_text(stool_with_leg_l(430, 219))
    run = cli("suggest", str(path), "--model", "rigid", "--format", "json",
              "--out", str(tmp_path / "out"), "--no-plots")
    assert run.returncode == 0, run.stderr
    entries = json.loads(run.stdout)["suggestions"]
    assert entries and all(check_file(entry["design_file"], "rigid").valid
                           for entry in entries)


def test_suggest_stands_a_hovering_leg_on_the_floor():
    """leg_l 4 mm above the floor, its top nailed to the seat: lengthen it by 3.5 to
    4.5 mm (its jointed end stays put, its foot goes down)."""
    from furncheck.design.model import with_model
    from furncheck.suggest import suggest_design

    result = suggest_design(with_model(parsed(stool_with_leg_l(434, 221)), "rigid"))
    lengthen = next(s for s in result.suggestions if s.dofs == ("leg_l.length",))
    assert 3.5 <= lengthen.changes[0] <= 4.5


def test_range_of_the_short_leg_finds_the_length_that_closes_both_gaps(tmp_path):
    """``range`` of the 4 mm short stool's leg_l.length (rigid): the current 430 mm is
    invalid; the nearest valid interval lies within the tolerance of 438 mm."""
    path = tmp_path / "stool-short.yaml"
    path.write_text(stool_with_leg_l(430, 219))
    run = cli("range", str(path), "leg_l.length", "--model", "rigid", "--format", "json")
    assert run.returncode == 0, run.stderr
    (entry,) = json.loads(run.stdout)["ranges"]
    low, high = entry["valid"]
    assert 437.0 - 0.1 <= low <= 438.0 <= high <= 439.0 + 0.1


def shelf_between_sides(mid_length: float) -> str:
    """A carcass: sides 18 mm thick centred at x = -+409 (inner faces at -+400), a bottom
    and a top 800 mm long between them, and a middle shelf of ``mid_length`` centred at
    x = 0: 800 fits; 784 misses each side by 8 mm, 802 cuts 1 mm into each, 830 15 mm."""
    return f"""furncheck: 1
name: shelf-{mid_length:g}
units: mm
model: rigid
material: {{thickness: 18}}
planks:
  - {{id: side_l, size: [1200, 300], center: [-409, 0, 600], rotation: [0, 90, 0]}}
  - {{id: side_r, size: [1200, 300], center: [409, 0, 600], rotation: [0, 90, 0]}}
  - {{id: bottom, size: [800, 300], center: [0, 0, 100]}}
  - {{id: mid, size: [{mid_length}, 300], center: [0, 0, 600]}}
  - {{id: top, size: [800, 300], center: [0, 0, 1191]}}
loads:
  - {{plank: mid, mass: 20, spread: true}}
  - {{plank: bottom, mass: 20, spread: true}}
"""


def test_a_shelf_short_at_both_ends_is_lengthened_not_lowered():
    """784 mm between inner faces 800 mm apart: 8 mm short at each end, so it floats 591
    mm up (it hangs on the two joints it misses).  That float is no plank to lower to the
    floor (``near.carried_groups``): the fix closes both gaps, 'Lengthen mid by 16 mm'
    (to 800, the distance between the faces), first; ``range`` of mid.length holds 800;
    the hand estimate says closing the joints carries it."""
    from furncheck.ranges import dof_ranges
    from furncheck.report.explanation import need_text
    from furncheck.suggest import suggest_design

    design = parsed(shelf_between_sides(784))
    kinds = sorted(v.kind for v in analyze(design).violations)
    assert kinds == ["disconnected", "disconnected", "floating"]
    result = suggest_design(design)
    first = result.suggestions[0]
    assert first.dofs == ("mid.length",) and first.changes == (16.0,)
    assert first.report.valid
    (found,) = dof_ranges(design, ["mid.length"])
    low, high = found.valid
    assert low <= 800.0 <= high and high - low < 2.0
    floating = next(n for n in result.explanation.needs if n.kind == "floating")
    assert "closing those carries it, nothing to lower" in need_text(floating, "mm")


def test_an_end_cutting_into_a_face_is_said_as_such():
    """802 mm: each end cuts 1 mm into a side (a near miss, an overlap): the hand estimate
    says the end cuts in and is drawn back 0.5 to 1.5 mm, and the fix shortens mid by 2
    mm.  830 mm, 15 mm into each side (beyond the 10 mm band): the plank joined to nothing
    says why."""
    from furncheck.report.explanation import need_text
    from furncheck.suggest import suggest_design

    result = suggest_design(parsed(shelf_between_sides(802)))
    assert result.suggestions[0].dofs == ("mid.length",)
    assert result.suggestions[0].changes == (-2.0,)
    texts = [need_text(n, "mm") for n in result.explanation.needs if n.kind == "disconnected"]
    assert texts and all("the end cuts 1 mm into the face; drawing it back by 0.5 to 1.5 mm"
                         in text for text in texts)
    through = analyze(parsed(shelf_between_sides(830)))
    message = next(v.message for v in through.violations if v.where == "mid"
                   and v.kind == "disconnected")
    assert message.endswith("its end cuts 15 mm into the face of side_l and of side_r: "
                            "shorten or move it to rest on those faces")


def test_a_cut_in_is_looked_for_among_the_overlapping_neighbours_only(monkeypatch):
    """The 830 mm shelf's ends cut 15 mm into both sides; forty boards lie on the floor
    far from the carcass, each joined to nothing.  Each plank joined to nothing measures
    only the neighbours whose boxes overlap its own (``cut_ins``): the shelf its two
    sides, the boards none, where every plank against every other (42 x 43 pairs) made a
    design of thousands of loose boards take minutes.  The message is as before."""
    from furncheck.geometry import fit

    boards = "".join(f"  - {{id: board{k}, size: [300, 200], center: [{2000 + 400 * k}, 0, "
                     f"9]}}\n" for k in range(40))
    text = shelf_between_sides(830).replace("loads:\n", boards + "loads:\n")
    measured = []
    real = fit._best_touches

    def counting(planks, pairs, *args, **kwargs):
        if kwargs.get("one_way"):
            measured.extend(tuple(pair) for pair in pairs.tolist())
        return real(planks, pairs, *args, **kwargs)

    monkeypatch.setattr(fit, "_best_touches", counting)
    geometry = analyze(parsed(text))
    loose = [v.where for v in geometry.violations if v.kind == "disconnected"]
    assert loose == ["mid"] + [f"board{k}" for k in range(40)]
    assert sorted(measured) == [(3, 0), (3, 1)]          # mid against side_l and side_r
    message = next(v.message for v in geometry.violations if v.where == "mid")
    assert message.endswith("its end cuts 15 mm into the face of side_l and of side_r: "
                            "shorten or move it to rest on those faces")


def test_boards_stacked_face_to_face_each_measure_their_two_neighbours_alone(monkeypatch):
    """Sixty boards stacked face to face (z = 6 + 12 k mm, 12 mm thick), no end on any
    face: each is joined to nothing, and its box meets at most those of the boards above
    and below it (they touch: which meet is round-off's).  Each message's search builds
    the face tables of those three boards (``faces._pairs_planks``), not of all sixty
    (the joints' and near misses' searches build the design's once each): a table of
    every plank per loose plank made a stack of 80,000 boards quadratic (not done after
    11 minutes; 11 s now).  The neighbours found all at once by sort and sweep
    (``fit.box_neighbours``) are those of the pairwise box test, and the messages are
    those each plank's own test gives."""
    from furncheck.geometry import faces as faces_module
    from furncheck.geometry import fit

    count = 60
    text = "furncheck: 1\nplanks:\n" + "".join(
        f"  - {{id: b{k}, size: [400, 300], center: [0, 0, {6 + 12 * k}]}}\n"
        for k in range(count))
    design = parsed(text)
    built = []
    real = faces_module._face_tables

    def counting(planks):
        built.append(len(planks))
        return real(planks)

    monkeypatch.setattr(faces_module, "_face_tables", counting)
    geometry = analyze(design)
    loose = [v for v in geometry.violations if v.kind == "disconnected"]
    assert [v.where for v in loose] == [f"b{k}" for k in range(count)]
    whole = [n for n in built if n == count]    # the joints' and near misses' search, once
    measured = [n for n in built if n != count]
    assert len(whole) <= 2 and len(measured) > count // 2 and max(measured) <= 3
    neighbours = fit.box_neighbours(design)
    lo, hi = faces_module._bounding_boxes(design.planks)
    for k in range(count):
        meets = np.all((lo <= hi[k]) & (lo[k] <= hi), axis=1)
        meets[k] = False
        assert neighbours[k].tolist() == np.flatnonzero(meets).tolist()
        assert set(neighbours[k].tolist()) <= {k - 1, k + 1}     # (touching: round-off)
        assert fit.cut_ins(design, k, neighbours[k]) == fit.cut_ins(design, k) == []


@pytest.mark.parametrize("name", ["cabinet-28.yaml", "table.yaml", "bookcase-pins.yaml",
                                  "chair-tilted.yaml"])
def test_touches_measured_on_the_pairs_planks_alone_are_those_of_the_whole_tables(name):
    """``faces._best_touches`` without the design's face tables builds them for the planks
    its pairs name alone (``_pairs_planks``) and remaps the pairs into them: every pair's
    contact, gap, area and point are those measured with the tables of every plank, bit
    for bit, for pairs drawn at random (seeded), repeated, reversed and a plank with
    itself, either way round or one way."""
    from furncheck.geometry import faces as faces_module

    design = load_design(ROOT / "designs" / name)
    whole = faces_module._face_tables(design.planks)
    n = len(design.planks)
    rng = np.random.default_rng(26)
    found = 0
    for one_way in (False, True):
        for size in (1, 3, 12):
            pairs = rng.integers(0, n, size=(size, 2))
            pairs = np.vstack([pairs, pairs[:1], pairs[:1, ::-1], [[0, 0]]])
            alone = faces_module._best_touches(design.planks, pairs, np.inf, True,
                                               one_way=one_way, bearing=0.0)
            full = faces_module._best_touches(design.planks, pairs, np.inf, True, whole,
                                              one_way=one_way, bearing=0.0)
            assert alone.keys() == full.keys()
            found += len(full)
            for key, touch in full.items():
                other = alone[key]
                assert (other.face.id, other.edge.id) == (touch.face.id, touch.edge.id)
                assert (other.gap, other.area, other.alignment) == \
                    (touch.gap, touch.area, touch.alignment)
                assert np.array_equal(other.point, touch.point)
    all_pairs = np.argwhere(np.ones((n, n), dtype=bool))
    alone = faces_module._best_touches(design.planks, all_pairs[::7], np.inf, True, bearing=0.0)
    found += len(alone)
    assert found > 0            # (contacts were measured, not only pairs with none)


# --- bearing: an end that covers a sliver of the face is no nail joint -------------------------

BENCH = """\
furncheck: 1
name: kids-bench
material: {thickness: 18}
planks:
  - {id: seat, size: [SEAT, 280], center: [0, 0, 321]}
  - {id: end_l, size: [312, 280], center: [-250, 0, 156], rotation: [0, -90, 0]}
  - {id: end_r, size: [312, 280], center: [250, 0, 156], rotation: [0, -90, 0]}
loads:
  - {plank: seat, mass: 35, at: [0, 0, 330]}
"""


@pytest.mark.parametrize(("seat", "bears"), [(483.0, False), (499.9, False), (500.1, True),
                                             (536.0, True)])
def test_a_nail_joint_needs_half_the_edge_planks_thickness_to_bear_on(seat, bears):
    """The end panels (18 mm, x = -259..-241 and 241..259) carry a seat of length L
    centred at x = 0: its ends at +-L/2 cover L/2 - 241 mm of each panel's 18 mm top end.
    A nail joint needs half of it, 9 mm (MIN_BEARING_SHARE): L = 483 (0.5 mm) and 499.9
    (8.95 mm) form no joint and are reported with the band they have; L = 500.1 and 536
    (the whole end) are joints."""
    assert tol.MIN_BEARING_SHARE == 0.5
    geometry = analyze(parsed(BENCH.replace("SEAT", str(seat))))
    joined = {(j.face, j.edge) for j in geometry.joints}
    slivers = [v for v in geometry.violations if v.kind == "disconnected" and "/" in v.where]
    if bears:
        assert joined == {("seat", "end_l"), ("seat", "end_r")} and not slivers
        return
    assert not joined
    band = seat / 2 - 241
    assert [v.where for v in slivers] == ["seat/end_l", "seat/end_r"]
    for violation in slivers:
        assert violation.message == (
            f"the end of {violation.where[5:]} bears on only {band:.3g} mm of the face of "
            f"seat across its 18 mm thickness: no joint forms (nails need at least 9 mm, "
            f"half the thickness)")


def test_a_listed_joint_on_a_sliver_is_disconnected_and_a_resting_one_holds():
    """The same 483 mm seat with its joints listed: nailed, each is disconnected with its
    0.5 mm band (and the seat, held by nothing, floats); listed as resting joints (no
    nails), they hold the seat as drawn."""
    text = BENCH.replace("SEAT", "483")
    nailed = parsed(text + "joints:\n  - [seat, end_l]\n  - [seat, end_r]\n")
    assert [(v.kind, v.where, v.message.split(":")[0]) for v in analyze(nailed).violations] \
        == [("disconnected", "seat/end_l", "the end of end_l bears on only 0.5 mm of the "
                                           "face of seat across its 18 mm thickness"),
            ("disconnected", "seat/end_r", "the end of end_r bears on only 0.5 mm of the "
                                           "face of seat across its 18 mm thickness"),
            ("floating", "seat", "1 plank touches the ground nowhere (lowest corner 312 mm "
                                 "above it)")]
    resting = parsed(text + "joints:\n  - {planks: [seat, end_l], type: rests}\n"
                            "  - {planks: [seat, end_r], type: rests}\n")
    assert not analyze(resting).violations


def test_a_sliver_is_reported_with_no_near_miss_band_too():
    """tolerance: 0 leaves no near-miss band, yet a sliver lies on the face within the
    tolerance: it is reported as with the default tolerance, for detected joints as for
    listed ones (it used to vanish: the seat read as a cantilever off one panel)."""
    text = BENCH.replace("SEAT", "483").replace("material:", "tolerance: 0\nmaterial:")
    detected = [v.where for v in analyze(parsed(text)).violations if v.kind == "disconnected"]
    listed = [v.where for v in analyze(parsed(
        text + "joints:\n  - [seat, end_l]\n  - [seat, end_r]\n")).violations
        if v.kind == "disconnected"]
    assert detected == listed == ["seat/end_l", "seat/end_r"]


@pytest.mark.parametrize(("phi", "dx", "dy"), [(33.0, 0.8, -1.7), (-123.4, 0.0, 2.5)])
def test_the_bearing_rule_is_the_same_wherever_the_design_stands(phi, dx, dy):
    """The bearing rule measures the band across the joint line, not along world axes:
    the benches of ``test_a_nail_joint_needs_half_...`` turned by phi about z and moved
    keep their joints (500.1 mm seat) and their slivers, with the same band (483 mm)."""
    import physics_designs as pd
    import yaml

    for seat, joined in ((483.0, 0), (500.1, 2)):
        tree = pd.rigid_motion(yaml.safe_load(BENCH.replace("SEAT", str(seat))), phi,
                               dx * 1000.0, dy * 1000.0)
        geometry = analyze(parsed(yaml.safe_dump(tree, sort_keys=False)))
        assert len(geometry.joints) == joined
        bands = sorted(round(m.bearing * 1000.0, 6) for m in geometry.near_misses
                       if m.bearing is not None)
        assert bands == ([0.5, 0.5] if joined == 0 else [])


def test_a_sliver_is_repaired_by_the_face_plank_reaching_over_the_ends():
    """The 483 mm seat over 0.5 mm of each 18 mm end: the explanation says what the
    joints need (9 mm; 8.5 to 17.5 mm more of it), and the reconnect rule lengthens the
    seat over both ends, 17.5 mm each (flush with their outer faces), which validates."""
    from furncheck.report.explanation import need_text
    from furncheck.suggest import suggest_design

    result = suggest_design(parsed(BENCH.replace("SEAT", "483")))
    texts = [need_text(need, "mm") for need in result.explanation.needs]
    assert ("disconnected seat/end_l: the end bears on 0.5 mm of its 18 mm "
                        "thickness, where nails need 9 mm: the face plank reaching 8.5 to "
                        "17.5 mm further over it (or the planks moved that much together) "
                        "would join them") in texts
    (fix,) = [s for s in result.suggestions if s.rule == "reconnect"]
    assert fix.advice.startswith("Lengthen seat by 35 mm (17.5 mm at the end over end_l "
                                 "and 17.5 mm at the end over end_r)")
    assert fix.design.plank("seat").length == pytest.approx(0.518)
    assert check_design(fix.design).valid


def test_a_resting_joints_corners_follow_an_edit_as_analyze_finds_them():
    """A seat resting on two end panels over 0.5 mm bands (resting joints keep any touch)
    moved 10 mm along y: the followed corners of its resting joints (the sensitivity's
    path) are the ones a fresh analysis finds, not the old ones kept (the followed touch
    used to drop the sliver)."""
    from dataclasses import replace

    import numpy as np

    from furncheck.geometry.analysis import follow

    design = parsed(BENCH.replace("SEAT", "483") + "joints:\n  - {planks: [seat, end_l], "
                    "type: rests}\n  - {planks: [seat, end_r], type: rests}\n")
    geometry = analyze(design)
    edited = replace(design, planks=tuple(
        replace(p, center=(p.center[0], p.center[1] + 0.01, p.center[2])) if p.id == "seat"
        else p for p in design.planks))
    followed, fresh = follow(geometry, edited), analyze(edited)
    resting = [(a.point, b.point) for a, b in zip(followed.contacts, fresh.contacts) if a.on]
    assert len(resting) == 8
    assert all(np.allclose(a, b, atol=1e-12) for a, b in resting)


def test_two_slivers_under_one_end_move_that_end_once():
    """A 983 mm top over four 18 mm legs at x = +-500 (each reaching 491.5 .. 509): each
    leg's end bears on 0.5 mm.  Two legs under each end: the top reaches 17.5 mm further
    at each end, once (1018 mm long), not once per leg; the advice names both legs."""
    from furncheck.suggest import suggest_design

    legs = "".join(f"  - {{id: {name}, size: [712, 100], center: [{x}, {y}, 356], "
                   f"rotation: [0, -90, 0]}}\n"
                   for name, x, y in (("l1", -500, -200), ("l2", -500, 200),
                                      ("r1", 500, -200), ("r2", 500, 200)))
    design = parsed("furncheck: 1\nmodel: rigid\nmaterial: {thickness: 18}\nplanks:\n"
                    "  - {id: top, size: [983, 600], center: [0, 0, 721]}\n" + legs
                    + "loads:\n  - {plank: top, mass: 20}\n")
    (fix,) = [s for s in suggest_design(design).suggestions if s.rule == "reconnect"]
    assert fix.advice.startswith("Lengthen top by 35 mm (17.5 mm at the end over l1 and l2 "
                                 "and 17.5 mm at the end over r1 and r2)")
    assert fix.design.plank("top").length == pytest.approx(1.018)


def test_a_sliver_along_a_long_side_widens_the_plank_over_it():
    """A leg turned so its 18 mm end lies across the seat's long side (its end's band
    runs along x, 8 mm of it under the seat): the seat is widened over it, by 10 mm, the
    rest of the leg's thickness (its centre beyond the seat's end along x does not make
    it a lengthening)."""
    from furncheck.suggest import suggest_design

    design = parsed("""\
furncheck: 1
model: rigid
material: {thickness: 18}
planks:
  - {id: seat, size: [1200, 300], center: [0, 0, 721]}
  - {id: leg_l, size: [712, 300], center: [-591, 0, 356], rotation: [0, -90, 0]}
  - {id: leg_r, size: [712, 100], center: [591, -90, 356], rotation: [0, -90, 0]}
  - {id: odd, size: [712, 100], center: [610, 151, 356], rotation: [0, -90, -90]}
loads:
  - {plank: seat, mass: 20}
""")
    (fix,) = [s for s in suggest_design(design).suggestions if s.rule == "reconnect"]
    assert fix.advice.startswith("Widen seat by 10 mm at the side over odd")
    assert fix.design.plank("seat").width == pytest.approx(0.310)


@pytest.mark.parametrize("x, depth", [(170.0, 12.0), (174.0, 8.0)])
def test_boards_drawn_through_each_other_are_disconnected_with_their_depth(x, depth):
    """The stool with leg_r pasted a second time (leg_r2) at x = ``x``: two 12 mm boards
    in one place (12 mm deep) or 4 mm apart (8 mm deep, the separating-axis overlap of
    their thicknesses, 12 - 4).  No joint forms between boards drawn through each other,
    so the pair is ``disconnected`` with that depth (it read as valid: every other joint
    and contact of both legs was there); a second leg drawn face to face beside it
    (x = 182: touching, not overlapping) is a board more, no violation."""
    leg = "  - {id: leg_r, size: [438, 300], center: [170, 0, 219], rotation: [0, -90, 0]}\n"
    doubled = STOOL.replace(leg, leg + leg.replace("leg_r,", "leg_r2,").replace("170,", f"{x},"))
    (violation,) = [v for v in check_design(parsed(doubled)).violations
                    if v.where == "leg_r/leg_r2"]
    assert violation.kind == "disconnected"
    assert violation.message.startswith(f"leg_r and leg_r2 are drawn through each other, "
                                        f"{depth:g} mm deep (tolerance 0.5 mm)")
    assert violation.line == doubled.splitlines().index(leg.rstrip("\n")) + 2
    beside = STOOL.replace(leg, leg + leg.replace("leg_r,", "leg_r2,").replace("170,", "182,"))
    assert not [v for v in check_design(parsed(beside)).violations if "leg_r2" in v.where]


def test_a_shelf_drawn_into_one_side_and_nearly_into_the_other_names_both():
    """The carcass's middle shelf 830 mm long, 10 mm left of centre, between faces 800 mm
    apart: its left end 25 mm into side_l (beyond the 10 mm near-miss band: drawn through
    it), its right end 5 mm into side_r (a near miss, said as such).  Each pair is named
    once, by what it is: an end that runs past the face it meets is told so, and how to
    mend it (a board cut too long)."""
    text = shelf_between_sides(830).replace("center: [0, 0, 600]", "center: [-10, 0, 600]")
    found = {v.where: v.message for v in check_design(parsed(text)).violations
             if v.kind == "disconnected"}
    assert set(found) == {"side_l/mid", "side_r/mid"} or set(found) == {"side_l/mid", "mid/side_r"}
    assert found["side_l/mid"] == (
        "an end of mid runs 25 mm past the face of side_l it meets (tolerance 0.5 mm): no "
        "joint forms; draw it back onto that face (a board cut too long), or move it out")
    right = found.get("side_r/mid", found.get("mid/side_r"))
    assert right.startswith("5 mm overlap: the end of mid cuts into the face of side_r")


def test_a_leg_drawn_too_long_up_through_the_seat_is_drawn_back():
    """designs/stool.yaml with leg_r 458 mm long (its top 20 mm past the seat's underside,
    8 mm out of its top), a newcomer's check: leg_r is joined to the rung, so not to
    nothing, and the pair read 'drawn through each other ... remove one if it is drawn
    twice', and suggest found nothing (its margins were the statics' of a stool whose leg
    misses the seat: the geometric repair was never formed), though its hand estimate
    said to draw it back 19.5 to 20.5 mm.  The message says the end runs past the face
    and to draw it back; in the rigid model (where the stool as drawn is valid) suggest
    gives 'Lower the top of leg_r by 20 mm (valid for 19.5-20.5 mm)': the window is the
    tolerance either side of the 20 mm, and ``range`` of leg_r.length holds 438 mm
    (it read 'no valid value found')."""
    from furncheck.design.model import with_model
    from furncheck.ranges import RangeFinder
    from furncheck.suggest import suggest_design

    text = STOOL.replace(
        "{id: leg_r, size: [438, 300], center: [170, 0, 219]",
        "{id: leg_r, size: [458, 300], center: [170, 0, 229]")
    design = parsed(text)
    (violation,) = [v for v in check_design(design).violations if v.kind == "disconnected"]
    assert violation.where == "seat/leg_r" and violation.message.startswith(
        "an end of leg_r runs 20 mm past the face of seat it meets (tolerance 0.5 mm)")
    rigid = with_model(design, "rigid")
    result = suggest_design(rigid)
    (shorter,) = result.suggestions
    assert shorter.dofs == ("leg_r.length",) and 19.5 <= -shorter.changes[0] <= 20.5
    assert check_design(parse_design(shorter.text, "s.yaml", "yaml")).valid
    (found,) = RangeFinder(rigid).ranges(["leg_r.length"])
    assert found.valid is not None and 437.5 <= found.valid[0] <= 438.0 <= found.valid[1] <= 438.5


@pytest.mark.parametrize("x, words", [
    (170.0, "leg_r2 is leg_r drawn a second time, in the same place: removing leg_r2 "
            "(its loads, joints and fixings then leg_r's) leaves the one board"),
    (174.0, "drawn 8 mm through each other: moving one 7.5 to 8 mm out of the other (the "
            "way they overlap least) would leave them touching, not joined")])
def test_the_explanation_says_how_to_part_boards_drawn_through_each_other(x, words):
    """A newcomer's check: suggest read "no hand estimate (neither plank's end faces the
    other)" for a leg pasted twice.  The estimate now says which is the copy (every corner
    within the tolerance of the other's) or how far apart to move them: the overlap less
    the tolerance, to the overlap (8 mm for legs drawn 4 mm apart in 12 mm boards)."""
    from furncheck.report.explanation import need_text
    from furncheck.suggest import suggest_design

    leg = "  - {id: leg_r, size: [438, 300], center: [170, 0, 219], rotation: [0, -90, 0]}\n"
    doubled = STOOL.replace(leg, leg + leg.replace("leg_r,", "leg_r2,").replace("170,", f"{x},"))
    result = suggest_design(parsed(doubled))
    (need,) = [n for n in result.explanation.needs if n.where == "leg_r/leg_r2"]
    assert need_text(need, "mm") == f"disconnected leg_r/leg_r2: {words}"


def test_a_board_pasted_many_times_is_told_once_per_copy():
    """The stool's leg_r pasted four more times in place: each copy is drawn through leg_r,
    and through every other copy; each copy is named once, with the first plank in the
    file it is drawn through (4 lines, not the 10 pairs)."""
    leg = "  - {id: leg_r, size: [438, 300], center: [170, 0, 219], rotation: [0, -90, 0]}\n"
    copies = "".join(leg.replace("leg_r,", f"leg_r{k},") for k in range(2, 6))
    found = [v.where for v in check_design(parsed(STOOL.replace(leg, leg + copies))).violations
             if v.kind == "disconnected"]
    assert found == [f"leg_r/leg_r{k}" for k in range(2, 6)]


def test_a_plank_joined_to_nothing_inside_another_is_said_to_be_drawn_through_it():
    """A second middle shelf, 13 mm lower and 24 mm shorter than the carcass's, inside the
    first one's thickness but for 5 mm (both 18 mm): joined to nothing (its ends reach
    neither side), and its message says nothing of what it cuts into, so the pair is told
    as well."""
    text = shelf_between_sides(800).replace(
        "  - {id: top,", "  - {id: mid2, size: [776, 300], center: [0, 0, 587]}\n  - {id: top,")
    found = {v.where: v.message for v in check_design(parsed(text)).violations
             if v.kind == "disconnected"}
    assert set(found) == {"mid2", "mid/mid2"}
    assert found["mid/mid2"].startswith("mid and mid2 are drawn through each other, 5 mm deep")


def test_a_plank_joined_to_nothing_that_cuts_into_its_sides_is_told_once():
    """The carcass's 830 mm middle shelf cuts 15 mm into each side: joined to nothing,
    its message names both faces (``geometry.cut_in_pairs``), so no pair of it is told
    again as drawn through."""
    found = [v.where for v in check_design(parsed(shelf_between_sides(830))).violations
             if v.kind == "disconnected"]
    assert found == ["mid"]
