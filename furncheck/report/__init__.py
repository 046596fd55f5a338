"""Reporters: a ``BatchReport`` -> text in one output format, chosen by name.

Each format is one small module with ``render(batch) -> str``; every output ends with a
newline and is deterministic (same batch, same bytes).  Floats are rounded in one place,
``furncheck.report.numbers``.

    text    human-readable lines and a summary        (furncheck.report.text)
    json    the schema of contract section 4          (furncheck.report.json_format)
    junit   JUnit XML, a testcase per load case        (furncheck.report.junit)
    github  GitHub Actions ::error annotations         (furncheck.report.github)
    sarif   SARIF 2.1.0, e.g. for code scanning        (furncheck.report.sarif)

Only the standard library is imported here, so the CLI can import this module cheaply.
"""

from __future__ import annotations

from collections.abc import Callable

from furncheck.report import github, json_format, junit, sarif, text
from furncheck.result import BatchReport

Renderer = Callable[[BatchReport], str]

REPORTERS: dict[str, Renderer] = {
    "text": text.render,
    "json": json_format.render,
    "junit": junit.render,
    "github": github.render,
    "sarif": sarif.render,
}
"""Format name -> render function, in the order ``--help`` lists them."""


def render(batch: BatchReport, fmt: str) -> str:
    """``batch`` in format ``fmt`` (a key of ``REPORTERS``); ValueError for an unknown one."""
    try:
        renderer = REPORTERS[fmt]
    except KeyError:
        raise ValueError(f"unknown report format {fmt!r}; "
                         f"choose one of {', '.join(REPORTERS)}") from None
    return renderer(batch)


__all__ = ["REPORTERS", "Renderer", "render"]
