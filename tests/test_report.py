"""Reporters on hand-built batches: schema, determinism, rounding, escaping."""

from __future__ import annotations

import json
import math
import xml.etree.ElementTree as ET

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from furncheck import __version__
from furncheck.report import REPORTERS, render
from furncheck.report.common import input_errors
from furncheck.report.github import escape_data, escape_property
from furncheck.report.numbers import format_number, format_percent, json_ready, round_significant
from furncheck.report.sarif import artifact_uri
from furncheck.result import (
    VIOLATION_KINDS,
    BatchReport,
    CaseResult,
    ContactResult,
    DesignReport,
    JointResult,
    LoadResult,
    Violation,
)


def joint(planks=("seat", "leg1"), utilization=0.42, pull=294.0, durable=True) -> JointResult:
    return JointResult(planks=planks, point=(0.0, 150.0, 450.0), nails=15,
                       force=(1.0 / 3.0, -0.0, -98.100000000001), moment=(0.0, 29.4, 1e-20),
                       pull=pull, shear=6.5, pull_capacity=700.0, shear_capacity=190.0,
                       utilization=utilization, durable=durable)


def case(name="default", joints=None, durable=True, stable=True, loads=()) -> CaseResult:
    joints = (joint(),) if joints is None else joints
    contacts = (ContactResult("base", (200.0, 150.0, 0.0), (0.0, -0.0, 31.2)),)
    return CaseResult(name, durable, stable, tuple(joints), contacts, loads=tuple(loads))


SEAT_LOAD = LoadResult("seat", 80.0, None, (0.0, 0.0, 450.00000000000006))
PUSH = LoadResult("seat", None, (100.0, 0.0, -0.0), (-200.0, 0.0, 444.0))
BOOKS = [LoadResult(shelf, 15.0, None, None, origin="books") for shelf in ("a", "b", "c")]

STOOL = DesignReport(
    design="designs/stool.yaml", name="stool", valid=True,
    cases=(case("default", (joint(utilization=0.1),), loads=[SEAT_LOAD]),
           case("sit", (joint(("seat", "leg2"), 0.3), joint(("seat", "leg1"), 0.42)),
                loads=[LoadResult("seat", 80.0, None, None, origin="default"), PUSH])))

SHELF = DesignReport(
    design="designs/shelf.yaml", name="shelf", valid=False,
    violations=(
        Violation("non-durable", "post/shelf", "default", "pull 812 N per nail exceeds 700 N",
                  line=14),
        Violation("floating", "lamp", None, "1 plank touches the ground nowhere"),
    ),
    cases=(case("default", (joint(("post", "shelf"), 1.16, 812.0, False),), durable=False,
                loads=[*BOOKS, LoadResult("d", 15.0, None, None, origin="books"),
                       LoadResult("post", None, (30.0, 0.0, -40.0), None, spread=True)]),
           case("lean")))

BROKEN = DesignReport(design="designs/broken.yaml", name="broken", valid=None,
                      error="designs/broken.yaml:3: planks[0].size: expected [length, width]")

BATCH = BatchReport((STOOL, SHELF, BROKEN))


# --- every format ---------------------------------------------------------------------------

@pytest.mark.parametrize("fmt", list(REPORTERS))
def test_every_format_is_deterministic_and_ends_with_newline(fmt):
    first = render(BATCH, fmt)
    again = render(BatchReport(tuple(BATCH.reports)), fmt)
    assert first == again
    assert first.endswith("\n") and not first.endswith("\n\n")


@pytest.mark.parametrize("fmt", list(REPORTERS))
def test_every_format_handles_an_empty_batch(fmt):
    assert render(BatchReport(()), fmt).endswith("\n")


def test_unknown_format_is_a_value_error():
    with pytest.raises(ValueError, match="unknown report format"):
        render(BATCH, "yaml")


# --- json -----------------------------------------------------------------------------------

def test_json_keys_are_exactly_the_contract_schema():
    document = json.loads(render(BATCH, "json"))
    assert list(document) == ["reports", "summary"]
    assert document["summary"] == {"designs": 3, "valid": 1, "invalid": 1, "errors": 1}
    assert list(document["summary"]) == ["designs", "valid", "invalid", "errors"]
    stool, shelf, broken = document["reports"]
    assert list(shelf) == ["design", "name", "valid", "violations", "cases"]
    assert list(shelf["violations"][0]) == ["kind", "where", "case", "message"]
    assert shelf["violations"][1]["case"] is None
    assert list(shelf["cases"][0]) == ["name", "durable", "stable", "joints", "contacts",
                                       "loads"]
    assert list(shelf["cases"][0]["joints"][0]) == [
        "planks", "point", "nails", "force", "moment", "pull", "shear", "pull_capacity",
        "shear_capacity", "utilization", "durable"]
    assert list(shelf["cases"][0]["contacts"][0]) == ["plank", "point", "force"]
    assert broken == {"design": "designs/broken.yaml", "name": "broken",
                      "error": "designs/broken.yaml:3: planks[0].size: expected [length, width]"}
    assert stool["valid"] is True and shelf["valid"] is False


def test_json_loads_say_what_the_file_said_and_where_they_came_from():
    """A mass is a mass (kg), a force a world vector (N); ``at`` null at the plank centre;
    ``spread`` only when true; ``from`` only for a load that came through ``include``."""
    stool, shelf, _ = json.loads(render(BATCH, "json"))["reports"]
    assert stool["cases"][0]["loads"] == [{"plank": "seat", "mass": 80.0,
                                           "at": [0.0, 0.0, 450.0]}]
    assert stool["cases"][1]["loads"] == [
        {"plank": "seat", "mass": 80.0, "at": None, "from": "default"},
        {"plank": "seat", "force": [100.0, 0.0, 0.0], "at": [-200.0, 0.0, 444.0]}]
    assert shelf["cases"][0]["loads"][-1] == {"plank": "post", "force": [30.0, 0.0, -40.0],
                                              "at": None, "spread": True}
    assert shelf["cases"][1]["loads"] == []


def test_json_rounds_floats_and_keeps_ints():
    text = render(BATCH, "json")
    joint_json = json.loads(text)["reports"][0]["cases"][0]["joints"][0]
    assert joint_json["force"] == [0.333333, 0.0, -98.1]
    assert joint_json["moment"] == [0.0, 29.4, 0.0]   # 1e-20 is solver round-off
    assert joint_json["nails"] == 15 and isinstance(joint_json["nails"], int)
    assert joint_json["planks"] == ["seat", "leg1"]
    assert "-0.0" not in text
    assert '"nails": 15,' in text and text.startswith('{\n  "reports": [\n')


def test_json_writes_non_finite_numbers_as_null():
    report = DesignReport("x.yaml", "x", True, cases=(case(joints=(joint(utilization=math.inf),)),))
    document = json.loads(render(BatchReport((report,)), "json"))
    assert document["reports"][0]["cases"][0]["joints"][0]["utilization"] is None


def test_round_significant():
    assert round_significant(123456789.0) == 123457000.0
    assert round_significant(-0.0) == 0.0 and math.copysign(1.0, round_significant(-0.0)) == 1.0
    assert round_significant(-1e-30) == 0.0            # below REPORT_DECIMALS: round-off
    assert round_significant(2.5e-5) == 2.5e-5
    assert round_significant(0.1 + 0.2) == 0.3
    assert math.isnan(round_significant(math.nan))


@settings(deadline=None, derandomize=True)
@given(st.floats(allow_nan=False, allow_infinity=False))
def test_rounding_is_idempotent_and_survives_json(value):
    rounded = round_significant(value)
    assert round_significant(rounded) == rounded
    assert json.loads(json.dumps(json_ready(value))) == rounded


def test_json_ready_accepts_numpy_values():
    np = pytest.importorskip("numpy")
    assert json_ready({"a": np.float64(-0.0), "b": np.int64(3), "c": np.array([1.0 / 3.0]),
                       "d": np.bool_(True)}) == {"a": 0.0, "b": 3, "c": [0.333333], "d": True}


def test_text_numbers():
    assert format_number(812.0000001) == "812"
    assert format_number(-0.0) == "0"
    assert format_number(0.125) == "0.125"
    assert format_percent(0.42) == "42 %"
    assert format_percent(0.0035) == "0.35 %"
    assert format_percent(0.0) == "0 %"


# --- text -----------------------------------------------------------------------------------

def test_text_report_lines():
    assert render(BATCH, "text").splitlines() == [
        "designs/stool.yaml: valid (worst joint seat/leg1 at 42 % in case 'sit')",
        "  case 'default': 1 load: 80 kg on seat at (0, 0, 450) mm",
        "  case 'sit': 2 loads (1 from default): 80 kg on seat; 100 N +x on seat at "
        "(-200, 0, 444) mm",
        "designs/shelf.yaml: INVALID, 2 violations",
        "  non-durable: post/shelf in case 'default': pull 812 N per nail exceeds 700 N "
        "(line 14)",
        "  floating: lamp: 1 plank touches the ground nowhere",
        "  case 'default': 5 loads (4 from books): 15 kg each on a, b, c, d; "
        "(30, 0, -40) N spread on post",
        "  case 'lean': self-weight only",
        "designs/broken.yaml: error: line 3: planks[0].size: expected [length, width]",
        "3 designs: 1 valid, 1 invalid, 1 error",
    ]


def test_text_singulars_and_designs_without_joints():
    single = DesignReport("one.yaml", "one", True, cases=(case(joints=()),))
    bad = DesignReport("bad.yaml", "bad", False, violations=(SHELF.violations[1],))
    assert render(BatchReport((single, bad)), "text").splitlines() == [
        "one.yaml: valid (no nail joints)",
        "  case 'default': self-weight only",
        "bad.yaml: INVALID, 1 violation",
        "  floating: lamp: 1 plank touches the ground nowhere",
        "2 designs: 1 valid, 1 invalid, 0 errors",
    ]


def test_text_case_line_stays_one_line_for_many_loads():
    """Seven different point loads: five phrases, then 'and 2 more', on one line."""
    loads = [LoadResult("shelf", float(kg), None, (kg * 10.0, 0.0, 600.0)) for kg in range(1, 8)]
    report = DesignReport("many.yaml", "many", True, cases=(case(loads=loads),))
    (line,) = [row for row in render(BatchReport((report,)), "text").splitlines()
               if row.startswith("  case ")]
    assert line == ("  case 'default': 7 loads: 1 kg on shelf at (10, 0, 600) mm; 2 kg on shelf "
                    "at (20, 0, 600) mm; 3 kg on shelf at (30, 0, 600) mm; 4 kg on shelf at "
                    "(40, 0, 600) mm; 5 kg on shelf at (50, 0, 600) mm; and 2 more")


def test_input_error_splits_file_and_line():
    assert input_errors(BROKEN) == [(3, "planks[0].size: expected [length, width]")]
    other = DesignReport("a.yaml", "a", None, error="a.yaml: not a mapping")
    assert input_errors(other) == [(None, "not a mapping")]
    internal = DesignReport("a.yaml", "a", None, error="internal error: boom")
    assert input_errors(internal) == [(None, "internal error: boom")]


# --- junit ----------------------------------------------------------------------------------

def test_junit_parses_and_counts():
    root = ET.fromstring(render(BATCH, "junit").encode("utf-8"))
    assert root.tag == "testsuites"
    suites = root.findall("testsuite")
    assert [s.get("name") for s in suites] == [r.design for r in BATCH.reports]
    # 2 cases + 2 cases + 1 load testcase
    assert len(root.findall("testsuite/testcase")) == 5
    assert (root.get("tests"), root.get("failures"), root.get("errors")) == ("5", "2", "1")
    stool, shelf, broken = suites
    assert (stool.get("tests"), stool.get("failures"), stool.get("errors")) == ("2", "0", "0")
    assert (shelf.get("tests"), shelf.get("failures")) == ("2", "2")
    default, lean = shelf.findall("testcase")
    assert (default.get("classname"), default.get("name")) == ("designs/shelf.yaml", "default")
    assert "post/shelf" in default.find("failure").text
    assert "lamp" in default.find("failure").text  # case None fails every case
    assert "post/shelf" not in lean.find("failure").text
    assert "lamp" in lean.find("failure").text
    assert broken.find("testcase/error") is not None and broken.get("errors") == "1"


def test_junit_survives_control_characters_and_geometry_only_designs():
    report = DesignReport("g.yaml", "g", False,
                          violations=(Violation("floating", "a", None, "bell \x07 rings"),))
    root = ET.fromstring(render(BatchReport((report,)), "junit").encode("utf-8"))
    (testcase,) = root.iter("testcase")
    assert testcase.get("name") == "geometry"
    assert "\x07" not in testcase.find("failure").text


# --- github ---------------------------------------------------------------------------------

def test_github_annotations():
    lines = render(BATCH, "github").splitlines()
    assert lines == [
        "::error file=designs/shelf.yaml,line=14,title=furncheck non-durable::"
        "post/shelf in case 'default': pull 812 N per nail exceeds 700 N",
        "::error file=designs/shelf.yaml,title=furncheck floating::"
        "lamp: 1 plank touches the ground nowhere",
        "::error file=designs/broken.yaml,line=3,title=furncheck input-error::"
        "planks[0].size: expected [length, width]",
        "::notice title=furncheck::3 designs: 1 valid, 1 invalid, 1 error",
    ]


def test_github_escaping():
    assert escape_data("100% a\r\nb: c, d") == "100%25 a%0D%0Ab: c, d"
    assert escape_property("a,b:c%\n") == "a%2Cb%3Ac%25%0A"
    report = DesignReport("odd, name:1.yaml", "odd", False,
                          violations=(Violation("sliding", "a", "x", "50%\nmore"),))
    (line, _) = render(BatchReport((report,)), "github").splitlines()
    assert line == ("::error file=odd%2C name%3A1.yaml,title=furncheck sliding::"
                    "a in case 'x': 50%25%0Amore")


def test_annotation_paths_lose_dot_slash_and_text_lines_never_start_a_command():
    """An annotation's ``file`` is the path as the SARIF log's URI has it ('./designs//x'
    named 'designs/x'); the text report shows a path that begins with '::' as './::...':
    a GitHub runner reads a log line that begins with '::' as a workflow command (a
    design named '::error::x.yaml' wrote an annotation from the text report), after any
    blanks (the runner strips them), and writes '##[' as '#\\x23[' anywhere (the runner's
    old command form, read anywhere in a line)."""
    from furncheck.report.github import annotation_path
    from furncheck.report.text import shown

    assert annotation_path("./designs//x.yaml") == "designs/x.yaml"
    assert annotation_path("/abs/x.yaml") == "/abs/x.yaml"
    assert shown("::error::x.yaml") == "./::error::x.yaml"
    assert shown(" ::error::x.yaml") == "./ ::error::x.yaml"    # the runner strips blanks
    assert shown("designs/::x.yaml") == "designs/::x.yaml"
    # the old form, '##[error]...', is read anywhere in a line: every text report's lines
    broken = DesignReport(design="a##[error]z.yaml", name="z", valid=None,
                          error="line 2: planks: expected a list")
    assert "##[" not in render(BatchReport((broken,)), "text")
    assert "a#\\x23[error]z.yaml" in render(BatchReport((broken,)), "text")
    report = DesignReport(design="::warning title=x::y.yaml", name="y", valid=None,
                          error="line 2: planks: expected a list")
    assert not any(line.startswith("::") for line in render(BatchReport((report,)),
                                                              "text").splitlines())


# --- sarif ----------------------------------------------------------------------------------

def test_sarif_log():
    log = json.loads(render(BATCH, "sarif"))
    assert log["version"] == "2.1.0" and "sarif" in log["$schema"]
    (run,) = log["runs"]
    driver = run["tool"]["driver"]
    assert driver["name"] == "furncheck" and driver["version"] == __version__
    rule_ids = [rule["id"] for rule in driver["rules"]]
    assert rule_ids == list(VIOLATION_KINDS) + ["input-error"]
    assert all(rule["shortDescription"]["text"] for rule in driver["rules"])
    results = run["results"]
    assert [r["ruleId"] for r in results] == ["non-durable", "floating", "input-error"]
    for result in results:
        assert result["level"] == "error" and result["message"]["text"]
        assert rule_ids[result["ruleIndex"]] == result["ruleId"]
    locations = [r["locations"][0]["physicalLocation"] for r in results]
    assert locations[0] == {"artifactLocation": {"uri": "designs/shelf.yaml"},
                            "region": {"startLine": 14}}
    assert "region" not in locations[1]
    assert locations[2]["region"] == {"startLine": 3}


def test_sarif_fingerprints_name_the_problem_not_its_line_or_numbers(tmp_path):
    """Code scanning matches alerts from run to run by ``partialFingerprints``: without
    them the upload hashes the line's text, the same for designs/stool.yaml's seat
    sagging in its three cases (one line).  Each result's fingerprint is its rule, file,
    planks and case: three cases, three fingerprints; the same design with a comment
    line above and 5 kg more on the seat (other lines, other numbers) gives the same."""
    from pathlib import Path

    from furncheck.batch import check_one
    from furncheck.report.sarif import FINGERPRINT

    source = (Path(__file__).resolve().parents[1] / "designs" / "stool.yaml").read_text()
    first = tmp_path / "stool.yaml"
    first.write_text(source)
    before = json.loads(render(BatchReport((check_one(str(first)),)), "sarif"))
    first.write_text("# moved down a line\n" + source.replace(
        "{plank: seat, mass: 80, at: [0, 0, 450]}", "{plank: seat, mass: 85, at: [0, 0, 450]}"))
    after = json.loads(render(BatchReport((check_one(str(first)),)), "sarif"))

    def read(log):
        return [(r["partialFingerprints"][FINGERPRINT],
                 r["locations"][0]["physicalLocation"]["region"]["startLine"],
                 r["message"]["text"]) for r in log["runs"][0]["results"]]

    old, new = read(before), read(after)
    assert len(old) == 3 and len({line for _, line, _ in old}) == 1
    assert len({fingerprint for fingerprint, _, _ in old}) == 3
    assert [f for f, _, _ in new] == [f for f, _, _ in old]
    assert all(b[1] == a[1] + 1 for a, b in zip(old, new))
    assert old[0][2] != new[0][2]           # the default case's sag, with 85 kg


def test_sarif_uris():
    assert artifact_uri("designs/my shelf.yaml") == "designs/my%20shelf.yaml"
    assert artifact_uri("/abs/x.yaml") == "file:///abs/x.yaml"


def test_a_toppling_case_names_the_joint_that_would_fail_held_down():
    """designs/bench-tips.yaml (elastic) topples; bolted down, its seat/leg_r joint pulls
    past capacity (its case reads durable: false) but raises no non-durable violation of
    its own (the toppling comes first): the lift-off message names it, with the pull of
    the case's worst failing joint, so a fix of the toppling alone is not taken for
    enough."""
    from pathlib import Path

    from furncheck.check import check_file
    from furncheck.plain import plain_number

    report = check_file(str(Path(__file__).resolve().parents[1] / "designs" /
                            "bench-tips.yaml"))
    (violation,) = report.violations
    (case,) = report.cases
    failing = [j for j in case.joints if not j.durable]
    assert violation.kind == "lift-off" and failing and not case.durable
    worst = max(failing, key=lambda j: j.utilization)
    assert violation.message.endswith(
        f"; so held, joint {'/'.join(worst.planks)} would fail too (pull "
        f"{plain_number(worst.pull)} N per nail exceeds {plain_number(worst.pull_capacity)} N)")


def test_every_violation_kind_has_a_sarif_rule_description():
    """Code scanning shows a rule's short description on every alert: each violation kind
    of the contract has its own sentence (sagging and overstressed, the elastic model's
    commonest, read "furncheck violation 'sagging'." before)."""
    from furncheck.report.sarif import RULE_DESCRIPTIONS
    from furncheck.result import VIOLATION_KINDS

    for kind in VIOLATION_KINDS:
        assert kind in RULE_DESCRIPTIONS and RULE_DESCRIPTIONS[kind].endswith("."), kind
