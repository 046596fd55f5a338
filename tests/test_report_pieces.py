"""Reports written piece by piece: the schema-fitted JSON writer against ``json.dumps``,
each format's pieces against the whole document, and streaming (a piece is out before the
next design is checked)."""

from __future__ import annotations

import json
import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_report import BATCH, BROKEN, SHELF, STOOL

from furncheck.report import FORMAT_MODULES, json_format, junit, reporter
from furncheck.report.entries import Entry
from furncheck.report.numbers import json_ready, real_text
from furncheck.result import (
    AnchorResult,
    BatchReport,
    CaseResult,
    ContactResult,
    DesignReport,
    JointResult,
    LoadResult,
    PlankResult,
    Violation,
)


def generic_json(batch: BatchReport) -> str:
    """The document as ``json.dumps`` writes the dicts of ``report_dict`` (what the JSON
    report was before the writer was fitted to the schema)."""
    document = {"reports": [json_format.report_dict(report) for report in batch.reports],
                "summary": dict(batch.summary)}
    return json.dumps(json_ready(document), indent=2, allow_nan=False) + "\n"


# --- numbers --------------------------------------------------------------------------------

@given(st.floats(allow_nan=True, allow_infinity=True))
@settings(max_examples=400, deadline=None, derandomize=True)
def test_real_text_is_json_of_the_rounded_number(value):
    assert real_text(value) == json.dumps(json_ready(value))


@pytest.mark.parametrize("value", [0.0, -0.0, 1e-7, -4e-7, 5e-7, 0.0000015, 123456.5,
                                   1234567.0, 2.5e-5, 0.1 + 0.2, 1e300, -1.7976931348623157e308,
                                   5e-324, 999999.5, 0.9999995, math.inf, -math.inf, math.nan])
def test_real_text_edges(value):
    """Rounding to 6 decimals then 6 significant digits: 1e-7 and 4e-7 are round-off (0.0,
    also for the negative one), 5e-7 rounds (half to even, of its binary value
    4.99999...e-7) to 0.0 too, 1.5e-6 stays; non-finite values are null."""
    assert real_text(value) == json.dumps(json_ready(value))


# --- the JSON writer ------------------------------------------------------------------------

def test_json_writer_matches_json_dumps_on_hand_built_batches():
    assert json_format.render(BATCH) == generic_json(BATCH)
    assert json_format.render(BatchReport(())) == generic_json(BatchReport(()))
    for report in (STOOL, SHELF, BROKEN):
        assert json_format.render(BatchReport((report,))) == generic_json(BatchReport((report,)))


reals = st.one_of(st.floats(allow_nan=True, allow_infinity=True),
                  st.floats(-1e4, 1e4).map(np.float64), st.integers(-10**6, 10**6))
texts = st.text(max_size=12)
points = st.tuples(reals, reals, reals)


@st.composite
def reports(draw) -> DesignReport:
    """Reports whose numbers are any floats (nan, inf, -0.0, subnormal, numpy's, ints in
    float fields) and whose texts are any unicode."""
    if draw(st.booleans()) and draw(st.booleans()):
        return DesignReport(draw(texts), draw(texts), None, error=draw(texts))
    cases = []
    for _ in range(draw(st.integers(0, 2))):
        joints = tuple(JointResult((draw(texts), draw(texts)), draw(points),
                                   draw(st.integers(0, 40)), draw(points), draw(points),
                                   draw(reals), draw(reals), draw(reals), draw(reals),
                                   draw(reals), draw(st.booleans()))
                       for _ in range(draw(st.integers(0, 2))))
        contacts = tuple(ContactResult(draw(texts), draw(points), draw(points),
                                       wall=draw(st.one_of(st.none(), st.integers(0, 3))),
                                       on=draw(st.one_of(st.none(), texts)))
                         for _ in range(draw(st.integers(0, 2))))
        loads = tuple(LoadResult(draw(texts), mass, None if mass is not None else draw(points),
                                 draw(st.one_of(st.none(), points)), draw(st.booleans()),
                                 draw(st.one_of(st.none(), texts)))
                      for mass in draw(st.lists(st.one_of(st.none(), reals), max_size=2)))
        planks = draw(st.one_of(st.none(), st.lists(st.builds(
            PlankResult, texts, reals, reals, reals, reals, reals), max_size=2)))
        anchors = tuple(draw(st.lists(st.builds(
            AnchorResult, texts, st.integers(0, 3), points, points, reals, reals, reals,
            st.integers(0, 3)),
            max_size=2)))
        cases.append(CaseResult(draw(texts), draw(st.booleans()), draw(st.booleans()),
                                joints, contacts, planks=None if planks is None
                                else tuple(planks), loads=loads, anchors=anchors))
    violations = tuple(Violation(draw(texts), draw(texts), draw(st.one_of(st.none(), texts)),
                                 draw(texts)) for _ in range(draw(st.integers(0, 2))))
    return DesignReport(draw(texts), draw(texts), draw(st.booleans()), violations,
                        tuple(cases))


@given(st.lists(reports(), max_size=3))
@settings(max_examples=150, deadline=None, derandomize=True)
def test_json_writer_matches_json_dumps_on_any_report(batch):
    batch = BatchReport(tuple(batch))
    assert json_format.render(batch) == generic_json(batch)


# --- every format: pieces make the document -------------------------------------------------

@pytest.mark.parametrize("fmt", list(FORMAT_MODULES))
def test_pieces_in_order_make_the_whole_document(fmt):
    """``document`` of the entries gives ``render``'s bytes, also for an empty batch; the
    pieces survive pickling (they come back from worker processes)."""
    import pickle

    module = reporter(fmt)
    for batch in (BATCH, BatchReport(()), BatchReport((BROKEN,))):
        entries = [pickle.loads(pickle.dumps(Entry.of(report, module.piece(report))))
                   for report in batch.reports]
        assert "".join(module.document(entries)) == module.render(batch)


def test_junit_document_is_the_indented_tree():
    """The junit document built from pieces is the document of one ``ET`` tree holding
    every suite, indented as a whole (the way it was written before pieces)."""
    root = ET.Element("testsuites", name="furncheck")
    totals = {"tests": 0, "failures": 0, "errors": 0}
    for report in BATCH.reports:
        suite = junit.design_suite(report)
        root.append(suite)
        for key in totals:
            totals[key] += int(suite.get(key))
    for key, count in totals.items():
        root.set(key, str(count))
    ET.indent(root)
    expected = ET.tostring(root, encoding="unicode", xml_declaration=True) + "\n"
    assert junit.render(BATCH) == expected
    empty = ET.Element("testsuites", name="furncheck", tests="0", failures="0", errors="0")
    assert junit.render(BatchReport(())) == \
        ET.tostring(empty, encoding="unicode", xml_declaration=True) + "\n"


@pytest.mark.parametrize("fmt,streams", [("text", True), ("json", True), ("github", True),
                                         ("junit", False), ("sarif", False)])
def test_streamed_formats_write_each_design_before_the_next_is_checked(fmt, streams):
    """text, json and github give out a design's piece before they ask for the next entry;
    junit and sarif (totals and rules come first) only after the last one."""
    module = reporter(fmt)
    asked = []

    def entries():
        for report in (SHELF, STOOL):      # the shelf has github lines, the stool none
            asked.append(report.design)
            yield Entry.of(report, module.piece(report))

    parts = module.document(entries())
    written = next(parts)
    while streams and "designs/shelf.yaml" not in written:
        written += next(parts)
    assert asked == (["designs/shelf.yaml"] if streams else
                     ["designs/shelf.yaml", "designs/stool.yaml"])
    written += "".join(parts)
    assert written == module.render(BatchReport((SHELF, STOOL)))
