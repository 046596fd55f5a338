"""Design file -> text -> a plain tree with line numbers (steps 1 and 2 of reading a design).

1. bytes -> text: the file must exist, be a regular file of at most ``MAX_FILE_BYTES``, hold
   no NUL bytes and be UTF-8 (a byte-order mark is dropped); ``load`` opens and reads it;
2. text -> a plain tree of dicts, lists and scalars (``_read_yaml``; JSON's is
   ``json_source._read_json``).  YAML is read event by event, never constructed: aliases
   are refused before anything is expanded, duplicate keys are refused, and the line of
   every key path is recorded.  A YAML scalar stays a ``_Scalar`` (its text and whether it
   was quoted) until the schema knows whether a number or a text belongs there.

Every problem raises ``DesignError(file, key path, line, message)``.  Step 3, the schema, is
in ``furncheck.design.load``, which also uses the message helpers at the end of this module.
"""

from __future__ import annotations

import codecs
import os
import re
import stat
from pathlib import Path
from typing import Any, NamedTuple

import yaml

from furncheck import tolerances as tol
from furncheck.errors import DesignError
from furncheck.files import as_utf8
from furncheck.plain import plain_number

FORMATS = {".yaml": "yaml", ".yml": "yaml", ".json": "json"}
"""File extension -> format."""

_PATH_SAFE_KEY = re.compile(r"[A-Za-z0-9_.-]+")   # keys a key path shows without ["..."]
_QUOTE_LIMIT = 40            # characters of a user's text repeated in a message

_Loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
_YAML_TAG = "tag:yaml.org,2002:"
_TEXT_TAGS = {"!", _YAML_TAG + "str"}
_PLAIN_TAGS = {_YAML_TAG + name for name in ("int", "float", "bool", "null")}
_CONTAINER_TAGS = {"!", _YAML_TAG + "map", _YAML_TAG + "seq"}


# --- step 1: bytes -> text ----------------------------------------------------------------------

def _format_of(path: str) -> str:
    fmt = FORMATS.get(Path(path).suffix.lower())
    if fmt is None:
        raise DesignError(path, "", None, f"unknown file type {_quote(Path(path).suffix)}; "
                                          "design files end in .yaml, .yml or .json")
    return fmt


def _check_regular_file(path: str) -> None:
    """Refuse a missing path, a directory, a special file and a file over the size limit."""
    try:
        info = os.stat(path)
    except FileNotFoundError:
        if os.path.islink(path):        # the link is there; where it leads is not
            raise DesignError(path, "", None, "broken symbolic link (it leads to "
                                              f"{os.path.realpath(path)}, which does not "
                                              "exist)") from None
        raise DesignError(path, "", None, "no such file") from None
    except OSError as error:
        raise DesignError(path, "", None, f"cannot read file: {error.strerror}") from None
    if stat.S_ISDIR(info.st_mode):
        raise DesignError(path, "", None, "is a directory, not a design file")
    if not stat.S_ISREG(info.st_mode):
        raise DesignError(path, "", None, "not a regular file")
    if info.st_size > tol.MAX_FILE_BYTES:
        raise _too_large(path, info.st_size)


def _too_large(source: str, size: int) -> DesignError:
    limit_mb = tol.MAX_FILE_BYTES / 2**20
    return DesignError(source, "", None,
                       f"file too large ({size / 2**20:.1f} MiB; the limit is "
                       f"{plain_number(limit_mb, 6)} MiB)")


def _decode(data: bytes, path: str) -> str:
    """A design file's text: UTF-8 (a byte-order mark dropped), or UTF-16 or UTF-32 that
    begins with its byte-order mark (``files.as_utf8``)."""
    try:
        data = as_utf8(data)
    except UnicodeDecodeError as error:
        wide = "-".join(error.encoding.upper().split("-")[:2])      # UTF-16, UTF-32
        raise DesignError(path, "", None, f"not a text file (it begins with the byte-order "
                                          f"mark of {wide}, but is not {wide} text)") from None
    if b"\x00" in data:
        raise DesignError(path, "", None, "not a text file (it holds NUL bytes)")
    data = data.removeprefix(codecs.BOM_UTF8)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        raise DesignError(path, "", None, "not a text file (not UTF-8)") from None


def _checked_text(text: str, source: str) -> str:
    """``text`` without a byte-order mark; refuses oversized, binary and empty text."""
    if not isinstance(text, str):
        raise DesignError(source, "", None, "not a text file")
    if len(text) > tol.MAX_FILE_BYTES:
        raise _too_large(source, len(text))
    if "\x00" in text:
        raise DesignError(source, "", None, "not a text file (it holds NUL bytes)")
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:
        raise DesignError(source, "", None, "not a text file (not UTF-8)") from None
    text = text.removeprefix("\ufeff")
    if not text.strip():
        raise DesignError(source, "", None, "empty file")
    return text


# --- step 2a: YAML text -> tree -----------------------------------------------------------------

class _Scalar(NamedTuple):
    """A YAML scalar as written: its text, and ``plain`` when it was not quoted (so its
    meaning, number, boolean, null or text, is decided by where it stands)."""

    text: str
    plain: bool


_NO_DOCUMENT = object()


class _Frame:
    """An open YAML mapping or list while its events are read: a mapping's ``key`` waiting
    for its value (and that value's ``key_path``), ``key_lines`` its keys' lines.  (The
    two classes here are a named tuple and a plain class, not dataclasses, which cost more
    to create on import: they are on the path of every cold ``furncheck validate``.)"""

    __slots__ = ("value", "path", "key", "key_path", "key_lines")

    def __init__(self, value: dict | list, path: str, key_lines: dict | None = None):
        self.value, self.path, self.key, self.key_path = value, path, None, ""
        self.key_lines = key_lines


def _read_yaml(text: str, source: str) -> tuple[Any, dict[str, int]]:
    """(tree, lines): dicts, lists and ``_Scalar``; key path -> 1-based line."""
    loader = None
    try:
        loader = _Loader(text)           # the pure-Python reader checks characters here
        return _build_yaml_tree(loader, source, _editor_lines(text))
    except yaml.YAMLError as error:
        raise _yaml_syntax_error(error, text, source) from None
    finally:
        if loader is not None:
            loader.dispose()


_SCALAR, _ALIAS, _MAPPING, _SEQUENCE, _END, _DOCUMENT, _OTHER = range(7)
_KINDS = {yaml.ScalarEvent: _SCALAR, yaml.AliasEvent: _ALIAS, yaml.MappingStartEvent: _MAPPING,
          yaml.SequenceStartEvent: _SEQUENCE, yaml.MappingEndEvent: _END,
          yaml.SequenceEndEvent: _END, yaml.DocumentStartEvent: _DOCUMENT}
"""YAML event class -> what it means for the tree (other classes: ``_kind_of``)."""


def _kind_of(event_class: type) -> int:
    """The ``_KINDS`` entry of an event class or of the nearest class it derives from
    (_OTHER: stream and document ends, and the like)."""
    return next((_KINDS[base] for base in event_class.__mro__ if base in _KINDS), _OTHER)


def _build_yaml_tree(loader, source: str, editor_line=None) -> tuple[Any, dict[str, int]]:
    """The tree and lines of the loader's events, in one loop (it runs for every event of
    every design file; a function call and a few type tests per event took a quarter of
    reading the catalog's designs): a node's key path is made once, when its slot is
    known (a list's next item, or the key just read), and recorded with its line (the
    parser's, or ``editor_line`` of its index where YAML breaks lines that an editor
    does not: ``_editor_lines``)."""
    lines: dict[str, int] = {}
    stack: list[_Frame] = []
    root: Any = _NO_DOCUMENT
    documents = 0
    kinds = _KINDS
    check_event, get_event = loader.check_event, loader.get_event
    while check_event():
        event = get_event()
        kind = kinds.get(type(event))
        if kind is None:
            kind = _kind_of(type(event))
        if kind == _END:
            value = stack.pop().value
            if not stack:
                root = value
                continue
            parent = stack[-1]
            if parent.key_lines is None:
                parent.value.append(value)
            else:
                parent.value[parent.key] = value
                parent.key = None
            continue
        if kind == _DOCUMENT or kind == _OTHER:
            if kind == _DOCUMENT:
                documents += 1
                if documents > 1:
                    raise DesignError(source, "", event.start_mark.line + 1
                                      if editor_line is None
                                      else editor_line(event.start_mark.index),
                                      "several YAML documents (the second starts here); "
                                      "put one design in each file")
            continue
        line = event.start_mark.line + 1 if editor_line is None \
            else editor_line(event.start_mark.index)
        parent = stack[-1] if stack else None
        if parent is None:
            path = ""
            lines[path] = line          # the whole design: where a missing key is missed
        elif parent.key_lines is None:                  # a list's next item
            path = f"{parent.path}[{len(parent.value)}]"
            lines[path] = line
        elif parent.key is not None:                    # the value of the key just read
            path = parent.key_path
        else:                                           # a mapping key
            _read_key(parent, event, kind, line, lines, source)
            continue
        if kind == _SCALAR:
            value = _yaml_scalar(event, path, line, source)
            if parent is None:
                root = value
            elif parent.key_lines is None:
                parent.value.append(value)
            else:
                parent.value[parent.key] = value
                parent.key = None
        elif kind == _ALIAS:
            raise DesignError(source, path, line, f"YAML aliases (*{event.anchor}) are not "
                                                  "allowed; write the value out")
        else:
            _check_container_tag(event, path, line, source)
            if len(stack) >= tol.MAX_NESTING:
                raise DesignError(source, path, line, "nested too deeply")
            stack.append(_Frame({}, path, {}) if kind == _MAPPING else _Frame([], path))
    return root, lines


def _read_key(frame: _Frame, event, kind: int, line: int, lines: dict[str, int],
              source: str) -> None:
    """Take ``event`` (of ``_KINDS`` ``kind``) as the next key of the mapping ``frame``:
    its path and line recorded, its value awaited."""
    if kind == _ALIAS:
        raise DesignError(source, frame.path, line, f"YAML aliases (*{event.anchor}) are not "
                                                    "allowed; write the value out")
    if kind != _SCALAR:
        raise DesignError(source, frame.path, line, "mapping keys must be plain text")
    key = event.value
    path = _child(frame.path, key)
    if key in frame.key_lines:
        raise DesignError(source, path, line, f"duplicate key {_quote(key)} (first on line "
                                              f"{frame.key_lines[key]})")
    frame.key_lines[key] = line
    frame.key, frame.key_path = key, path
    lines[path] = line


def _yaml_scalar(event, path: str, line: int, source: str) -> _Scalar:
    tag = event.tag
    if tag is None:
        plain = event.style in (None, "") and event.implicit[0]
    elif tag in _TEXT_TAGS:
        plain = False
    elif tag in _PLAIN_TAGS:
        plain = True
    else:
        raise _tag_error(tag, path, line, source)
    return _Scalar(event.value, plain)


def _check_container_tag(event, path: str, line: int, source: str) -> None:
    if event.tag is not None and event.tag not in _CONTAINER_TAGS:
        raise _tag_error(event.tag, path, line, source)


def _tag_error(tag: str, path: str, line: int, source: str) -> DesignError:
    shown = "!!" + tag[len(_YAML_TAG):] if tag.startswith(_YAML_TAG) else tag
    return DesignError(source, path, line, f"unsupported YAML tag {_quote(shown)}")


_FLOW_CONTEXTS = {"while parsing a flow mapping": "{",
                  "while parsing a flow sequence": "["}
"""PyYAML's contexts of a bracket left open -> the bracket."""


def _closed(text: str, start: int, bracket: str) -> bool:
    """Whether the ``bracket`` ('{' or '[') at ``text[start]`` is closed further on: its
    match found counting brackets of both kinds, outside quoted text and comments (a
    '#' after a space or at a line's start)."""
    closing = {"{": "}", "[": "]"}
    stack: list[str] = []
    quote = None
    k = start
    while k < len(text):
        c = text[k]
        if quote is not None:
            if c == "\\" and quote == '"':
                k += 1
            elif c == quote:
                if quote == "'" and text[k + 1:k + 2] == "'":
                    k += 1                              # '' inside single quotes
                else:
                    quote = None
        elif c in "'\"":
            quote = c
        elif c == "#" and (k == 0 or text[k - 1] in " \t\n\r"):
            end = text.find("\n", k)
            k = len(text) if end < 0 else end
            continue
        elif c in closing:
            stack.append(closing[c])
        elif c in "}]":
            if not stack or stack.pop() != c:
                return False
            if not stack:
                return True
        k += 1
    return False


def _yaml_syntax_error(error: yaml.YAMLError, text: str, source: str) -> DesignError:
    """The parser's error as one line at the line it names: where the problem is, or,
    when the parser ran into the end of the file (a bracket or quote never closed), the
    line where what it was reading began (its context, where that lies before the end),
    else the file's last line, with 'at the end of the file' said: a line of the file,
    not the one past its last."""
    problem_mark = getattr(error, "problem_mark", None)
    context_mark = getattr(error, "context_mark", None)
    problem = getattr(error, "problem", None)
    if problem is None and hasattr(error, "reason"):          # yaml.reader.ReaderError
        line = text.count("\n", 0, max(0, error.position)) + 1
        return DesignError(source, "", line, f"not a text file ({error.reason})")
    context = getattr(error, "context", None)
    message = problem or "cannot be read"
    if context:
        message = f"{message} ({context})"
    editor_line = _editor_lines(text)

    def line_of(mark) -> int:
        return mark.line + 1 if editor_line is None else editor_line(mark.index)

    mark = problem_mark or context_mark
    line = None if mark is None else line_of(mark)
    if context in _FLOW_CONTEXTS and problem_mark is not None and context_mark is not None \
            and line_of(context_mark) < line_of(problem_mark) \
            and problem_mark.index < len(text) \
            and not _closed(text, context_mark.index, _FLOW_CONTEXTS[context]):
        # a bracket left open: the parser stumbles on the next line's item, but the
        # mistake is on the line where the bracket was opened (one closed further on
        # is missing a comma where the parser stopped: its line stays)
        bracket = _FLOW_CONTEXTS[context]
        message = (f"the {bracket!r} opened on this line is not closed ({problem}, found "
                   f"on line {line_of(problem_mark)})")
        line = line_of(context_mark)
    if problem_mark is not None and problem_mark.index >= len(text):
        message = f"{message}, at the end of the file"
        if context_mark is not None and context_mark.index < len(text):
            line = line_of(context_mark)
        else:                       # the last line, counted as the parser counts breaks
            line = min(line, max(_line_count(text) if editor_line is None
                                 else editor_line(len(text) - 1), 1))
    if problem_mark is not None and problem_mark.index < len(text) \
            and text[problem_mark.index] == "\t" and "\t" not in message:
        message = f"{message}; a tab there: YAML indents with spaces"
    elif problem_mark is not None and problem_mark.index < len(text) and problem:
        hint = next((hint for start, hint in _BLOCK_HINTS if problem.startswith(start)), None)
        message = message if hint is None else f"{message}; {hint}"
    marks = [m.index for m in (context_mark, problem_mark) if m is not None]
    if editor_line is not None and marks:   # a break the parser saw on the lines it read
        start = text.rfind("\n", 0, min(marks)) + 1      # up to the error may be the
        end = text.find("\n", max(marks))                # mistake: said where it is
        near = text[start:len(text) if end < 0 else end]
        shown = ", ".join(f"U+{ord(c):04X}" for c in _YAML_ONLY_BREAKS if c in near)
        if shown:
            message = f"{message}; line {line_of(problem_mark or context_mark)} holds " \
                      f"{shown}, which YAML reads as a line break"
    return DesignError(source, "", line, _one_line(f"YAML syntax error: {message}"))


_BLOCK_HINTS = (
    ("did not find expected key", "check this line's indentation against the keys above it"),
    ("did not find expected '-' indicator",
     "check this line's indentation against the list items above it"),
    ("mapping values are not allowed",
     "check this line's indentation, or quote a value that holds ': '"),
    ("expected <block end>", "check this line's indentation against the lines above it"),
)
"""PyYAML's problems of a block indented out of line (its words name the parser's state,
not the file's mistake; the last, the pure-Python parser's where libyaml is missing) ->
what to look at."""


_YAML_ONLY_BREAKS = "\x85\u2028\u2029"
"""Characters YAML (1.1, as PyYAML reads it) breaks lines at and editors do not: NEL, LS
and PS."""


def _editor_lines(text: str):
    """None where YAML breaks the lines of ``text`` where an editor does (LF, CR LF, CR:
    the parser's line numbers are the file's); else index -> 1-based line as an editor
    counts it, so that a message (and a CI annotation) lands on the line a maker sees (a
    NEL inside a quoted name moved every later line's number by one)."""
    if not any(c in text for c in _YAML_ONLY_BREAKS):
        return None
    import bisect

    starts = [0] + [found.end() for found in re.finditer(r"\r\n|\r|\n", text)]
    return lambda index: bisect.bisect_right(starts, index)


def _line_count(text: str) -> int:
    """The lines of ``text`` as YAML counts them: broken by CR LF, CR, LF, NEL, LS or PS
    (a last line without a break counts too)."""
    breaks = text.replace("\r\n", "\n")
    count = sum(breaks.count(c) for c in "\r\n\x85\u2028\u2029")
    return count + (0 if breaks.endswith(tuple("\r\n\x85\u2028\u2029")) else 1)


# --- messages: shared with the schema in load.py ------------------------------------------------

def _quote(text: str) -> str:
    """``text`` in double quotes on one line, shortened, unprintable characters escaped."""
    short = text if len(text) <= _QUOTE_LIMIT else text[:_QUOTE_LIMIT] + "..."
    return '"' + _one_line(short) + '"'


def _one_line(text: str) -> str:
    return "".join(c if c.isprintable() else f"\\u{ord(c):04x}" for c in text)


def _child(path: str, key: str) -> str:
    """Key path of mapping entry ``key`` under ``path``; odd keys are written ``["..."]``."""
    safe = _SAFE_KEYS.get(key)
    if safe is None:
        safe = _PATH_SAFE_KEY.fullmatch(key) is not None
        if len(_SAFE_KEYS) < _SAFE_KEYS_MAX and len(key) <= _SAFE_KEY_LENGTH:
            _SAFE_KEYS[key] = safe
    if not safe:
        return f"{path}[{_quote(key)}]"
    return f"{path}.{key}" if path else key


_SAFE_KEYS: dict[str, bool] = {}
_SAFE_KEYS_MAX, _SAFE_KEY_LENGTH = 4096, 64
"""Keys already told safe or odd for key paths (a design's few dozen names recur in every
file), up to this many, of at most this many characters (a batch reads many files)."""
