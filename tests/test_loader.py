"""The design loader and writer (contract section 1).

Bad input: one test per class of problem, each checking the ``DesignError``'s key path and
line, and that ``str(error)`` is one line naming the file, the line and the key.  Good input:
defaults, units, loads, joints, load cases, recorded lines, and the write -> read round trip.
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import replace as replace_fields

import numpy as np
import pytest
import yaml
from click.testing import CliRunner

from furncheck import tolerances as tol
from furncheck.cli.main import main
from furncheck.design import (
    Design,
    JointSpec,
    Load,
    LoadCase,
    Material,
    Plank,
    design_to_document,
    load_design,
    parse_design,
    write_design,
)
from furncheck.design import load as load_module
from furncheck.design import source as source_module
from furncheck.errors import DesignError
from furncheck.tolerances import GRAVITY

# A bench: seat on two legs standing on their end faces (rotation [0, 90, 0] maps local
# x to world -z).  Line numbers are used by the tests below.
BASE = """\
furncheck: 1
name: bench
planks:
  - id: seat
    size: [400, 300]
    center: [0, 0, 406]
  - id: leg1
    size: [400, 300]
    center: [-194, 0, 200]
    rotation: [0, 90, 0]
  - id: leg2
    size: [400, 300]
    center: [194, 0, 200]
    rotation: [0, 90, 0]
loads:
  - {plank: seat, mass: 10}
"""
LINE = {"furncheck": 1, "name": 2, "planks": 3, "planks[0]": 4, "planks[0].size": 5,
        "planks[0].center": 6, "planks[1]": 7, "planks[1].id": 7, "planks[1].size": 8,
        "planks[1].rotation": 10, "planks[2].id": 11, "loads": 15, "loads[0]": 16}


def base_dict() -> dict:
    return yaml.safe_load(BASE)


def replace(old: str, new: str, text: str = BASE) -> str:
    assert old in text, old
    return text.replace(old, new, 1)


def error_of(text: str, fmt: str = "yaml", source: str = "bench.yaml") -> DesignError:
    """The DesignError that ``text`` raises, checked to be one line with file, line, key."""
    with pytest.raises(DesignError) as info:
        parse_design(text, source, fmt)
    return checked(info.value, source)


def checked(error: DesignError, source: str) -> DesignError:
    line = str(error)
    assert "\n" not in line and "\r" not in line
    assert line.startswith(source)
    if error.line is not None:
        assert line.startswith(f"{source}:{error.line}: ")
    if error.key:
        assert f": {error.key}: " in line
    return error


def expect(text: str, key: str, line: int | None, fragment: str, fmt: str = "yaml"):
    error = error_of(text, fmt)
    assert (error.key, error.line) == (key, line), str(error)
    assert fragment in error.message, str(error)
    return error


# --- file level -------------------------------------------------------------------------------

def test_missing_file(tmp_path):
    path = str(tmp_path / "nope.yaml")
    with pytest.raises(DesignError) as info:
        load_design(path)
    assert checked(info.value, path).message == "no such file"
    assert (info.value.key, info.value.line) == ("", None)


def test_broken_symbolic_link(tmp_path):
    """A link whose target is gone is named as such, not as a missing file (the link is
    there, in the folder scanned), with where it leads: through a chain of links, the
    path that is missing at its end, not the link in the middle (which exists)."""
    gone = tmp_path.resolve() / "gone.yaml"
    middle = tmp_path / "middle.yaml"
    middle.symlink_to(gone)
    path = tmp_path / "shelf.yaml"
    path.symlink_to(middle)
    for link in (middle, path):
        with pytest.raises(DesignError) as info:
            load_design(str(link))
        assert checked(info.value, str(link)).message == \
            f"broken symbolic link (it leads to {gone}, which does not exist)"


def test_directory(tmp_path):
    folder = tmp_path / "shelf.yaml"
    folder.mkdir()
    with pytest.raises(DesignError, match="is a directory"):
        load_design(str(folder))


def test_unknown_extension(tmp_path):
    path = tmp_path / "bench.txt"
    path.write_text(BASE)
    with pytest.raises(DesignError, match='unknown file type ".txt"'):
        load_design(str(path))


def test_unreadable(tmp_path, monkeypatch):
    """Root can read a chmod 000 file, so the permission error is simulated."""
    path = tmp_path / "bench.yaml"
    path.write_text(BASE)

    def refuse(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(load_module, "open", refuse, raising=False)
    with pytest.raises(DesignError) as info:
        load_design(str(path))
    assert checked(info.value, str(path)).message == "cannot read file: Permission denied"


@pytest.mark.parametrize("content", [b"", b"  \n\t\n", b"# only a comment\n"])
def test_empty_file(tmp_path, content):
    path = tmp_path / "bench.yaml"
    path.write_bytes(content)
    with pytest.raises(DesignError) as info:
        load_design(str(path))
    assert checked(info.value, str(path)).message == "empty file"


@pytest.mark.parametrize("codec", ["utf-16", "utf-16-be", "utf-32", "utf-32-be"])
@pytest.mark.parametrize("suffix", [".yaml", ".json"])
def test_utf16_and_utf32_text_with_its_byte_order_mark_is_read(tmp_path, codec, suffix):
    """A design saved as UTF-16 or UTF-32 with its byte-order mark (an editor's 'Unicode';
    YAML and JSON both allow it) reads as its UTF-8 copy does, line numbers included (it
    was 'not a text file (it holds NUL bytes)', and a scan passed it over as no design);
    such a mark before text that does not decode says so."""
    text = BASE if suffix == ".yaml" else json.dumps(yaml.safe_load(BASE), indent=1)
    plain, wide = tmp_path / f"plain{suffix}", tmp_path / f"wide{suffix}"
    plain.write_text(text, encoding="utf-8")
    mark = {"utf-16-be": b"\xfe\xff", "utf-32-be": b"\x00\x00\xfe\xff"}.get(codec, b"")
    wide.write_bytes(mark + text.encode(codec))
    assert load_design(str(wide)).planks == load_design(str(plain)).planks
    from furncheck.detect import declares_design
    from furncheck.scan import find_design_files

    assert declares_design(wide.read_bytes(), suffix[1:])
    assert str(wide) in find_design_files(str(tmp_path)).files
    broken = tmp_path / f"broken{suffix}"
    broken.write_bytes(b"\xff\xfe" + b"f\x00u")               # an odd byte at its end
    with pytest.raises(DesignError) as info:
        load_design(str(broken))
    assert info.value.message == ("not a text file (it begins with the byte-order mark of "
                                  "UTF-16, but is not UTF-16 text)")


def test_empty_json(tmp_path):
    path = tmp_path / "bench.json"
    path.write_bytes(b"\n \n")
    with pytest.raises(DesignError, match="empty file"):
        load_design(str(path))


@pytest.mark.parametrize("content", [b"furncheck: 1\x00\x01", b"\xff\xfe\x00a\x00",
                                     b"name: \xe9t\xe9"])
def test_binary_file(tmp_path, content):
    path = tmp_path / "bench.yaml"
    path.write_bytes(content)
    with pytest.raises(DesignError) as info:
        load_design(str(path))
    assert checked(info.value, str(path)).message.startswith("not a text file")


def test_text_with_nul_or_lone_surrogate():
    assert error_of("furncheck: 1\x00").message.startswith("not a text file")
    assert error_of("name: \ud800").message.startswith("not a text file")


def test_a_json_name_with_an_escaped_lone_surrogate_gets_its_line():
    """JSON reads "\\ud800" as a lone surrogate, which a name may not hold; the line of a
    JSON key is found by reading the text as YAML, which refuses that escape: the message
    had no line.  The escape is read as a private-use character's for the lines, and a
    key holding one (a load case's name) finds its own line, not its parent's."""
    for text, line in (('{"furncheck": 1, "name": "a\\ud800b", "planks": []}', 1),
                       ('{"furncheck": 1,\n "name": "a\\uDC00",\n "planks": []}', 2)):
        expect(text, "name", line, "must be printable text on one line", fmt="json")
    keys = ('{"furncheck": 1,\n "planks": [{"id": "p", "size": [100, 100], "center": [0, 0, 6]}],'
            '\n "load_cases": {\n  "c\\ud800": {"loads": []},\n  "d\\udfff": {"loads": []}}}')
    expect(keys, 'load_cases["c\\ud800"]', 4, "invalid load case name", fmt="json")


def test_too_large(tmp_path):
    path = tmp_path / "bench.yaml"
    with open(path, "wb") as handle:
        handle.truncate(5 * 2**20 + 1)          # sparse: no 5 MB written
    with pytest.raises(DesignError, match=r"file too large \(5\.0 MiB; the limit is 5 MiB\)"):
        load_design(str(path))


def test_utf8_byte_order_mark_is_fine(tmp_path):
    path = tmp_path / "bench.json"
    path.write_bytes(b"\xef\xbb\xbf" + json.dumps(base_dict()).encode())
    assert load_design(str(path)).name == "bench"


def test_yaml_syntax_error_has_line():
    """A '[' left open on line 6: the parser stumbles on line 7's item, but the line
    named (and so a GitHub annotation's) is the one with the mistake, and the message says
    what it is; the parser's own words stay in it."""
    text = replace("    center: [0, 0, 406]", "    center: [0, 0, 406")
    expect(text, "", 6, "YAML syntax error: the '[' opened on this line is not closed (did "
                        "not find expected ',' or ']', found on line 7)")
    mapping = replace("  - {plank: seat, mass: 10}", "  - {plank: seat, mass: 10\n  - x: 1")
    expect(mapping, "", 16, "the '{' opened on this line is not closed")
    # a bracket closed further on, a comma missing inside it: the parser's own line (where
    # the next item starts) and words, not 'not closed' (quotes and comments with
    # brackets in them do not count)
    comma = ("furncheck: 1\nname: 'a [b'\nplanks: [\n  {id: a, size: [1, 1], center: [0, 0, 6]}"
             "  # {\n  {id: b, size: [1, 1], center: [0, 0, 6]}\n]\n")
    error = expect(comma, "", 5, "did not find expected ',' or ']' (while parsing a flow "
                                 "sequence)")
    assert "not closed" not in error.message


def test_a_tab_indenting_a_line_is_named():
    """A tab that indents a block line: the C parser's message says only that a character
    cannot start a token (it drops the character); the message says it is a tab, which
    YAML does not indent with, at that line."""
    text = "furncheck: 1\nplanks:\n  - id: a\n    size: [300, 300]\n\tcenter: [0, 0, 6]\n"
    expect(text, "", 5, "found character that cannot start any token (while scanning for "
                        "the next token); a tab there: YAML indents with spaces")


def test_a_block_indented_out_of_line_says_to_check_the_indentation():
    """PyYAML's words for a block line indented out of line name its parser's state ('did
    not find expected key', '... '-' indicator', 'mapping values are not allowed'); the
    message keeps them, at the line they name, and says what to look at."""
    item = ("furncheck: 1\nname: x\nplanks:\n  - {id: a, size: [100, 100], center: [0, 0, 6]}"
            "\n   - {id: b, size: [100, 100], center: [0, 0, 18]}\n")
    expect(item, "", 5, "did not find expected '-' indicator (while parsing a block "
                        "collection); check this line's indentation against the list items "
                        "above it")
    key = "furncheck: 1\nname: x\nplanks:\n- id: a\n  size: [100, 100]\n   center: [0, 0, 6]\n"
    expect(key, "", 6, "did not find expected key (while parsing a block mapping); check "
                       "this line's indentation against the keys above it")
    nested = "furncheck: 1\n  name: x\n"
    expect(nested, "", 2, "mapping values are not allowed in this context; check this "
                          "line's indentation, or quote a value that holds ': '")
    colon = "furncheck: 1\nname: chair: big\n"
    expect(colon, "", 2, "or quote a value that holds ': '")
    # the pure-Python parser's words, where libyaml is missing
    import yaml

    from furncheck.design.source import _yaml_syntax_error

    for text, line in ((item, 5), (key, 6)):
        with pytest.raises(yaml.YAMLError) as raised:
            yaml.load(text, Loader=yaml.SafeLoader)
        error = _yaml_syntax_error(raised.value, text, "d.yaml")
        assert error.line == line and error.message.endswith(
            "check this line's indentation against the lines "
            "above it"), error.message


def test_lines_are_counted_as_an_editor_counts_them_where_yaml_breaks_more():
    """YAML (1.1, as PyYAML reads it) breaks lines at NEL (U+0085), LS (U+2028) and PS
    (U+2029) too; an editor, grep and a GitHub annotation do not.  A NEL inside a quoted
    name on line 2: the size on line 4 is named on line 4 (it read 5); an LS in a comment
    on line 2 makes what follows it YAML content, a syntax error named on line 2 (it read
    3), whose message says which character the parser broke the line at."""
    nel = ('furncheck: 1\nname: "a\x85b"\nplanks:\n'
           '  - {id: a, size: [400, 300, 12], center: [0, 0, 6]}\n')
    expect(nel, "planks[0].size", 4, "expected 2 numbers")
    separator = ("furncheck: 1\n# \u2028 ls\nplanks:\n"
                 "  - {id: a, size: [400, 300], center: [0, 0, 6]}\n")
    error = expect(separator, "", 2, "YAML syntax error")
    assert error.message.endswith("line 2 holds U+2028, which YAML reads as a line break")
    # a NEL in a name, a bracket left open two lines further on: the bracket's line, and
    # no word of the NEL, which has nothing to do with it
    elsewhere = ('furncheck: 1\nname: "a\x85b"\nplanks:\n'
                 '  - {id: a, size: [400, 300], center: [0, 0, 6]\n  - {id: b}\n')
    error = expect(elsewhere, "", 4, "the '{' opened on this line is not closed")
    assert "U+0085" not in error.message and "found on line 5" in error.message


def test_a_bracket_never_closed_names_the_line_it_opens_on():
    """The parser runs into the end of the file (line 6 of a 5-line file, or 4 of 3):
    the error names the line where the unclosed mapping, sequence or quote began, one of
    the file's, and says that the file ended."""
    flow = ("furncheck: 1\nname: x\nplanks:\n  - {id: a, size: [100, 100], center: [0, 0, 6]}"
            "\n  - {id: b, size: [100, 100], center: [0, 0, 6]\n")
    error = expect(flow, "", 5, "did not find expected ',' or '}'")
    assert error.message.endswith("at the end of the file")
    quoted = 'furncheck: 1\nname: "abc\nplanks: []\n'
    assert expect(quoted, "", 2, "quoted scalar").message.endswith("at the end of the file")
    # lines broken by CR alone count as YAML counts them
    expect(flow.replace("\n", "\r"), "", 5, "did not find expected ',' or '}'")
    # where the parser gives no line before the end (a sequence left open after a comma),
    # the file's last line
    sequence = ("furncheck: 1\nplanks: [\n  {id: a, size: [100, 100], center: [0, 0, 6]},\n"
                "  {id: b, size: [100, 100], center: [0, 0, 6]},\n")
    assert expect(sequence, "", 4, "expected node content").message.endswith(
        "at the end of the file")
    # a problem inside the file keeps its own line
    tab = "furncheck: 1\nname: x\nplanks:\n  - {id: a, size: [100, 100], center: [0, 0, 6]}\n\t\n"
    assert not expect(tab, "", 5, "cannot start any token").message.endswith("file")


def test_json_syntax_error_has_line():
    text = json.dumps(base_dict(), indent=2).replace('"seat"', "seat", 1)
    error = error_of(text, "json", "bench.json")
    assert error.key == "" and error.message.startswith("JSON syntax error")
    assert error.line == text.splitlines().index('      "id": seat,') + 1


def test_several_yaml_documents():
    expect(BASE + "---\nfurncheck: 1\n", "", 17, "several YAML documents")


@pytest.mark.parametrize("text, got", [("- 1\n- 2\n", "a list"),
                                       ("just text\n", 'text "just text"'),
                                       ("~\n", "nothing (null)")])
def test_top_level_not_a_mapping(text, got):
    expect(text, "", 1, f"the top level must be a mapping, got {got}")


def test_top_level_json_list():
    expect("[1, 2]", "", 1, "the top level must be a mapping, got a list", "json")


# --- YAML specifics ---------------------------------------------------------------------------

def test_alias_is_refused_with_its_line():
    text = replace("    size: [400, 300]\n    center: [-194",
                   "    size: *seat_size\n    center: [-194").replace(
        "size: [400, 300]", "size: &seat_size [400, 300]", 1)
    expect(text, "planks[1].size", 8, "YAML aliases (*seat_size) are not allowed")


def test_billion_laughs_is_refused_at_its_first_alias(monkeypatch):
    """Nine levels of ten aliases each would expand to 10^9 strings.  The loader reads the
    YAML event by event and refuses the first alias (line 2, key path a1[0]) as soon as it
    reads it: by then it has read 8 events (stream, document and mapping start, the key a0
    and its scalar, the key a1, its list's start, the alias) of the file's 125 (3 starts,
    2 for a0, 9 levels of 13: key, list start, 10 aliases, list end; 3 ends), and it never
    asks PyYAML to compose or construct a node, the steps where an alias is resolved.  The
    behaviour is asserted, not a time: a slow machine cannot fail this test, and a loader
    that read on or resolved aliases fails it by these counts."""
    lines = ['a0: &a0 "lol"']
    lines += [f"a{i}: &a{i} [{', '.join([f'*a{i - 1}'] * 10)}]" for i in range(1, 10)]
    text = "\n".join(lines) + "\n"
    counts = {"events": 0, "nodes": 0}

    class CountingLoader(source_module._Loader):
        def get_event(self):
            counts["events"] += 1
            return super().get_event()

        def get_single_node(self):
            counts["nodes"] += 1
            return super().get_single_node()

        def get_node(self):
            counts["nodes"] += 1
            return super().get_node()

        def get_single_data(self):
            counts["nodes"] += 1
            return super().get_single_data()

        def construct_document(self, node):
            counts["nodes"] += 1
            return super().construct_document(node)

    all_events = CountingLoader(text)
    try:
        while all_events.check_event():
            all_events.get_event()
    finally:
        all_events.dispose()
    assert counts == {"events": 3 + 2 + 9 * 13 + 3, "nodes": 0}   # the counter counts
    counts["events"] = 0
    monkeypatch.setattr(source_module, "_Loader", CountingLoader)
    error = error_of(text)
    assert (error.key, error.line) == ("a1[0]", 2)
    assert "aliases" in error.message
    assert counts == {"events": 8, "nodes": 0}


def test_duplicate_key_has_line_of_the_second():
    text = replace("    center: [0, 0, 406]\n", "    center: [0, 0, 406]\n    size: [1, 2]\n")
    expect(text, "planks[0].size", 7, 'duplicate key "size" (first on line 5)')


def test_unsupported_tag():
    text = replace("name: bench", "name: !!python/object:os.system bench")
    expect(text, "name", 2, 'unsupported YAML tag "!!python/object:os.system"')


def test_nested_too_deeply():
    expect("furncheck: 1\nx: " + "[" * 40 + "]" * 40 + "\n", "x" + "[0]" * 31, 2,
           "nested too deeply")


@pytest.mark.parametrize("depth", [40, 900, 30000])
def test_json_nested_too_deeply_has_key_and_line(depth):
    """A JSON design nested past MAX_NESTING is refused as a YAML one is, at the key path
    and line where the limit is passed (Python's json reads such a file, and the schema
    then named an unknown key with no line; nested 30,000 deep, past the YAML parser's
    own limit, it was 'nested too deeply' with neither)."""
    text = '{"furncheck": 1,\n "x":\n' + "[" * depth + "]" * depth + "}"
    expect(text, "x" + "[0]" * 31, 3, "nested too deeply", "json")


def test_quoted_number_is_text():
    text = replace("size: [400, 300]", 'size: ["400", 300]')
    expect(text, "planks[0].size[0]", 5, 'expected a number, got text "400"')


def test_boolean_is_not_a_number():
    text = replace("size: [400, 300]", "size: [yes, 300]")
    expect(text, "planks[0].size[0]", 5, "expected a number, got a boolean (yes)")


@pytest.mark.parametrize("value", [".nan", ".inf", "-.Inf"])
def test_non_finite_number(value):
    text = replace("center: [0, 0, 406]", f"center: [0, {value}, 406]")
    expect(text, "planks[0].center[1]", 6, f"not a finite number ({value})")


@pytest.mark.parametrize(("value", "shown"), [
    ("1e999", "1e999"),
    ("1" + "0" * 340, "1000000000...0000, 341 digits"),
    ("1" + "0" * 340 + "e5", "1000000000...00e5, 341 digits"),
])
def test_a_number_beyond_the_floats_is_out_of_range_and_shown_short(value, shown):
    """A number written in digits that no float holds (1e999, or 341 digits) is out of
    range, not 'not a finite number' (it is finite as written), and a long one is shown
    cut: the message used to carry all 341 digits."""
    text = replace("center: [0, 0, 406]", f"center: [0, {value}, 406]")
    error = expect(text, "planks[0].center[1]", 6, f"out of range ({shown}: beyond "
                                                    "+-1.8e308, the largest a number can be)")
    assert len(error.message) < 120
    # in a JSON design too (where it read 'not a finite number (Infinity)'), negative too
    sign = "-" if len(value) < 10 else ""
    document = json.dumps(base_dict()).replace('"mass": 10', f'"mass": {sign}{value}')
    error = error_of(document, "json", "bench.json")
    assert error.key == "loads[0].mass"
    assert error.message == (f"out of range ({sign}{shown}: beyond +-1.8e308, the largest a "
                             f"number can be)")


def test_plain_exponent_notation_is_a_number():
    """PyYAML 1.1 reads 1e3 and -2E-1 as text; a design file reads them as numbers."""
    text = replace("size: [400, 300]", "size: [4e2, 3.0E+2]")
    text = replace("center: [0, 0, 406]", "center: [-2E-1, 1_0, 406]", text)
    seat = parse_design(text, "bench.yaml", "yaml").planks[0]
    assert (seat.length, seat.width) == pytest.approx((0.4, 0.3))
    assert seat.center == pytest.approx((-0.0002, 0.01, 0.406))


def test_unquoted_ids_are_text():
    """``id: 1`` is the id "1"; ``id: no`` is "no", not the boolean of YAML 1.1."""
    text = replace("id: seat", "id: 1").replace("plank: seat", "plank: 1")
    text = replace("id: leg1", "id: no", text)
    assert [p.id for p in parse_design(text, "bench.yaml", "yaml").planks] == ["1", "no", "leg2"]


# --- schema: keys and types -------------------------------------------------------------------

def test_unknown_top_level_key():
    error = expect(BASE + "colour: red\n", "colour", 17, 'unknown key "colour"')
    assert "allowed keys: furncheck, name, units" in error.message


def test_unknown_nested_key_suggests_the_right_one():
    text = replace("    center: [0, 0, 406]", "    centre: [0, 0, 406]")
    expect(text, "planks[0].centre", 6, 'unknown key "centre" (did you mean "center"?)')


def test_missing_required_key():
    text = replace("    size: [400, 300]\n", "")
    expect(text, "planks[0].size", LINE["planks[0]"], 'missing required key "size"')


def test_missing_planks_and_version():
    """A missing top-level key is reported at the line where the design begins (its first
    key, after any comments)."""
    expect("furncheck: 1\nname: x\n", "planks", 1, 'missing required key "planks"')
    expect("# a shelf\n\nfurncheck: 1\nname: x\n", "planks", 3,
           'missing required key "planks"')
    expect('{"furncheck": 1, "name": "x"}', "planks", 1, 'missing required key "planks"',
           "json")
    text = replace("furncheck: 1\n", "")
    first = next(n for n, line in enumerate(text.splitlines(), 1)
                 if line.strip() and not line.startswith("#"))
    expect(text, "furncheck", first, 'missing required key "furncheck"')


@pytest.mark.parametrize("value, fragment", [("2", "unsupported format version 2"),
                                             ('"1"', 'expected a number, got text "1"'),
                                             ("true", "a boolean (true)")])
def test_bad_version(value, fragment):
    expect(replace("furncheck: 1", f"furncheck: {value}"), "furncheck", 1, fragment)


def test_empty_planks():
    expect("furncheck: 1\nplanks: []\n", "planks", 2, "at least one plank")


@pytest.mark.parametrize("old, new, key, line, fragment", [
    ("size: [400, 300]", "size: [400]", "planks[0].size", 5, "expected 2 numbers, got 1"),
    ("center: [0, 0, 406]", "center: [0, 406]", "planks[0].center", 6, "expected 3 numbers, got 2"),
    ("rotation: [0, 90, 0]", "rotation: 90", "planks[1].rotation", 10,
     "expected a list, got a number (90)"),
    ("size: [400, 300]", "size: {length: 400}", "planks[0].size", 5,
     "expected a list, got a mapping"),
    ("  - id: seat", "  - id: [seat]", "planks[0].id", 4, "expected text, got a list"),
    ("name: bench", "name:", "name", 2, "expected text, got nothing (null)"),
    ("  - id: seat", "  - id: seat one", "planks[0].id", 4, 'invalid plank id "seat one"'),
])
def test_wrong_shapes_and_types(old, new, key, line, fragment):
    expect(replace(old, new), key, line, fragment)


def test_duplicate_plank_id_names_both():
    expect(replace("id: leg1", "id: seat"), "planks[1].id", 7,
           'duplicate plank id "seat" (planks[0] and planks[1])')


def test_unknown_unit():
    expect("units: cm\n" + BASE, "units", 1, 'unknown unit "cm"; use mm or m')


# --- schema: ranges ---------------------------------------------------------------------------

@pytest.mark.parametrize("old, new, key, line, fragment", [
    ("size: [400, 300]", "size: [0, 300]", "planks[0].size[0]", 5, "must be positive, got 0 mm"),
    ("size: [400, 300]", "size: [400, -3]", "planks[0].size[1]", 5, "must be positive, got -3 mm"),
    ("size: [400, 300]", "size: [1e-9, 300]", "planks[0].size[0]", 5,
     "out of range: 0.000000001 mm; allowed 0.01 to 1,000,000 mm"),
    ("center: [0, 0, 406]", "center: [2e6, 0, 406]", "planks[0].center[0]", 6,
     "out of range: 2,000,000 mm; allowed -1,000,000 to 1,000,000 mm"),
    ("rotation: [0, 90, 0]", "rotation: [0, 1e5, 0]", "planks[1].rotation[1]", 10,
     "allowed -10,000 to 10,000 degrees"),
    ("center: [0, 0, 406]", "center: [0, 0, 406]\n    thickness: 0", "planks[0].thickness", 7,
     "must be positive"),
    ("mass: 10", "mass: -1", "loads[0].mass", 16,
     "out of range: -1 kg; allowed 0 to 10,000,000 kg"),
    ("mass: 10", "mass: 2e7", "loads[0].mass", 16, "out of range"),
])
def test_out_of_range_in_planks_and_loads(old, new, key, line, fragment):
    expect(replace(old, new), key, line, fragment)


@pytest.mark.parametrize("entry, key, fragment", [
    ("safety_factor: 0", "safety_factor", "must be positive, got 0"),
    ("safety_factor: 1e4", "safety_factor", "out of range: 10,000; allowed 0.001 to 1000"),
    ("tolerance: -0.5", "tolerance", "out of range: -0.5 mm; allowed 0 to 1,000,000 mm"),
    ("material: {density: 0}", "material.density", "must be positive, got 0 kg/m^3"),
    ("material: {density: 1e6}", "material.density", "allowed 0 to 100,000 kg/m^3"),
    ("material: {friction: -0.1}", "material.friction", "out of range: -0.1; allowed 0 to 10"),
    ("material: {nail_pull: 1e8}", "material.nail_pull", "allowed 0 to 10,000,000 N"),
    ("material: {nail_shear: -5}", "material.nail_shear", "must be positive"),
    ("material: {nail_spacing: 0.001}", "material.nail_spacing", "allowed 0.01 to 1,000,000 mm"),
    ("material: {thickness: .nan}", "material.thickness", "not a finite number (.nan)"),
    ("material: {glue: 1}", "material.glue", 'unknown key "glue"'),
    ("material: 12", "material", "expected a mapping, got a number (12)"),
])
def test_top_level_values(entry, key, fragment):
    expect(BASE + entry + "\n", key, 17, fragment)


def test_ranges_are_stated_in_metres_for_a_metre_file():
    text = "units: m\n" + BASE.replace("size: [400, 300]", "size: [0.4, 3000]", 1)
    expect(text, "planks[0].size[1]", 6, "out of range: 3000 m; allowed 0.00001 to 1000 m")


# --- joints -----------------------------------------------------------------------------------

JOINTS = BASE + "joints:\n  - [seat, leg1]\n  - {planks: [seat, leg2], nails: 10}\n"


def test_listed_joints():
    design = parse_design(JOINTS, "bench.yaml", "yaml")
    assert design.joints == (JointSpec(("seat", "leg1")), JointSpec(("seat", "leg2"), 10))
    assert design.lines["joints[1]"] == 19


def test_auto_joints_are_none():
    assert parse_design(BASE, "bench.yaml", "yaml").joints is None
    assert parse_design(BASE + "joints: auto\n", "bench.yaml", "yaml").joints is None


def test_whole_float_nail_count_is_fine():
    design = parse_design(JOINTS.replace("nails: 10", "nails: 10.0"), "b.yaml", "yaml")
    assert design.joints[1].nails == 10 and isinstance(design.joints[1].nails, int)


@pytest.mark.parametrize("old, new, key, line, fragment", [
    ("[seat, leg1]", "[seat, leg3]", "joints[0][1]", 18, 'unknown plank "leg3" (did you mean'),
    ("[seat, leg1]", "[leg1, leg1]", "joints[0]", 18, 'two different planks, got "leg1" twice'),
    ("[seat, leg1]", "[leg2, seat]", "joints[1]", 19,
     "joint seat/leg2 is listed twice (joints[0] and joints[1])"),
    ("[seat, leg1]", "[seat, leg1, leg2]", "joints[0]", 18, "expected 2 plank ids, got 3"),
    ("[seat, leg1]", "seat", "joints[0]", 18, "expected [plank, plank]"),
    ("nails: 10", "nails: 10.5", "joints[1].nails", 19, "whole number of nails"),
    ("nails: 10", "nails: 0", "joints[1].nails", 19, "whole number of nails"),
    ("planks: [seat, leg2]", "plank: [seat, leg2]", "joints[1].plank", 19,
     'unknown key "plank" (did you mean "planks"?)'),
    ("joints:\n  - [seat, leg1]\n  - {planks: [seat, leg2], nails: 10}", "joints: sometimes",
     "joints", 17, 'expected "auto" or a list of joints, got text "sometimes"'),
])
def test_bad_joints(old, new, key, line, fragment):
    expect(replace(old, new, JOINTS), key, line, fragment)


# --- loads and load cases ---------------------------------------------------------------------

def test_mass_load_pulls_down():
    """10 kg at the plank centre: force (0, 0, -10 x 9.81) N, point None, mass kept."""
    (case,) = parse_design(BASE, "bench.yaml", "yaml").load_cases
    assert case == LoadCase("default", (Load("seat", (0.0, 0.0, -10 * GRAVITY), None, 10.0),))


def test_force_load_at_a_point_on_the_plank():
    """The seat's top face is z = 412; a point there is on the plank, in metres inside."""
    text = replace("{plank: seat, mass: 10}",
                   "{plank: seat, force: [5, 0, -50], at: [100, 50, 412]}")
    (load,) = parse_design(text, "bench.yaml", "yaml").load_cases[0].loads
    assert load.force == (5.0, 0.0, -50.0) and load.mass is None
    assert load.point == pytest.approx((0.1, 0.05, 0.412))


def test_point_on_a_rotated_plank_within_tolerance():
    """leg1 stands with its thickness along x (faces at x = -200 and -188); a point 0.4 mm
    outside its face is within the 0.5 mm tolerance, 0.6 mm outside is not."""
    ok = replace("{plank: seat, mass: 10}", "{plank: leg1, mass: 1, at: [-187.6, 0, 300]}")
    assert parse_design(ok, "bench.yaml", "yaml").load_cases[0].loads[0].point[0] == \
        pytest.approx(-0.1876)
    bad = replace("{plank: seat, mass: 10}", "{plank: leg1, mass: 1, at: [-187.4, 0, 300]}")
    error = expect(bad, "loads[0].at", 16, 'point (-187.4, 0, 300) is not on plank "leg1"')
    assert "0.6 mm beyond its thickness (tolerance 0.5 mm)" in error.message


@pytest.mark.parametrize("new, key, fragment", [
    ("{plank: table, mass: 10}", "loads[0].plank", 'unknown plank "table"'),
    ("{plank: seat, mass: 10, force: [0, 0, 1]}", "loads[0]", "not both"),
    ("{plank: seat}", "loads[0]", "needs a mass (kg) or a force"),
    ("{mass: 10}", "loads[0].plank", 'missing required key "plank"'),
    ("{plank: seat, force: [0, 1]}", "loads[0].force", "expected 3 numbers, got 2"),
    ("{plank: seat, force: [0, 0, -2e9]}", "loads[0].force[2]",
     "allowed -1,000,000,000 to 1,000,000,000 N"),
    ("{plank: seat, mass: 10, at: [0, 0, 900]}", "loads[0].at", 'is not on plank "seat"'),
    ("{plank: seat, mass: '10'}", "loads[0].mass", 'expected a number, got text "10"'),
])
def test_bad_loads(new, key, fragment):
    expect(replace("{plank: seat, mass: 10}", new), key, 16, fragment)


def test_load_case_order_default_first_then_file_order():
    text = BASE + "load_cases:\n  sit: [{plank: seat, mass: 80}]\n  lean: []\n"
    design = parse_design(text, "bench.yaml", "yaml")
    assert [c.name for c in design.load_cases] == ["default", "sit", "lean"]
    assert design.load_cases[1].loads[0].force[2] == pytest.approx(-80 * GRAVITY)
    assert design.lines["load_cases.sit"] == 18 and design.lines["load_cases.sit[0]"] == 18


def test_only_load_cases_means_no_default_case():
    text = BASE.replace("loads:\n  - {plank: seat, mass: 10}\n",
                        "load_cases:\n  b: []\n  a: [{plank: leg1, mass: 1}]\n")
    assert [c.name for c in parse_design(text, "bench.yaml", "yaml").load_cases] == ["b", "a"]


def test_no_loads_is_one_self_weight_case():
    text = BASE.replace("loads:\n  - {plank: seat, mass: 10}\n", "")
    assert parse_design(text, "bench.yaml", "yaml").load_cases == (LoadCase("default"),)


def test_case_named_default_next_to_loads():
    expect(BASE + "load_cases:\n  default: []\n", "load_cases.default", 18,
           'case "default" is already given by "loads"')


def test_bad_case_name_and_case_value():
    expect(BASE + "load_cases:\n  sit down: []\n", 'load_cases["sit down"]', 18,
           'invalid load case name "sit down"')
    expect(BASE + "load_cases:\n  sit: 80\n", "load_cases.sit", 18, "expected a list")


# --- JSON -------------------------------------------------------------------------------------

def json_text(design: dict) -> str:
    return json.dumps(design, indent=2)


def test_json_design_equals_yaml_design():
    from_yaml = parse_design(BASE, "bench.yaml", "yaml")
    from_json = parse_design(json_text(base_dict()), "bench.json", "json")
    assert replace_fields(from_json, source="bench.yaml") == from_yaml
    assert from_json.lines["planks[0]"] == 5        # its "{", looked up from the JSON text


def test_json_duplicate_key_has_line():
    text = '{\n  "furncheck": 1,\n  "planks": [],\n  "planks": []\n}'
    expect(text, "planks", 4, 'duplicate key "planks" (first on line 3)', "json")


def test_json_nan_names_key_and_line():
    design = base_dict()
    design["planks"][1]["center"][2] = float("nan")
    text = json_text(design)
    line = next(i for i, row in enumerate(text.splitlines(), 1) if "NaN" in row)
    expect(text, "planks[1].center[2]", line, "not a finite number (NaN)", "json")


def test_json_key_path_error_finds_its_line():
    design = base_dict()
    design["planks"][2]["size"] = "400 x 300"
    text = json_text(design)
    line = next(i for i, row in enumerate(text.splitlines(), 1) if "400 x 300" in row)
    expect(text, "planks[2].size", line, 'expected a list, got text "400 x 300"', "json")


def test_json_booleans_and_quoted_numbers_are_not_numbers():
    design = base_dict()
    design["safety_factor"] = True
    assert "a boolean (true)" in error_of(json_text(design), "json").message
    design["safety_factor"] = "2"
    assert 'got text "2"' in error_of(json_text(design), "json").message


def test_unknown_format_name():
    with pytest.raises(DesignError, match="unknown format"):
        parse_design(BASE, "bench.toml", "toml")


# --- good input -------------------------------------------------------------------------------

def test_defaults():
    design = parse_design("furncheck: 1\nplanks: [{id: p, size: [400, 300], center: [0, 0, 6]}]\n",
                          "designs/my-shelf.yaml", "yaml")
    assert design.name == "my-shelf"
    assert (design.units, design.unit_scale) == ("mm", 0.001)
    assert design.source == "designs/my-shelf.yaml"
    assert design.material == Material()
    assert (design.tolerance, design.safety_factor, design.joints) == (0.0005, 1.0, None)
    assert design.planks == (Plank("p", 0.4, 0.3, 0.012, (0.0, 0.0, 0.006)),)
    assert design.load_cases == (LoadCase("default"),)


def test_material_and_thickness_override():
    text = BASE + ("material: {thickness: 18, density: 600, nail_spacing: 25, nail_pull: 500,"
                   " nail_shear: 150, friction: 0}\nsafety_factor: 2\ntolerance: 1\n")
    text = replace("    center: [0, 0, 406]", "    center: [0, 0, 406]\n    thickness: 9", text)
    design = parse_design(text, "bench.yaml", "yaml")
    m = design.material
    assert (m.thickness, m.density, m.nail_spacing) == pytest.approx((0.018, 600, 0.025))
    assert (m.nail_pull, m.nail_shear, m.friction) == (500, 150, 0)
    assert (design.safety_factor, design.tolerance) == pytest.approx((2, 0.001))
    assert [p.thickness for p in design.planks] == pytest.approx([0.009, 0.018, 0.018])


def numbers(design: Design) -> np.ndarray:
    """Every number of the design (SI), flattened, for comparisons up to round-off."""
    m = design.material
    values = [m.thickness, m.density, m.nail_spacing, m.nail_pull, m.nail_shear, m.friction,
              design.tolerance, design.safety_factor]
    for p in design.planks:
        values += [p.length, p.width, p.thickness, *p.center, *p.rotation]
    for case in design.load_cases:
        for load in case.loads:
            values += [*load.force, *(load.point or ())]
    return np.array(values)


def test_metres_and_millimetres_give_the_same_design():
    """The same bench in m: same SI numbers; the default tolerance is 0.5 mm in both."""
    mm = parse_design(BASE + "tolerance: 0.5\n", "bench.yaml", "yaml")
    metre_doc = base_dict()
    metre_doc["units"] = "m"
    for plank in metre_doc["planks"]:
        plank["size"] = [v / 1000 for v in plank["size"]]
        plank["center"] = [v / 1000 for v in plank["center"]]
    m = parse_design(yaml.safe_dump(metre_doc), "bench.yaml", "yaml")
    assert (m.units, m.unit_scale, m.tolerance) == ("m", 1.0, 0.0005)
    assert [p.id for p in m.planks] == [p.id for p in mm.planks]
    assert m.load_cases == mm.load_cases
    np.testing.assert_allclose(numbers(m), numbers(mm), rtol=1e-12, atol=1e-15)


def test_lines_are_recorded_for_keys_and_items():
    design = parse_design(BASE, "bench.yaml", "yaml")
    for key, line in LINE.items():
        assert design.lines[key] == line, key
    assert design.line_of("planks[1].size[1]") == 8


def test_error_line_fallback_to_parent_in_json():
    design = base_dict()
    del design["planks"][1]["center"]
    text = json_text(design)
    line = next(i for i, row in enumerate(text.splitlines(), 1) if '"leg1"' in row) - 1
    expect(text, "planks[1].center", line, 'missing required key "center"', "json")


# --- writing ----------------------------------------------------------------------------------

FULL = (BASE.replace("name: bench\n", "name: bench\nunits: mm\n")
        + "material: {thickness: 18, friction: 0.3}\n"
        + "joints:\n  - [seat, leg1]\n  - {planks: [seat, leg2], nails: 7}\n"
        + "load_cases:\n  push: [{plank: seat, force: [30, 0, 0], at: [200, 0, 406]}]\n"
        + "  sit: [{plank: seat, mass: 80, at: [10.5, -20, 415]}]\n"
        + "safety_factor: 1.5\ntolerance: 0.2\n")


def assert_same_design(a: Design, b: Design):
    assert (a.name, a.units, a.unit_scale, a.joints) == (b.name, b.units, b.unit_scale, b.joints)
    assert [p.id for p in a.planks] == [p.id for p in b.planks]
    assert [(c.name, [(ld.plank, ld.mass is None, ld.point is None) for ld in c.loads])
            for c in a.load_cases] == \
        [(c.name, [(ld.plank, ld.mass is None, ld.point is None) for ld in c.loads])
         for c in b.load_cases]
    np.testing.assert_allclose(numbers(a), numbers(b), rtol=1e-12, atol=1e-15)


def test_document_key_order_and_contents():
    doc = design_to_document(parse_design(FULL, "bench.yaml", "yaml"))
    assert list(doc) == ["furncheck", "name", "units", "model", "material", "planks", "joints",
                         "loads", "load_cases", "safety_factor", "tolerance"]
    assert doc["loads"] == [{"plank": "seat", "mass": 10.0}]
    assert doc["material"]["thickness"] == 18.0 and doc["tolerance"] == 0.2
    assert doc["joints"] == [["seat", "leg1"], {"planks": ["seat", "leg2"], "nails": 7}]
    assert doc["load_cases"]["sit"] == [{"plank": "seat", "mass": 80.0, "at": [10.5, -20.0, 415.0]}]
    assert "thickness" not in doc["planks"][0]
    assert json.loads(json.dumps(doc)) == doc                 # plain types only


@pytest.mark.parametrize("text", [BASE, FULL, "units: m\n" + BASE.replace("406", "0.406")])
def test_round_trip_through_yaml_dump(text):
    design = parse_design(text, "bench.yaml", "yaml")
    again = parse_design(yaml.safe_dump(design_to_document(design), sort_keys=False),
                         "bench.yaml", "yaml")
    assert_same_design(design, again)


@pytest.mark.parametrize("suffix", [".yaml", ".yml", ".json"])
def test_write_design_round_trip(tmp_path, suffix):
    design = parse_design(FULL.replace("id: leg2", "id: leg2\n    thickness: 9"), "b.yaml", "yaml")
    path = str(tmp_path / f"bench{suffix}")
    write_design(design, path)
    again = load_design(path)
    assert_same_design(design, again)
    assert again.planks[2].thickness == pytest.approx(0.009)


def test_auto_joints_are_not_written():
    doc = design_to_document(parse_design(BASE, "bench.yaml", "yaml"))
    assert "joints" not in doc


def test_only_named_cases_round_trip():
    text = BASE.replace("loads:\n  - {plank: seat, mass: 10}\n",
                        "load_cases:\n  b: []\n  default: [{plank: leg1, mass: 1}]\n")
    design = parse_design(text, "bench.yaml", "yaml")
    again = parse_design(yaml.safe_dump(design_to_document(design)), "bench.yaml", "yaml")
    assert [c.name for c in again.load_cases] == ["b", "default"]


def test_write_unknown_extension(tmp_path):
    design = parse_design(BASE, "bench.yaml", "yaml")
    with pytest.raises(DesignError, match="unknown file type"):
        write_design(design, str(tmp_path / "bench.toml"))
    assert not os.path.exists(tmp_path / "bench.toml")


def test_in_memory_design_writes_and_reads_back(tmp_path):
    design = Design("pair", (Plank("a", 0.4, 0.3, 0.012, (0.0, 0.0, 0.006)),),
                    (LoadCase("default", (Load.of_mass("a", 2.0), Load("a", (1.0, 0.0, 0.0),
                                                                      (0.1, 0.0, 0.012)))),))
    path = str(tmp_path / "pair.yaml")
    write_design(design, path)
    again = load_design(path)
    assert_same_design(design, again)
    assert math.isclose(again.load_cases[0].loads[0].force[2], -2.0 * GRAVITY)


def test_the_readme_design_example_is_a_design():
    """The README's design-file example (every key of the format, walls and anchors
    included) reads without an error: it is checked, not refused."""
    from pathlib import Path

    from furncheck.check import check_design
    from furncheck.design import parse_design

    readme = (Path(__file__).resolve().parents[1] / "README.md").read_text(encoding="utf-8")
    section = readme[readme.index("## Design files"):]
    example = section.split("```yaml", 1)[1].split("```", 1)[0]
    design = parse_design(example, "README.md", "yaml")
    assert [c.name for c in design.load_cases] == ["default", "lean", "books-and-push"]
    assert len(design.walls) == 1 and len(design.anchors) == 1
    report = check_design(design)
    assert report.error is None and not any(v.kind == "penetration" for v in report.violations)


def test_written_files_drop_the_round_off_of_zero():
    """A centre at x = 1.3e-15 mm beside z = 456 mm (the round-off of a suggestion's
    geometry) is written 0, a rotation of 1e-14 degrees beside 90 too; each component
    keeps 12 significant digits of its vector's largest, and the design reads back the
    same up to that round-off."""
    from dataclasses import replace

    from furncheck.design.load import parse_design
    from furncheck.design.write import design_text

    design = parse_design("furncheck: 1\nplanks:\n- {id: a, size: [400, 300], "
                          "center: [0, 0, 6]}\n", "a.yaml", "yaml")
    plank = replace(design.planks[0], center=(1.30104260698e-18, 0.25e-3, 0.456),
                    rotation=(90.0, 1e-14, -2.5e-13))
    text = design_text(replace(design, planks=(plank,)), "yaml")
    assert "center: [0.0, 0.25, 456.0]" in text and "rotation: [90.0, 0.0, 0.0]" in text
    assert "e-" not in text


def test_with_model_refuses_an_unknown_model():
    """The library's ``with_model`` takes the two models and None (as the design is); any
    other name is refused there rather than carried into a statics that reads it as one of
    the two."""
    from furncheck.design.load import parse_design
    from furncheck.design.model import with_model

    design = parse_design("furncheck: 1\nplanks:\n- {id: a, size: [400, 300], "
                          "center: [0, 0, 6]}\n", "a.yaml", "yaml")
    assert with_model(design, None) is design
    assert with_model(design, "rigid").model == "rigid"
    assert with_model(design, "elastic") is design
    with pytest.raises(ValueError, match="unknown statics model 'steel'"):
        with_model(design, "steel")


def test_a_json_designs_violations_carry_their_lines(tmp_path):
    """A JSON design's violations get the lines of their key paths, as a YAML design's do
    (looked up only when a line is asked for: ``json_source.JsonLines``), so its GitHub
    annotations and SARIF regions point into the file; the design pickles with them."""
    import json
    import pickle

    from furncheck.check import check_file

    document = {"furncheck": 1, "planks": [
        {"id": "base", "size": [400, 400], "center": [0, 0, 6]},
        {"id": "post", "size": [800, 400], "center": [-150, 0, 412],
         "rotation": [0, -90, 0]},
        {"id": "shelf", "size": [300, 300], "center": [6, 0, 600]}],
        "loads": [{"plank": "shelf", "mass": 40, "at": [100, 0, 606]}]}
    path = tmp_path / "shelf.json"
    path.write_text(json.dumps(document, indent=2))
    report = check_file(str(path), model="rigid")
    assert report.violations
    lines = path.read_text().splitlines()
    for violation in report.violations:
        assert violation.line is not None
        plank = violation.where.split("/")[-1].split(",")[0]
        assert f'"id": "{plank}"' in "\n".join(lines[violation.line - 2:violation.line + 1])
    design = load_design(str(path))
    assert pickle.loads(pickle.dumps(design)).line_of("planks[2]") == \
        design.line_of("planks[2]") is not None


# --- every problem of a file, one line each -----------------------------------------------------

THREE_PROBLEMS = """\
furncheck: 1
colour: red
planks:
  - {id: board, size: [400, 300, 12], center: [0, 0, 6]}
loads:
  - {plank: nope, mass: 1}
"""


def test_every_problem_of_a_file_is_reported_one_line_each(tmp_path):
    """Contract section 4, 'one line per problem': an unknown top-level key (line 2), a
    plank's size of three numbers (line 4) and a load on a plank that does not exist
    (line 6) are all reported, in the file's order, each with its line and key path;
    the text report gives a line each, the JSON entry its first as ``error`` and all as
    ``errors``, GitHub an annotation each; exit 2."""
    with pytest.raises(DesignError) as info:
        parse_design(THREE_PROBLEMS, "three.yaml", "yaml")
    problems = (info.value, *info.value.more)
    assert [(p.line, p.key) for p in problems] == [(2, "colour"), (4, "planks[0].size"),
                                                     (6, "loads[0].plank")]
    assert info.value.lines() == [p.one_line() for p in problems]
    assert str(info.value) == problems[0].one_line()
    path = tmp_path / "three.yaml"
    path.write_text(THREE_PROBLEMS)
    text = CliRunner().invoke(main, ["validate", str(path)])
    assert text.exit_code == 2
    assert [line.split(": error: ")[1][:7] for line in text.output.splitlines()[:3]] == \
        ["line 2:", "line 4:", "line 6:"]
    document = json.loads(CliRunner().invoke(main, ["validate", str(path), "--format",
                                                    "json"]).output)
    (entry,) = document["reports"]
    assert entry["error"] == entry["errors"][0] and len(entry["errors"]) == 3
    github = CliRunner().invoke(main, ["validate", str(path), "--format", "github"]).output
    assert [line.split(",")[1] for line in github.splitlines() if line.startswith("::error")] \
        == ["line=2", "line=4", "line=6"]


MATERIAL_PROBLEMS = """\
furncheck: 1
material: {density: abc, nail_pull: 0, friction: -1}
planks:
  - {id: board, size: [400, 300], center: [0, 0, 6], material: {colour: red, density: x,
                                                               elastic_modulus: -3}}
"""


def test_every_problem_of_a_material_is_reported_one_line_each():
    """A material written with several mistakes is told of all of them, in the order they
    are written (README: "A file's problems are all reported"): the top-level material's
    density (text), nail_pull (0) and friction (-1), and a plank's own material's
    unknown key, density and modulus; each with its key path and line.  (The first of
    them alone was reported before.)"""
    with pytest.raises(DesignError) as info:
        parse_design(MATERIAL_PROBLEMS, "materials.yaml", "yaml")
    problems = (info.value, *info.value.more)
    assert [(p.line, p.key) for p in problems] == [
        (2, "material.density"), (2, "material.nail_pull"), (2, "material.friction"),
        (4, "planks[0].material.colour"), (4, "planks[0].material.density"),
        (5, "planks[0].material.elastic_modulus")]
    assert "must be positive, got 0 N" in problems[1].message
    assert 'unknown key "colour"' in problems[3].message


@pytest.mark.parametrize(("plank", "why"), [
    ("{id: seat one, size: [400, 300], center: [0, 0, 6]}", 'invalid plank id "seat one"'),
    ("{id: seat, size: [400], center: [0, 0, 6]}", "expected 2 numbers, got 1"),
])
def test_what_names_a_plank_that_could_not_be_read_is_left_unchecked(plank, why):
    """A plank whose entry fails is one problem: the load on it is not reported as a load
    on an unknown plank too (a plank whose id could not be read may be any name)."""
    text = f"furncheck: 1\nplanks:\n  - {plank}\nloads:\n  - {{plank: seat, mass: 5}}\n"
    with pytest.raises(DesignError) as info:
        parse_design(text, "one.yaml", "yaml")
    assert why in info.value.message and info.value.more == ()


VALUES_ON_UNREAD_PLANKS = """\
furncheck: 1
planks:
  - {id: a, size: [400, 300], centre: [0, 0, 6]}
  - {id: b, size: [400, 300], center: [0, 0, 300]}
walls:
  - {point: [0, 150, 0], normal: [0, -1, 0]}
anchors:
  - {plank: a, at: [0, 150, 6], wall: 3, capacity: -1}
  - {plank: q, at: [0, 150, 6], wall: 0, capacity: abc}
  - {plank: a, at: [0, 150, 6], wall: 0, capacity: 100}
loads:
  - {plank: a, mass: 100kg}
  - {plank: z, force: [1, 2]}
  - {plank: a, mass: 5, at: [9, 9, 9]}
"""


def test_a_load_or_anchor_on_an_unread_plank_still_has_its_own_values_checked():
    """Plank a's line has a problem ('centre'), so where a load or anchor on it sits is
    left unchecked (its point, on a plank not read as the file means it), but its own
    values are not: 'mass: 100kg' on a, an anchor's wall 3 of one and capacity -1, are
    reported now, not once 'centre' is fixed; an unknown plank and a bad value in one
    entry are both reported, in the order written; a load and an anchor on a with good
    values are left unchecked, as before."""
    with pytest.raises(DesignError) as info:
        parse_design(VALUES_ON_UNREAD_PLANKS, "values.yaml", "yaml")
    assert [(p.line, p.key) for p in (info.value, *info.value.more)] == [
        (3, "planks[0].centre"), (8, "anchors[0].wall"), (8, "anchors[0].capacity"),
        (9, "anchors[1].plank"), (9, "anchors[1].capacity"), (12, "loads[0].mass"),
        (13, "loads[1].plank"), (13, "loads[1].force")]


def test_a_misspelt_required_key_is_one_problem():
    """'centre' for 'center': the unknown key (with its 'did you mean') is the problem; the
    missing 'center' it stands for is not reported again."""
    with pytest.raises(DesignError) as info:
        parse_design("furncheck: 1\nplanks:\n  - {id: a, size: [400, 300], "
                     "centre: [0, 0, 6]}\n", "typo.yaml", "yaml")
    assert 'did you mean "center"' in info.value.message and info.value.more == ()


def test_the_problems_reported_are_capped():
    """Thirty planks with a bad size each: the reading stops at MAX_INPUT_PROBLEMS (20),
    reported, and a last line says so, not thirty."""
    planks = "".join(f"  - {{id: p{k}, size: [1], center: [0, 0, {k}]}}\n" for k in range(30))
    with pytest.raises(DesignError) as info:
        parse_design(f"furncheck: 1\nplanks:\n{planks}", "many.yaml", "yaml")
    lines = info.value.lines()
    assert len(lines) == tol.MAX_INPUT_PROBLEMS + 1 == 21
    assert lines[-1] == "many.yaml: more problems may follow: the reading stopped after 20"
    assert lines[19].startswith("many.yaml:22: planks[19].size")


SEVERAL_SECTIONS = """\
furncheck: 1
planks:
  - {id: seat, size: [1200, 300], center: [0, 0, 444]}
  - {id: leg_l, size: [438, -300], center: [-520, 0, 219], rotation: [0, -90, 0]}
  - {id: leg_r, size: [438, 300], center: [520, 0, 219], rotation: [0, -90, 0]}
joints:
  - [seat, leg_l]
  - [seat, legr]
  - [seat, seat]
loads:
  - {plank: leg_l, mass: 5}
  - {plank: seat, mass: -1}
load_cases:
  sit: [{plank: sate, mass: 1}]
colour: red
"""


def test_each_item_of_a_section_is_checked_and_problems_come_in_line_order():
    """Problems in several sections, each joint and load on its own, sorted by line (the
    unknown top-level key on the last line comes last though it is read first); the joint
    and the load on leg_l, whose entry failed, are left unchecked, not reported as being
    on an unknown plank."""
    with pytest.raises(DesignError) as info:
        parse_design(SEVERAL_SECTIONS, "several.yaml", "yaml")
    assert [(p.line, p.key) for p in (info.value, *info.value.more)] == [
        (4, "planks[1].size[1]"), (8, "joints[1][1]"), (9, "joints[2]"),
        (12, "loads[1].mass"), (14, "load_cases.sit[0].plank"), (15, "colour")]


@pytest.mark.parametrize("wrong", ["material: {thickness: 18, colour: red}",
                                   "material: {thickness: 18, density: abc}",
                                   "tolerence: 2", "tolerance: 2 mm"])
def test_a_default_standing_for_a_value_leaves_what_uses_it_unchecked(wrong):
    """An 18 mm seat whose load and anchor sit on its top face (z = 458): where the file's
    material or tolerance could not be read, the defaults (12 mm, 0.5 mm) would put them
    off the plank; they are left unchecked, the one problem reported alone."""
    text = f"""\
furncheck: 1
{wrong}
planks:
  - {{id: seat, size: [1200, 300], center: [0, 0, 449], thickness: 18}}
  - {{id: leg_l, size: [440, 300], center: [-520, 0, 220], rotation: [0, -90, 0]}}
loads:
  - {{plank: seat, mass: 80, at: [0, 0, 458]}}
walls:
  - {{point: [0, 150, 0], normal: [0, -1, 0]}}
anchors:
  - {{plank: seat, at: [0, 150, 458], wall: 0, capacity: 100}}
""".replace(", thickness: 18}", "}") if "material" in wrong else f"""\
furncheck: 1
{wrong}
planks:
  - {{id: seat, size: [1200, 300], center: [0, 0, 450]}}
loads:
  - {{plank: seat, mass: 80, at: [0, 0, 457.5]}}
"""
    with pytest.raises(DesignError) as info:
        parse_design(text, "default.yaml", "yaml")
    assert info.value.line == 2 and info.value.more == ()


def test_a_path_with_a_newline_keeps_its_error_whole(tmp_path):
    """A file's problems are kept as a list, not joined into one text: a file whose name
    holds a line break gets its whole error line in JSON."""
    path = tmp_path / "new\nline.yaml"
    path.write_text("furncheck: 1\nplanks: []\n")
    result = CliRunner().invoke(main, ["validate", str(path), "--format", "json"])
    (entry,) = json.loads(result.output)["reports"]
    assert entry["error"] == f"{path}:2: planks: a design needs at least one plank"
    assert "errors" not in entry
