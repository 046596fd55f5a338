"""``[tool.furncheck]`` in pyproject.toml (contract section 4; ``furncheck.config``).

Precedence is checked through the command line: with the fake checker of ``test_cli``
where only the choice of files or the format matters, and with the real checker where the
statics model matters (designs/stool.yaml: its 12 mm seat sags beyond span / 400 in the
elastic model, which rigid planks cannot do, so the file is invalid (exit 1) in the
elastic model and valid (exit 0) in the rigid one; README, "Using it").
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
from test_cli import run, write

from furncheck.config import Config, ConfigError, load_config

ROOT = Path(__file__).resolve().parents[1]


def pyproject(folder: Path, table: str) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "pyproject.toml"
    path.write_text(f"[project]\nname = 'x'\n\n[tool.furncheck]\n{table}\n")
    return path


def test_no_pyproject_means_no_options(tmp_path):
    (tmp_path / ".git").mkdir()           # the search stops at the repository's top
    assert load_config([str(tmp_path)]) == Config()


def test_the_nearest_pyproject_with_a_furncheck_table_is_used(tmp_path):
    """repo/pyproject.toml has the table; repo/sub/pyproject.toml has none (passed over);
    a file in repo/sub/designs gets repo's options, anchored at repo/."""
    (tmp_path / ".git").mkdir()
    path = pyproject(tmp_path, 'model = "rigid"\nexclude = ["drafts"]\ncache-dir = "c"')
    (tmp_path / "sub" / "designs").mkdir(parents=True)
    (tmp_path / "sub" / "pyproject.toml").write_text("[project]\nname = 'sub'\n")
    config = load_config([str(tmp_path / "sub" / "designs" / "a.yaml")])
    assert config == Config(path=str(path), folder=str(tmp_path), exclude=("drafts",),
                            model="rigid", cache_dir=str(tmp_path / "c"))


def test_the_search_stops_at_the_repository_top(tmp_path):
    """A pyproject.toml with the table above the repository does not count."""
    pyproject(tmp_path, 'model = "rigid"')
    (tmp_path / "repo" / ".git").mkdir(parents=True)
    assert load_config([str(tmp_path / "repo")]) == Config()


@pytest.mark.parametrize(("table", "message"), [
    ('formt = "json"', "unknown key 'formt' (did you mean 'format'? known: cache, "),
    ('format = "yml"', "format: expected one of text, json, junit, github, sarif, got 'yml'"),
    ("jobs = 0", "jobs: expected a whole number of at least 1, got 0"),
    ("jobs = true", "jobs: expected a whole number"),
    ('model = "steel"', "model: expected one of elastic, rigid"),
    ('cache = "no"', "cache: expected true or false"),
    ("exclude = [1]", "exclude: expected a list of gitignore patterns"),
    ('cache-dir = "a\\u0000b"', "cache-dir: expected a folder, got 'a\\x00b'"),
    ("furncheck = 1", "unknown key 'furncheck'"),
])
def test_bad_options_are_one_line_naming_the_file_and_key(checked_paths, tmp_path, monkeypatch,
                                                         table, message):
    path = pyproject(tmp_path, table)
    (design,) = write(tmp_path, "valid.yaml")
    result = run("validate", design)
    assert result.exit_code == 2 and checked_paths == []
    assert result.stderr.splitlines() == [result.stderr.strip()]
    assert str(path) in result.stderr and message in result.stderr
    with pytest.raises(ConfigError):
        load_config([design])


def test_broken_toml_is_one_line_and_exit_2(checked_paths, tmp_path):
    (tmp_path / "pyproject.toml").write_text("[tool.furncheck\n")
    (design,) = write(tmp_path, "valid.yaml")
    result = run("validate", design)
    assert result.exit_code == 2 and "not valid TOML" in result.stderr
    assert "Traceback" not in result.output


@pytest.mark.parametrize("text, found", [
    ("[tool]\nfurncheck = {jobs = 3}\n", 3),
    ('tool.furncheck.jobs = 3\n', 3),
    ('[ tool . "furncheck" ]\njobs = 3\n', 3),
    ("[tool.ruff]\nline-length = 100\n[project]\nname = 'furncheck'\n", None),
    ("this is not [TOML at all\n", None),
])
def test_a_pyproject_is_parsed_only_where_it_may_hold_the_table(tmp_path, text, found):
    """Every way TOML can write tool.furncheck is read (a bare [tool] table, a dotted key,
    a spaced and quoted header); a file that names no such table is passed over unparsed,
    even when it is not valid TOML (it says nothing about furncheck)."""
    (tmp_path / "pyproject.toml").write_text(text)
    (design,) = write(tmp_path, "valid.yaml")
    assert load_config([design]).jobs == found


def test_the_command_line_wins_over_the_format(checked_paths, tmp_path):
    pyproject(tmp_path, 'format = "json"')
    (design,) = write(tmp_path, "valid.yaml")
    assert json.loads(run("validate", design).stdout)["summary"]["valid"] == 1
    assert run("validate", design, "--format", "text").stdout.endswith(
        "1 design: 1 valid, 0 invalid, 0 errors\n")


def test_excludes_of_config_and_command_line_add_up(checked_paths, tmp_path, monkeypatch):
    """Config: 'drafts' (any depth) and '/top.yaml' (anchored at the pyproject's folder,
    tmp_path); command line: 'old' (relative to the current folder, also tmp_path).  The
    scan of tmp_path/designs keeps only designs/a.yaml."""
    pyproject(tmp_path, 'exclude = ["drafts", "/designs/top.yaml"]')
    write(tmp_path, "designs/a.yaml", "designs/top.yaml", "designs/drafts/b.yaml",
          "designs/old/c.yaml")
    monkeypatch.chdir(tmp_path)
    run("validate", "designs", "--exclude", "old")
    assert [Path(path).as_posix() for path in checked_paths] == ["designs/a.yaml"]


def test_jobs_come_from_the_config_unless_given(checked_paths, tmp_path, monkeypatch):
    from furncheck import batch

    used = []
    original = batch.entries
    monkeypatch.setattr(batch, "entries",
                        lambda sources, fmt, jobs, *rest: used.append(jobs)
                        or original(sources, fmt, 1, *rest))
    pyproject(tmp_path, "jobs = 3\ncache = false")
    (design,) = write(tmp_path, "valid.yaml")
    run("validate", design)
    run("validate", design, "--jobs", "2")
    assert used == [3, 2]


def test_cache_settings_come_from_the_config(checked_paths, tmp_path, monkeypatch):
    """cache-dir is relative to the pyproject's folder; cache = false turns it off, and
    --cache on the command line turns it on again."""
    monkeypatch.delenv("FURNCHECK_CACHE_DIR")
    path = pyproject(tmp_path, 'cache-dir = "results-cache"')
    (design,) = write(tmp_path, "valid.yaml")
    run("validate", design)
    assert list((tmp_path / "results-cache").rglob("*")), "nothing cached"
    shutil.rmtree(tmp_path / "results-cache")
    path.write_text('[tool.furncheck]\ncache = false\ncache-dir = "results-cache"\n')
    run("validate", design)
    assert not (tmp_path / "results-cache").exists()
    run("validate", design, "--cache")
    assert (tmp_path / "results-cache").exists()


@pytest.fixture
def stool(tmp_path) -> Path:
    """designs/stool.yaml copied beside a pyproject.toml setting the rigid model."""
    pyproject(tmp_path, 'model = "rigid"')
    target = tmp_path / "stool.yaml"
    shutil.copy(ROOT / "designs" / "stool.yaml", target)
    return target


def test_the_model_comes_from_the_config_and_the_command_line_wins(stool):
    assert run("validate", str(stool)).exit_code == 0              # rigid: valid
    assert run("validate", str(stool), "--model", "elastic").exit_code == 1


def test_suggest_and_range_read_the_model_too(stool):
    """The stool file sets no model (elastic by default, where it sags): suggest says it is
    valid, so it ran in the config's rigid model; range of seat.z reads the same as with
    --model rigid and differs from --model elastic (where the sagging seat is valid
    nowhere)."""
    suggested = run("suggest", str(stool), "--format", "json")
    assert suggested.exit_code == 0 and json.loads(suggested.stdout)["valid"] is True
    ranges = {model: run("range", str(stool), "seat.z", "--format", "json", *flags).stdout
              for model, flags in (("config", ()), ("rigid", ("--model", "rigid")),
                                   ("elastic", ("--model", "elastic")))}
    assert ranges["config"] == ranges["rigid"] != ranges["elastic"]


def test_standard_input_gets_the_options_of_its_stdin_filename(stool, tmp_path,
                                                                 monkeypatch):
    """An editor pipes the stool (elastic: invalid) from another folder as '-' with
    --stdin-filename naming it beside the pyproject.toml that sets the rigid model: the
    search starts in that file's folder, so it reads rigid (valid, exit 0), as the file
    itself does; without --stdin-filename the current folder's (none: elastic, exit 1).
    suggest and range alike (suggest says valid: it ran rigid)."""
    elsewhere = tmp_path / "elsewhere"
    (elsewhere / ".git").mkdir(parents=True)
    monkeypatch.chdir(elsewhere)
    from click.testing import CliRunner

    from furncheck.cli.main import main

    text = stool.read_text()

    def piped(*args: str):
        return CliRunner().invoke(main, list(args), input=text)

    assert piped("validate", "-", "--stdin-filename", str(stool)).exit_code == 0
    assert piped("validate", "-").exit_code == 1
    suggested = piped("suggest", "-", "--stdin-filename", str(stool), "--format", "json")
    assert json.loads(suggested.stdout)["valid"] is True
    ranges = piped("range", "-", "seat.z", "--stdin-filename", str(stool), "--format",
                   "json")
    assert ranges.exit_code == 0
    assert json.loads(ranges.stdout)["ranges"] == json.loads(
        run("range", str(stool), "seat.z", "--format", "json").stdout)["ranges"]


def test_no_flags_turn_the_configs_true_off(checked_paths, tmp_path, monkeypatch):
    """force-exclude = true and skip-non-designs = true in [tool.furncheck]: a named file
    in an excluded folder and a named YAML file that is no design are left out, and
    --no-force-exclude / --no-skip-non-designs check them for one run (both reach the
    checker, here the fake of test_cli), each flag on its own turning its key off."""
    pyproject(tmp_path, 'exclude = ["drafts"]\nforce-exclude = true\n'
                        'skip-non-designs = true')
    write(tmp_path / "drafts", "d.yaml")
    (tmp_path / "ci.yml").write_text("stages: [test]\n")
    monkeypatch.chdir(tmp_path)
    assert run("validate", "drafts/d.yaml", "ci.yml").exit_code == 0
    assert checked_paths == []
    result = run("validate", "drafts/d.yaml", "ci.yml", "--no-force-exclude",
                 "--no-skip-non-designs", "--no-cache")
    assert checked_paths == ["drafts/d.yaml", "ci.yml"] and result.exit_code == 0
    checked_paths.clear()
    run("validate", "drafts/d.yaml", "ci.yml", "--no-force-exclude", "--no-cache")
    assert checked_paths == ["drafts/d.yaml"]
    checked_paths.clear()
    run("validate", "drafts/d.yaml", "ci.yml", "--no-skip-non-designs", "--no-cache")
    assert checked_paths == ["ci.yml"]


def test_the_cache_folder_is_the_command_lines_then_the_variables_then_the_configs(
        checked_paths, tmp_path, monkeypatch):
    """--cache-dir, else $FURNCHECK_CACHE_DIR (a CI job's variable), else cache-dir of
    [tool.furncheck]: the variable used to lose to the repository's file, so a CI recipe
    that sets it and saves that folder saved an empty one."""
    pyproject(tmp_path, 'cache-dir = "from-config"')
    (design,) = write(tmp_path, "valid.yaml")
    monkeypatch.setenv("FURNCHECK_CACHE_DIR", str(tmp_path / "from-variable"))
    run("validate", design)
    assert list((tmp_path / "from-variable").rglob("*")) and \
        not (tmp_path / "from-config").exists()
    run("validate", design, "--cache-dir", str(tmp_path / "from-option"))
    assert list((tmp_path / "from-option").rglob("*")) and \
        not (tmp_path / "from-config").exists()
    monkeypatch.delenv("FURNCHECK_CACHE_DIR")
    run("validate", design)
    assert list((tmp_path / "from-config").rglob("*"))
