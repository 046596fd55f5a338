"""A design's finished part of a report (``Entry``) and the batch summary kept as the entries
go by (``Summary``): what lets a report be written piece by piece, each piece made where
its design was checked.

Every reporter has ``piece(report)``, the design's part in that format (text for most,
see each module), and ``document(entries)``, the whole report from the entries in input
order, as a sequence of strings written one after the other.  ``render(batch)`` is the two
together.  Only the standard library is imported here.
"""

from __future__ import annotations

from typing import Any, NamedTuple

from furncheck import exitcodes
from furncheck.result import DesignReport


class Entry(NamedTuple):
    """One design's verdict (``valid``: as ``DesignReport.valid``; ``error``: whether it
    could not be read or checked) and its ``piece`` of the report, made by the reporter's
    ``piece``.  (A named tuple: cheap to make, to pickle and to import.)"""

    valid: bool | None
    error: bool
    piece: Any

    @classmethod
    def of(cls, report: DesignReport, piece: Any) -> Entry:
        return cls(report.valid, report.error is not None, piece)


def is_text(value: Any) -> bool:
    """Whether ``value`` has the shape of a text piece (``is_piece`` of the formats whose
    pieces are text: a cached piece is checked before it is used)."""
    return type(value) is str


class Summary:
    """The batch's counts, kept while its entries are written (``BatchReport.summary``
    and ``return_code`` for a batch that is never held whole)."""

    def __init__(self) -> None:
        self.designs = self.valid = self.invalid = self.errors = 0

    def add(self, entry: Entry) -> Entry:
        """Count ``entry`` in; returns it."""
        self.designs += 1
        self.valid += entry.valid is True
        self.invalid += entry.valid is False
        self.errors += entry.error
        return entry

    def as_dict(self) -> dict[str, int]:
        """``{"designs", "valid", "invalid", "errors"}``, as ``BatchReport.summary``."""
        return {"designs": self.designs, "valid": self.valid, "invalid": self.invalid,
                "errors": self.errors}

    @property
    def return_code(self) -> int:
        """The exit code of ``furncheck validate`` (``exitcodes.validate_code``)."""
        return exitcodes.validate_code(self.errors > 0, self.invalid > 0)
