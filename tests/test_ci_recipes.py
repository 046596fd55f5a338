"""What CI recipes rely on: the pre-commit hook, ``-o`` written atomically, a design on
standard input, ``python -m furncheck``, and the progress bar only on a terminal.

The pre-commit hook is exercised in a temporary git repository with pre-commit itself:
the hook of ``.pre-commit-hooks.yaml`` (its entry, file types and options exactly) as a
``repo: local`` hook run by this test's Python environment (``language: system``), so no
hook environment has to be installed from a package index.  The full install from the
worktree (``pre-commit try-repo``, which builds furncheck and its dependencies into a new
environment) runs when FURNCHECK_TEST_PRE_COMMIT_INSTALL=1.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml
from test_cli import run, write

from furncheck import files as files_module

ROOT = Path(__file__).resolve().parents[1]
HOOKS = ROOT / ".pre-commit-hooks.yaml"


# --- pre-commit ---------------------------------------------------------------------------

def hook_definition() -> dict:
    (hook,) = yaml.safe_load(HOOKS.read_text())
    return hook


def test_the_hook_definition_is_complete():
    hook = hook_definition()
    assert hook["id"] == "furncheck" and hook["language"] == "python"
    assert hook["entry"].split()[:2] == ["furncheck", "validate"]
    # the changed files that are no designs, or that [tool.furncheck] excludes, are left
    # out, as a CI run of the folder leaves them out
    assert {"--skip-non-designs", "--force-exclude"} <= set(hook["entry"].split()[2:])
    assert set(hook["types_or"]) == {"yaml", "json"}


def git(repository: Path, *args: str) -> None:
    subprocess.run(["git", *args], cwd=repository, check=True, capture_output=True)


@pytest.fixture
def repository(tmp_path) -> Path:
    """A git repository holding a valid design (rigid stool), an invalid one (bench that
    tips), a CI workflow and a package.json (no designs), all staged."""
    if shutil.which("git") is None or shutil.which("pre-commit",
                                                  path=os.path.dirname(sys.executable)) is None:
        pytest.skip("git or pre-commit is not installed")
    repository = tmp_path / "repo"
    (repository / "designs").mkdir(parents=True)
    (repository / ".github" / "workflows").mkdir(parents=True)
    stool = (ROOT / "designs" / "stool.yaml").read_text()
    rigid = stool.replace("furncheck: 1\n", "furncheck: 1\nmodel: rigid\n", 1)
    (repository / "designs" / "stool.yaml").write_text(rigid)
    shutil.copy(ROOT / "designs" / "bench-tips.yaml", repository / "designs")
    (repository / "ci.yml").write_text("on: push\njobs: {}\n")
    (repository / "package.json").write_text('{"name": "shop"}\n')
    git(repository, "init", "-q")
    git(repository, "config", "user.email", "test@example.com")
    git(repository, "config", "user.name", "test")
    return repository


def pre_commit(repository: Path, *args: str) -> subprocess.CompletedProcess:
    environment = dict(os.environ, PRE_COMMIT_HOME=str(repository.parent / "pre-commit-home"),
                       PATH=os.path.dirname(sys.executable) + os.pathsep + os.environ["PATH"])
    return subprocess.run([os.path.join(os.path.dirname(sys.executable), "pre-commit"), *args],
                          cwd=repository, capture_output=True, text=True, env=environment)


def test_the_pre_commit_hook_passes_valid_designs_and_stops_invalid_ones(repository):
    """With only the valid stool staged the hook passes (ci.yml and package.json are passed
    to it too, and skipped: no designs); with the tipping bench staged it fails, and its
    output names the bench's lift-off."""
    hook = {**hook_definition(), "language": "system"}
    (repository / ".pre-commit-config.yaml").write_text(yaml.safe_dump(
        {"repos": [{"repo": "local", "hooks": [hook]}]}))
    git(repository, "add", ".pre-commit-config.yaml", "ci.yml", "package.json",
        "designs/stool.yaml")
    passed = pre_commit(repository, "run")
    assert passed.returncode == 0, passed.stdout + passed.stderr
    assert "furncheck" in passed.stdout and "Passed" in passed.stdout
    git(repository, "add", "designs/bench-tips.yaml")
    failed = pre_commit(repository, "run", "--verbose")
    assert failed.returncode == 1
    assert "Failed" in failed.stdout and "bench-tips.yaml: INVALID" in failed.stdout
    assert "lift-off" in failed.stdout and "stool.yaml: valid" in failed.stdout


@pytest.mark.skipif(os.environ.get("FURNCHECK_TEST_PRE_COMMIT_INSTALL") != "1",
                    reason="installs furncheck and its dependencies into a new environment "
                           "(network, minutes): set FURNCHECK_TEST_PRE_COMMIT_INSTALL=1")
def test_the_hook_installs_from_the_worktree(repository):
    git(repository, "add", "ci.yml", "package.json", "designs/stool.yaml")
    result = pre_commit(repository, "try-repo", str(ROOT), "furncheck")
    assert result.returncode == 0, result.stdout + result.stderr


# --- -o is written atomically -------------------------------------------------------------

class _Interrupted:
    """A stream that takes half of what is written, then is interrupted (Ctrl-C)."""

    def __init__(self, stream):
        self.stream = stream

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.stream.close()

    def write(self, data):
        self.stream.write(data[:len(data) // 2])
        self.stream.flush()
        raise KeyboardInterrupt

    def __getattr__(self, name):
        return getattr(self.stream, name)


def test_an_interrupted_report_leaves_the_old_file(checked_paths, tmp_path, monkeypatch):
    """-o report.json exists from an earlier run; this run is interrupted halfway through
    writing the new report: report.json still holds the old report, whole, and no
    temporary file is left in its folder."""
    valid, bad = write(tmp_path / "designs", "valid.yaml", "bad.yaml")
    out = tmp_path / "out"
    out.mkdir()
    report = out / "report.json"
    report.write_text("old report\n")
    real_fdopen = os.fdopen
    monkeypatch.setattr(files_module.os, "fdopen",
                        lambda *args, **kwargs: _Interrupted(real_fdopen(*args, **kwargs)))
    result = run("validate", valid, bad, "--format", "json", "-o", str(report))
    assert result.exit_code == 130          # 128 + SIGINT: no finished run exits so
    assert "furncheck: interrupted (SIGINT); the report is incomplete" in result.output
    assert report.read_text() == "old report\n"
    assert sorted(path.name for path in out.iterdir()) == ["report.json"]
    monkeypatch.undo()
    run("validate", valid, bad, "--format", "json", "-o", str(report), "--no-cache")
    assert json.loads(report.read_text())["summary"]["designs"] == 2


STOPPED_RUN = """
import os, sys, time
from pathlib import Path
import furncheck.batch as batch
from furncheck.cli.main import run

marker = Path(sys.argv.pop(1))
parent = os.getpid()
in_workers = "--jobs" in sys.argv and sys.argv[sys.argv.index("--jobs") + 1] != "1"
batch.PARALLEL_AFTER = 0.0

def slow(path, *args, **kwargs):    # under way: the parent may be signalled now
    if in_workers and os.getpid() == parent:
        return batch.Entry(True, False, path)       # the first design, checked here
    marker.write_text("checking")
    time.sleep(60)

batch.entry_of = slow
sys.argv[0] = "furncheck"
run()
"""


@pytest.mark.parametrize("jobs", ["1", "2"])
@pytest.mark.parametrize("name, code", [("SIGTERM", 143), ("SIGINT", 130)])
def test_a_signalled_run_exits_with_its_own_code(tmp_path, name, code, jobs):
    """The console script stopped by SIGTERM (a CI's cancel or timeout) or SIGINT while
    it checks, here or in its worker pool (--jobs 2, the workers busy for a minute): one
    line on stderr, exit 128 + the signal's number (143, 130: no finished run exits so,
    where 1 means 'some design invalid'), at once (the busy workers are stopped, not
    waited for: an interrupted run with a pool took seconds to exit, and a second signal
    in that time hung it), the -o file as it was and no temporary copy left beside it
    (SIGTERM used to kill the process on the spot, leaving '.report.json.XXXX.tmp')."""
    import signal
    import time

    valid, bad, *more = write(tmp_path / "designs", "valid.yaml", "bad.yaml",
                              *[f"valid{k}.yaml" for k in range(4)])
    out = tmp_path / "out"
    out.mkdir()
    report = out / "report.json"
    report.write_text("old report\n")
    marker = tmp_path / "marker"
    process = subprocess.Popen(
        [sys.executable, "-c", STOPPED_RUN, str(marker), "validate", valid, bad, *more,
         "--no-cache", "--jobs", jobs, "--format", "json", "-o", str(report)],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 60
        while not marker.exists() and process.poll() is None and time.monotonic() < deadline:
            time.sleep(0.05)
        assert marker.exists(), process.communicate()
        process.send_signal(getattr(signal, name))
        _, stderr = process.communicate(timeout=30)     # not the workers' minute
    finally:
        if process.poll() is None:
            process.kill()
    assert process.returncode == code
    assert stderr.strip().splitlines() == [
        f"furncheck: interrupted ({name}); the report is incomplete"]
    assert report.read_text() == "old report\n"
    assert sorted(path.name for path in out.iterdir()) == ["report.json"]


def test_after_the_first_signal_the_next_ends_the_run_at_once(monkeypatch):
    """The console script's handler (``cli.main._stop``) stops the run on the first SIGINT
    or SIGTERM and leaves both to their default action from then on: a CI's SIGTERM
    7.5 s after its SIGINT ends the process instead of raising again inside its
    unwinding (which hung it).  An inherited 'ignore' of SIGINT (a shell's trap) does not
    keep Ctrl-C from stopping it either: the handler is installed whatever was there."""
    import signal

    from furncheck.cli import main as cli_main

    monkeypatch.setattr(signal, "signal", lambda number, handler: set_to.append(
        (number, handler)))
    set_to: list = []
    with pytest.raises(KeyboardInterrupt):
        cli_main._stop(signal.SIGINT, None)
    assert set_to == [(signal.SIGINT, signal.SIG_DFL), (signal.SIGTERM, signal.SIG_DFL)]
    set_to.clear()
    with pytest.raises(cli_main._Terminated):
        cli_main._stop(signal.SIGTERM, None)
    assert set_to == [(signal.SIGINT, signal.SIG_DFL), (signal.SIGTERM, signal.SIG_DFL)]


@pytest.mark.parametrize("raised, code", [("KeyboardInterrupt", 130), ("_Terminated", 143)])
def test_a_signal_while_the_options_are_read_is_said_alike(monkeypatch, raised, code):
    """A signal that arrives while the command line is parsed (before the command runs)
    exits the same way as one during the run, not click's 'Aborted!' (exit 1) or a
    traceback."""
    import click

    from furncheck.cli import main as cli_main

    error = KeyboardInterrupt() if raised == "KeyboardInterrupt" else \
        cli_main._Terminated(15)

    def interrupted(*args, **kwargs):
        raise error

    monkeypatch.setattr(click.Group, "parse_args", interrupted)
    result = run("validate", "x.yaml")
    assert result.exit_code == code
    assert result.output.strip().startswith("furncheck: interrupted (SIG")


def test_a_report_never_replaces_a_design_it_checks(tmp_path):
    """-o naming one of the designs (given, found in a folder, or through a symbolic
    link) is refused with one line and exit 2, the design untouched, for validate (and
    its --html page), suggest and range; the report used to replace the design."""
    valid, bad = write(tmp_path / "designs", "valid.yaml", "bad.yaml")
    link = tmp_path / "link.yaml"
    link.symlink_to(valid)
    before = Path(valid).read_text()
    for args in (("validate", bad, valid, "-o", valid),
                 ("validate", str(tmp_path / "designs"), "-o", str(link)),
                 ("validate", valid, "--html", valid),
                 ("suggest", valid, "-o", valid),
                 ("range", valid, "-o", str(link))):
        result = run(*args, "--no-cache") if args[0] == "validate" else run(*args)
        assert result.exit_code == 2, args
        assert result.output.strip().endswith("it is one of the designs to check"), args
        assert Path(valid).read_text() == before


def test_a_missing_report_folder_is_made(checked_paths, tmp_path):
    """-o reports/ci/x.json where reports/ does not exist yet: the folders are made when
    the report is written (as --views makes its own), none by a run refused before it
    writes; below a file, or -o naming a folder ('out/'), one line and exit 2."""
    (valid,) = write(tmp_path / "designs", "valid.yaml")
    report = tmp_path / "reports" / "ci" / "x.json"
    result = run("validate", valid, "--no-cache", "--format", "json", "-o", str(report))
    assert result.exit_code == 0
    assert json.loads(report.read_text())["summary"]["designs"] == 1
    refused = tmp_path / "other" / "x.json"
    assert run("validate", valid, "--exclude", "[", "-o", str(refused)).exit_code == 2
    assert not (tmp_path / "other").exists()
    blocked = tmp_path / "designs" / "valid.yaml" / "x.json"
    result = run("validate", valid, "--no-cache", "-o", str(blocked))
    assert result.exit_code == 2
    assert result.output == (f"furncheck: cannot write the report to {blocked}: "
                             f"{tmp_path / 'designs' / 'valid.yaml'} is a file, not a "
                             "folder\n")
    folder = str(tmp_path / "new") + os.sep
    result = run("validate", valid, "--no-cache", "-o", folder)
    assert result.exit_code == 2 and result.output.endswith("it names a folder\n")
    assert not (tmp_path / "new").exists()


def test_output_keeps_the_files_permissions_and_symlinks(checked_paths, tmp_path):
    """-o over an existing file keeps its permission bits; -o through a symlink replaces
    the file it points to and leaves the link."""
    (valid,) = write(tmp_path, "valid.yaml")
    report = tmp_path / "report.txt"
    report.write_text("old\n")
    report.chmod(0o640)
    link = tmp_path / "link.txt"
    link.symlink_to(report)
    run("validate", valid, "-o", str(link))
    assert link.is_symlink() and report.read_text().startswith(valid)
    assert report.stat().st_mode & 0o777 == 0o640


def test_output_to_dev_stdout_on_a_pipe_and_to_a_long_name(tmp_path):
    """-o /dev/stdout with stdout a pipe writes the report there (it resolved to no file
    at all: 'No such file or directory', exit 2); -o with a 250-byte name works, its
    temporary file named short (it was '.NAME.XXXXXXXX.tmp', past the 255-byte limit)."""
    stool = str(ROOT / "designs" / "stool.yaml")
    args = [sys.executable, "-m", "furncheck", "validate", stool, "--model", "rigid",
            "--no-cache", "-o"]
    piped = subprocess.run([*args, "/dev/stdout"], capture_output=True, text=True)
    assert piped.returncode == 0, piped.stderr
    assert piped.stdout.startswith(f"{stool}: valid")
    long = tmp_path / ("r" * 246 + ".txt")
    named = subprocess.run([*args, str(long)], capture_output=True, text=True)
    assert named.returncode == 0, named.stderr
    assert long.read_text().startswith(f"{stool}: valid")
    assert [path.name for path in tmp_path.iterdir()] == [long.name]


# --- standard input, python -m furncheck --------------------------------------------------

def test_a_design_on_standard_input(tmp_path):
    """'-' reads the design from stdin: the stool in the rigid model is valid; named
    '<stdin>' unless --stdin-filename names it; JSON is recognized by its '{'."""
    text = (ROOT / "designs" / "stool.yaml").read_text()
    result = run_input(text, "validate", "-", "--model", "rigid")
    assert result.exit_code == 0 and result.stdout.startswith("<stdin>: valid")
    named = run_input(text, "validate", "-", "--model", "rigid", "--stdin-filename",
                      "designs/stool.yaml", "--format", "json")
    assert json.loads(named.stdout)["reports"][0]["design"] == "designs/stool.yaml"
    as_json = json.dumps(yaml.safe_load(text))
    assert run_input(as_json, "validate", "-", "--model", "rigid").exit_code == 0
    broken = run_input("furncheck: 1\nplanks: [\n", "validate", "-")
    assert broken.exit_code == 2 and broken.stdout.startswith("<stdin>: error: line ")


def test_suggest_and_range_read_standard_input_too():
    """``suggest -`` and ``range -`` read the design from stdin as ``validate -`` does: the
    same report as for the file, named '<stdin>' or by --stdin-filename; a broken
    document is one line and exit 2."""
    path = ROOT / "designs" / "stool.yaml"
    text = path.read_text()
    for command, extra in (("suggest", ("--max-suggestions", "1")), ("range", ("seat.z",))):
        from_file = run_input("", command, str(path), *extra, "--format", "json")
        named = run_input(text, command, "-", *extra, "--format", "json",
                          "--stdin-filename", str(path))
        assert named.exit_code == from_file.exit_code == 0, named.output
        assert named.stdout == from_file.stdout
        plain = run_input(text, command, "-", *extra)
        assert plain.exit_code == 0 and plain.stdout.startswith("<stdin>")
        broken = run_input("furncheck: 1\nplanks: [\n", command, "-")
        assert broken.exit_code == 2 and len(broken.output.splitlines()) == 1
        assert broken.output.startswith("furncheck: <stdin>:2: YAML syntax error")
    for command in ("validate", "suggest", "range"):        # a forgotten '-'
        named = run_input(text, command, str(path), "--stdin-filename", "x.yaml")
        assert named.exit_code == 2 and named.output == (
            "furncheck: --stdin-filename names the design read from '-' (standard input), "
            "and no '-' was given\n")


def test_a_closed_standard_input_is_an_error_of_its_design_alone():
    """Started with standard input closed ('<&-'), '-' is an error entry of its own and
    the other files are still checked (``validate``: the stool's report follows, exit 2);
    ``suggest -`` and ``range -`` say so in one line, exit 2.  It was 'internal error:
    AttributeError' with no report at all."""
    stool = str(ROOT / "designs" / "stool.yaml")
    for args, lines in ((["validate", "-", stool, "--model", "rigid", "--no-cache"], None),
                        (["suggest", "-"], 1), (["range", "-"], 1)):
        result = subprocess.run([sys.executable, "-m", "furncheck", *args],
                                capture_output=True, text=True, preexec_fn=lambda: os.close(0))
        assert result.returncode == 2, result.stderr
        assert "Traceback" not in result.stderr and "internal error" not in result.stderr
        if lines is None:
            assert result.stdout.startswith(
                "<stdin>: error: cannot read standard input: it is closed\n"
                f"{stool}: valid"), result.stdout
        else:
            assert result.stderr == \
                "furncheck: <stdin>: cannot read standard input: it is closed\n"


def test_a_closed_standard_output_and_an_empty_path_are_errors():
    """Started with standard output closed ('>&-'), each command says so and exits 2 (the
    report was lost without a word and validate exited 0).  An empty path (an unset
    variable in a script) is an error entry named '' (it read ': error: : no such
    file')."""
    stool = str(ROOT / "designs" / "stool.yaml")
    for args in (["validate", stool, "--no-cache"], ["suggest", stool],
                 ["range", stool, "seat.z"]):
        result = subprocess.run([sys.executable, "-m", "furncheck", *args], text=True,
                                stderr=subprocess.PIPE, preexec_fn=lambda: os.close(1))
        assert result.returncode == 2
        assert result.stderr == \
            "furncheck: cannot write the report to standard output: it is closed\n"
    empty = run("validate", "", stool, "--model", "rigid", "--no-cache")
    assert empty.exit_code == 2
    assert empty.stdout.startswith(f"'': error: an empty path names no file\n{stool}: valid")


def run_input(text: str, *args: str):
    from click.testing import CliRunner

    from furncheck.cli.main import main

    return CliRunner().invoke(main, list(args), input=text)


def test_python_m_furncheck_is_the_command():
    result = subprocess.run([sys.executable, "-m", "furncheck", "--version"],
                            capture_output=True, text=True, check=True)
    assert result.stdout.startswith("furncheck ")
    helped = subprocess.run([sys.executable, "-m", "furncheck", "validate", "--help"],
                            capture_output=True, text=True, check=True)
    assert helped.stdout.startswith("Usage: furncheck validate")


# --- progress bar -------------------------------------------------------------------------

def test_no_progress_bar_when_stderr_is_no_terminal(checked_paths, tmp_path):
    from furncheck.cli.validate import PROGRESS_MIN_FILES

    write(tmp_path, *[f"valid{i:03d}.yaml" for i in range(PROGRESS_MIN_FILES)])
    result = run("validate", str(tmp_path), "--jobs", "1")
    assert result.exit_code == 0 and result.stderr == ""


def test_the_progress_bar_counts_the_files_checked(checked_paths, tmp_path, monkeypatch):
    """On a terminal, PROGRESS_MIN_FILES files to check get a bar of that length, advanced
    once per file; a warm run (every file from the cache), a run with one file fewer, a
    run whose report goes to the terminal too (no -o), and one in a CI job (CI set: a
    runner that gives the job a terminal would log every frame) or on a dumb terminal
    get none."""
    import click

    from furncheck.cli import validate as validate_module

    bars = []

    class Bar:
        def __init__(self, length, **options):
            self.length, self.steps, self.file = length, [], options["file"]
            bars.append(self)

        def __enter__(self):
            return self

        def __exit__(self, *exc):
            return False

        def update(self, steps):
            self.steps.append(steps)

    monkeypatch.setattr(validate_module, "_is_terminal", lambda stream: True)
    monkeypatch.setattr(click, "progressbar", Bar)
    monkeypatch.delenv("CI", raising=False)             # the suite may run in a CI job
    monkeypatch.setenv("TERM", "xterm")
    count = validate_module.PROGRESS_MIN_FILES
    write(tmp_path / "many", *[f"valid{i:03d}.yaml" for i in range(count)])
    write(tmp_path / "fewer", *[f"valid{i:03d}.yaml" for i in range(count - 1)])
    report = ["-o", str(tmp_path / "report.txt")]
    run("validate", str(tmp_path / "many"), "--jobs", "1", "--no-cache")
    assert bars == []                                  # the report goes to the terminal
    run("validate", str(tmp_path / "many"), "--jobs", "1", *report)
    assert [(bar.length, bar.steps) for bar in bars] == [(count, [1] * count)]
    run("validate", str(tmp_path / "many"), "--jobs", "1", *report)
    run("validate", str(tmp_path / "fewer"), "--jobs", "1", *report)
    assert len(bars) == 1
    for name, value in (("CI", "true"), ("TERM", "dumb")):   # a CI job given a terminal
        with monkeypatch.context() as scoped:
            scoped.setenv(name, value)
            run("validate", str(tmp_path / "many"), "--jobs", "1", "--no-cache", *report)
        assert len(bars) == 1, name


# --- the README's CI recipes --------------------------------------------------------------

def readme_ci_blocks() -> list[str]:
    """The YAML blocks of the README's "In CI" section."""
    text = (ROOT / "README.md").read_text()
    section = text.split("### In CI", 1)[1].split("\n### ", 1)[0]
    return [block.split("```", 1)[0] for block in section.split("```yaml\n")[1:]]


def test_the_readme_recipes_are_yaml_whose_commands_furncheck_accepts(checked_paths,
                                                                     tmp_path, monkeypatch):
    """Three blocks (pre-commit, GitHub Actions, GitLab CI) that parse; the pre-commit one
    names this repository's hook; every furncheck command line in the jobs runs on a
    designs/ folder (exit 0, no usage error) and writes the report files the next steps
    upload."""
    import shlex

    blocks = readme_ci_blocks()
    assert len(blocks) == 3
    pre_commit_config, github, gitlab = (yaml.safe_load(block) for block in blocks)
    assert pre_commit_config["repos"][0]["hooks"][0]["id"] == hook_definition()["id"]
    commands = [step["run"] for step in github["jobs"]["furncheck"]["steps"] if "run" in step]
    commands += gitlab["furncheck"]["script"]
    commands = [part.strip() for command in commands for part in command.split("||")
                if part.strip().startswith("furncheck ")]
    assert len(commands) == 4
    write(tmp_path / "designs", "valid.yaml")
    monkeypatch.chdir(tmp_path)
    for command in commands:
        result = run(*shlex.split(command)[1:])
        assert result.exit_code == 0, (command, result.output)
    upload = [step for step in github["jobs"]["furncheck"]["steps"]
              if step.get("uses", "").startswith("github/codeql-action/upload-sarif")]
    assert json.loads(Path(upload[0]["with"]["sarif_file"]).read_text())["version"] == "2.1.0"
    assert Path(gitlab["furncheck"]["artifacts"]["reports"]["junit"]).read_text().startswith(
        "<?xml")


def test_the_readme_recipes_keep_the_cache_whatever_the_verdict():
    """A job that finds an invalid design fails (exit 1), and both platforms save their
    caches only from jobs that succeed unless told otherwise (actions/cache's post step,
    GitLab's 'when: on_success'): the GitHub recipe restores and saves in steps of their
    own, the save run on failure too, with the restore's path and key; the GitLab one
    says 'when: always'.  Each caches the folder its FURNCHECK_CACHE_DIR names."""
    _, github, gitlab = (yaml.safe_load(block) for block in readme_ci_blocks())
    job = github["jobs"]["furncheck"]
    steps = {step["uses"].split("@")[0]: step for step in job["steps"] if "uses" in step}
    restore, save = steps["actions/cache/restore"], steps["actions/cache/save"]
    assert "actions/cache" not in steps
    assert "failure()" in save["if"]
    assert save["with"]["path"] == restore["with"]["path"] and \
        save["with"]["key"] == restore["with"]["key"]
    assert job["env"]["FURNCHECK_CACHE_DIR"].endswith("/" + restore["with"]["path"])
    assert job["steps"].index(save) == len(job["steps"]) - 1      # after every check
    cache = gitlab["furncheck"]["cache"]
    assert cache["when"] == "always"
    assert gitlab["furncheck"]["variables"]["FURNCHECK_CACHE_DIR"].endswith(
        "/" + cache["paths"][0].rstrip("/"))


def test_the_readme_recipes_in_a_scanned_folder_are_no_designs(checked_paths, tmp_path,
                                                               monkeypatch):
    """The GitLab recipe, whose job is named 'furncheck' (a top-level key holding a
    mapping), saved as ci/furncheck.gitlab-ci.yml (an include file: not hidden), and the
    GitHub one as ci/furncheck.yml, in a scanned tree: skipped as no designs, not read as
    a design whose format version is a mapping (exit 2, a failed job and a blocked
    commit)."""
    _, github, gitlab = readme_ci_blocks()
    write(tmp_path / "designs", "valid.yaml")
    (tmp_path / "ci").mkdir()
    (tmp_path / "ci" / "furncheck.gitlab-ci.yml").write_text(gitlab)
    (tmp_path / "ci" / "furncheck.yml").write_text(github)
    monkeypatch.chdir(tmp_path)
    result = run("validate", ".", "--no-cache")
    assert result.exit_code == 0, result.output
    assert checked_paths == [str(Path("designs") / "valid.yaml")]
    assert "skipped 2 files" in result.stderr
