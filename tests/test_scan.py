"""Which files a directory scan checks (contract section 4; ``furncheck.scan``).

The library is tested on trees built in a temporary folder; the command line on the same
trees with ``check_file`` replaced by the fake of ``test_cli`` (the verdict comes from the
file name), so only the choice of files is under test.  Where git is installed, its own
idea of ignored files is the reference for the .gitignore rules.
"""

from __future__ import annotations

import io
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from test_cli import run

from furncheck.detect import declares_design
from furncheck.ignores import patterns
from furncheck.scan import ScanOptions, collect, find_design_files

DESIGN = "furncheck: 1\nplanks: []\n"


def tree(root: Path, files: dict[str, str]) -> Path:
    """Write ``files`` (relative path -> text) under ``root``; returns ``root``."""
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return root


def found(folder: Path, **options) -> list[str]:
    """The design files a scan of ``folder`` finds, relative to it, in order."""
    scan = find_design_files(str(folder), **options)
    return [Path(path).relative_to(folder).as_posix() for path in scan.files]


def git_listed(root: Path, *paths: str) -> list[str]:
    """The YAML and JSON files under ``root`` (or its ``paths``) that git does not ignore
    (``git ls-files --others --exclude-standard``, after ``git init``), in scan order."""
    subprocess.run(["git", "init", "-q", str(root)], check=True)
    listed = subprocess.run(["git", "ls-files", "--others", "--exclude-standard", "--",
                             *paths], cwd=root, capture_output=True, text=True,
                            check=True).stdout
    return sorted((name for name in listed.splitlines()
                   if name.endswith((".yaml", ".yml", ".json"))),
                  key=lambda name: name.split("/"))


# --- .gitignore ---------------------------------------------------------------------------

def test_gitignore_files_in_the_tree_apply_below_their_folder(tmp_path):
    """Root .gitignore: 'build/' (folders only), '*.draft.yaml' except 'keep.draft.yaml';
    sub/.gitignore: 'local.yaml' (any depth below sub/) and '/top.yaml' (anchored at sub/).
    So: build/ is not entered, a.draft.yaml goes, keep.draft.yaml stays, sub/local.yaml and
    sub/deep/local.yaml go, local.yaml at the root stays (sub's rules do not reach up),
    sub/top.yaml goes but sub/deep/top.yaml stays."""
    (tmp_path / ".git").mkdir()
    tree(tmp_path, {
        ".gitignore": "build/\n*.draft.yaml\n!keep.draft.yaml\n",
        "sub/.gitignore": "local.yaml\n/top.yaml\n",
        "a.yaml": DESIGN, "a.draft.yaml": DESIGN, "keep.draft.yaml": DESIGN,
        "build/out.yaml": DESIGN, "local.yaml": DESIGN,
        "sub/local.yaml": DESIGN, "sub/deep/local.yaml": DESIGN,
        "sub/top.yaml": DESIGN, "sub/deep/top.yaml": DESIGN, "sub/b.yaml": DESIGN,
    })
    assert found(tmp_path) == ["a.yaml", "keep.draft.yaml", "local.yaml", "sub/b.yaml",
                               "sub/deep/top.yaml"]


def test_gitignore_files_above_the_scanned_folder_apply_up_to_the_repository(tmp_path):
    """repo/.gitignore ignores 'designs/drafts/' and '*.bak.yaml'; a .gitignore above the
    repository ignores everything ('*') but is outside it, so it does not count; scanning
    repo/designs leaves out drafts/ and x.bak.yaml only.  Without .git (no repository)
    only the scanned tree's own .gitignore files count: the same scan keeps both."""
    outer = tmp_path / "outer"
    repo = outer / "repo"
    tree(outer, {".gitignore": "*\n"})
    tree(repo, {".gitignore": "designs/drafts/\n*.bak.yaml\n",
                "designs/a.yaml": DESIGN, "designs/x.bak.yaml": DESIGN,
                "designs/drafts/d.yaml": DESIGN})
    assert found(repo / "designs") == ["a.yaml", "drafts/d.yaml", "x.bak.yaml"]
    (repo / ".git").mkdir()
    assert found(repo / "designs") == ["a.yaml"]


def test_git_info_exclude_counts_at_the_repository_top(tmp_path):
    """.git/info/exclude holds 'private.yaml': left out like a root .gitignore entry, and a
    root .gitignore '!private.yaml' overrides it (the .gitignore files rank above it)."""
    tree(tmp_path, {".git/info/exclude": "private.yaml\n", "private.yaml": DESIGN,
                    "a.yaml": DESIGN})
    assert found(tmp_path) == ["a.yaml"]
    (tmp_path / ".gitignore").write_text("!private.yaml\n")
    assert found(tmp_path) == ["a.yaml", "private.yaml"]


@pytest.mark.skipif(shutil.which("git") is None, reason="git is not installed")
def test_the_gitignore_rules_agree_with_git(tmp_path):
    """A tree with nested .gitignore files, negations, anchored, folder-only and ** patterns:
    the design files found are exactly the YAML/JSON files that ``git ls-files --others
    --exclude-standard`` lists (git's own rules), hidden ones left out."""
    tree(tmp_path, {
        ".gitignore": "node_modules/\n/out\n*.tmp.yaml\ndocs/**/gen-*.yaml\n"
                      "!docs/keep/gen-1.yaml\n",
        "a/.gitignore": "*.yaml\n!important.yaml\nnested/\n",
        "a/b/.gitignore": "!*.yaml\n",
        "a/x.yaml": DESIGN, "a/important.yaml": DESIGN, "a/b/y.yaml": DESIGN,
        "a/nested/z.yaml": DESIGN, "a/c/w.json": '{"furncheck": 1}',
        "node_modules/pkg/d.yaml": DESIGN, "out/o.yaml": DESIGN, "sub/out/o.yaml": DESIGN,
        "t.tmp.yaml": DESIGN, "docs/p/q/gen-2.yaml": DESIGN, "docs/keep/gen-1.yaml": DESIGN,
        "docs/gen-3.yaml": DESIGN, "docs/plain.yml": DESIGN, "top.yaml": DESIGN,
    })
    expected = git_listed(tmp_path)
    assert "a/b/y.yaml" in expected and "a/x.yaml" not in expected  # the tree is not trivial
    assert found(tmp_path) == expected


@pytest.mark.skipif(shutil.which("git") is None, reason="git is not installed")
@pytest.mark.parametrize("files", [
    {".gitignore": "*\n!*/\n!*.yaml\n", "top.yaml": DESIGN, "designs/a.yaml": DESIGN,
     "designs/sub/b.yaml": DESIGN, "designs/notes.txt": "x"},
    {".gitignore": "*.yaml\n", "a/.gitignore": "!a/\n", "a/a/a.yaml": DESIGN,
     "a/b.json": '{"furncheck": 1}'},
    {".gitignore": "\ufeffbom.yaml\n!\n\\\nbad[.yaml\n  \nspace.yaml   \n",
     "bom.yaml": DESIGN, "space.yaml": DESIGN, "z.yaml": DESIGN, "bad[.yaml": DESIGN},
], ids=["whitelist", "negated-folder", "odd-lines"])
def test_folder_patterns_match_the_folder_itself_as_in_git(tmp_path, files):
    """Git matches each path while it walks the tree: a pattern names a folder itself, not
    what is in it.  The whitelist idiom ('*', '!*/', '!*.yaml') keeps every YAML file in
    every folder (pathspec's matching of '!*/' left every folder out: the designs in them
    went unchecked, exit 0); '!a/' re-includes the folder a/a but not the '*.yaml' files
    in it.  A byte-order mark before the first pattern is dropped, a lone '!' or '\\'
    matches nothing (it ended the scan with an internal error), and trailing spaces are
    dropped: git's own list decides."""
    tree(tmp_path, files)
    assert found(tmp_path) == git_listed(tmp_path)


@pytest.mark.skipif(shutil.which("git") is None, reason="git is not installed")
def test_a_named_folder_keeps_the_patterns_that_do_not_leave_it_out(tmp_path):
    """Scanning a folder below a whitelist .gitignore ('*', '!*/', '!*.yaml'), as CI
    recipes name designs/: '!*/' re-includes the folder, so '*' still leaves out its
    JSON files, as git's list of that folder says (dropping every pattern that matched
    the folder let them in); a folder that 'build/**' or '*' does leave out is searched
    when named, 'build/**' then leaving out nothing in it (it named the contents through
    the folder's own name), '*' still what it names on its own (the subfolder s/, which
    '!*.yaml' does not re-include); the other patterns apply ('*.skip.yaml')."""
    tree(tmp_path, {".gitignore": "*\n!*/\n!*.yaml\n", "x/a.yaml": DESIGN,
                    "x/d.json": '{"furncheck": 1}', "x/y/b.yaml": DESIGN,
                    "x/y/e.json": '{"furncheck": 1}'})
    for folder in ("x", "x/y"):
        listed = git_listed(tmp_path, folder)
        assert [f"{folder}/{name}" for name in found(tmp_path / folder)] == listed
        assert not any(name.endswith(".json") for name in listed)
    for patterns_text, expected in (("build/**\n*.skip.yaml\n", ["a.yaml", "s/b.yaml"]),
                                    ("*\n!*.yaml\n*.skip.yaml\n", ["a.yaml"])):
        (tmp_path / ".gitignore").write_text(patterns_text)
        tree(tmp_path, {"build/a.yaml": DESIGN, "build/s/b.yaml": DESIGN,
                        "build/c.skip.yaml": DESIGN})
        assert found(tmp_path / "build") == expected, patterns_text


def test_a_gitignore_pattern_with_bytes_that_are_not_utf8_matches_its_file(tmp_path):
    """A .gitignore line b'caf\\xe9.yaml' (Latin-1, as git compares bytes) leaves out the
    file of that name, as git does (the bytes were replaced by U+FFFD, which matched no
    name)."""
    name = os.fsdecode(b"caf\xe9.yaml")
    try:
        tree(tmp_path, {".git/HEAD": "", name: DESIGN, "a.yaml": DESIGN})
    except (OSError, UnicodeEncodeError):
        pytest.skip("this file system takes UTF-8 names only")
    (tmp_path / ".gitignore").write_bytes(b"caf\xe9.yaml\n")
    assert found(tmp_path) == ["a.yaml"]


def test_a_pattern_that_does_not_compile_matches_nothing(tmp_path):
    """A reversed range ('[z-a].yaml', which Python's re refuses) in a .gitignore or an
    exclude is left out, where it ended the scan with an internal error (git reads it as
    the range's first character alone, so it leaves z.yaml out: a pattern nobody means)."""
    tree(tmp_path, {".gitignore": "[z-a].yaml\nb.yaml\n", "a.yaml": DESIGN,
                    "b.yaml": DESIGN, "z.yaml": DESIGN})
    excludes = (patterns(["[z-a]", "!"], str(tmp_path), "--exclude"),)
    assert found(tmp_path, excludes=excludes) == ["a.yaml", "z.yaml"]


def test_a_named_folder_is_scanned_even_when_ignored(tmp_path):
    """.gitignore ignores 'build/'; naming build/ on the command line scans it (as a named
    file is always checked), and the rules still apply inside it ('*.skip.yaml')."""
    tree(tmp_path, {".git/HEAD": "", ".gitignore": "build/\n*.skip.yaml\n",
                    "build/a.yaml": DESIGN, "build/b.skip.yaml": DESIGN})
    assert found(tmp_path / "build") == ["a.yaml"]


def test_a_nested_repository_keeps_its_own_ignore_rules(tmp_path):
    """An outer repository ignoring '*.yaml' holds sub/, a repository of its own with a
    design and a .git/info/exclude that leaves out 'draft.yaml' (and lib/, a submodule,
    whose exclude file lies where its .git file points): as in git, the outer
    .gitignore stops at sub/'s top, so a scan of the outer folder and one of sub/ (and
    --force-exclude of the file) agree: sub/a.yaml is checked, sub/draft.yaml is not."""
    tree(tmp_path, {".git/HEAD": "", ".gitignore": "*.yaml\n", "top.yaml": DESIGN,
                    "sub/.git/HEAD": "", "sub/.git/info/exclude": "draft.yaml\n",
                    "sub/a.yaml": DESIGN, "sub/draft.yaml": DESIGN})
    assert found(tmp_path) == ["sub/a.yaml"]
    assert found(tmp_path / "sub") == ["a.yaml"]
    named = [str(tmp_path / "sub" / name) for name in ("a.yaml", "draft.yaml")]
    assert collect(named, ScanOptions(force_exclude=True)).sources == named[:1]
    # a submodule: its .git is a file pointing into the parent's .git/modules, where its
    # info/exclude lies
    tree(tmp_path, {"lib/.git": "gitdir: ../.git/modules/lib\n",
                    ".git/modules/lib/info/exclude": "secret.yaml\n",
                    "lib/a.yaml": DESIGN, "lib/secret.yaml": DESIGN})
    assert found(tmp_path / "lib") == ["a.yaml"]
    assert "lib/secret.yaml" not in found(tmp_path)


def test_a_pattern_that_leaves_out_a_named_folder_still_applies_inside_it(tmp_path):
    """A CI engineer's cases: with 'out*' in .gitignore, naming out/ searches it, and
    'out*' still leaves out out/output-tmp/ (it names that folder on its own), as a
    --force-exclude of a file in it says too; --exclude 'd*' with designs/ named leaves
    out designs/drafts/; --exclude '*' --exclude '!stool.yaml' keeps stool.yaml alone;
    'logs/**/tmp' with logs/tmp/ named leaves out logs/tmp/a/tmp/ (as git check-ignore
    does)."""
    tree(tmp_path, {".git/HEAD": "", ".gitignore": "out*\n", "out/good/a.yaml": DESIGN,
                    "out/output-tmp/stale.yaml": DESIGN, "designs/drafts/t.yaml": DESIGN,
                    "designs/stool.yaml": DESIGN, "designs/table.yaml": DESIGN})
    assert found(tmp_path / "out") == ["good/a.yaml"]
    stale = str(tmp_path / "out" / "output-tmp" / "stale.yaml")
    assert collect([stale], ScanOptions(force_exclude=True)).sources == []
    base = str(tmp_path)
    assert found(tmp_path / "designs", excludes=(patterns(["d*"], base, "--exclude"),)) \
        == ["stool.yaml", "table.yaml"]
    only = (patterns(["*", "!stool.yaml"], base, "--exclude"),)
    assert found(tmp_path / "designs", excludes=only) == ["stool.yaml"]
    # an anchored '**' pattern naming the folder still names folders deeper in it
    tree(tmp_path, {".gitignore": "logs/**/tmp\n", "logs/tmp/y.yaml": DESIGN,
                    "logs/tmp/a/tmp/x.yaml": DESIGN})
    assert found(tmp_path / "logs" / "tmp") == ["y.yaml"]


# --- --exclude, hidden paths --------------------------------------------------------------

def test_exclude_patterns_are_gitignore_patterns_anchored_at_their_folder(tmp_path):
    """'drafts' (no slash) matches a name at any depth; '/b.yaml' only b.yaml right in the
    base folder; '**/old-*.yaml' any depth.  An exclude beats a .gitignore '!' rule."""
    tree(tmp_path, {".gitignore": "!b.yaml\n", "a.yaml": DESIGN, "b.yaml": DESIGN,
                    "sub/b.yaml": DESIGN, "drafts/c.yaml": DESIGN,
                    "sub/drafts/d.yaml": DESIGN, "sub/old-e.yaml": DESIGN})
    excludes = (patterns(["drafts", "/b.yaml", "**/old-*.yaml"], str(tmp_path), "test"),)
    assert found(tmp_path, excludes=excludes) == ["a.yaml", "sub/b.yaml"]


def test_hidden_files_and_folders_are_skipped(tmp_path):
    tree(tmp_path, {"a.yaml": DESIGN, ".b.yaml": DESIGN, ".hidden/c.yaml": DESIGN,
                    "sub/.d.yml": DESIGN})
    assert found(tmp_path) == ["a.yaml"]
    assert found(tmp_path / ".hidden") == ["c.yaml"]   # named: scanned


def test_exclude_on_the_command_line_is_relative_to_the_current_folder(checked_paths, tmp_path,
                                                                      monkeypatch):
    """--exclude sub/x.yaml (anchored: it has a slash) from tmp_path leaves out sub/x.yaml
    but not other/sub/x.yaml; --exclude is repeatable."""
    tree(tmp_path, {"sub/x.yaml": DESIGN, "other/sub/x.yaml": DESIGN, "y.yaml": DESIGN,
                    "z.yaml": DESIGN})
    monkeypatch.chdir(tmp_path)
    result = run("validate", ".", "--exclude", "sub/x.yaml", "--exclude", "z.yaml")
    assert [Path(path).as_posix() for path in checked_paths] == ["other/sub/x.yaml", "y.yaml"]
    assert result.exit_code == 0


def test_an_exclude_is_typed_as_a_path_and_checked(checked_paths, tmp_path, monkeypatch):
    """--exclude ./sub/x.yaml is sub/x.yaml and ./y.yaml is y.yaml in the current folder
    alone, not sub/y.yaml (a leading './' is how paths are typed; git would read it
    literally and match nothing); a pattern that is none ('[', a reversed range, a lone
    '!' or '/', './'), on the command line or in [tool.furncheck], is one line and exit 2
    instead of excluding nothing unseen; a blank entry or a '#' comment in the config is
    passed over, as in a .gitignore."""
    tree(tmp_path, {"sub/x.yaml": DESIGN, "sub/y.yaml": DESIGN, "y.yaml": DESIGN})
    monkeypatch.chdir(tmp_path)
    result = run("validate", ".", "--exclude", "./sub/x.yaml", "--no-cache")
    assert [Path(path).as_posix() for path in checked_paths] == ["sub/y.yaml", "y.yaml"]
    assert result.exit_code == 0
    checked_paths.clear()
    run("validate", ".", "--exclude", "./y.yaml", "--no-cache")
    assert [Path(path).as_posix() for path in checked_paths] == ["sub/x.yaml", "sub/y.yaml"]
    for pattern in ("[", "[z-a]", "!", "/", "./"):
        result = run("validate", ".", "--exclude", pattern)
        assert result.exit_code == 2
        assert result.output.startswith(
            f"furncheck: --exclude: {pattern!r} is not a valid gitignore pattern")
    (tmp_path / "pyproject.toml").write_text('[tool.furncheck]\nexclude = ["[z-a]"]\n')
    result = run("validate", ".")
    assert result.exit_code == 2 and "[tool.furncheck] exclude: '[z-a]' is not" in result.output
    (tmp_path / "pyproject.toml").write_text(
        '[tool.furncheck]\nexclude = ["", "#wip", "sub"]\n')
    checked_paths.clear()
    assert run("validate", ".", "--no-cache").exit_code == 0
    assert [Path(path).as_posix() for path in checked_paths] == ["y.yaml"]


def test_an_exclude_typed_as_a_path_to_elsewhere_is_anchored_there(checked_paths, tmp_path,
                                                                     monkeypatch):
    """Excludes a user types as paths do what they say, where gitignore syntax read
    literally would match nothing unseen: an absolute path ('$PWD/sub/drafts'), one
    typed from a subfolder of the scanned tree ('../sub/drafts' from sub/, scanning
    '..'), and on the command line a name beginning with '#' ('#d.yaml', which a config's
    list reads as a comment); '/drafts' stays anchored at the current folder."""
    tree(tmp_path, {"sub/a.yaml": DESIGN, "sub/drafts/d.yaml": DESIGN,
                    "sub/#d.yaml": DESIGN, "top.yaml": DESIGN})
    monkeypatch.chdir(tmp_path)
    run("validate", "sub", "--exclude", str(tmp_path / "sub" / "drafts"), "--exclude",
        "#d.yaml", "--no-cache")
    assert [Path(p).as_posix() for p in checked_paths] == ["sub/a.yaml"]
    checked_paths.clear()
    monkeypatch.chdir(tmp_path / "sub")
    run("validate", "..", "--exclude", "../sub/drafts", "--exclude", "../top.yaml",
        "--no-cache")
    assert [Path(p).as_posix() for p in checked_paths] == ["../sub/#d.yaml", "../sub/a.yaml"]
    checked_paths.clear()
    run("validate", ".", "--exclude", "/drafts", "--no-cache")
    assert [Path(p).as_posix() for p in checked_paths] == ["#d.yaml", "a.yaml"]


def test_force_exclude_leaves_out_named_files_as_a_scan_would(checked_paths, tmp_path,
                                                             monkeypatch):
    """With exclude = ["drafts"] in [tool.furncheck], a scan of designs/ leaves out
    designs/drafts/; a hook that names designs/drafts/t.yaml checks it (a named file is
    always checked) unless --force-exclude (the hook's own option) or force-exclude = true
    says to leave it out too; an empty run is then 0 designs, exit 0.  So are named files
    in hidden folders and git-ignored ones, as a scan leaves them out."""
    tree(tmp_path, {"designs/drafts/t.yaml": DESIGN, "designs/ok.yaml": DESIGN})
    monkeypatch.chdir(tmp_path)
    (tmp_path / "pyproject.toml").write_text('[tool.furncheck]\nexclude = ["drafts"]\n')
    run("validate", "designs")
    assert [Path(path).as_posix() for path in checked_paths] == ["designs/ok.yaml"]
    checked_paths.clear()
    named = ("designs/drafts/t.yaml", "designs/ok.yaml")
    run("validate", *named, "--no-cache")
    assert checked_paths == list(named)
    checked_paths.clear()
    run("validate", *named, "--force-exclude", "--no-cache")
    assert checked_paths == ["designs/ok.yaml"]
    checked_paths.clear()
    (tmp_path / "pyproject.toml").write_text(
        '[tool.furncheck]\nexclude = ["drafts"]\nforce-exclude = true\n')
    result = run("validate", "designs/drafts/t.yaml")
    assert checked_paths == [] and result.exit_code == 0
    assert "0 designs" in result.output
    assert result.stderr == ("furncheck: left out 1 named file that a scan would leave out "
                             "(--force-exclude)\n")
    # a folder whose designs the patterns all leave out says so
    result = run("validate", "designs", "--exclude", "*.yaml", "--no-cache")
    assert result.exit_code == 2
    assert "no design files (.yaml, .yml or .json with a top-level 'furncheck' key) in " \
           "this directory (2 left out by .gitignore or exclude patterns)" in result.output
    # what a scan leaves out besides: a hidden folder's file, a git-ignored one
    tree(tmp_path, {".git/HEAD": "", ".gitignore": "old/\n", ".wip/h.yaml": DESIGN,
                    "designs/old/o.yaml": DESIGN})
    run("validate", ".wip/h.yaml", "designs/old/o.yaml", "designs/ok.yaml", "--no-cache")
    assert checked_paths == ["designs/ok.yaml"]


def _commit(root: Path, *paths: str) -> None:
    """``git add -f`` the ``paths`` and commit them in the repository at ``root``."""
    subprocess.run(["git", "init", "-q", str(root)], check=True)
    subprocess.run(["git", "add", "-f", "--", *paths], cwd=root, check=True)
    subprocess.run(["git", "-c", "user.email=t@t", "-c", "user.name=t", "commit", "-qm",
                    "designs"], cwd=root, check=True)


@pytest.mark.skipif(shutil.which("git") is None, reason="git is not installed")
def test_a_file_git_tracks_is_checked_though_a_gitignore_matches_it(tmp_path, monkeypatch,
                                                                   checked_paths):
    """A .gitignore never ignores a tracked file, in git: designs/shelf.json committed
    before '*.json' was added, and build/t.yaml committed inside the later ignored
    'build/' (or forced in with 'git add -f'), are checked by a scan and kept by
    --force-exclude (the pre-commit hook's: an edit to them was left unchecked, the run
    green); build/new.yaml and designs/new.json beside them, untracked, stay ignored.
    What git lists (tracked, and untracked not ignored) is what the scan checks.  Without
    git on the PATH the ignore rules alone decide, as before."""
    files = ("designs/shelf.json", "designs/a.yaml", "build/t.yaml")
    tree(tmp_path, {name: DESIGN for name in files})
    _commit(tmp_path, *files)
    tree(tmp_path, {".gitignore": "*.json\nbuild/\n", "build/new.yaml": DESIGN,
                    "designs/new.json": DESIGN, "designs/b.yaml": DESIGN})
    tracked = subprocess.run(["git", "ls-files"], cwd=tmp_path, capture_output=True,
                             text=True, check=True).stdout.split()
    expected = sorted({*git_listed(tmp_path), *(n for n in tracked if n != ".gitignore")},
                      key=lambda name: name.split("/"))
    assert expected == ["build/t.yaml", "designs/a.yaml", "designs/b.yaml",
                        "designs/shelf.json"]
    assert found(tmp_path) == expected
    monkeypatch.chdir(tmp_path)
    run("validate", "--force-exclude", "--no-cache", "designs/shelf.json", "build/t.yaml",
        "build/new.yaml", "designs/new.json", "designs/b.yaml")
    assert [Path(p).as_posix() for p in checked_paths] == [
        "designs/shelf.json", "build/t.yaml", "designs/b.yaml"]
    from furncheck import tracked

    monkeypatch.setattr(tracked, "_TRACKED", {})
    monkeypatch.setattr(shutil, "which", lambda name, *args, **kwargs: None)
    assert found(tmp_path) == ["designs/a.yaml", "designs/b.yaml"]


@pytest.mark.skipif(shutil.which("git") is None, reason="git is not installed")
def test_git_runs_no_command_of_the_repository_nor_a_hooks_index(tmp_path, monkeypatch):
    """Asking git what it tracks runs no command the repository's configuration names
    (core.fsmonitor, which 'git ls-files' runs: a .git planted above the scanned folder
    by someone else would run theirs), and a commit hook's GIT_INDEX_FILE (the outer
    repository's index) does not stand for a nested repository's: lib/ (its own
    repository, whose .gitignore ignores *.yaml) keeps its tracked keep.yaml."""
    marker = tmp_path / "ran"
    monitor = tmp_path / "monitor.sh"
    monitor.write_text(f"#!/bin/sh\ntouch {marker}\n")
    monitor.chmod(0o755)
    tree(tmp_path / "outer", {"lib/keep.yaml": DESIGN, "top.yaml": DESIGN})
    _commit(tmp_path / "outer" / "lib", "keep.yaml")
    subprocess.run(["git", "-C", str(tmp_path / "outer" / "lib"), "config", "core.fsmonitor",
                    str(monitor)], check=True)
    tree(tmp_path / "outer", {"lib/.gitignore": "*.yaml\n", ".gitignore": "lib/\n"})
    _commit(tmp_path / "outer", "top.yaml", ".gitignore")
    monkeypatch.setenv("GIT_INDEX_FILE", str(tmp_path / "outer" / ".git" / "index"))
    from furncheck.tracked import forget

    forget()
    assert found(tmp_path / "outer" / "lib") == ["keep.yaml"]
    assert not marker.exists()


def test_force_exclude_leaves_out_a_file_in_a_cache_folder(tmp_path):
    """A scan enters no folder that holds a CACHEDIR.TAG, so --force-exclude leaves out a
    named file below one too (what a hook is handed, a scan would pass over)."""
    tree(tmp_path, {"a.yaml": DESIGN, "gen/x.yaml": DESIGN,
                    "gen/CACHEDIR.TAG": "Signature: 8a477f597d28d172789f06886806bc55\n"})
    assert found(tmp_path) == ["a.yaml"]
    named = [str(tmp_path / "a.yaml"), str(tmp_path / "gen" / "x.yaml")]
    collected = collect(named, ScanOptions(force_exclude=True))
    assert collected.sources == named[:1] and collected.force_excluded == 1


def test_force_exclude_leaves_out_standard_input_by_its_stdin_filename(tmp_path, monkeypatch):
    """A hook that pipes a changed file to '-' and names it with --stdin-filename gets the
    file's own verdict from --force-exclude: left out (0 designs, exit 0, standard input
    not even read) where a scan would leave that file out, checked where it would not."""
    from click.testing import CliRunner

    from furncheck.cli.main import main

    tree(tmp_path, {"designs/drafts/t.yaml": DESIGN, "designs/ok.yaml": DESIGN})
    monkeypatch.chdir(tmp_path)

    class Unread(io.BytesIO):
        """Standard input that fails the test if it is read."""

        def read(self, *args):
            if args and args[0] == 0:       # (click's probe for a binary stream)
                return b""
            raise AssertionError("standard input was read")

        read1 = readline = read

    def piped(name: str, stdin=None):
        return CliRunner().invoke(main, ["validate", "-", "--stdin-filename", name,
                                         "--force-exclude", "--exclude", "drafts",
                                         "--no-cache"], input=stdin or DESIGN)

    left_out = piped("designs/drafts/t.yaml", Unread(DESIGN.encode()))
    assert left_out.exit_code == 0 and "0 designs" in left_out.output
    assert "left out 1 named file" in left_out.stderr
    checked = piped("designs/ok.yaml")
    assert "1 design:" in checked.output and "left out" not in checked.stderr


def test_force_exclude_reads_each_folders_gitignores_once(tmp_path, monkeypatch):
    """Two hundred named files of one folder inside a repository: --force-exclude reads
    the .gitignore files above that folder once, not once per file."""
    import furncheck.ignores as ignores

    tree(tmp_path, {".git/HEAD": "", ".gitignore": "old/\n", "designs/.gitignore": "x\n"})
    for i in range(200):
        (tmp_path / "designs" / f"d{i:03}.yaml").write_text(DESIGN)
    monkeypatch.chdir(tmp_path)
    reads = []
    real = ignores.read_pattern_file
    monkeypatch.setattr(ignores, "read_pattern_file",
                        lambda path, *rest: reads.append(path) or real(path, *rest))
    named = sorted(str(p.relative_to(tmp_path)) for p in (tmp_path / "designs").iterdir()
                   if p.suffix == ".yaml")
    collected = collect(named, ScanOptions(force_exclude=True))
    assert len(collected.sources) == 200
    assert len(reads) == len(set(reads)) <= 3     # info/exclude, ./.gitignore, designs/


def test_a_design_too_large_to_check_is_found_wherever_its_key_stands(tmp_path, monkeypatch):
    """Files over the 5 MiB limit (MAX_FILE_BYTES): a JSON design whose "furncheck" key
    comes last, after 6 MB of planks, and a YAML one whose key line follows 6 MB of
    comments, are designs (their reports say they are too large: exit 2), in a scan and
    with --skip-non-designs, not files without the key that a scan skips (exit 0); a
    large JSON file that only mentions furncheck in a value, and one without the word,
    are no designs."""
    import furncheck.detect as detect
    from furncheck import tolerances as tol

    filler = "x" * (tol.MAX_FILE_BYTES + 1024 * 1024)
    monkeypatch.setattr(detect, "SNIFF_BLOCK", 1 << 16)     # many blocks, keys across them
    tree(tmp_path, {
        "big/late.json": '{"planks": ["' + filler + '"], "furncheck": 1}',
        "big/late.yaml": "# " + filler + "\nfurncheck: 1\n",
        "big/mention.json": '{"note": "' + filler + ' furncheck"}',
        "big/plain.json": '{"note": "' + filler + '"}',
    })
    monkeypatch.chdir(tmp_path)
    result = run("validate", "big", "--no-cache")
    assert result.exit_code == 2
    assert "big/late.json: error: file too large" in result.output
    assert "big/late.yaml: error: file too large" in result.output
    assert "2 designs: 0 valid, 0 invalid, 2 errors" in result.output
    assert "skipped 2 files without a top-level 'furncheck' key" in result.stderr
    named = run("validate", "big/late.json", "big/plain.json", "--skip-non-designs",
                "--no-cache")
    assert named.exit_code == 2 and "1 design: 0 valid, 0 invalid, 1 error" in named.output
    for offset in range(0, 80, 7):      # a key across two blocks is still found
        data = b"y" * ((1 << 16) - offset) + b'\n"furncheck": 1'
        assert detect.declares_design_at_large(io.BytesIO(data), "json")
        assert not detect.declares_design_at_large(io.BytesIO(data.replace(b"\n", b"z")
                                                              .replace(b'"', b"")), "yaml")
    # a block read after the last 64 bytes of the one before, which start with the key
    # in the middle of a line: no line starts there
    mid_line = b"y" * ((1 << 16) - 64) + b"furncheck: 1" + b"z" * 100
    assert not detect.declares_design_at_large(io.BytesIO(mid_line), "yaml")
    # beyond SNIFF_LIMIT nothing is read: a data file of hundreds of MB costs no more
    monkeypatch.setattr(detect, "SNIFF_LIMIT", 4 << 16)
    late = b"y" * (5 << 16) + b"\nfurncheck: 1\n"
    assert not detect.declares_design_at_large(io.BytesIO(late), "yaml")
    assert detect.declares_design_at_large(io.BytesIO(late[-(3 << 16):]), "yaml")


# --- files that are no designs ------------------------------------------------------------

def test_yaml_and_json_files_without_a_furncheck_key_are_skipped_and_counted(checked_paths,
                                                                              tmp_path):
    """A project folder: package.json, tsconfig.json, node_modules/x/package.json, a CI
    workflow that mentions furncheck in a command, a compose file with a nested furncheck
    key, and a package.json depending on a package named furncheck: 6 files that are no
    designs.  The designs: a YAML and a JSON one, and a YAML design with a syntax error (it
    starts with its furncheck key: still a design, its report says what is wrong)."""
    tree(tmp_path, {
        "package.json": '{"name": "x", "version": "1.0.0"}',
        "tsconfig.json": '{"compilerOptions": {}}',
        "node_modules/x/package.json": '{"name": "x"}',
        "ci.yml": "jobs:\n  check:\n    steps:\n      - run: furncheck validate designs/\n",
        "compose.yaml": "services:\n  furncheck:\n    image: x\n",
        "deps/package.json": '{"dependencies": {"furncheck": "^1.0"}}',
        "designs/shelf.yaml": DESIGN,
        "designs/table.json": '{"furncheck": 1, "planks": []}',
        "designs/broken.yaml": "furncheck: 1\nplanks: [\n",
    })
    result = run("validate", str(tmp_path))
    checked = sorted(Path(path).relative_to(tmp_path).as_posix() for path in checked_paths)
    assert checked == ["designs/broken.yaml", "designs/shelf.yaml", "designs/table.json"]
    assert "skipped 6 files without a top-level 'furncheck' key (not designs)" in result.stderr
    line = next(line for line in result.stderr.splitlines() if "skipped 6" in line)
    shown = sorted(str(tmp_path / name) for name in (
        "package.json", "tsconfig.json", "node_modules/x/package.json", "ci.yml",
        "compose.yaml", "deps/package.json"))
    assert line.endswith(f"(not designs): {', '.join(shown[:5])} and 1 more")


def test_an_emptied_design_in_a_scanned_folder_is_named_first_among_the_skipped(tmp_path):
    """A design file emptied by mistake (0 bytes) has no furncheck key: a scan skips it as
    no design (contract section 4), and the line that counts the skipped files names it
    first, marked empty, before six non-designs whose names sort before it (five names
    shown, then how many more); a file of comments alone is empty too.  The folder's
    other design is checked."""
    files = {"shelf.yaml": DESIGN, "stool.yaml": "", "notes.yaml": "# to do\n\n# later\n"}
    files.update({f"a{k}.json": '{"name": "x"}' for k in range(6)})
    tree(tmp_path, files)
    result = run("validate", str(tmp_path))
    line = result.stderr.strip().splitlines()[-1]
    assert line.endswith(
        "skipped 8 files without a top-level 'furncheck' key (not designs): "
        f"{tmp_path / 'notes.yaml'} (empty), {tmp_path / 'stool.yaml'} (empty), "
        f"{tmp_path / 'a0.json'}, {tmp_path / 'a1.json'}, {tmp_path / 'a2.json'} and 3 more")
    assert "1 design:" in result.stdout


@pytest.mark.skipif(sys.platform == "win32", reason="a newline in a file name")
def test_a_skipped_file_whose_name_holds_a_newline_is_named_on_one_line(tmp_path):
    """A name is written quoted with its escapes where it is not printable text: the
    skipped files' line stays one line, and no part of a name reads as a line of its own
    (a workflow annotation, '::error ...', in GitHub's log)."""
    tree(tmp_path, {"shelf.yaml": DESIGN, "x\n::error file=a.yaml::y.json": "{}"})
    result = run("validate", str(tmp_path), "--format", "github")
    assert not any(line.startswith("::error file=a.yaml") for line in
                   result.stderr.splitlines() + result.stdout.splitlines())
    (line,) = [line for line in result.stderr.splitlines() if "skipped 1 file" in line]
    assert line.endswith(repr(str(tmp_path / "x\n::error file=a.yaml::y.json")))


@pytest.mark.parametrize(("text", "fmt", "expected"), [
    ("furncheck: 1\n", "yaml", True),
    ("# a comment\n---\nfurncheck: 1\n", "yaml", True),
    ("name: x\nfurncheck: 1\n", "yaml", True),            # not the first key
    ("{name: x, furncheck: 1}", "yaml", True),            # flow mapping
    ('"furncheck": 1\n', "yaml", True),                   # quoted key
    ("a:\n  furncheck: 1\n", "yaml", False),              # nested
    ("- furncheck: 1\n", "yaml", False),                  # a list at the top
    ("furncheck_version: 1\n", "yaml", False),
    ("furncheck\n", "yaml", False),                       # a scalar document
    ("x: 1\n---\nfurncheck: 1\n", "yaml", False),         # only the first document counts
    ("name: [\nfurncheck: 1\n", "yaml", True),            # broken, key at a line start
    ("text: [furncheck\n", "yaml", False),                # broken, no key
    ('{"furncheck": 1}', "json", True),
    ('{"a": {"furncheck": 1}}', "json", False),
    ('["furncheck"]', "json", False),
    ('{"furncheck": 1,', "json", True),                   # broken JSON with the key
    ('{"name": "furncheck",', "json", False),             # broken JSON, no key
    ("{furncheck: 1}", "json", True),                     # YAML in a .json file: a design
    ("furncheck: 1\nplanks: []\n", "json", True),          # (with a JSON syntax error)
    # a 'furncheck' that holds a mapping or list is no format version: a GitLab CI job
    ("furncheck:\n  stage: test\n  script: [furncheck validate .]\n", "yaml", False),
    ("furncheck: {stage: test}\n", "yaml", False),
    ("stages: [test]\nfurncheck:\n  - a\n", "yaml", False),
    ('{"furncheck": {"stage": "test"}}', "json", False),
    ('{"furncheck": [1]}', "json", False),
    ("furncheck:\n  1\n", "yaml", True),                  # a version on its own line
    ("furncheck: # the format\n  1\n", "yaml", True),
    ("furncheck:\nplanks: []\n", "yaml", True),            # no version: a design's error
    ("furncheck: two\n", "yaml", True),
    ('{"furncheck": null}', "json", True),
])
def test_declares_design(text, fmt, expected):
    assert declares_design(text.encode(), fmt) is expected


def test_a_file_that_is_no_design_is_counted_once(checked_paths, tmp_path):
    """A folder named twice, or named and one of its files named with --skip-non-designs,
    skips its package.json once (it was counted once per scan); a result cache inside the
    scanned folder is not scanned, so a warm run says what a cold one says (its entries
    were counted as files without a furncheck key from the second run on)."""
    tree(tmp_path, {"d/package.json": '{"name": "x"}', "d/a.yaml": DESIGN})
    folder = str(tmp_path / "d")
    for args in ((folder, folder), (folder, folder + "/."),
                 (folder, folder + "/package.json", "--skip-non-designs")):
        result = run("validate", *args, "--no-cache")
        assert "skipped 1 file without" in result.stderr, args
    cache = str(tmp_path / "d" / "results-cache")
    cold = run("validate", folder, "--cache-dir", cache)
    warm = run("validate", folder, "--cache-dir", cache)
    uncached = run("validate", folder, "--cache-dir", cache, "--no-cache")
    assert list(Path(cache).rglob("*.*"))
    assert cold.stderr == warm.stderr == uncached.stderr
    assert "skipped 1 file without" in warm.stderr
    assert cold.stdout == warm.stdout == uncached.stdout
    # the cache's folder named as the folder to scan is scanned (it holds no design)
    named = run("validate", cache, "--cache-dir", cache)
    assert "no design files" in named.output
    # nor is it scanned while another cache is in use: its entries' folder holds a
    # CACHEDIR.TAG (the Cache Directory Tagging Specification), and a scan enters no
    # folder that holds one (its pieces were listed as files without a furncheck key)
    tag = Path(cache) / "v1" / "CACHEDIR.TAG"
    assert tag.read_bytes().startswith(b"Signature: 8a477f597d28d172789f06886806bc55")
    (Path(cache) / ".gitignore").unlink()           # a folder the user made beforehand
    other = run("validate", folder, "--cache-dir", str(tmp_path / "other"))
    assert other.stderr == cold.stderr and other.stdout == cold.stdout


def test_a_named_file_is_always_checked(checked_paths, tmp_path):
    """A hidden, git-ignored, excluded file that is no design and no YAML, named on the
    command line, is checked; with --skip-non-designs the named YAML/JSON files without a
    furncheck key and files of other types are left out (and counted)."""
    tree(tmp_path, {".git/HEAD": "", ".gitignore": ".notes.txt\nci.yml\n",
                    ".notes.txt": "hello", "ci.yml": "on: push\n", "d.yaml": DESIGN})
    named = [str(tmp_path / name) for name in (".notes.txt", "ci.yml", "d.yaml")]
    run("validate", *named, "--exclude", "*.yml")
    assert checked_paths == named
    checked_paths.clear()
    result = run("validate", *named, "--skip-non-designs", "--no-cache")
    assert checked_paths == named[2:]
    assert "skipped 2 files without a top-level" in result.stderr


# --- symlinks -----------------------------------------------------------------------------

def symlink(link: Path, target: Path) -> None:
    try:
        os.symlink(target, link, target_is_directory=True)
    except (OSError, NotImplementedError):
        pytest.skip("symlinks cannot be made here")


def test_symlinked_folders_are_followed_once(tmp_path):
    """real/ holds a.yaml; 'alias' links to real/ (listed under its real path only, the
    real folder being searched first); 'outside' links to a folder outside the tree
    (followed); real/loop links back to the top (a loop: not entered again)."""
    top = tmp_path / "top"
    tree(top, {"real/a.yaml": DESIGN})
    tree(tmp_path, {"elsewhere/b.yaml": DESIGN})
    symlink(top / "alias", top / "real")
    symlink(top / "outside", tmp_path / "elsewhere")
    symlink(top / "real" / "loop", top)
    assert found(top) == ["outside/b.yaml", "real/a.yaml"]


def test_a_symlinked_file_is_listed_by_its_targets_path_where_the_scan_finds_it(tmp_path):
    """a.yaml -> z.yaml beside it: listed once, as z.yaml (as a linked folder is listed
    by its real path; a.yaml, first in name order, hid z.yaml); b.yaml -> a file outside
    the tree: listed as b.yaml (the scan finds no other path of it)."""
    tree(tmp_path, {"top/z.yaml": DESIGN, "elsewhere/x.yaml": DESIGN})
    symlink(tmp_path / "top" / "a.yaml", tmp_path / "top" / "z.yaml")
    symlink(tmp_path / "top" / "b.yaml", tmp_path / "elsewhere" / "x.yaml")
    assert found(tmp_path / "top") == ["b.yaml", "z.yaml"]
    assert collect([str(tmp_path / "top")], ScanOptions()).sources == [
        str(tmp_path / "top" / "b.yaml"), str(tmp_path / "top" / "z.yaml")]


def test_a_folder_that_links_to_itself_ends(tmp_path):
    """self -> . and a pair a/to_b -> b, b/to_a -> a: every folder is searched once."""
    tree(tmp_path, {"a/x.yaml": DESIGN, "b/y.yaml": DESIGN})
    symlink(tmp_path / "self", tmp_path)
    symlink(tmp_path / "a" / "to_b", tmp_path / "b")
    symlink(tmp_path / "b" / "to_a", tmp_path / "a")
    assert found(tmp_path) == ["a/x.yaml", "b/y.yaml"]


def test_a_file_reached_twice_is_checked_once(tmp_path):
    """A file named, and also found in a named folder through a symlinked folder."""
    tree(tmp_path, {"real/a.yaml": DESIGN})
    symlink(tmp_path / "alias", tmp_path / "real")
    collected = collect([str(tmp_path / "real" / "a.yaml"), str(tmp_path / "alias")],
                        ScanOptions())
    assert collected.sources == [str(tmp_path / "real" / "a.yaml")]
