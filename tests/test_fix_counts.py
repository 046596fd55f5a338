"""How many suggestions an invalid catalog design gets (issue 15: "at least 4 suggestions
where 4 distinct valid fixes exist").

For every invalid catalog design, in both models, ``suggest`` must list at least
min(4, E) suggestions, where E counts the distinct valid fixes found here without
``suggest``'s search (its margins, directions, line searches, ranking and dedup):

* one per DOF whose ``range`` (``ranges.finder``: probes and sampling of that DOF alone)
  holds a valid value within the search's limits -- half the design's size for a length,
  MAX_STEP radians for a turn -- except a turn that tilts a level plank (a top, seat or
  shelf) out of level and a change that is valid only past where the elastic model
  turns a plank's one beam (``ranges.notes.turn_reasons``, which the row names: past
  its other side, or for a plank nailed along both edges to panels past where their
  lines cover three quarters of its length; a stool's seat widened past 401 mm stops
  bending across its legs in the model, not in the shop, and a nightstand's side cut
  under 299 mm deep turns its top's beam back to its depth);
* one per discrete rule whose fix, written to YAML and checked again here, is valid,
  unless it only adds a part to the thicker-board fix: it makes every plank that fix
  thickens at least as thick (read off the design files), or builds what a fix counted
  before builds (the same planks, whatever the added ones are called: a rail under the
  top between two legs is the apron there);
* ``reconnect`` (closing a near miss as drawn) only when no DOF closes it alone: it is
  the same edit as the one-DOF closure.

Designs with 4 or more suggestions pass without counting (min(4, E) <= 4).
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from furncheck.check import check_design, check_file
from furncheck.design.load import load_design, parse_design
from furncheck.design.model import Design, with_model
from furncheck.design.write import design_text
from furncheck.dofs import design_size
from furncheck.geometry import analyze
from furncheck.ranges.finder import dof_ranges
from furncheck.report.suggestions import advice
from furncheck.suggest.candidates import MAX_STEP
from furncheck.suggest.discrete import RULES
from furncheck.suggest.discrete.common import Search
from furncheck.suggest.discrete.reconnect import reconnect_near_misses

CATALOG = Path(__file__).resolve().parents[1] / "designs"
MODELS = ("rigid", "elastic")
WANTED = 4
LEVEL_COS = 0.95        # a plank whose face normal is this close to vertical lies level

INVALID = [(path.name, model) for model in MODELS for path in sorted(CATALOG.glob("*.yaml"))
           if not check_file(str(path), model).valid]


def _counted_dofs(design: Design) -> list[str]:
    """The DOFs with a valid value within the search's limits (module docstring)."""
    size = design_size(design)
    counted = []
    for found in dof_ranges(design):
        if found.valid is None:
            continue
        plank_id, kind = found.dof.rsplit(".", 1)
        plank = design.plank(plank_id)
        turn = found.unit == "deg"
        limit = math.degrees(MAX_STEP) if turn else MAX_STEP * size
        low = max(found.valid[0], found.value - limit)
        high = min(found.valid[1], found.value + limit)
        if low > high:
            continue
        if turn and kind in ("rx", "ry") and abs(plank.rotation_matrix[2, 2]) >= LEVEL_COS:
            continue                    # a level plank tilted
        turns = [reason for reason in (found.reason or "").split("; ")
                 if reason.startswith("past ") and ("is square and then turned" in reason
                                                    or "beam is turned" in reason
                                                    or "beams of" in reason)]
        if turns:
            where = float(turns[0].split()[1].replace(",", ""))  # where the range says it turns
            if (low > where) if found.value <= where else (high < where):
                continue                # valid only with its beam turned
        counted.append(found.dof)
    return counted


def _thicknesses(design: Design) -> dict[str, float]:
    return {p.id: p.thickness for p in design.planks}


def _counted_fixes(design: Design, dofs_found: bool) -> list[str]:
    """The discrete rules with a valid, not merely added-to, fix (module docstring)."""
    geometry = analyze(design)
    search = Search(design, geometry, check_design(design, geometry))
    fixes = [fix for fix in (rule(search) for rule in RULES) if fix is not None]
    if geometry.violations and not dofs_found:
        fixes += [fix for fix in [reconnect_near_misses(search)] if fix is not None]
    original = _thicknesses(design)
    valid = []
    for fix in fixes:
        text = design_text(fix.design, "yaml")
        if check_design(parse_design(text, "fix.yaml", "yaml")).valid:
            valid.append((fix.rule, _thicknesses(fix.design), _build(fix.design)))
    alone = next((after for rule, after, _ in valid if rule == "thicker"), None)
    counted, builds = [], set()
    for rule, after, build in valid:
        if alone is not None and rule != "thicker":
            grown = {p: t for p, t in alone.items() if t > original.get(p, t)}
            if grown and all(after.get(p, 0.0) >= t for p, t in grown.items()):
                continue                # the thicker fix with a part added
        if build in builds:
            continue                    # another rule's fix, built alike
        builds.add(build)
        counted.append(rule)
    return counted


def _build(design: Design) -> tuple:
    """The planks a design builds, by size, place and turn (mm, degrees), not by name."""
    return tuple(sorted((round(p.length * 1000, 3), round(p.width * 1000, 3),
                         round(p.thickness * 1000, 3),
                         tuple(round(v * 1000, 3) for v in p.center),
                         tuple(round(v, 3) for v in p.rotation)) for p in design.planks))


@pytest.mark.parametrize("name, model", INVALID)
def test_as_many_suggestions_as_distinct_valid_fixes(catalog_suggestions, name, model):
    """suggest lists at least min(4, E) suggestions (E: module docstring)."""
    design, result = catalog_suggestions(name, model)
    listed = len(result.suggestions)
    if listed >= WANTED:
        return
    dofs = _counted_dofs(design)
    fixes = _counted_fixes(design, bool(dofs))
    assert listed >= min(WANTED, len(dofs) + len(fixes)), (
        name, model, [s.advice for s in result.suggestions], dofs, fixes)


def test_a_fix_that_spares_a_board_is_counted_and_listed(catalog_suggestions):
    """The table in the elastic model: an apron under its top (the rail rule builds the
    same part, and whichever comes first is counted and listed, once) lets the top stay
    12 mm where the thicker-board fix alone makes it 22 mm (legs 22 mm both): a fix of
    its own, counted here and listed by suggest."""
    design = with_model(load_design(str(CATALOG / "table.yaml")), "elastic")
    counted = _counted_fixes(design, False)
    assert len({"apron", "rail"} & set(counted)) == 1
    _, result = catalog_suggestions("table.yaml", "elastic")
    listed = [s.rule for s in result.suggestions]
    assert len({"apron", "rail"} & set(listed)) == 1


def test_each_way_to_close_a_gap_is_offered_with_the_boards_it_needs(catalog_suggestions):
    """bookshelf-gap in the elastic model: its shelf ends 3 mm short of side_r, and its
    12 mm shelf and bottom sag (with creep 29 mm against 2.98 mm, 5.93 against 1.5).  The
    rigid model closes the gap four ways (shelf longer, sides closer, either side moved);
    in the elastic one each of them is offered with the thicker boards it then needs, the
    shelf's once (reconnect), each file valid as checked here from its text, and the
    advice says the change in shop words before the boards, in amounts a maker measures
    (``shop_round``): closing the 3 mm gap to within the 0.5 mm tolerance takes 2.5 to
    3.5 mm, so one side moves 3 mm, and the two sides 1.5 mm each (1 mm each would leave
    a 1 mm gap; 2 mm each would close 4 mm, the shelf's end 1 mm into the side)."""
    _, rigid = catalog_suggestions("bookshelf-gap.yaml", "rigid")
    design, elastic = catalog_suggestions("bookshelf-gap.yaml", "elastic")
    closing = [s for s in elastic.suggestions if s.rule == "reconnect"]
    assert len(closing) == len(rigid.suggestions) == 4
    changed = {frozenset(e.plank for e in s.edits
                         if {f.field for f in e.fields} - {"thickness"}) for s in closing}
    assert len(changed) == 4
    for suggestion in closing:
        assert check_design(parse_design(suggestion.text, "s.yaml", "yaml")).valid
        assert any(e.field("thickness") for e in suggestion.edits)
    words = sorted(advice(s, design).split(";")[0] for s in closing if s.dofs)
    assert words == ["Move side_l 3 mm toward side_r",
                     "Move side_l and side_r closer together by 1.5 mm each",
                     "Move side_r 3 mm toward side_l"]
    for suggestion in closing:          # the bottom and top between the sides follow
        if suggestion.dofs:
            assert "; to fit, shorten bottom and top by 3 mm each (600 -> 597 mm), and " \
                "make bottom 22 mm thick" in advice(suggestion, design)
