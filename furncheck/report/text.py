"""``--format text``: a few lines for a human at a terminal.

    designs/stool.yaml: valid (worst joint seat/leg1 at 42 % in case 'sit')
      case 'default': 1 load: 80 kg on seat at (0, 0, 450) mm
      case 'sit': 2 loads (1 from default): 80 kg on seat at (0, 0, 450) mm; 100 N +x on seat
    designs/shelf.yaml: INVALID, 2 violations
      non-durable: post/shelf in case 'default': pull 812 N per nail exceeds 700 N (line 14)
      floating: base, post: 2 planks touch the ground nowhere (lowest corner 3 mm above it)
      case 'default': 2 loads: 10 kg each on shelf, post
    designs/broken.yaml: error: line 3: planks[0].size: expected [length, width]
    3 designs: 1 valid, 1 invalid, 1 error

Each checked design ends with one line per load case naming the loads that act in it
(``case_line``; self-weight acts in every case and is not listed).
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping

from furncheck import tolerances as tol
from furncheck.files import neutral
from furncheck.report.common import (
    describe_violation,
    input_errors,
    plural,
    worst_joint,
    worst_plank,
)
from furncheck.report.entries import Entry, Summary, is_text
from furncheck.report.numbers import format_number, format_percent
from furncheck.result import BatchReport, CaseResult, DesignReport, LoadResult

INDENT = "  "
MAX_LOAD_PHRASES = 6
"""Phrases of a case line before the rest are counted ('and 3 more'): one line each."""
_AXIS_NAMES = ("x", "y", "z")


def render(batch: BatchReport) -> str:
    """One block per design in input order, then the summary line."""
    return "".join(document(Entry.of(report, piece(report)) for report in batch.reports))


is_piece = is_text
"""Whether a value is shaped as ``piece`` returns it (a cached piece is checked)."""


def shown(path: str) -> str:
    """A file's path as a report line shows it: what is not printable (a line break in a
    file name, a byte that is not UTF-8) escaped, so that each design keeps its one
    verdict line; an empty path (an unset variable in a script) as ''; a relative path
    that begins with '::' (after blanks) as './::...', the same file: a GitHub Actions
    runner reads a line of the log that begins with '::' as a workflow command (a design
    named '::error::x.yaml' in a pull request wrote an annotation, or '::add-mask::' and
    '::stop-commands::' lines, into the text report's job; ``neutral`` the rest)."""
    if path.lstrip().startswith("::"):
        path = "./" + path
    if path.isprintable():
        return path or "''"
    return "".join(c if c.isprintable() else f"\\x{ord(c):02x}" if ord(c) < 0x100
                   else f"\\u{ord(c):04x}" for c in path)


def piece(report: DesignReport) -> str:
    """The design's block: ``design_lines``, each ending with a newline (``neutral``)."""
    return neutral("\n".join(design_lines(report)) + "\n")


def document(entries: Iterable[Entry]) -> Iterator[str]:
    """The blocks of ``entries`` in order, then the summary line."""
    summary = Summary()
    for entry in entries:
        yield summary.add(entry).piece
    yield summary_line(summary.as_dict()) + "\n"


def design_lines(report: DesignReport) -> list[str]:
    """The verdict line of one design and, when invalid, one indented line per violation."""
    if report.error is not None or report.valid is None:
        return [f"{shown(report.design)}: error: "
                f"{f'line {line}: ' if line is not None else ''}{message}"
                for line, message in input_errors(report)]
    if report.valid:
        lines = [f"{shown(report.design)}: valid ({_worst_joint_phrase(report)})"]
    else:
        lines = [f"{shown(report.design)}: INVALID, "
                 f"{plural(len(report.violations), 'violation')}"]
    for violation in report.violations:
        at_line = f" (line {violation.line})" if violation.line is not None else ""
        lines.append(f"{INDENT}{violation.kind}: {describe_violation(violation)}{at_line}")
    lines.extend(INDENT + case_line(case, report.units) for case in report.cases)
    return lines


def case_line(case: CaseResult, units: str) -> str:
    """``case 'push': 3 loads (2 from default): 15 kg each on shelf_a, shelf_b; 80 N +y on
    side_l at (0, -200, 900) mm``: the loads acting in the case, how many came through
    ``include`` and from where; equal loads at plank centres in a row share a phrase."""
    head = f"case '{case.name}'"
    if not case.loads:
        return f"{head}: self-weight only"
    origins: dict[str, int] = {}
    for load in case.loads:
        if load.origin is not None:
            origins[load.origin] = origins.get(load.origin, 0) + 1
    included = (" (" + ", ".join(f"{count} from {name}" for name, count in origins.items())
                + ")") if origins else ""
    phrases = _load_phrases(case.loads, units)
    if len(phrases) > MAX_LOAD_PHRASES:
        rest = len(phrases) - (MAX_LOAD_PHRASES - 1)
        phrases = phrases[:MAX_LOAD_PHRASES - 1] + [f"and {rest} more"]
    return f"{head}: {plural(len(case.loads), 'load')}{included}: {'; '.join(phrases)}"


def _load_phrases(loads: tuple[LoadResult, ...], units: str) -> list[str]:
    """One phrase per load, ``15 kg on shelf at (0, 0, 606) mm``, ``80 N +y on post``,
    ``20 kg spread on shelf``; a run of equal loads without a point reads ``15 kg each on
    a, b, c``."""
    runs: list[tuple[str, list[str]]] = []      # (what, planks) of equal point-less loads
    for load in loads:
        what = _load_amount(load) + (" spread" if load.spread else "")
        if load.at is not None:
            at = ", ".join(format_number(c, 4) for c in load.at)
            runs.append((f"{what} on {load.plank} at ({at}) {units}", []))
        elif runs and runs[-1][1] and runs[-1][0] == what:
            runs[-1][1].append(load.plank)
        else:
            runs.append((what, [load.plank]))
    return [what if not planks else
            f"{what} on {planks[0]}" if len(planks) == 1 else
            f"{what} each on {', '.join(planks)}" for what, planks in runs]


def _load_amount(load: LoadResult) -> str:
    """``15 kg``; a force along one world axis ``80 N +y``, else ``(30, 0, -40) N``."""
    if load.mass is not None:
        return f"{format_number(load.mass, 4)} kg"
    along = [axis for axis, value in enumerate(load.force) if value != 0.0]
    if len(along) == 1:
        value = load.force[along[0]]
        return f"{format_number(abs(value), 4)} N {'+' if value > 0 else '-'}" \
               f"{_AXIS_NAMES[along[0]]}"
    return f"({', '.join(format_number(c, 4) for c in load.force)}) N"


def summary_line(summary: Mapping[str, int]) -> str:
    """``12 designs: 9 valid, 2 invalid, 1 error`` (``summary``: ``BatchReport.summary``)."""
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
    anchors = [(anchor.utilization, -anchor.index, case.name, anchor)
               for case in report.cases for anchor in case.anchors]
    if anchors:
        _, index, case_name, anchor = max(anchors, key=lambda item: item[:2])
        phrase += (f"; worst anchor anchors[{-index}] ({anchor.plank}) at "
                   f"{format_percent(anchor.utilization)} in case '{case_name}'")
        phrase += _wall_friction_phrase(next(case for case in report.cases
                                             if case.name == case_name))
    return phrase


def _wall_friction_phrase(case: CaseResult) -> str:
    """``, with the wall's friction holding up 118 N of its 178 N of weight and loads``:
    where the friction of the walls' contacts (the vertical part of their forces: a
    wall's normal is level) holds up at least WALL_FRICTION_SHARE of what the supports
    hold up (the floor's contacts, the walls' and the anchors', resting joints' corners
    being inside the design), so that the anchors' utilization counts on it; else
    nothing."""
    by_wall = sum(c.force[2] for c in case.contacts if c.wall is not None)
    held = by_wall + sum(c.force[2] for c in case.contacts
                         if c.wall is None and c.on is None) \
        + sum(a.force[2] for a in case.anchors)
    if held <= 0.0 or by_wall < tol.WALL_FRICTION_SHARE * held:
        return ""
    return (f", with the wall's friction holding up {format_number(by_wall, 3)} N of its "
            f"{format_number(held, 3)} N of weight and loads")
