"""Whether a YAML or JSON file found in a directory scan is a design file at all.

A design file's top level has a ``furncheck`` key (the format version, contract section
1); ``package.json``, ``tsconfig.json``, a CI workflow or a docker-compose file have none
and are not designs.  ``declares_design`` decides that for the file's bytes:

- without the word ``furncheck`` anywhere, no (one substring search: most files stop here);
- JSON: the document is an object with a ``furncheck`` key whose value is no object or
  array (``package.json`` depending on a package named furncheck is no design);
- YAML: the first line that is not blank, a comment or ``---`` starts with ``furncheck:``
  and a value on that line (the first key of a top-level block mapping: how design files
  begin), or else the first document's top-level mapping has a ``furncheck`` key whose
  value is no mapping or list, read event by event (nothing is constructed, values are
  skipped).  The key's value is a design's format version: a ``furncheck:`` that holds a
  mapping is something else's (a GitLab CI job of that name, as the README's recipe
  writes one);
- a file that does not parse: a top-level ``furncheck`` key written at the start of a line
  (YAML; in a ``.json`` file too: a design written in YAML but named .json) or a
  ``"furncheck":`` key (JSON): a design with a syntax error is still a design, and its
  report says what is wrong;
- a file too large to be checked (``declares_design_at_large``): the same key patterns,
  looked for in its first SNIFF_LIMIT bytes a block at a time: a design, however large, whose key
  comes last is still a design, and its report says it is too large (exit code 2) where
  a scan that read only its first blocks passed it over as no design.
"""

from __future__ import annotations

import json
import re
from typing import BinaryIO

import yaml

from furncheck.files import as_utf8

KEY = "furncheck"

_Loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
_YAML_KEY_LINE = re.compile(rb"""^(?:\{\s*)?["']?furncheck["']?\s*:""", re.MULTILINE)
_YAML_FIRST_KEY = re.compile(rb"""(?:\xef\xbb\xbf)?(?:[ \t]*(?:#[^\n]*)?\r?\n|---[ \t]*\r?\n)*"""
                             rb"""furncheck[ \t]*:[ \t]+[^\s{\[&!*#]""")
_JSON_KEY = re.compile(rb'"furncheck"\s*:')

SNIFF_BLOCK = 1 << 20
"""Bytes read at a time where a file too large to check is searched for its key."""

SNIFF_LIMIT = 20 * (1 << 20)
"""Bytes of a file too large to check searched for its key, at most: a design's key
stands in its first 20 MiB (one over 5 MiB is already refused), and a data file of hundreds
of MB in a scanned tree is not read to its end on every run."""


def declares_design(data: bytes, fmt: str) -> bool:
    """Whether ``data`` (a file's bytes; ``fmt`` 'yaml' or 'json') has a top-level
    ``furncheck`` key: see the module docstring."""
    try:
        data = as_utf8(data)
    except UnicodeDecodeError:
        return False
    if KEY.encode() not in data:
        return False
    try:
        text = data.decode("utf-8-sig")
        if fmt == "json":
            document = json.loads(text)
            return isinstance(document, dict) and KEY in document \
                and not isinstance(document[KEY], (dict, list))
        if _YAML_FIRST_KEY.match(data):
            return True
        return _yaml_top_level_has_key(text)
    except (UnicodeDecodeError, ValueError, yaml.YAMLError, RecursionError):
        return _YAML_KEY_LINE.search(data) is not None or \
            (fmt == "json" and _JSON_KEY.search(data) is not None)


def declares_design_at_large(stream: BinaryIO, fmt: str) -> bool:
    """``declares_design`` for a file too large to read whole (``stream``: open for
    binary reading at its start): whether a ``furncheck`` key of either form (a YAML key
    at the start of a line; in JSON also a ``"furncheck":`` key) appears, read
    SNIFF_BLOCK bytes at a time (each block read after the last bytes of the one before,
    so a key across two blocks is found), in its first SNIFF_LIMIT bytes."""
    tail = b""
    overlap = 64
    for _ in range(max(1, SNIFF_LIMIT // SNIFF_BLOCK)):
        block = stream.read(SNIFF_BLOCK)
        if not block:
            return False
        data = tail + block
        if KEY.encode() in data and (
                _YAML_KEY_LINE.search(data) is not None
                or (fmt == "json" and _JSON_KEY.search(data) is not None)):
            return True
        tail = b"x" + data[-overlap:]    # (a line start only after a newline in it)
    return False


def _yaml_top_level_has_key(text: str) -> bool:
    """Whether the first YAML document of ``text`` is a mapping with the key ``furncheck``."""
    loader = _Loader(text)
    try:
        while loader.check_event():
            event = loader.get_event()
            if isinstance(event, yaml.MappingStartEvent):
                return _mapping_has_key(loader)
            if isinstance(event, (yaml.NodeEvent, yaml.DocumentEndEvent)):
                return False      # the first document is a scalar or a list, or empty
        return False
    finally:
        loader.dispose()


def _mapping_has_key(loader) -> bool:
    """Reads the pairs of the mapping just opened; True at the first key ``furncheck``."""
    while True:
        key = loader.get_event()
        if isinstance(key, yaml.MappingEndEvent):
            return False
        if isinstance(key, yaml.ScalarEvent) and key.value == KEY:
            return not isinstance(loader.peek_event(), yaml.CollectionStartEvent)
        if isinstance(key, yaml.CollectionStartEvent):   # a complex key: skip it
            _skip_collection(loader)
        _skip_node(loader)                               # the value


def _skip_node(loader) -> None:
    event = loader.get_event()
    if isinstance(event, yaml.CollectionStartEvent):
        _skip_collection(loader)


def _skip_collection(loader) -> None:
    depth = 1
    while depth:
        event = loader.get_event()
        if isinstance(event, yaml.CollectionStartEvent):
            depth += 1
        elif isinstance(event, yaml.CollectionEndEvent):
            depth -= 1
