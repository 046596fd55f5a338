"""Small pieces that several reporters share: wording of a violation, where an input
error points, the worst joint of a design."""

from __future__ import annotations

import re

from furncheck.result import DesignReport, JointResult, PlankResult, Violation

INPUT_ERROR = "input-error"
"""Kind used by annotation formats (github, sarif, junit) for an unreadable input."""

_LINE_PREFIX = re.compile(r"(\d+): ?")


def input_errors(report: DesignReport) -> list[tuple[int | None, str]]:
    """(line, message) of each problem of an errored report (one per line of its error:
    a file's problems are all reported, contract section 4), without the file name the
    message repeats.

    ``check_file`` writes a ``DesignError`` as ``file:line: key: message``, one line per
    problem.  The file is already in every report line, so the leading ``file:`` is
    dropped and the line number split off; any other message is returned whole.
    """
    return [_input_error(report.design, line) for line in (report.errors or ("no verdict",))]


def _input_error(design: str, message: str) -> tuple[int | None, str]:
    prefix = f"{design}:"
    if not design or not message.startswith(prefix):
        return None, message
    rest = message[len(prefix):]
    match = _LINE_PREFIX.match(rest)
    if match:
        return int(match.group(1)), rest[match.end():]
    return None, rest.lstrip()


def describe_violation(violation: Violation) -> str:
    """``post/shelf in case 'default': pull 812 N per nail exceeds 700 N``.

    Geometric violations (case None) hold in every load case and name no case.  Several
    planks (``base,post``: ids hold no comma) read as a list, ``base, post``.
    """
    where = violation.where.replace(",", ", ")
    if violation.case is not None:
        where = f"{where} in case '{violation.case}'"
    return f"{where}: {violation.message}" if where else violation.message


def case_violations(report: DesignReport, case: str | None) -> list[Violation]:
    """Violations that make ``case`` fail: its own and those with case None (all cases)."""
    return [v for v in report.violations if v.case is None or v.case == case]


def worst_joint(report: DesignReport) -> tuple[str, JointResult] | None:
    """(case name, joint) with the highest utilization over all cases; first on ties."""
    worst: tuple[str, JointResult] | None = None
    for case in report.cases:
        joint = case.worst_joint
        if joint is not None and (worst is None or joint.utilization > worst[1].utilization):
            worst = (case.name, joint)
    return worst


def worst_plank(report: DesignReport) -> tuple[str, PlankResult] | None:
    """(case name, plank) with the highest sag or stress utilization over all cases (elastic
    model; None in the rigid one); first on ties."""
    worst: tuple[str, PlankResult] | None = None
    for case in report.cases:
        for plank in case.planks or ():
            if worst is None or plank.utilization > worst[1].utilization:
                worst = (case.name, plank)
    return worst


def plural(count: int, noun: str) -> str:
    """``'1 violation'``, ``'2 violations'``."""
    return f"{count} {noun}" if count == 1 else f"{count} {noun}s"
