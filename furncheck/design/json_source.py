"""JSON design text -> a plain tree (step 2 of reading a design, for JSON files; YAML's is in
``source``): every number a float, duplicate keys refused, nesting limited as YAML's is,
and the lines of key paths looked up only when a message asks (``JsonLines``, reading the
text as YAML).  Every problem raises ``DesignError(file, key path, line, message)``.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from typing import Any

import yaml

from furncheck import tolerances as tol
from furncheck.design.source import _one_line, _quote, _read_yaml, _Scalar
from furncheck.errors import DesignError


class _DuplicateKey(Exception):
    def __init__(self, key: str):
        super().__init__(key)
        self.key = key


def _json_object(pairs: list[tuple[str, Any]]) -> dict:
    mapping: dict = {}
    for key, value in pairs:
        if key in mapping:
            raise _DuplicateKey(key)
        mapping[key] = value
    return mapping


def _json_constant(name: str) -> float:
    """NaN / Infinity / -Infinity become floats that every number check refuses as 'not a
    finite number', naming their key path."""
    return float(name.replace("Infinity", "inf"))


def _json_number(text: str) -> float | _Scalar:
    """A JSON number as a float; one no float holds (1e400, 400 digits) kept as written,
    as a YAML scalar, so that its message can show it ('out of range (1e400: ...)')."""
    value = float(text)
    return value if math.isfinite(value) else _Scalar(text, True)


def _read_json(text: str, source: str) -> Any:
    """Tree of dicts, lists, str, float (every number), bool and None."""
    import json  # for JSON designs only: YAML is the common case

    try:
        tree = json.loads(text, object_pairs_hook=_json_object, parse_constant=_json_constant,
                          parse_int=_json_number, parse_float=_json_number)
    except _DuplicateKey as duplicate:
        raise _json_duplicate_error(text, source, duplicate.key) from None
    except json.JSONDecodeError as error:
        raise DesignError(source, "", error.lineno,
                          f"JSON syntax error: {error.msg} (column {error.colno})") from None
    except RecursionError:
        raise _json_nesting_error(text, source) from None
    except ValueError as error:
        raise DesignError(source, "", None, _one_line(f"JSON syntax error: {error}")) from None
    if _depth(tree) > tol.MAX_NESTING:
        raise _json_nesting_error(text, source)
    return tree


def _depth(tree: Any) -> int:
    """How deep mappings and lists nest in ``tree`` (a scalar: 0)."""
    deepest, level = 0, [(tree, 1)]
    while level:
        node, depth = level.pop()
        children = node.values() if isinstance(node, dict) else node \
            if isinstance(node, list) else None
        if children is not None:
            deepest = max(deepest, depth)
            level.extend((child, depth + 1) for child in children)
    return deepest


def _json_nesting_error(text: str, source: str) -> DesignError:
    """A JSON design nested deeper than MAX_NESTING refused as a YAML one is: at the
    path and line where the limit is passed, found by reading the text as YAML up to
    just past that point (read whole, a JSON nested a thousand deep met the YAML
    parser's own limit first, and its message had no line)."""
    depth, cut = 0, len(text)
    for token in re.finditer(r'"(?:\\.|[^"\\])*"|[\[\]{}]', text):
        bracket = token.group()
        if bracket in "[{":
            depth += 1
            if depth > tol.MAX_NESTING + 1:
                cut = token.end()
                break
        elif bracket in "]}":
            depth -= 1
    try:
        _read_yaml(text[:cut], source)
    except DesignError as error:
        if error.message == "nested too deeply":
            return error
    return DesignError(source, "", None, "nested too deeply")


def _json_duplicate_error(text: str, source: str, key: str) -> DesignError:
    """The duplicate key's path and line, found by reading the JSON text as YAML."""
    try:
        _read_yaml(text, source)
    except DesignError as error:
        if error.message.startswith("duplicate key"):
            return error
    except (yaml.YAMLError, ValueError, RecursionError):
        pass
    return DesignError(source, "", None, f"duplicate key {_quote(key)}")


def _json_lines(text: str, source: str) -> dict[str, int]:
    """Best effort: key path -> line of a JSON text, read as YAML; {} when that fails.
    JSON escapes a lone surrogate (``"\\ud800"``, which JSON reads and YAML refuses): each
    is read as the escape of a private-use character (U+E000 to U+E7FF, as many
    characters: no line moves), and the keys' paths get their surrogates back."""
    try:
        return _read_yaml(text, source)[1]
    except (DesignError, yaml.YAMLError, ValueError, RecursionError):
        pass
    if not _SURROGATE_ESCAPE.search(text):
        return {}
    private = _SURROGATE_ESCAPE.sub(
        lambda m: f"\\u{int(m.group(0)[2:], 16) + _PRIVATE_SHIFT:04x}", text)
    try:
        lines = _read_yaml(private, source)[1]
    except (DesignError, yaml.YAMLError, ValueError, RecursionError):
        return {}
    return {_surrogates_back(key): line for key, line in lines.items()}


def _surrogates_back(key: str) -> str:
    """A key path read from ``_json_lines``' private-use text with its surrogates back:
    as characters, and as the escapes that a path writes them as (``source._one_line``)."""
    key = key.translate(_SURROGATES_BACK)
    return _PRIVATE_ESCAPE.sub(
        lambda m: f"\\u{int(m.group(0)[2:], 16) - _PRIVATE_SHIFT:04x}", key)


_SURROGATE_ESCAPE = re.compile(r"\\u[dD][89a-fA-F][0-9a-fA-F]{2}")
"""A JSON escape of a UTF-16 surrogate (``_json_lines``)."""
_PRIVATE_SHIFT = 0xE000 - 0xD800
_SURROGATES_BACK = {code + _PRIVATE_SHIFT: code for code in range(0xD800, 0xE000)}
_PRIVATE_ESCAPE = re.compile(r"\\ue[0-7][0-9a-f]{2}")


class JsonLines(Mapping):
    """Key path -> line of a JSON design, looked up the first time a line is asked for
    (a violation's, for annotations; ``_json_lines``): a design that holds costs nothing."""

    __slots__ = ("_text", "_source", "_found")

    def __init__(self, text: str, source: str):
        self._text, self._source, self._found = text, source, None

    def _lines(self) -> dict[str, int]:
        found = self._found         # (threads may both look them up: the same lines)
        if found is None:
            found = self._found = _json_lines(self._text, self._source)
        return found

    def __getitem__(self, key: str) -> int:
        return self._lines()[key]

    def __contains__(self, key: object) -> bool:
        return key in self._lines()

    def __iter__(self):
        return iter(self._lines())

    def __len__(self) -> int:
        return len(self._lines())

    def __eq__(self, other: object) -> bool:    # the same object: no lookup (edits share it)
        return self is other or (isinstance(other, Mapping) and dict(self) == dict(other))

    __hash__ = None
