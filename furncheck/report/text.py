"""``--format text``: a few lines for a human at a terminal.

    designs/stool.yaml: valid (worst joint seat/leg1 at 42 % in case 'sit')
    designs/shelf.yaml: INVALID, 2 violations
      non-durable: post/shelf in case 'default': pull 812 N per nail exceeds 700 N (line 14)
      floating: base,post: 2 planks touch the ground nowhere (lowest corner 3 mm above it)
    designs/broken.yaml: error: line 3: planks[0].size: expected [length, width]
    3 designs: 1 valid, 1 invalid, 1 error
"""

from __future__ import annotations

from furncheck.report.common import (
    describe_violation,
    input_error,
    plural,
    worst_joint,
    worst_plank,
)
from furncheck.report.numbers import format_percent
from furncheck.result import BatchReport, DesignReport

INDENT = "  "


def render(batch: BatchReport) -> str:
    """One block per design in input order, then the summary line."""
    lines: list[str] = []
    for report in batch.reports:
        lines.extend(design_lines(report))
    lines.append(summary_line(batch))
    return "\n".join(lines) + "\n"


def design_lines(report: DesignReport) -> list[str]:
    """The verdict line of one design and, when invalid, one indented line per violation."""
    if report.error is not None or report.valid is None:
        line, message = input_error(report)
        where = f"line {line}: " if line is not None else ""
        return [f"{report.design}: error: {where}{message}"]
    if report.valid:
        return [f"{report.design}: valid ({_worst_joint_phrase(report)})"]
    lines = [f"{report.design}: INVALID, {plural(len(report.violations), 'violation')}"]
    for violation in report.violations:
        at_line = f" (line {violation.line})" if violation.line is not None else ""
        lines.append(f"{INDENT}{violation.kind}: {describe_violation(violation)}{at_line}")
    return lines


def summary_line(batch: BatchReport) -> str:
    """``12 designs: 9 valid, 2 invalid, 1 error``."""
    summary = batch.summary
    return (f"{plural(summary['designs'], 'design')}: {summary['valid']} valid, "
            f"{summary['invalid']} invalid, {plural(summary['errors'], 'error')}")


def _worst_joint_phrase(report: DesignReport) -> str:
    worst = worst_joint(report)
    if worst is None:
        phrase = "no nail joints"
    else:
        case, joint = worst
        phrase = (f"worst joint {'/'.join(joint.planks)} at "
                  f"{format_percent(joint.utilization)} in case '{case}'")
    plank = worst_plank(report)
    if plank is not None:
        case, result = plank
        phrase += (f"; worst plank {result.id} at {format_percent(result.utilization)} "
                   f"in case '{case}'")
    return phrase
