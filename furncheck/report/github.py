"""``--format github``: GitHub Actions workflow commands, shown as annotations on the diff.

    ::error file=designs/shelf.yaml,line=14,title=furncheck non-durable::post/shelf in ...
    ::error file=designs/broken.yaml,line=3,title=furncheck input-error::planks[0].size: ...
    ::notice title=furncheck::3 designs: 1 valid, 1 invalid, 1 error

One ``::error`` per violation and per unreadable input; ``line=`` only when the line is
known.  Valid designs get no line of their own; the last line is one ``::notice`` with the
batch summary.  Escaping follows the runner's rules: ``%``, CR and LF in the message;
additionally ``:`` and ``,`` in property values.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from pathlib import PurePosixPath

from furncheck.files import readable
from furncheck.report.common import INPUT_ERROR, describe_violation, input_errors
from furncheck.report.entries import Entry, Summary, is_text
from furncheck.report.text import summary_line
from furncheck.result import BatchReport, DesignReport


def render(batch: BatchReport) -> str:
    """One workflow command per line, ending with the summary notice."""
    return "".join(document(Entry.of(report, piece(report)) for report in batch.reports))


is_piece = is_text
"""Whether a value is shaped as ``piece`` returns it (a cached piece is checked)."""


def piece(report: DesignReport) -> str:
    """The design's commands (``design_commands``), each ending with a newline; '' for a
    valid design."""
    return "".join(line + "\n" for line in design_commands(report))


def document(entries: Iterable[Entry]) -> Iterator[str]:
    """The commands of ``entries`` in order, then the summary notice."""
    summary = Summary()
    for entry in entries:
        yield summary.add(entry).piece
    yield command("notice", {"title": "furncheck"}, summary_line(summary.as_dict())) + "\n"


def design_commands(report: DesignReport) -> list[str]:
    """The ``::error`` lines of one design (none when it is valid)."""
    if report.error is not None or report.valid is None:
        return [command("error", _properties(report.design, line, INPUT_ERROR), message)
                for line, message in input_errors(report)]
    return [
        command("error", _properties(report.design, v.line, v.kind), describe_violation(v))
        for v in report.violations
    ]


def command(name: str, properties: dict[str, str], message: str) -> str:
    """``::name key=value,...::message`` with GitHub's escaping applied, in UTF-8: a file
    name's bytes that are not UTF-8 (held as surrogates, as Python reads such names) are
    written escaped ('bad\\udcffname.yaml', as the text report shows them), not raw."""
    props = ",".join(f"{key}={escape_property(value)}" for key, value in properties.items())
    head = f"{name} {props}" if props else name
    return readable(f"::{head}::{escape_data(message)}")


def escape_data(text: str) -> str:
    """Escape a command's message: ``%`` -> ``%25``, CR -> ``%0D``, LF -> ``%0A``."""
    return text.replace("%", "%25").replace("\r", "%0D").replace("\n", "%0A")


def escape_property(text: str) -> str:
    """Escape a property value: as ``escape_data``, plus ``:`` -> ``%3A``, ``,`` -> ``%2C``."""
    return escape_data(text).replace(":", "%3A").replace(",", "%2C")


def _properties(file: str, line: int | None, kind: str) -> dict[str, str]:
    properties = {"file": annotation_path(file)}
    if line is not None:
        properties["line"] = str(line)
    properties["title"] = f"furncheck {kind}"
    return properties


def annotation_path(path: str) -> str:
    """A design's path as an annotation's ``file``: a relative one without its './' and
    doubled slashes ('./designs//x.yaml' -> 'designs/x.yaml'), as the SARIF log's URI
    has it, so that the runner finds the file in the diff whichever way it was named."""
    if not path or path.startswith("/"):
        return path
    return str(PurePosixPath(path))
