"""``--format junit``: JUnit XML for CI test dashboards.

    <testsuites name="furncheck" tests=".." failures=".." errors="..">
      <testsuite name="designs/shelf.yaml" tests="2" failures="1" errors="0" skipped="0">
        <testcase classname="designs/shelf.yaml" name="default">
          <failure type="non-durable" message="1 violation">non-durable: post/shelf ...</failure>
        </testcase>
        <testcase classname="designs/shelf.yaml" name="sit" />
      </testsuite>
      ...

One testsuite per design, one testcase per load case.  A violation with case None
(geometry) fails every case.  A design with violations but no load case results gets one
testcase named ``geometry``; an unreadable input one testcase named ``load`` with an
``<error>``.  No ``time`` attributes: the output is deterministic.
"""

from __future__ import annotations

import functools
import re
import xml.etree.ElementTree as ET
from collections.abc import Iterable, Iterator
from typing import Any

from furncheck.files import readable
from furncheck.report.common import INPUT_ERROR, case_violations, describe_violation, plural
from furncheck.report.entries import Entry
from furncheck.result import BatchReport, DesignReport, Violation

LOAD_TESTCASE = "load"
"""Name of the single testcase of an input that could not be read."""
GEOMETRY_TESTCASE = "geometry"
"""Name of the single testcase of a design that has violations but no load case results."""

_XML_INVALID = "[^\t\n\r\x20-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]"
"""Characters XML 1.0 cannot hold (compiled on first use: keeps CLI start-up fast)."""


DECLARATION = "<?xml version='1.0' encoding='utf-8'?>"
"""What ``ET.tostring(..., encoding="unicode", xml_declaration=True)`` starts with."""

_TOTALS = ("tests", "failures", "errors")


def render(batch: BatchReport) -> str:
    """The batch as a JUnit XML document (UTF-8 declaration, indented, trailing newline)."""
    return "".join(document(Entry.of(report, piece(report)) for report in batch.reports))


def piece(report: DesignReport) -> tuple[str, tuple[int, int, int]]:
    """(the design's ``<testsuite>``, indented as in the document, in one line per element,
    with no line end after it; its tests, failures and errors)."""
    suite = design_suite(report)
    ET.indent(suite, level=1)
    counts = tuple(int(suite.get(key, "0")) for key in _TOTALS)
    return "  " + ET.tostring(suite, encoding="unicode"), counts


def is_piece(value: Any) -> bool:
    """Whether ``value`` is shaped as ``piece`` returns it (a cached piece is checked)."""
    return type(value) is tuple and len(value) == 2 and type(value[0]) is str \
        and type(value[1]) is tuple and len(value[1]) == 3 \
        and all(type(count) is int for count in value[1])


def document(entries: Iterable[Entry]) -> Iterator[str]:
    """``<testsuites>`` with the suites of ``entries`` in order.  Its start tag holds the
    totals, so nothing is written before the last entry has arrived."""
    suites: list[str] = []
    totals = [0, 0, 0]
    for entry in entries:
        text, counts = entry.piece
        suites.append(text)
        totals = [total + count for total, count in zip(totals, counts)]
    start = "<testsuites name=\"furncheck\" " + " ".join(
        f'{key}="{count}"' for key, count in zip(_TOTALS, totals))
    if not suites:
        yield f"{DECLARATION}\n{start} />\n"
        return
    yield f"{DECLARATION}\n{start}>\n"
    for text in suites:
        yield text + "\n"
    yield "</testsuites>\n"


def design_suite(report: DesignReport) -> ET.Element:
    """The ``<testsuite>`` of one design, its counts set."""
    suite = ET.Element("testsuite", name=_clean(report.design))
    if report.error is not None or report.valid is None:
        case = _testcase(report, LOAD_TESTCASE)
        errors = report.errors or ("no verdict",)
        ET.SubElement(case, "error", type=INPUT_ERROR,   # the first problem; all in the text
                      message=_clean(errors[0])).text = _clean("\n".join(errors))
        suite.append(case)
    else:
        failing = {case.name: case_violations(report, case.name) for case in report.cases}
        if not failing and report.violations:
            failing = {GEOMETRY_TESTCASE: list(report.violations)}
        for name, violations in failing.items():
            case = _testcase(report, name)
            if violations:
                _add_failure(case, violations)
            suite.append(case)
    suite.set("tests", str(len(suite)))
    suite.set("failures", str(len(suite.findall("testcase/failure"))))
    suite.set("errors", str(len(suite.findall("testcase/error"))))
    suite.set("skipped", "0")
    return suite


def _testcase(report: DesignReport, name: str) -> ET.Element:
    return ET.Element("testcase", classname=_clean(report.design), name=_clean(name))


def _add_failure(testcase: ET.Element, violations: list[Violation]) -> None:
    """One ``<failure>`` listing every violation; its type is the first violation's kind."""
    kinds = dict.fromkeys(v.kind for v in violations)  # distinct, in order
    message = f"{plural(len(violations), 'violation')}: {', '.join(kinds)}"
    body = "\n".join(
        f"{v.kind}: {describe_violation(v)}" + (f" (line {v.line})" if v.line is not None else "")
        for v in violations)
    failure = ET.SubElement(testcase, "failure", type=violations[0].kind, message=_clean(message))
    failure.text = _clean(body)


def _clean(text: str) -> str:
    """``text`` without the characters XML 1.0 cannot hold: a file name's bytes that are
    not UTF-8 (held as surrogates, as Python reads such names) written escaped
    ('bad\\udcffname.yaml', as every other report shows them: two such names stay two),
    control characters replaced."""
    return _xml_invalid().sub("\ufffd", readable(text))


@functools.cache
def _xml_invalid() -> re.Pattern[str]:
    return re.compile(_XML_INVALID)
