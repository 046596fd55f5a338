"""The cut list of a suggestion (``suggest.cutlist``): every plank it changes, adds or
removes, from -> to, including what the geometric constraints change.

The catalog test reads the input file and each suggestion's written file as plain YAML
documents (not through the loader or ``plank_values``) and compares their planks field by
field: the suggestion's ``edits`` must be exactly that difference.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
import yaml
from click.testing import CliRunner

from furncheck.check import check_file
from furncheck.cli.main import main
from furncheck.design.load import parse_design
from furncheck.suggest.cutlist import plank_edits

CATALOG = Path(__file__).resolve().parents[1] / "designs"
MODELS = ("rigid", "elastic")
INVALID = [(path.name, model) for path in sorted(CATALOG.glob("*.yaml")) for model in MODELS
           if not check_file(str(path), model).valid]

TWO_PLANKS = """
furncheck: 1
name: two
units: mm
planks:
  - {id: top, size: [400, 300], center: [0, 0, 506]}
  - {id: post, size: [500, 300], center: [0, 0, 250], rotation: [0, 90, 0]}
"""


def design(text: str):
    return parse_design(text, "two.yaml", "yaml")


def as_dict(edits) -> dict:
    return {e.plank: (e.action, {f.field: (f.before, f.after) for f in e.fields})
            for e in edits}


def test_a_changed_plank_lists_only_its_changed_fields():
    """top lengthened from 400 to 450 mm and moved 25 mm along x: two fields, from -> to in
    the file's unit; post untouched is not listed."""
    after = design(TWO_PLANKS.replace("{id: top, size: [400, 300], center: [0, 0, 506]}",
                                      "{id: top, size: [450, 300], center: [25, 0, 506]}"))
    assert as_dict(plank_edits(design(TWO_PLANKS), after)) == {
        "top": ("change", {"length": (400.0, 450.0), "x": (0.0, 25.0)})}


def test_a_turn_that_changes_several_angles_is_said_as_one_turn():
    """The post stood up by ry = 90 degrees, tilted 1.5 degrees about world x: the file's
    angles change by far more than that (near ry = 90 the three angles trade places), so
    the cut list line says the turn it is, 1.5 degrees about x, after them; a change of
    one angle alone is its own turn and gets no note."""
    import numpy as np

    from furncheck.design.model import rotation_matrix
    from furncheck.dofs import euler_degrees
    from furncheck.report.cutlist import cut_list_lines

    tilt = np.radians(1.5)
    about_x = np.array([[1, 0, 0], [0, np.cos(tilt), -np.sin(tilt)],
                        [0, np.sin(tilt), np.cos(tilt)]])
    angles = [round(float(v), 9) for v in euler_degrees(about_x @ rotation_matrix((0, 90, 0)),
                                                         (0.0, 90.0, 0.0))]
    before = design(TWO_PLANKS)
    after = design(TWO_PLANKS.replace("rotation: [0, 90, 0]", f"rotation: {angles}"))
    (line,) = cut_list_lines(plank_edits(before, after), before)[1:]
    assert sum(f" {name} " in line for name in ("rx", "ry", "rz")) >= 2, line
    assert line.endswith(" (a turn of 1.5 degrees about x)"), line
    one = design(TWO_PLANKS.replace("rotation: [0, 90, 0]", "rotation: [0, 88.5, 0]"))
    (line,) = cut_list_lines(plank_edits(before, one), before)[1:]
    assert line == "  post: ry 90 -> 88.5 degrees", line
    same = design(TWO_PLANKS.replace("rotation: [0, 90, 0]", "rotation: [30, 90, 30]"))
    (line,) = cut_list_lines(plank_edits(before, same), before)[1:]
    assert line.endswith(" (the same turn, its angles written otherwise)"), line
    half = design(TWO_PLANKS.replace("center: [0, 0, 506]}", "center: [0, 0, 506], "
                                     "rotation: [180, 0, 180]}"))
    (line,) = cut_list_lines(plank_edits(before, half), before)[1:]
    assert line.endswith(" (a turn of 180 degrees about y)"), line


def test_an_added_plank_lists_every_field_and_a_removed_one_too():
    """A support added: every field with no 'before'; the post taken away: every field
    with no 'after' (its rotation 90 degrees about y as written)."""
    added = TWO_PLANKS + "  - {id: support, size: [494, 80], center: [150, 0, 250], " \
                         "rotation: [0, 90, 0]}\n"
    edits = as_dict(plank_edits(design(TWO_PLANKS), design(added)))
    assert edits == {"support": ("add", {
        "length": (None, 494.0), "width": (None, 80.0), "thickness": (None, 12.0),
        "x": (None, 150.0), "y": (None, 0.0), "z": (None, 250.0),
        "rx": (None, 0.0), "ry": (None, 90.0), "rz": (None, 0.0)})}
    removed = as_dict(plank_edits(design(added), design(TWO_PLANKS)))
    assert removed["support"][0] == "remove"
    assert removed["support"][1]["ry"] == (90.0, None)


def test_thickness_and_own_material_values_are_fields_too():
    """A thicker top (18 mm) of pine (E = 11000 N/mm^2, its own value) reads as two
    changes, in the file's units (mm, N/mm^2)."""
    after = design(TWO_PLANKS.replace(
        "{id: top, size: [400, 300], center: [0, 0, 506]}",
        "{id: top, size: [400, 300], center: [0, 0, 509], thickness: 18, "
        "material: {elastic_modulus: 11000}}"))
    assert as_dict(plank_edits(design(TWO_PLANKS), after)) == {
        "top": ("change", {"thickness": (12.0, 18.0), "z": (506.0, 509.0),
                           "material.elastic_modulus": (None, 11000.0)})}


def test_a_change_below_a_micrometre_is_no_change():
    """CUT_LIST_EPS is 1e-6 of the unit: 0.0000004 mm is round-off, 0.001 mm is a
    change."""
    before = design(TWO_PLANKS)
    tiny = design(TWO_PLANKS.replace("center: [0, 0, 506]", "center: [0.0000004, 0, 506]"))
    small = design(TWO_PLANKS.replace("center: [0, 0, 506]", "center: [0.001, 0, 506]"))
    assert plank_edits(before, tiny) == ()
    assert as_dict(plank_edits(before, small)) == {"top": ("change", {"x": (0.0, 0.001)})}


def test_the_cut_list_is_in_the_designs_own_unit():
    """A design in metres: the fields are read in metres (a 0.4 m top lengthened by
    0.05 m)."""
    text = TWO_PLANKS.replace("units: mm", "units: m").replace("[400, 300]", "[0.4, 0.3]") \
        .replace("[500, 300]", "[0.5, 0.3]").replace("506", "0.506").replace("250]", "0.25]")
    text = text.replace("furncheck: 1", "furncheck: 1\nmaterial: {thickness: 0.012}")
    after = design(text.replace("[0.4, 0.3]", "[0.45, 0.3]"))
    assert as_dict(plank_edits(design(text), after)) == {
        "top": ("change", {"length": (0.4, 0.45)})}


# --- the catalog: edits == the difference between the input and the written file ----------

def file_planks(text: str) -> dict[str, dict[str, float]]:
    """Plank id -> its fields as the YAML document writes them (defaults filled in: rotation
    0, thickness the material's or 12 mm)."""
    document = yaml.safe_load(text)
    thickness = document.get("material", {}).get("thickness", 12.0)
    planks = {}
    for entry in document["planks"]:
        own = dict(entry.get("material", {}))
        rotation = entry.get("rotation", [0, 0, 0])
        values = {"length": entry["size"][0], "width": entry["size"][1],
                  "thickness": entry.get("thickness", own.pop("thickness", thickness)),
                  "x": entry["center"][0], "y": entry["center"][1], "z": entry["center"][2],
                  "rx": rotation[0], "ry": rotation[1], "rz": rotation[2]}
        values.update({f"material.{key}": value for key, value in own.items()})
        planks[entry["id"]] = {key: float(value) for key, value in values.items()}
    return planks


def file_difference(before: str, after: str) -> dict:
    old, new = file_planks(before), file_planks(after)
    difference = {}
    for plank, values in old.items():
        if plank not in new:
            difference[plank] = ("remove", {k: (v, None) for k, v in values.items()})
            continue
        fields = {k: (values.get(k), new[plank].get(k))
                  for k in {**values, **new[plank]}
                  if values.get(k) is None or new[plank].get(k) is None
                  or abs(values[k] - new[plank][k]) > 1e-6}
        if fields:
            difference[plank] = ("change", fields)
    for plank, values in new.items():
        if plank not in old:
            difference[plank] = ("add", {k: (None, v) for k, v in values.items()})
    return difference


@pytest.mark.parametrize("name, model", INVALID)
def test_every_cut_list_is_the_difference_of_the_files(catalog_suggestions, name, model):
    """For every suggestion on every invalid catalog design, in both models: its edits are
    the difference between the input file and its written file, plank by plank and field
    by field (values to 1e-9 of the unit)."""
    _, result = catalog_suggestions(name, model)
    source = (CATALOG / name).read_text(encoding="utf-8")
    for suggestion in result.suggestions:
        expected = file_difference(source, suggestion.text)
        found = as_dict(suggestion.edits)
        assert found.keys() == expected.keys(), (name, suggestion.rank)
        for plank, (action, fields) in expected.items():
            assert found[plank][0] == action
            assert found[plank][1].keys() == fields.keys(), (name, suggestion.rank, plank)
            for field, (old, new) in fields.items():
                for value, expected_value in zip(found[plank][1][field], (old, new)):
                    assert (value is None) == (expected_value is None)
                    if value is not None:
                        assert value == pytest.approx(expected_value, rel=1e-9, abs=1e-9)


@pytest.mark.parametrize("name, model", INVALID)
def test_every_moved_load_is_the_difference_of_the_files(catalog_suggestions, name, model):
    """Every load at a point whose point differs between the input file and a suggestion's
    written file is in its ``loads_moved`` (from -> to, file unit), and nothing else."""
    _, result = catalog_suggestions(name, model)
    before = parse_design((CATALOG / name).read_text(encoding="utf-8"), name, "yaml")
    scale = before.unit_scale
    for suggestion in result.suggestions:
        after = parse_design(suggestion.text, "s.yaml", "yaml")
        expected = set()
        for old_case, new_case in zip(before.load_cases, after.load_cases):
            for old, new in zip(old_case.loads, new_case.loads):
                if old.point is not None and any(
                        abs(a - b) / scale > 1e-6 for a, b in zip(old.point, new.point)):
                    expected.add((old.plank, tuple(round(v / scale, 6) for v in old.point),
                                  tuple(round(v / scale, 6) for v in new.point)))
        found = {(m.plank, tuple(round(v, 6) for v in m.before),
                  tuple(round(v, 6) for v in m.after)) for m in suggestion.loads_moved}
        assert found == expected, (name, model, suggestion.rank)


@pytest.mark.parametrize("name, model", INVALID)
def test_every_spread_load_on_a_resized_plank_is_said(catalog_suggestions, name, model):
    """Every spread load whose plank's length or width differs between the input file and
    a suggestion's written file is in its ``loads_spread`` (plank sizes from -> to, file
    unit), and nothing else."""
    _, result = catalog_suggestions(name, model)
    before = parse_design((CATALOG / name).read_text(encoding="utf-8"), name, "yaml")
    scale = before.unit_scale
    for suggestion in result.suggestions:
        after = parse_design(suggestion.text, "s.yaml", "yaml")
        sizes = {p.id: (round(p.length / scale, 6), round(p.width / scale, 6))
                 for p in after.planks}
        expected = set()
        for case in before.load_cases:
            for load in case.loads:
                old = before.plank(load.plank)
                start = (round(old.length / scale, 6), round(old.width / scale, 6))
                if load.spread and sizes[load.plank] != start:
                    expected.add((load.plank, start, sizes[load.plank]))
        found = {(s.plank, tuple(round(v, 6) for v in s.before),
                  tuple(round(v, 6) for v in s.after)) for s in suggestion.loads_spread}
        assert found == expected, (name, model, suggestion.rank)


def test_a_lengthened_top_says_its_spread_load_spreads_thinner():
    """A table top 1200 x 700 mm carrying 20 kg spread along it: a suggestion that
    lengthens the top says that the same 20 kg now spreads over the longer top, in text
    and JSON (``loads_spread``); two such loads on it are two lines, and a case that
    includes them adds none."""
    from furncheck.report.cutlist import load_spread_lines, load_spreads_json
    from furncheck.suggest.cutlist import load_spreads

    text = """\
furncheck: 1
name: spread-top
units: mm
planks:
  - {id: top, size: [1200, 700], center: [0, 0, 744], thickness: 18}
loads:
  - {plank: top, mass: 20, spread: true}
"""
    before = parse_design(text, "t.yaml", "yaml")
    after = parse_design(text.replace("[1200, 700]", "[1749, 700]"), "t.yaml", "yaml")
    (spread,) = load_spreads(before, after)
    assert (spread.plank, spread.load, spread.before, spread.after) == \
        ("top", "20 kg", (1200.0, 700.0), (1749.0, 700.0))
    assert load_spread_lines((spread,), before) == [
        "spreads 1 load over its resized plank:",
        "  20 kg spread on top (case 'default'): over 1749 x 700 mm, was 1200 x 700 mm"]
    assert load_spreads_json((spread,)) == [{"case": "default", "plank": "top",
                                             "load": "20 kg", "from": [1200.0, 700.0],
                                             "to": [1749.0, 700.0]}]
    assert load_spreads(before, before) == ()
    two = text.replace("  - {plank: top, mass: 20, spread: true}\n",
                       "  - {plank: top, mass: 20, spread: true}\n"
                       "  - {plank: top, mass: 20, spread: true}\n"
                       "load_cases:\n  more:\n    include: [default]\n")
    before, after = (parse_design(two.replace("[1200, 700]", size), "t.yaml", "yaml")
                     for size in ("[1200, 700]", "[1749, 700]"))
    assert [s.case for s in load_spreads(before, after)] == ["default", "default"]


def test_a_shortened_seat_carries_its_load_to_the_same_place_along_it():
    """bench-tips (rigid): 80 kg at x = 560 mm on a 1200 mm seat centred at x = 0;
    'Shorten seat by 553 mm' (1200 -> 647, centre kept) carries the load to the same
    fraction of its half length, x = 560 x 647 / 1200 = 301.9 mm, and says so."""
    from furncheck.design import load_design
    from furncheck.design.model import with_model
    from furncheck.report.cutlist import load_move_lines
    from furncheck.suggest import suggest_design

    design = with_model(load_design(str(CATALOG / "bench-tips.yaml")), "rigid")
    result = suggest_design(design)
    shorten = next(s for s in result.suggestions if s.dofs == ("seat.length",))
    length = next(e for e in shorten.edits if e.plank == "seat").field("length").after
    (move,) = shorten.loads_moved
    assert move.before == (560.0, 0.0, 450.0)
    assert move.after[0] == pytest.approx(560.0 * length / 1200.0, abs=1e-6)
    assert load_move_lines(shorten.loads_moved, design)[1] == (
        f"  80 kg on seat (case 'default'): at (560, 0, 450) -> "
        f"({560.0 * length / 1200.0:.1f}, 0, 450) mm")


def test_the_report_shows_the_cut_list_in_text_and_json(tmp_path):
    """bench-tips (rigid): every suggestion's text lists as many planks as its JSON edits,
    and the JSON edits are the written file's difference (rounded to 6 digits)."""
    path = str(CATALOG / "bench-tips.yaml")
    runner = CliRunner()
    text = runner.invoke(main, ["suggest", path, "--model", "rigid"]).output
    out = tmp_path / "out"
    document = json.loads(runner.invoke(main, ["suggest", path, "--model", "rigid",
                                               "--format", "json", "--out", str(out)]).output)
    counts = [int(n) for n in re.findall(r"changes (\d+) planks?:", text)]
    assert counts == [len(entry["edits"]) for entry in document["suggestions"]]
    source = Path(path).read_text(encoding="utf-8")
    for entry in document["suggestions"]:
        written = Path(entry["design_file"]).read_text(encoding="utf-8")
        expected = file_difference(source, written)
        assert {e["plank"] for e in entry["edits"]} == expected.keys()
        for edit in entry["edits"]:
            action, fields = expected[edit["plank"]]
            assert edit["edit"] == action and edit["fields"].keys() == fields.keys()
            for field, (old, new) in fields.items():
                for value, expected_value in zip(edit["fields"][field], (old, new)):
                    assert (value is None) == (expected_value is None)
                    if value is not None:
                        assert value == pytest.approx(expected_value, rel=1e-5, abs=1e-9)


def test_an_anchored_plank_moved_lists_its_wall_fixings():
    """The wall shelf's back board (hung on two fixings at z = 1470 mm) raised 50 mm by its
    DOF: the fixings ride with it (README "Anchors"), so the suggestion must say that they
    go in 50 mm higher, in text and JSON, each from -> to in the file's unit; a fixing
    that stays where it is (the shelf moved instead) is not listed."""
    from shop_designs import WALL_SHELF

    from furncheck.design.write import design_text
    from furncheck.dofs import apply_dof, parse_dof, structure
    from furncheck.geometry import analyze
    from furncheck.report.cutlist import anchor_move_lines, anchor_moves_json
    from furncheck.suggest.cutlist import anchor_moves

    before = parse_design(WALL_SHELF, "wall.yaml", "yaml")
    frame = structure(before, analyze(before))
    raised = apply_dof(before, frame, parse_dof(before, "back.z"), 50.0)
    after = parse_design(design_text(raised, "yaml"), "after.yaml", "yaml")  # its file
    moves = anchor_moves(before, after)
    assert [(m.anchor, m.plank, m.wall, m.before, m.after) for m in moves] == [
        (0, "back", 0, (-200.0, 0.0, 1470.0), (-200.0, 0.0, 1520.0)),
        (1, "back", 0, (200.0, 0.0, 1470.0), (200.0, 0.0, 1520.0))]
    assert anchor_move_lines(moves, before) == [
        "moves 2 wall fixings with their planks:",
        "  anchors[0] on back (wall 0): at (-200, 0, 1470) -> (-200, 0, 1520) mm",
        "  anchors[1] on back (wall 0): at (200, 0, 1470) -> (200, 0, 1520) mm"]
    assert anchor_moves_json(moves)[0] == {"anchor": 0, "plank": "back", "wall": 0,
                                           "from": [-200.0, 0.0, 1470.0],
                                           "to": [-200.0, 0.0, 1520.0]}
    shelf_moved = apply_dof(before, frame, parse_dof(before, "shelf.x"), 20.0)
    assert anchor_moves(before, shelf_moved) == ()


def test_a_moved_load_is_written_with_the_digits_that_show_its_move():
    """A load carried 0.004 mm with its plank (moved by more than CUT_LIST_EPS, so in the
    cut list) is written with the digits that show it, not as '(0, 395, 745) -> (0, 395,
    745)', which a woodworker read as a move of nothing."""
    from furncheck.design import load_design
    from furncheck.report.cutlist import load_move_lines
    from furncheck.suggest.cutlist import LoadMove

    design = load_design(str(Path(__file__).resolve().parents[1] / "designs" / "stool.yaml"))
    (line,) = load_move_lines((LoadMove("sit", "top", "100 kg", (0.0, 395.0, 745.0),
                                        (0.0, 395.004, 745.0)),), design)[1:]
    assert line == "  100 kg on top (case 'sit'): at (0, 395, 745) -> (0, 395.004, 745) mm"
