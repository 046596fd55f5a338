"""Reporters: a ``BatchReport`` -> text in one output format, chosen by name.

Each format is one small module with ``render(batch) -> str``; every output ends with a
newline and is deterministic (same batch, same bytes).  Floats are rounded in one place,
``furncheck.report.numbers``.

    text    human-readable lines and a summary        (furncheck.report.text)
    json    the schema of contract section 4          (furncheck.report.json_format)
    junit   JUnit XML, a testcase per load case        (furncheck.report.junit)
    github  GitHub Actions ::error annotations         (furncheck.report.github)
    sarif   SARIF 2.1.0, e.g. for code scanning        (furncheck.report.sarif)

For a catalog the report is written piece by piece (``furncheck.report.entries``): each
module also has ``piece(report)``, one design's finished part, made where the design is
checked, and ``document(entries)``, the report from those parts in input order.

Only the standard library is imported here, and a format's module only when it is used,
so the CLI can import this module cheaply.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Iterator, Mapping
from types import ModuleType

from furncheck.result import BatchReport

Renderer = Callable[[BatchReport], str]

FORMAT_MODULES = {
    "text": "furncheck.report.text",
    "json": "furncheck.report.json_format",
    "junit": "furncheck.report.junit",
    "github": "furncheck.report.github",
    "sarif": "furncheck.report.sarif",
}
"""Format name -> its module, in the order ``--help`` lists them."""


def reporter(fmt: str) -> ModuleType:
    """The module of format ``fmt`` (``render``, ``piece``, ``document``), imported on first
    use; ValueError for an unknown one."""
    try:
        name = FORMAT_MODULES[fmt]
    except KeyError:
        raise ValueError(f"unknown report format {fmt!r}; "
                         f"choose one of {', '.join(FORMAT_MODULES)}") from None
    return importlib.import_module(name)


class _Renderers(Mapping):
    """Format name -> render function, each module imported when its function is asked
    for."""

    def __getitem__(self, fmt: str) -> Renderer:
        if fmt not in FORMAT_MODULES:
            raise KeyError(fmt)
        return reporter(fmt).render

    def __iter__(self) -> Iterator[str]:
        return iter(FORMAT_MODULES)

    def __len__(self) -> int:
        return len(FORMAT_MODULES)


REPORTERS: Mapping[str, Renderer] = _Renderers()
"""Format name -> render function, in the order ``--help`` lists them."""


def render(batch: BatchReport, fmt: str) -> str:
    """``batch`` in format ``fmt`` (a key of ``REPORTERS``); ValueError for an unknown one."""
    return reporter(fmt).render(batch)


__all__ = ["FORMAT_MODULES", "REPORTERS", "Renderer", "render", "reporter"]
