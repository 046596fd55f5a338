"""``suggest --out DIR`` owns its folder, ``--no-plots``, and ``validate --views DIR``.

bench-tips in the rigid model gets three suggestions (README), fast enough to run the
command several times.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from click.testing import CliRunner

from furncheck.cli.main import main

CATALOG = Path(__file__).resolve().parents[1] / "designs"
TIPS = str(CATALOG / "bench-tips.yaml")


def suggest(out: Path, *args: str):
    result = CliRunner().invoke(main, ["suggest", TIPS, "--model", "rigid", "--out", str(out),
                                       "--format", "json", *args])
    assert result.exit_code == 0, result.output
    return json.loads(result.output)


def listed(document) -> set[str]:
    names = set()
    for entry in document["suggestions"]:
        names.add(Path(entry["design_file"]).name)
        names.update(Path(path).name for path in entry["meshes"] + entry["plots"])
    return names


def test_a_second_run_removes_only_its_own_stale_files(tmp_path: Path) -> None:
    """A stale suggestion-09 of the same design (its design file names it
    bench-tips-suggestion-09) goes, with its mesh; a file the command never writes stays;
    the folder then holds exactly what the run lists plus the design's own files."""
    out = tmp_path / "out"
    out.mkdir()
    (out / "suggestion-09.yaml").write_text("furncheck: 1\nname: bench-tips-suggestion-09\n")
    (out / "suggestion-09.glb").write_bytes(b"old")
    (out / "notes.txt").write_text("mine")
    document = suggest(out, "--no-plots")
    assert document["suggestions"]           # the count is the ranking's business
    own = {"bench-tips.glb", "bench-tips.obj", "bench-tips.mtl", "index.html"}
    assert {p.name for p in out.iterdir()} == listed(document) | own | {"notes.txt"}
    assert all(name.startswith("suggestion-0") for name in listed(document))


def test_another_designs_files_are_kept_and_ours_named_after_the_design(tmp_path) -> None:
    """suggestion-01.yaml of a design named 'shelf' is not ours: it stays as it was and
    this run writes bench-tips-suggestion-NN.*; run again, the same names are reused."""
    out = tmp_path / "out"
    out.mkdir()
    foreign = "furncheck: 1\nname: shelf-suggestion-01\n"
    (out / "suggestion-01.yaml").write_text(foreign)
    first = suggest(out, "--no-plots")
    names = listed(first)
    assert names and all(name.startswith("bench-tips-suggestion-0") for name in names)
    assert (out / "suggestion-01.yaml").read_text() == foreign
    second = suggest(out, "--no-plots")
    assert listed(second) == names


def test_no_plots_writes_no_pictures_and_plots_write_both(tmp_path: Path) -> None:
    pytest.importorskip("matplotlib")
    quiet = suggest(tmp_path / "quiet", "--no-plots")
    assert all(entry["plots"] == [] for entry in quiet["suggestions"])
    assert not list((tmp_path / "quiet").glob("*.png"))
    drawn = suggest(tmp_path / "drawn", "--max-suggestions", "1")
    (entry,) = drawn["suggestions"]
    assert [Path(p).name for p in entry["plots"]] == ["suggestion-01-forces.png",
                                                      "suggestion-01-view.png"]
    assert (tmp_path / "drawn" / "bench-tips-view.png").stat().st_size > 0


def test_validate_views_writes_one_png_per_design(tmp_path: Path) -> None:
    """Two designs, two views named after them; the exit code is validate's own (1: an
    invalid design); a --views that is a file is a usage error (2)."""
    pytest.importorskip("matplotlib")
    views = tmp_path / "views"
    result = CliRunner().invoke(main, ["validate", TIPS, str(CATALOG / "bench.yaml"),
                                       "--model", "rigid", "--views", str(views)])
    assert result.exit_code == 1, result.output
    assert sorted(p.name for p in views.iterdir()) == ["bench-tips-view.png", "bench-view.png"]
    blocker = tmp_path / "file"
    blocker.write_text("x")
    bad = CliRunner().invoke(main, ["validate", TIPS, "--views", str(blocker)])
    assert bad.exit_code == 2 and "not a directory" in bad.output
    assert "Traceback" not in bad.output


def test_catalog_view_names_count_repeated_names() -> None:
    from furncheck.export.catalog import view_names
    from furncheck.result import DesignReport

    reports = [DesignReport("a/t.yaml", "t", True), DesignReport("b/t.yaml", "t", False),
               DesignReport("x.yaml", "x", None, error="bad")]
    assert view_names(reports) == ["t-view.png", "t-2-view.png", None]


def test_view_names_are_file_names_inside_the_folder_and_distinct() -> None:
    """A design's name is made a file name (``folders.file_stem``): a path separator or
    space becomes '_', leading dots go, a Windows device name gets 'design-' before it, a
    long name is cut; a name taken by an earlier design ('a-2' after two designs named
    'a', 'A' after 'a' on a folder that ignores case) gets the next free number."""
    from furncheck.export.catalog import view_names
    from furncheck.export.folders import file_stem
    from furncheck.result import DesignReport

    names = ["../../pwned", "/tmp/abs", "sub/x", "a", "a", "a-2", "Bücher regal", "...",
             "A", "con", "Nul.txt"]
    reports = [DesignReport(f"{k}.yaml", name, True) for k, name in enumerate(names)]
    assert view_names(reports) == [
        "_.._pwned-view.png", "_tmp_abs-view.png", "sub_x-view.png", "a-view.png",
        "a-2-view.png", "a-2-2-view.png", "Bücher_regal-view.png", "design-view.png",
        "A-3-view.png", "design-con-view.png", "design-Nul.txt-view.png"]
    assert file_stem("stool-thick-seat") == "stool-thick-seat"    # plain names as they are
    long = file_stem("é" * 200)                 # 400 bytes: cut, told apart by its hash
    assert len(long.encode()) <= 120 and long != file_stem("é" * 199 + "e")


def test_files_named_from_a_design_stay_in_their_folder(tmp_path: Path) -> None:
    """bench-tips renamed '../escape' writes its view and meshes inside the folders given
    (``validate --views``, ``suggest --out``), not beside them; renamed 'suggestion-01',
    its own files in the ``--out`` folder are 'design-suggestion-01.*', apart from
    suggestion 1's."""
    pytest.importorskip("matplotlib")
    text = Path(TIPS).read_text()
    assert "\nname: bench-tips\n" in text
    for name, stem, own in (("../escape", "_escape", "_escape"),
                            ("suggestion-01", "suggestion-01", "design-suggestion-01")):
        path = tmp_path / f"{own}.yaml"
        path.write_text(text.replace("\nname: bench-tips\n", f"\nname: '{name}'\n"))
        views = tmp_path / own / "views" / "deep"
        result = CliRunner().invoke(main, ["validate", str(path), "--model", "rigid",
                                           "--views", str(views)])
        assert result.exit_code == 1, result.output
        assert [p.name for p in views.iterdir()] == [f"{stem}-view.png"]
        out = tmp_path / own / "out" / "deep"
        result = CliRunner().invoke(main, ["suggest", str(path), "--model", "rigid", "--out",
                                           str(out), "--max-suggestions", "1", "--no-plots"])
        assert result.exit_code == 0, result.output
        assert sorted(p.name for p in out.iterdir()) == sorted(
            [f"{own}.glb", f"{own}.obj", f"{own}.mtl", "index.html", "suggestion-01.yaml",
             "suggestion-01.glb", "suggestion-01.obj", "suggestion-01.mtl"])
        assert sorted(p.name for p in (tmp_path / own).iterdir()) == ["out", "views"]


def test_pictures_drawn_in_workers_are_those_drawn_here(tmp_path: Path, monkeypatch) -> None:
    """With several suggestions the pictures are drawn in forked worker processes; with
    one core, here.  Both write the same files, byte for byte."""
    pytest.importorskip("matplotlib")
    import os

    parallel = suggest(tmp_path / "parallel")
    monkeypatch.setattr(os, "cpu_count", lambda: 1)
    serial = suggest(tmp_path / "serial")
    assert listed(parallel) == listed(serial)
    for name in listed(parallel):
        assert (tmp_path / "parallel" / name).read_bytes() == \
            (tmp_path / "serial" / name).read_bytes(), name


@pytest.mark.parametrize("broken", [None, "top", "deep"])
def test_validate_views_without_matplotlib_reports_and_says_so(tmp_path: Path, monkeypatch,
                                                               broken: bool) -> None:
    """--views where matplotlib cannot be imported (not installed, or installed but
    failing on import): the designs are checked and reported as without --views, with
    validate's own exit code (1: bench-tips topples), and one line on stderr says the
    views were not written, as suggest --out says of its pictures (it was exit 2 and no
    report; a broken install was an internal error)."""
    from conftest import without_matplotlib

    without_matplotlib(broken, tmp_path, monkeypatch)
    result = CliRunner().invoke(main, ["validate", TIPS, "--views", str(tmp_path / "v"),
                                       "--no-cache"])
    assert result.exit_code == 1
    assert "bench-tips.yaml: INVALID" in result.stdout
    assert result.stderr == ("furncheck: views not written: pictures need matplotlib, which "
                             "cannot be imported: pip install matplotlib\n")
    assert not list((tmp_path / "v").iterdir())
