"""The typed reading of a design document's tree: ``_Doc`` (numbers, text, flags, lists
and mappings, each checked, every problem a ``DesignError`` with key path and line), the
YAML 1.1 scalar rules behind it (``_resolved``), the words of its messages (``_describe``,
``_unknown_key_message``) and the quantities the schema reads with it (``_quantity``,
``_length``, ``_vector``, ``_point``, ``_identifier``, ``_plank_ref``: SI values from file
units).  The schema that uses them is ``load`` (and ``cases`` for the loads)."""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, NoReturn, TypeVar

from furncheck import tolerances as tol
from furncheck.design.json_source import JsonLines, _json_lines
from furncheck.design.model import Plank
from furncheck.design.source import _PATH_SAFE_KEY, _child, _one_line, _quote, _Scalar
from furncheck.errors import DesignError
from furncheck.plain import closest, plain_number

_NULL_WORDS = {"", "~", "null", "Null", "NULL"}
_BOOL_WORDS = {word: value for value, words in
               ((True, ("yes", "true", "on")), (False, ("no", "false", "off")))
               for base in words for word in (base, base.capitalize(), base.upper())}
_DECIMAL = re.compile(r"[-+]?(?:[0-9][0-9_]*(?:\.[0-9_]*)?|\.[0-9][0-9_]*)(?:[eE][-+]?[0-9]+)?")
_JSON_CONSTANTS = {"nan": "NaN", "inf": "Infinity", "-inf": "-Infinity"}
_NON_FINITE = re.compile(r"[-+]?\.(?:inf|Inf|INF|nan|NaN|NAN)")
_IDENTIFIER = _PATH_SAFE_KEY   # plank ids and case names: what a key path shows bare
T = TypeVar("T")

UNNAMED = ""
"""In ``_Doc.unread_planks``: every plank name (a plank whose entry failed before a valid
id was read, which may be any; or a default standing for a value the checks of all planks
use: ``_Doc.unsure``)."""


class _Skipped(Exception):
    """A part of the document that names a plank which itself could not be read: left
    unchecked (its problem would only repeat that plank's), not a problem of its own."""


class _Doc:
    """The document being checked: raises ``DesignError`` with key path and line, and reads
    typed values (numbers, text, mappings, lists) from tree nodes.

    Parts that do not depend on each other are read under ``collect``: a part's problem is
    kept and the reading goes on, so that a file's problems are all reported at once (one
    line each, contract section 4), up to ``tolerances.MAX_INPUT_PROBLEMS``;
    ``raise_problems`` raises the first with the others as its ``more``."""

    def __init__(self, source: str, fmt: str, text: str, lines: dict[str, int] | None):
        self.source = source
        self.fmt = fmt
        self.source_text = text
        self._lines = lines
        self.problems: list[DesignError] = []
        self.unread_planks: set[str] = set()    # ids of planks whose entries failed

    def collect(self, read: Callable[..., T], *args: Any, default: Any = None) -> T | Any:
        """``read(*args)``, or ``default`` with its problems kept (``raise_problems``);
        the reading stops once MAX_INPUT_PROBLEMS are kept."""
        try:
            return read(*args)
        except DesignError as error:
            self.problems.extend((error, *error.more))
            if len(self.problems) >= tol.MAX_INPUT_PROBLEMS:
                self.raise_problems()
        except _Skipped:
            pass
        return default

    def raise_problems(self) -> None:
        """Raise the problems kept, by line (the file's order), the first with the others
        as its ``more``; past MAX_INPUT_PROBLEMS a last line says the reading stopped;
        nothing when there is none."""
        if not self.problems:
            return
        kept = sorted(self.problems[:tol.MAX_INPUT_PROBLEMS],
                      key=lambda problem: -1 if problem.line is None else problem.line)
        if len(self.problems) >= tol.MAX_INPUT_PROBLEMS:
            kept.append(DesignError(self.source, "", None, f"more problems may follow: the "
                                    f"reading stopped after {tol.MAX_INPUT_PROBLEMS}"))
        first, *rest = kept
        first.more = tuple(rest)
        raise first

    def unsure(self, planks: str = UNNAMED) -> None:
        """What names ``planks`` (a plank's id; by default every plank) is left unchecked:
        a part the checks of those names depend on could not be read as written."""
        self.unread_planks.add(planks)

    @property
    def lines(self) -> dict[str, int]:
        """Key path -> line: recorded for YAML, looked up on demand for JSON."""
        if self._lines is None:
            self._lines = _json_lines(self.source_text, self.source)
        return self._lines

    def design_lines(self) -> Mapping[str, int]:
        """The lines a ``Design`` keeps: YAML's; a JSON text's, looked up when first asked
        for (``json_source.JsonLines``: a violation's line)."""
        if self._lines is not None:
            return self._lines
        return JsonLines(self.source_text, self.source) if self.fmt == "json" else {}

    def line_of(self, key: str) -> int | None:
        """Line of ``key``, else of its closest recorded parent."""
        lines = self.lines
        while key:
            if key in lines:
                return lines[key]
            cut = max(key.rfind("."), key.rfind("["))
            key = key[:cut] if cut > 0 else ""
        return None

    def fail(self, key: str, message: str) -> NoReturn:
        """Raise the DesignError of ``key``, at its line, else its closest recorded
        parent's, else the line where the design begins (a missing top-level key, a top
        level that is no mapping)."""
        raise self.error(key, message)

    def error(self, key: str, message: str) -> DesignError:
        """``fail``'s DesignError, not raised."""
        line = self.line_of(key)
        return DesignError(self.source, key, self.lines.get("") if line is None else line,
                           message)

    def number(self, node: Any, key: str) -> float:
        """A finite number (booleans and quoted text are not numbers)."""
        value = _resolved(node)
        if isinstance(value, bool) or not isinstance(value, float):
            self.fail(key, f"expected a number, got {_describe(node)}")
        if not math.isfinite(value):
            written = node.text if isinstance(node, _Scalar) else _JSON_CONSTANTS[str(value)]
            if isinstance(node, _Scalar) and _DECIMAL.fullmatch(written):
                self.fail(key, f"out of range ({_long_number(written)}: beyond "
                               f"+-1.8e308, the largest a number can be)")
            self.fail(key, f"not a finite number ({_one_line(written)})")
        return value

    def flag(self, node: Any, key: str) -> bool:
        """A boolean (true/false, yes/no, on/off)."""
        value = _resolved(node)
        if not isinstance(value, bool):
            self.fail(key, f"expected true or false, got {_describe(node)}")
        return value

    def text(self, node: Any, key: str) -> str:
        """Text; an unquoted YAML scalar counts as the text it shows (``id: 1`` is "1")."""
        if isinstance(node, str):
            return node
        if isinstance(node, _Scalar) and _resolved(node) is not None:
            return node.text
        self.fail(key, f"expected text, got {_describe(node)}")

    def sequence(self, node: Any, key: str) -> list:
        if not isinstance(node, list):
            self.fail(key, f"expected a list, got {_describe(node)}")
        return node

    def mapping(self, node: Any, key: str, allowed: tuple[str, ...] | None = None,
                required: tuple[str, ...] = (), keep_going: bool = False) -> dict:
        """A mapping whose keys are all ``allowed`` (any when None) and hold ``required``;
        every unknown and missing key is a problem, raised together (the first, the rest
        its ``more``).  ``keep_going``: unknown keys are kept as problems of the document
        (``collect``) and the mapping's known keys returned, to be read on."""
        if not isinstance(node, dict):
            self.fail(key, f"expected a mapping, got {_describe(node)}")
        unknown = [name for name in node if allowed is not None and name not in allowed]
        meant = {name: closest(name, allowed) for name in unknown}
        problems = [self.error(_child(key, name), _unknown_key_message(name, allowed,
                                                                        meant[name]))
                    for name in unknown]
        meant = set(meant.values())                             # a typo is one problem:
        missing = [self.error(_child(key, name), f"missing required key {_quote(name)}")
                   for name in required if name not in node and name not in meant]
        if unknown and not missing and any(name not in node for name in required):
            keep_going = False              # the key it lacks is misspelt: read no further
        if keep_going and not missing:
            self.problems.extend(problems)
            if len(self.problems) >= tol.MAX_INPUT_PROBLEMS:
                self.raise_problems()
            return {name: value for name, value in node.items()
                    if allowed is None or name in allowed} if problems else node
        problems += missing
        if problems:
            problems[0].more = tuple(problems[1:])
            raise problems[0]
        return node


NUMBER_SHOWN = 24
"""A number written with more characters than this is shown cut ('1000000000...0000, 341
digits') in a message: a line for the user, not the whole of it."""


def _long_number(text: str) -> str:
    """``text``, a number as written, for a message (``NUMBER_SHOWN``)."""
    if len(text) <= NUMBER_SHOWN:
        return text
    mantissa = text.lower().split("e")[0]
    digits = sum(c.isdigit() for c in mantissa)
    return f"{text[:10]}...{text[-4:]}, {digits} digits"


def _resolved(node: Any) -> Any:
    """A YAML scalar's value (None, bool, float or str); other nodes as they are.  Plain
    scalars resolve as YAML 1.1 does, except that numbers follow the decimal notation
    (``1e3``, ``-2E-1``, ``010`` = ten)."""
    if not isinstance(node, _Scalar):
        return node
    if not node.plain:
        return node.text
    text = node.text
    if text in _NULL_WORDS:
        return None
    if text in _BOOL_WORDS:
        return _BOOL_WORDS[text]
    if _DECIMAL.fullmatch(text):            # the common case first: the two never overlap
        try:
            return float(text.replace("_", "") if "_" in text else text)
        except ValueError:
            return text
    if _NON_FINITE.fullmatch(text):
        return float(text.replace(".", "", 1))
    return text


def _describe(node: Any) -> str:
    """What a node is, in words, for messages: 'a list', 'text "400"', 'a boolean (yes)'."""
    value = _resolved(node)
    if isinstance(value, dict):
        return "a mapping"
    if isinstance(value, list):
        return "a list"
    if value is None:
        return "nothing (null)"
    if isinstance(value, bool):
        shown = node.text if isinstance(node, _Scalar) else str(value).lower()
        return f"a boolean ({_one_line(shown)})"
    if isinstance(value, float):
        shown = _one_line(node.text) if isinstance(node, _Scalar) else plain_number(value, 6)
        return f"a number ({shown})"
    return f"text {_quote(value)}"


def _unknown_key_message(name: str, allowed: tuple[str, ...], close: Any = ...) -> str:
    """``close``: the closest allowed key or None, when the caller has it (``plain.closest``)."""
    close = closest(name, allowed) if close is ... else close
    meant = f" (did you mean {_quote(close)}?)" if close is not None else ""
    return f"unknown key {_quote(name)}{meant}; allowed keys: {', '.join(allowed)}"


def _did_you_mean(name: str, choices) -> str:
    """`` (did you mean "x"?)`` with the closest of ``choices``, or ''."""
    close = closest(name, choices)
    return f" (did you mean {_quote(close)}?)" if close is not None else ""


# --- quantities: SI values from the file's units -----------------------------------------------

@dataclass(frozen=True)
class _Units:
    """The file's length unit: ``name`` ('mm' or 'm'), ``scale`` metres per unit."""

    name: str
    scale: float



def _quantity(doc: _Doc, node: Any, key: str, low: float, high: float, scale: float = 1.0,
              unit: str = "", positive: bool = False) -> float:
    """A number written in ``unit`` (``scale`` SI units each), checked to lie in
    [low, high] (SI) and, if ``positive``, to be > 0.  Returns it in SI."""
    value = doc.number(node, key)
    if positive and value <= 0:
        doc.fail(key, f"must be positive, got {plain_number(value, 6)}{_shown(unit)}")
    if not low <= value * scale <= high:
        shown = _shown(unit)
        doc.fail(key, f"out of range: {plain_number(value, 6)}{shown}; allowed "
                      f"{plain_number(low / scale, 6)} to {plain_number(high / scale, 6)}{shown}")
    return value * scale


def _shown(unit: str) -> str:
    """A unit as a message writes it after a number (' mm'), or ''."""
    return f" {unit}" if unit else ""


def _length(doc: _Doc, node: Any, key: str, units: _Units) -> float:
    """m: a size, thickness or spacing in [MIN_LENGTH, MAX_LENGTH]."""
    return _quantity(doc, node, key, tol.MIN_LENGTH, tol.MAX_LENGTH, units.scale, units.name,
                     positive=True)


def _vector(doc: _Doc, node: Any, key: str, count: int, low: float, high: float,
            scale: float = 1.0, unit: str = "", positive: bool = False) -> tuple[float, ...]:
    """``count`` numbers, each as ``_quantity``; SI."""
    items = doc.sequence(node, key)
    if len(items) != count:
        doc.fail(key, f"expected {count} numbers, got {len(items)}")
    return tuple(_quantity(doc, item, f"{key}[{i}]", low, high, scale, unit, positive)
                 for i, item in enumerate(items))


def _point(doc: _Doc, node: Any, key: str, units: _Units) -> tuple[float, float, float]:
    """m: a world point, every |coordinate| <= MAX_COORDINATE."""
    return _vector(doc, node, key, 3, -tol.MAX_COORDINATE, tol.MAX_COORDINATE,
                   units.scale, units.name)


def _identifier(doc: _Doc, node: Any, key: str, what: str) -> str:
    name = doc.text(node, key)
    if not _IDENTIFIER.fullmatch(name):
        doc.fail(key, f"invalid {what} {_quote(name)}: use letters, digits, '_', '.' and '-'")
    return name


def _plank_ref(doc: _Doc, node: Any, key: str, by_id: dict[str, Plank]) -> Plank:
    """The plank that ``node`` names."""
    name = doc.text(node, key)
    if name in doc.unread_planks or UNNAMED in doc.unread_planks:
        raise _Skipped(name)            # (``_Doc.unsure``: not read as the file means it)
    if name not in by_id:
        doc.fail(key, f"unknown plank {_quote(name)}{_did_you_mean(name, by_id)}")
    return by_id[name]
