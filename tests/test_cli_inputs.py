"""The real ``furncheck validate`` on bad input of every class: exit code 2, one line naming
the file, the line and the key path, no traceback; the rest of the batch is still checked.

(tests/test_loader.py checks the loader's DesignError for each class in depth; this file
checks what a user sees at the command line.)
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from furncheck.cli.main import main

CATALOG = Path(__file__).resolve().parents[1] / "designs"

GOOD = """\
furncheck: 1
planks:
  - id: base
    size: [400, 300]
    center: [0, 0, 6]
  - id: post
    size: [700, 300]
    center: [0, 0, 362]
    rotation: [0, 90, 0]
loads:
  - {plank: base, mass: 2}
"""

# name -> (file suffix, content, key path or fragment expected in the line, line or None)
BAD_INPUTS = {
    "unknown key": (".yaml", GOOD.replace("    center: [0, 0, 6]", "    centre: [0, 0, 6]"),
                    "planks[0].centre", 5),
    "missing key": (".yaml", GOOD.replace("    size: [400, 300]\n", ""), "planks[0]", 3),
    "wrong type": (".yaml", GOOD.replace("size: [400, 300]", "size: {a: 1}"),
                   "planks[0].size", 4),
    "text for a number": (".yaml", GOOD.replace("[400, 300]", '["400", 300]'),
                          "planks[0].size[0]", 4),
    "NaN": (".yaml", GOOD.replace("[400, 300]", "[.nan, 300]"), "planks[0].size[0]", 4),
    "inf": (".yaml", GOOD.replace("[400, 300]", "[400, .inf]"), "planks[0].size[1]", 4),
    "zero size": (".yaml", GOOD.replace("[400, 300]", "[0, 300]"), "planks[0].size[0]", 4),
    "negative size": (".yaml", GOOD.replace("[400, 300]", "[400, -3]"), "planks[0].size[1]", 4),
    "wrong list length": (".yaml", GOOD.replace("[400, 300]", "[400, 300, 12]"),
                          "planks[0].size", 4),
    "duplicate id": (".yaml", GOOD.replace("id: post", "id: base"), "planks[1].id", 6),
    "unknown plank in load": (".yaml", GOOD.replace("{plank: base, mass: 2}",
                                                    "{plank: shelf, mass: 2}"),
                              "loads[0].plank", 11),
    "load off its plank": (".yaml", GOOD.replace("{plank: base, mass: 2}",
                                                 "{plank: base, mass: 2, at: [0, 0, 90]}"),
                           "loads[0].at", 11),
    "mass and force": (".yaml", GOOD.replace("{plank: base, mass: 2}",
                                             "{plank: base, mass: 2, force: [0, 0, 1]}"),
                       "loads[0]", 11),
    "bad units": (".yaml", GOOD.replace("furncheck: 1\n", "furncheck: 1\nunits: inch\n"),
                  "units", 2),
    "bad material": (".yaml", GOOD.replace("furncheck: 1\n",
                                           "furncheck: 1\nmaterial: {density: -5}\n"),
                     "material.density", 2),
    "syntax error": (".yaml", GOOD.replace("size: [400, 300]", "size: [400, 300"), "", None),
    "json syntax error": (".json", '{"furncheck": 1,\n "planks": [\n}', "JSON", 3),
    "empty file": (".yaml", "", "empty", None),
    "top-level list": (".yaml", "- furncheck: 1\n", "mapping", None),
    "alias bomb": (".yaml", "a: &a [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]\n"
                            "b: &b [*a, *a, *a, *a, *a, *a, *a, *a, *a, *a]\n"
                            "c: &c [*b, *b, *b, *b, *b, *b, *b, *b, *b, *b]\n"
                            "d: [*c, *c, *c, *c, *c, *c, *c, *c, *c, *c]\n", "alias", 2),
}


def run(*args: str):
    return CliRunner().invoke(main, ["validate", *args])


@pytest.mark.parametrize("name", sorted(BAD_INPUTS))
def test_bad_input_is_one_clear_line_and_exit_2(tmp_path: Path, name: str) -> None:
    suffix, content, fragment, line = BAD_INPUTS[name]
    path = tmp_path / f"design{suffix}"
    path.write_text(content, encoding="utf-8")
    result = run(str(path))
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output
    first = result.output.splitlines()[0]
    assert str(path) in first and fragment in first, first
    if line is not None:
        assert f"line {line}" in first or f":{line}:" in first, first


@pytest.mark.parametrize("args, fragment", [
    (("validate", "--bogus", "designs/stool.yaml"),
     "furncheck validate: no such option '--bogus'"),
    (("suggest",), "furncheck suggest: missing argument 'DESIGN'"),
    (("frob",), "furncheck: no such command 'frob'"),
    (("validate", "--jobs", "x", "designs"), "furncheck validate: invalid value for '-j'"),
    (("range", "designs/stool.yaml", "--model", "foo"),
     "furncheck range: invalid value for '--model'"),
    (("suggest", "designs/stool.yaml", "--max-dofs", "9"),
     "furncheck suggest: invalid value for '--max-dofs'"),
])
def test_a_usage_error_is_one_line_and_exit_2(args, fragment) -> None:
    """A wrong command line (unknown option or command, missing argument, bad value) is
    one line naming the command, click's message and where help is; exit 2."""
    result = CliRunner().invoke(main, list(args))
    assert result.exit_code == 2
    assert len(result.output.splitlines()) == 1, result.output
    assert result.output.startswith(fragment), result.output
    command = fragment.split(":")[0]
    assert result.output.rstrip().endswith(f"(see '{command} --help')")


def test_an_internal_error_is_one_line_and_exit_2(monkeypatch) -> None:
    """A bug (any exception the command does not expect) is one line naming it and exit 2
    (CI reads exit 1 as 'invalid design'), not a traceback; FURNCHECK_DEBUG=1 shows the
    traceback before that line, for a developer, and the exit code stays 2 (letting the
    exception through exited 1: a crash a CI step took for invalid designs)."""
    import furncheck.suggest

    def broken(*_args, **_kwargs):
        raise ValueError("max() arg is an\nempty sequence")

    monkeypatch.setattr(furncheck.suggest, "suggest_design", broken)
    result = CliRunner().invoke(main, ["suggest", "designs/stool.yaml"])
    assert result.exit_code == 2 and result.output == (
        "furncheck: internal error: ValueError: max() arg is an empty sequence (a bug: "
        "please report it with the design; FURNCHECK_DEBUG=1 shows the traceback)\n")
    monkeypatch.setenv("FURNCHECK_DEBUG", "1")
    debug = CliRunner().invoke(main, ["suggest", "designs/stool.yaml"])
    assert debug.exit_code == 2
    assert debug.output.startswith("Traceback (most recent call last):")
    assert 'raise ValueError("max() arg is an' in debug.output
    assert debug.output.endswith(result.output)


def test_an_os_error_is_the_machines_one_line_not_a_bug(monkeypatch) -> None:
    """An OSError on the way (a full disk, a dead pipe) is the machine's, not a bug: its
    own words on one line, exit 2."""
    import furncheck.suggest

    def full(*_args, **_kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(furncheck.suggest, "suggest_design", full)
    result = CliRunner().invoke(main, ["suggest", "designs/stool.yaml"])
    assert result.exit_code == 2 and result.output == "furncheck: No space left on device\n"


def test_a_bare_command_still_shows_its_help() -> None:
    result = CliRunner().invoke(main, [])
    assert "Usage: furncheck" in result.output and "validate" in result.output


def test_binary_and_missing_files(tmp_path: Path) -> None:
    binary = tmp_path / "blob.yaml"
    binary.write_bytes(b"\x00\x01\x02furncheck\xff")
    result = run(str(binary), str(tmp_path / "missing.yaml"))
    assert result.exit_code == 2
    assert "not a text file" in result.output and "no such file" in result.output


def test_a_bad_file_does_not_stop_the_batch(tmp_path: Path) -> None:
    """Errors keep their place; every good file still gets its full report."""
    (tmp_path / "a-bad.yaml").write_text("furncheck: 1\nplanks: []\n", encoding="utf-8")
    (tmp_path / "b-good.yaml").write_text(GOOD, encoding="utf-8")
    result = run(str(tmp_path), "--format", "json")
    assert result.exit_code == 2
    reports = json.loads(result.output)["reports"]
    assert [Path(r["design"]).name for r in reports] == ["a-bad.yaml", "b-good.yaml"]
    assert "error" in reports[0] and "valid" not in reports[0]
    assert reports[1]["valid"] is True and reports[1]["cases"][0]["joints"]


def test_json_report_is_byte_identical_on_rerun() -> None:
    designs = str(Path(__file__).resolve().parents[1] / "designs")
    first, second = run(designs, "--format", "json"), run(designs, "--format", "json")
    assert first.exit_code == second.exit_code == 1
    assert first.output == second.output


@pytest.mark.parametrize("command", ["suggest", "range"])
def test_a_bad_design_in_json_is_a_json_error_document(tmp_path, command) -> None:
    """``suggest`` and ``range`` with ``--format json`` on a file that cannot be read, or
    with a DOF that does not exist: exit 2, the one line on stderr, and on stdout (or
    ``-o``) a JSON document of its own, ``{"design", "error"}`` (the error as ``validate
    --format json`` reports it), so that a tool reading the report finds the reason there
    too."""
    bad = tmp_path / "bad.yaml"
    bad.write_text("furncheck: 1\nplanks: 3\n")
    result = CliRunner().invoke(main, [command, str(bad), "--format", "json"])
    assert result.exit_code == 2
    document = json.loads(result.stdout)
    assert document == {"design": str(bad),
                        "error": f"{bad}:2: planks: expected a list, got a number (3)"}
    assert result.stderr == f"furncheck: {document['error']}\n"
    report = tmp_path / "report.json"
    result = CliRunner().invoke(main, [command, str(bad), "--format", "json", "-o",
                                       str(report)])
    assert result.exit_code == 2 and json.loads(report.read_text()) == document
    result = CliRunner().invoke(main, [command, "designs/stool.yaml", "--lock", "seat.bogus",
                                       "--format", "json"])
    assert result.exit_code == 2
    assert json.loads(result.stdout) == {
        "design": "designs/stool.yaml",
        "error": "designs/stool.yaml: seat.bogus: unknown DOF kind 'bogus'; expected one of "
                 "x, y, z, rx, ry, rz, length, width"}


@pytest.mark.parametrize("command", [["suggest"], ["range", "top.z"]])
def test_a_design_too_big_in_json_is_a_json_error_document(monkeypatch, command) -> None:
    """A design refused as too big (here with the limit lowered to 18 unknowns) gets the
    JSON error document from ``suggest`` and ``range`` too, as ``validate`` gives it an
    error entry."""
    from furncheck import tolerances

    monkeypatch.setattr(tolerances, "MAX_GROUND_UNKNOWNS", 18)
    path = "designs/coffee-table-splayed.yaml"
    result = CliRunner().invoke(main, [command[0], path, *command[1:], "--format", "json"])
    assert result.exit_code == 2
    document = json.loads(result.stdout)
    assert document["design"] == path and "too big" in document["error"]


@pytest.mark.parametrize("fmt", ["text", "json", "junit", "github", "sarif"])
def test_a_file_name_that_is_not_utf8_is_reported_in_every_format(tmp_path: Path,
                                                                  fmt: str) -> None:
    """A design file named with a byte that is not UTF-8 (b'bad\\xffname.yaml', which
    Python reads as a surrogate; its content is not a design) is reported on stdout and
    with -o, the report valid UTF-8 with the odd byte escaped ('\\udcff'; in a SARIF URI
    '%FF'); it ended in 'internal error while writing the report' with nothing written.
    (JUnit wrote U+FFFD for the byte, so that bad\\xfe and bad\\xff named one suite; JSON
    wrote it as the escape of the surrogate itself.)"""
    import os
    import xml.etree.ElementTree as ElementTree

    folder = tmp_path / "enc"
    folder.mkdir()
    try:
        (folder / os.fsdecode(b"bad\xffname.yaml")).write_text("furncheck: 1\nplanks: 3\n")
    except (OSError, UnicodeEncodeError):
        pytest.skip("this file system takes UTF-8 names only")
    out = tmp_path / f"report.{fmt}"
    for args in (["validate", str(folder), "--format", fmt, "--no-cache"],
                 ["validate", str(folder), "--format", fmt, "--no-cache", "-o", str(out)]):
        result = CliRunner().invoke(main, args)
        assert result.exit_code == 2, result.output
        text = (out.read_bytes() if "-o" in args else result.stdout_bytes).decode("utf-8")
        if fmt in ("json", "sarif"):
            # the name as the text every report shows, not a JSON escape that reads back
            # as a lone surrogate (RFC 8259 8.2: undefined; jq wrote U+FFFD for it)
            json.dumps(json.loads(text), ensure_ascii=False).encode("utf-8")
            if fmt == "json":
                assert json.loads(text)["reports"][0]["design"].endswith(
                    "bad\\udcffname.yaml")
        elif fmt == "junit":
            ElementTree.fromstring(text.encode("utf-8"))
        escaped = {"sarif": "bad%FFname.yaml", "json": "bad\\\\udcffname.yaml"}
        assert escaped.get(fmt, "bad\\udcffname.yaml") in text
    # the console script's own stdout, in the C locale (Python's UTF-8 mode writes a
    # name's odd bytes back raw where a format does not escape them: github did)
    import subprocess
    import sys

    written = subprocess.run([sys.executable, "-m", "furncheck", "validate", str(folder),
                              "--format", fmt, "--no-cache"], capture_output=True,
                             env={**os.environ, "LC_ALL": "C"}).stdout
    assert b"\xff" not in written
    assert escaped.get(fmt, "bad\\udcffname.yaml") in written.decode("utf-8")


def test_a_file_name_with_a_line_break_keeps_its_one_verdict_line(tmp_path: Path) -> None:
    """The text report escapes what is not printable in a file's path ('two\\x0alines'):
    a name with a line break split the design's verdict line in two."""
    path = tmp_path / "two\nlines.yaml"
    path.write_text(GOOD)
    result = CliRunner().invoke(main, ["validate", str(path), "--model", "rigid",
                                       "--no-cache"])
    assert result.exit_code == 0, result.output
    first, summary = result.output.splitlines()[0], result.output.splitlines()[-1]
    assert first.startswith(f"{tmp_path}/two\\x0alines.yaml: valid")
    assert summary == "1 design: 1 valid, 0 invalid, 0 errors"


def test_two_outputs_of_one_run_are_not_one_file_and_an_empty_path_is_none(
        tmp_path: Path) -> None:
    """``validate -o r.html --html r.html``: the page replaced the report, which the run
    said it had written; now refused up front, one line, exit 2, nothing checked or
    written; also where one names it through a linked folder.  ``-o ''`` said 'Is a
    directory', ``--html ''`` only after the whole run."""
    same = tmp_path / "r.html"
    stool = str(CATALOG / "stool.yaml")
    result = CliRunner().invoke(main, ["validate", stool, "-o", str(same), "--html",
                                       str(same)])
    assert result.exit_code == 2 and not same.exists()
    assert result.output == f"furncheck: cannot write the report page to {same}: the " \
        "report (-o) goes there\n"
    real = tmp_path / "real"
    real.mkdir()
    (tmp_path / "link").symlink_to(real)
    linked = CliRunner().invoke(main, ["validate", stool, "-o", str(tmp_path / "link" / "r"),
                                       "--html", str(real / "r")])
    assert linked.exit_code == 2 and not (real / "r").exists()     # one file, two names
    for option in ("-o", "--html"):
        empty = CliRunner().invoke(main, ["validate", stool, option, ""])
        assert empty.exit_code == 2 and "an empty path names no file" in empty.output
        assert "valid" not in empty.output


def test_pages_and_suggestion_files_of_a_file_named_not_in_utf8(tmp_path: Path) -> None:
    """``validate --html`` and ``suggest --out`` of designs whose file name has a byte that
    is not UTF-8 (b'bad\\xffname.yaml'; without a ``name`` key the design is named after
    its file): the page and the suggestion's files are written, valid UTF-8, the byte
    escaped ('\\udcff') as the reports escape it.  Both ended in 'internal error:
    UnicodeEncodeError' with no page, the other design's part lost with it."""
    import os
    import shutil

    folder = tmp_path / "enc"
    folder.mkdir()
    source = (CATALOG / "shelf-cantilever-overloaded.yaml").read_text()
    unnamed = "\n".join(line for line in source.splitlines() if not line.startswith("name:"))
    try:
        odd = folder / os.fsdecode(b"bad\xffname.yaml")
        odd.write_text(unnamed)
    except (OSError, UnicodeEncodeError):
        pytest.skip("this file system takes UTF-8 names only")
    shutil.copy(CATALOG / "stool.yaml", folder / "good.yaml")
    page = tmp_path / "page.html"
    result = CliRunner().invoke(main, ["validate", str(folder), "--no-cache", "--model",
                                       "rigid", "--html", str(page)])
    assert result.exit_code == 1, result.output
    text = page.read_bytes().decode("utf-8")
    assert "bad\\udcffname" in text and "good.yaml" in text
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["suggest", str(odd), "--model", "rigid", "--out",
                                       str(out), "--no-plots", "--max-suggestions", "1"])
    assert result.exit_code == 0, result.output
    for written in out.iterdir():
        if written.suffix in (".html", ".yaml", ".obj", ".mtl"):
            written.read_bytes().decode("utf-8")
    assert "name: bad\\udcffname-suggestion-01" in (out / "suggestion-01.yaml").read_text()


@pytest.mark.filterwarnings("error::RuntimeWarning")
def test_absurd_but_legal_values_give_results_and_no_numpy_warnings(tmp_path: Path) -> None:
    """The stool with ``tolerance: 1000`` (mm: larger than the stool, so contacts are made
    of edges whose corners lie at one place along a plank) and a density of 1e-320
    (denormal loads): ``range`` ended in 'internal error: LinAlgError: SVD did not
    converge' (0 / 0 in a station's place along its beam) and the checks printed numpy's
    RuntimeWarnings; now each gives its result, and no warning (turned into errors
    here)."""
    stool = (CATALOG / "stool.yaml").read_text()
    wide = tmp_path / "wide.yaml"
    wide.write_text(stool + "tolerance: 1000\n")
    result = CliRunner().invoke(main, ["range", str(wide), "leg_l.length", "--format",
                                       "json"])
    assert result.exit_code == 0, result.output
    assert json.loads(result.stdout)["ranges"][0]["dof"] == "leg_l.length"
    light = tmp_path / "light.yaml"
    light.write_text(stool.replace("planks:", "material: {density: 1.0e-320}\nplanks:", 1))
    result = CliRunner().invoke(main, ["validate", str(light), "--no-cache"])
    assert result.exit_code in (0, 1) and "0 errors" in result.output, result.output
