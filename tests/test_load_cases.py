"""Load cases that ``include`` others (contract section 1): what acts, in which order, what
the reports list, what the design file writes back, and one clear line for each bad
``include`` at the real command line."""

from __future__ import annotations

import copy
import json
from dataclasses import replace
from pathlib import Path

import physics_designs as pd
import pytest
import yaml
from click.testing import CliRunner

from furncheck.check import check_design
from furncheck.cli.main import main
from furncheck.design import Load, LoadCase, parse_design
from furncheck.design.model import with_model
from furncheck.design.write import design_text
from furncheck.dofs import apply_dof, parse_dof, structure
from furncheck.geometry import analyze

G = pd.G
DESIGNS = Path(__file__).resolve().parents[1] / "designs"


class _NoAliases(yaml.SafeDumper):
    """Writes a value that appears twice twice (design files refuse YAML aliases)."""

    def ignore_aliases(self, data) -> bool:
        return True


def text_of(design: dict) -> str:
    return yaml.dump(design, Dumper=_NoAliases, sort_keys=False)


def parsed(design: dict):
    return parse_design(text_of(design), "design.yaml", "yaml")


def bench_with_push(include: bool) -> dict:
    """The two-leg bench with 80 kg at the seat centre (``default``) and a case ``push``:
    the same 80 kg plus 20 kg at x = +175 mm, through ``include`` or written out."""
    design = pd.bench(mass=80.0, x=0.0)
    extra = {"plank": "seat", "mass": 20.0, "at": [175.0, 0.0, pd.BENCH_SEAT_TOP]}
    if include:
        design["load_cases"] = {"push": {"include": ["default"], "loads": [extra]}}
    else:
        design["load_cases"] = {"push": [*copy.deepcopy(design["loads"]), extra]}
    return design


def without_loads(report):
    """The report's cases with their ``loads`` lists taken out (all else compared)."""
    return [replace(case, loads=()) for case in report.cases]


def leg_reactions(case) -> dict[str, float]:
    """N: the ground's vertical force summed per leg."""
    sums: dict[str, float] = {}
    for contact in case.contacts:
        sums[contact.plank] = sums.get(contact.plank, 0.0) + contact.force[2]
    return sums


# --- what acts ----------------------------------------------------------------------------------

@pytest.mark.parametrize("model", ["rigid", "elastic"])
def test_an_included_case_equals_the_same_loads_written_out(model):
    """Bench: seat 800 x 300 x 12 (2.16 kg) on two legs 450 x 300 x 12 (1.215 kg each) at
    x = +-350, so W = 4.59 kg of self-weight at x = 0.  ``push`` = default's 80 kg at x = 0
    plus its own 20 kg at x = +175.  Total 104.59 kg x 9.81 = 1026.0 N on the ground; moments
    about the left leg: right leg = (84.59 x 350 + 20 x 525) / 700 kg = 57.30 kg = 562.1 N,
    left 47.30 kg = 464.0 N (the corners sit at 350 +- 6 mm: the lever 350 becomes
    sum x_i^2 / (4 x 350) = 350.1, 0.03 %).  Written out or included: the same joint
    forces, contacts and verdict, bit for bit."""
    included = with_model(parsed(bench_with_push(True)), model)
    written = with_model(parsed(bench_with_push(False)), model)
    assert included.load_cases[1].loads == written.load_cases[1].loads
    first, second = check_design(included), check_design(written)
    assert without_loads(first) == without_loads(second)
    assert first.valid == second.valid and first.violations == second.violations
    push = first.cases[1]
    legs = leg_reactions(push)
    assert sum(legs.values()) == pytest.approx(104.5905 * G, rel=1e-3)
    assert legs["leg_r"] == pytest.approx(562.1, rel=0.01)
    assert legs["leg_l"] == pytest.approx(464.0, rel=0.01)
    assert [load.origin for load in push.loads] == ["default", None]
    assert [load.mass for load in push.loads] == [80.0, 20.0]


def chained() -> dict:
    """default: 1 kg on the seat; b includes default, adds 2 kg; a includes b and default
    (default twice: through b and directly), adds 3 kg; c includes a and b."""
    design = pd.bench(mass=1.0)
    load = design["loads"][0]
    design["load_cases"] = {
        "a": {"include": ["b", "default"], "loads": [{**load, "mass": 3.0}]},
        "b": {"include": ["default"], "loads": [{**load, "mass": 2.0}]},
        "c": {"include": ["a", "b"]},
    }
    return design


def test_includes_chain_and_each_case_acts_once_in_include_order():
    """a -> b -> default: default's load (once, though a reaches it twice), then b's, then
    a's own.  c includes a and b: b is already in through a, so c = a's loads."""
    cases = {case.name: case for case in parsed(chained()).load_cases}
    masses = {name: [load.mass for load in case.loads] for name, case in cases.items()}
    assert masses == {"default": [1.0], "a": [1.0, 2.0, 3.0], "b": [1.0, 2.0],
                      "c": [1.0, 2.0, 3.0]}
    assert cases["a"].origins == ("default", "b", "a")
    assert cases["c"].origins == ("default", "b", "a") and cases["c"].own_loads == ()
    assert cases["a"].includes == ("b", "default") and cases["default"].includes == ()
    assert cases["b"].own_loads == (Load.of_mass("seat", 2.0, (0.0, 0.0, 0.462)),)


def test_mapping_forms_without_include_or_own_loads():
    """``{loads: [...]}`` is the plain list; ``{include: [...]}`` has no loads of its own;
    ``include: []`` includes nothing."""
    design = pd.bench(mass=1.0)
    design["load_cases"] = {"own": {"loads": [{"plank": "seat", "mass": 2.0}]},
                            "same": {"include": ["default"]},
                            "none": {"include": []}}
    default, own, same, none = parsed(design).load_cases
    assert own == LoadCase("own", (Load.of_mass("seat", 2.0),))
    assert same.loads == default.loads and same.origins == ("default",)
    assert none == LoadCase("none")


# --- writing the design back --------------------------------------------------------------------

def test_written_design_keeps_include_and_reads_back_the_same():
    design = parsed(chained())
    text = design_text(design, "yaml")
    document = yaml.safe_load(text)
    assert document["load_cases"]["c"] == {"include": ["a", "b"]}
    assert document["load_cases"]["a"] == {
        "include": ["b", "default"],
        "loads": [{"plank": "seat", "mass": 3.0, "at": [0.0, 0.0, 462.0]}]}
    again = parse_design(text, "again.yaml", "yaml")
    assert again.load_cases == design.load_cases
    json_again = parse_design(design_text(design, "json"), "again.json", "json")
    assert json_again.load_cases == design.load_cases


def test_included_loads_ride_with_their_plank():
    """Moving the seat 40 mm along x moves default's load and the same load included in
    ``push`` alike; the written design still includes default."""
    design = with_model(parsed(bench_with_push(True)), "rigid")
    moved = apply_dof(design, structure(design, analyze(design)), parse_dof(design, "seat.x"),
                      40.0)
    default, push = moved.load_cases
    assert push.loads[0] == default.loads[0]
    assert default.loads[0].point[0] == pytest.approx(0.040)
    assert push.loads[1].point[0] == pytest.approx(0.175 + 0.040)
    assert yaml.safe_load(design_text(moved, "yaml"))["load_cases"]["push"]["include"] == \
        ["default"]


# --- the command line ---------------------------------------------------------------------------

def run(*args: str):
    return CliRunner().invoke(main, list(args))


def write(folder: Path, name: str, design: dict) -> str:
    path = folder / name
    path.write_text(text_of(design), encoding="utf-8")
    return str(path)


def test_json_lists_each_cases_loads_with_where_they_came_from(tmp_path):
    path = write(tmp_path, "bench.yaml", bench_with_push(True))
    result = run("validate", path, "--format", "json", "--model", "rigid")
    default, push = json.loads(result.output)["reports"][0]["cases"]
    assert default["loads"] == [{"plank": "seat", "mass": 80.0, "at": [0.0, 0.0, 462.0]}]
    assert push["loads"] == [
        {"plank": "seat", "mass": 80.0, "at": [0.0, 0.0, 462.0], "from": "default"},
        {"plank": "seat", "mass": 20.0, "at": [175.0, 0.0, 462.0]}]
    assert run("validate", path, "--format", "json", "--model", "rigid").output == result.output


def test_text_names_each_cases_loads_on_one_line(tmp_path):
    design = bench_with_push(True)
    design["load_cases"]["push"]["loads"].append(
        {"plank": "seat", "force": [0, 80, 0], "at": [-400, 0, 456]})
    design["load_cases"]["empty"] = []
    result = run("validate", write(tmp_path, "bench.yaml", design), "--model", "rigid")
    lines = [line for line in result.output.splitlines() if line.startswith("  case ")]
    assert lines == [
        "  case 'default': 1 load: 80 kg on seat at (0, 0, 462) mm",
        "  case 'push': 3 loads (1 from default): 80 kg on seat at (0, 0, 462) mm; 20 kg on "
        "seat at (175, 0, 462) mm; 80 N +y on seat at (-400, 0, 456) mm",
        "  case 'empty': self-weight only",
    ]


def test_catalog_cases_that_include_list_the_included_loads():
    """bookshelf-20's pull = default's ten shelves (15 kg each) + 60 N pulling the cap."""
    result = run("validate", str(DESIGNS / "bookshelf-20.yaml"), "--format", "json",
                 "--model", "rigid")
    cases = {case["name"]: case for case in json.loads(result.output)["reports"][0]["cases"]}
    pull = cases["pull"]["loads"]
    assert len(pull) == 11 and all(load["from"] == "default" for load in pull[:10])
    assert [load["mass"] for load in pull[:10]] == [15.0] * 10
    assert pull[10] == {"plank": "cap", "force": [0.0, -60.0, 0.0], "at": [0.0, -160.0, 1806.0]}


def range_json(path: str) -> list:
    result = run("range", path, "seat.x", "seat.length", "--format", "json", "--model", "rigid")
    assert result.exit_code == 0, result.output
    return json.loads(result.output)["ranges"]


def test_range_is_the_same_with_included_or_written_out_loads(tmp_path):
    included = range_json(write(tmp_path, "included.yaml", bench_with_push(True)))
    written = range_json(write(tmp_path, "written.yaml", bench_with_push(False)))
    assert included == written


BENCH = """\
furncheck: 1
planks:
  - {id: seat, size: [800, 300], center: [0, 0, 456]}
  - {id: leg_l, size: [450, 300], center: [-350, 0, 225], rotation: [0, -90, 0]}
  - {id: leg_r, size: [450, 300], center: [350, 0, 225], rotation: [0, -90, 0]}
loads:
  - {plank: seat, mass: 1, at: [0, 0, 462]}
load_cases:
"""
"""The bench with 1 kg on its seat; ``load_cases:`` is line 8, the first case line 9."""

BAD_INCLUDES = {
    # name -> (load_cases text, key path, line, message fragment)
    "unknown case": ("  push: {include: [defualt]}\n", "load_cases.push.include[0]", 9,
                     'unknown load case "defualt" (did you mean "default"?); cases: default, '
                     "push"),
    "circular": ("  a: {include: [b]}\n  b: {include: [a]}\n", "load_cases.a.include", 9,
                 "circular include a -> b -> a"),
    "circular further on": (
        "  a: {include: [default, b]}\n  b: {include: [c]}\n  c: {include: [b]}\n",
        "load_cases.b.include", 10, "circular include b -> c -> b"),
    "self": ("  a:\n    include: [a]\n", "load_cases.a.include", 10, "circular include a -> a"),
    "not a list": ("  push:\n    include: default\n", "load_cases.push.include", 10,
                   'expected a list of load case names, got text "default" '
                   "(write include: [default])"),
    "not names": ("  push: {include: [{case: default}]}\n", "load_cases.push.include[0]", 9,
                  "expected a load case name, got a mapping"),
    "twice": ("  push:\n    include:\n      - default\n      - default\n",
              "load_cases.push.include[1]", 12,
              'case "default" is included twice (load_cases.push.include[0] and '
              "load_cases.push.include[1])"),
    "unknown key": ("  push:\n    includes: [default]\n", "load_cases.push.includes", 10,
                    'unknown key "includes" (did you mean "include"?); allowed keys: include, '
                    "loads"),
    "empty mapping": ("  push: {}\n", "load_cases.push", 9, "an empty load case mapping"),
    "not a case": ("  push: 80\n", "load_cases.push", 9,
                   "expected a list of loads or a mapping {include: [case, ...], loads: [...]}, "
                   "got a number (80)"),
    "bad own load": ("  push:\n    include: [default]\n    loads: [{plank: sea, mass: 2}]\n",
                     "load_cases.push.loads[0].plank", 11,
                     'unknown plank "sea" (did you mean "seat"?)'),
}


@pytest.mark.parametrize("name", sorted(BAD_INCLUDES))
def test_bad_include_is_one_line_with_key_path_and_line(tmp_path, name):
    cases, key, line, message = BAD_INCLUDES[name]
    path = tmp_path / "bad.yaml"
    path.write_text(BENCH + cases, encoding="utf-8")
    result = run("validate", str(path))
    assert result.exit_code == 2 and "Traceback" not in result.output
    lines = result.output.splitlines()
    assert len(lines) == 2 and lines[1] == "1 design: 0 valid, 0 invalid, 1 error"
    assert lines[0].startswith(f"{path}: error: line {line}: {key}: "), lines[0]
    assert message in lines[0], lines[0]


def test_include_of_default_without_top_level_loads(tmp_path):
    design = pd.bench(mass=0.0)
    del design["loads"]
    design["load_cases"] = {"push": {"include": ["default"]}}
    result = run("validate", write(tmp_path, "bad.yaml", design))
    assert result.exit_code == 2
    assert 'load_cases.push.include[0]: unknown load case "default": the file has no ' \
           'top-level "loads"' in result.output
