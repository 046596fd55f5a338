"""``furncheck validate`` through click's CliRunner, with ``check_file`` replaced by a fake.

The fake decides the verdict from the file name (valid*, bad*, boom*, garbage*), so these
tests need neither the loader nor the solver and run in well under a second.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest
from click.testing import CliRunner

from furncheck import batch
from furncheck.cli.main import main
from furncheck.result import (
    CaseResult,
    DesignReport,
    JointResult,
    Violation,
)

ROOT = Path(__file__).resolve().parents[1]


def fake_check_file(path: str, model: str | None = None) -> DesignReport:
    """Verdict by file name; a path that does not exist is an input error, like the real one."""
    stem = Path(path).stem
    if not Path(path).is_file():
        return DesignReport(path, stem, None, error=f"{path}: no such file")
    if stem.startswith("boom"):
        raise RuntimeError("solver exploded")
    if stem.startswith("garbage"):
        return 42  # type: ignore[return-value]
    joint = JointResult(("a", "b"), (0.0, 0.0, 1.0), 3, (0.0, 0.0, -1.0), (0.0, 0.1, 0.0),
                        10.0, 1.0, 700.0, 190.0, len(stem) / 100.0, True)
    cases = (CaseResult("default", True, True, (joint,), ()),)
    if stem.startswith("bad"):
        violation = Violation("lift-off", "a", "default", "topples", line=2)
        return DesignReport(path, stem, False, (violation,), cases)
    return DesignReport(path, stem, True, (), cases)


@pytest.fixture
def calls(checked_paths) -> list[str]:
    """``furncheck.check`` replaced by the fake; the paths it checked
    (``conftest.checked_paths``)."""
    return checked_paths


def run(*args: str):
    return CliRunner().invoke(main, list(args))


def write(folder: Path, *names: str) -> list[str]:
    paths = []
    for name in names:
        path = folder / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text('{"furncheck": 1}\n' if path.suffix == ".json" else "furncheck: 1\n")
        paths.append(str(path))
    return paths


def test_version_and_help():
    result = run("--version")
    assert result.exit_code == 0 and "furncheck" in result.output
    assert run("validate", "--help").exit_code == 0


def test_no_path_is_a_usage_error(calls):
    result = run("validate")
    assert result.exit_code == 2 and "PATH" in result.output and calls == []


@pytest.mark.parametrize("args", [("--format", "yaml"), ("--jobs", "0"), ("--nope",)])
def test_bad_options_are_usage_errors(calls, tmp_path, args):
    (path,) = write(tmp_path, "valid.yaml")
    result = run("validate", path, *args)
    assert result.exit_code == 2 and "Traceback" not in result.output


@pytest.mark.parametrize("value", ["abc", "0", "1.5", "", "1_0", "-2"])
def test_a_bad_job_count_is_said_in_words(calls, tmp_path, value):
    """--jobs that is no whole number of at least 1: one line in words, exit 2, where
    click said "'abc' is not a valid integer range" or "0 is not in the range x>=1"."""
    (path,) = write(tmp_path, "valid.yaml")
    result = run("validate", path, "--jobs", value)
    assert result.exit_code == 2 and calls == []
    assert result.output == (f"furncheck validate: invalid value for '-j' / '--jobs': "
                             f"expected a whole number of at least 1, got {value!r} (see "
                             f"'furncheck validate --help')\n")


def test_exit_codes(calls, tmp_path):
    valid, bad = write(tmp_path, "valid.yaml", "bad.yaml")
    assert run("validate", valid).exit_code == 0
    assert run("validate", valid, bad).exit_code == 1
    assert run("validate", valid, bad, str(tmp_path / "missing.yaml")).exit_code == 2


def test_missing_path_keeps_the_batch_going(calls, tmp_path):
    valid, bad = write(tmp_path, "valid.yaml", "bad.yaml")
    missing = str(tmp_path / "missing.yaml")
    result = run("validate", missing, valid, bad, "--format", "json")
    assert result.exit_code == 2
    document = json.loads(result.stdout)
    assert [r["design"] for r in document["reports"]] == [missing, valid, bad]
    assert document["reports"][0]["error"].endswith("no such file")
    assert document["summary"] == {"designs": 3, "valid": 1, "invalid": 1, "errors": 1}


def test_explicit_file_of_another_type_is_checked_anyway(calls, tmp_path):
    (notes,) = write(tmp_path, "notes.txt")
    run("validate", notes)
    assert calls == [notes]


def test_directories_are_searched_recursively_and_sorted(calls, tmp_path):
    write(tmp_path, "b.yaml", "a.json", "sub/c.yml", "sub/deeper/d.yaml", "a-b/e.yaml",
          "readme.md", ".hidden/x.yaml", ".dot.yaml")
    (tmp_path / "empty").mkdir()
    result = run("validate", str(tmp_path), str(tmp_path / "empty"), "--format", "json")
    names = [Path(r["design"]).relative_to(tmp_path).as_posix()
             for r in json.loads(result.stdout)["reports"]]
    assert names == ["a-b/e.yaml", "a.json", "b.yaml", "sub/c.yml", "sub/deeper/d.yaml", "empty"]
    assert result.exit_code == 2  # the empty directory is an error entry
    assert "no design files" in json.loads(result.stdout)["reports"][-1]["error"]


def test_a_file_named_twice_is_checked_once(calls, tmp_path):
    (valid,) = write(tmp_path, "valid.yaml")
    run("validate", valid, str(tmp_path), valid)
    assert calls == [valid]


def test_text_output(calls, tmp_path):
    valid, bad = write(tmp_path, "valid.yaml", "bad.yaml")
    result = run("validate", valid, bad)
    assert result.stdout.splitlines() == [
        f"{valid}: valid (worst joint a/b at 5 % in case 'default')",
        "  case 'default': self-weight only",
        f"{bad}: INVALID, 1 violation",
        "  lift-off: a in case 'default': topples (line 2)",
        "  case 'default': self-weight only",
        "2 designs: 1 valid, 1 invalid, 0 errors",
    ]


def test_unexpected_exceptions_become_error_entries(calls, tmp_path):
    boom, garbage, valid = write(tmp_path, "boom.yaml", "garbage.yaml", "valid.yaml")
    result = run("validate", boom, garbage, valid, "--format", "json")
    assert result.exit_code == 2 and "Traceback" not in result.output
    reports = json.loads(result.stdout)["reports"]
    assert reports[0]["error"] == "internal error: RuntimeError: solver exploded"
    assert reports[1]["error"].startswith("internal error: the checker returned a int")
    assert reports[2]["valid"] is True


@pytest.mark.parametrize("fmt", ["text", "json", "junit", "github", "sarif"])
def test_output_file_gets_exactly_the_report(calls, tmp_path, fmt):
    valid, bad = write(tmp_path, "valid.yaml", "bad.yaml")
    out = tmp_path / f"report.{fmt}"
    to_file = run("validate", valid, bad, "--format", fmt, "-o", str(out))
    to_stdout = run("validate", valid, bad, "--format", fmt)
    assert to_file.exit_code == to_stdout.exit_code == 1
    assert to_file.stdout == ""
    assert out.read_text(encoding="utf-8") == to_stdout.stdout
    assert to_file.stderr == (f"furncheck: 2 designs: 1 valid, 1 invalid, 0 errors; report "
                              f"written to {out}\n")     # the CI log still gets the count


@pytest.mark.parametrize("target", ["valid.yaml/report.json", "."])
def test_unwritable_output_is_one_line_and_exit_2(calls, tmp_path, target):
    """-o below a file (its folder cannot be made: a missing folder is made) or naming a
    folder: one line, exit 2, before any design is checked."""
    (valid,) = write(tmp_path, "valid.yaml")
    result = run("validate", valid, "-o", str(tmp_path / target))
    assert result.exit_code == 2
    assert result.stdout == ""
    assert len(result.stderr.splitlines()) == 1 and "cannot write" in result.stderr
    assert calls == []  # found before any design was checked


@pytest.mark.skipif(not os.path.isfile("/proc/version") or not os.access("/proc/version",
                                                                          os.W_OK),
                    reason="needs Linux's /proc/version reported writable (as root)")
def test_a_file_in_a_folder_that_takes_no_new_files_says_so(tmp_path):
    """-o /proc/version as root: the file is there and writable as far as access() says,
    but /proc makes no new files, so the atomic write's temporary file fails with ENOENT;
    the line said 'No such file or directory' of a file that exists."""
    (valid,) = write(tmp_path, "valid.yaml")
    result = run("validate", valid, "-o", "/proc/version")
    assert result.exit_code == 2
    assert result.stderr.splitlines()[-1] == (
        "furncheck: cannot write the report to /proc/version: its folder /proc takes no new "
        "files (No such file or directory)")


@pytest.mark.parametrize("fmt", ["text", "json", "junit", "github", "sarif"])
def test_jobs_give_the_same_output(calls, tmp_path, monkeypatch, fmt):
    """With workers started after the first design (PARALLEL_AFTER 0), ``--jobs 2`` gives
    the bytes of ``--jobs 1`` in every format; the parent checked only some of the files
    (the workers' calls are not seen here), so the workers really ran."""
    monkeypatch.setattr(batch, "PARALLEL_AFTER", 0.0)
    names = [f"valid{i:02d}.yaml" for i in range(10)] + ["bad.yaml", "boom.yaml"]
    write(tmp_path, *names)
    (tmp_path / "empty-subfolder").mkdir()  # inside a searched folder: no entry
    one = run("validate", str(tmp_path), "--jobs", "1", "--format", fmt, "--no-cache")
    assert len(calls) == 12
    two = run("validate", str(tmp_path), "--jobs", "2", "--format", fmt,
              str(tmp_path / "missing.yaml"), "--no-cache")
    assert 12 < len(calls) < 24
    one_more = run("validate", str(tmp_path), "--jobs", "1", "--format", fmt,
                   str(tmp_path / "missing.yaml"), "--no-cache")
    assert one.exit_code == two.exit_code == one_more.exit_code == 2
    assert two.stdout == one_more.stdout
    if fmt == "json":
        assert len(json.loads(one_more.stdout)["reports"]) == 13


def test_worker_pool_matches_sequential(calls, tmp_path):
    paths = write(tmp_path, *[f"valid{i}.yaml" for i in range(9)], "bad.yaml")
    parallel = list(batch.entries_in_workers(paths, "json", 2))
    assert calls == []  # every design was checked by a worker
    sequential = [batch.entry_of(path, "json") for path in paths]
    assert parallel == sequential
    assert [entry.valid for entry in parallel] == [True] * 9 + [False]


def test_workers_leave_ctrl_c_to_the_parent(tmp_path, monkeypatch):
    """Every pool's workers ignore SIGINT (``workers.quiet_worker``): Ctrl-C reaches the
    whole process group, and a worker that took it printed a traceback from inside
    multiprocessing after the parent's 'Aborted!'.  SIGTERM ends a worker as by default
    (a forked worker would inherit the console script's handler).  The checking workers
    report the handlers they run with."""
    import signal

    monkeypatch.setattr(batch, "entry_of", lambda path, *args: batch.Entry(
        True, False, str((signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)))))
    paths = write(tmp_path, *[f"valid{i}.yaml" for i in range(6)])
    handler = signal.signal(signal.SIGTERM, lambda *args: None)    # as the console script
    try:
        pieces = {entry.piece for entry in batch.entries_in_workers(paths, "json", 2)}
    finally:
        signal.signal(signal.SIGTERM, handler)
    assert pieces == {str((signal.SIG_IGN, signal.SIG_DFL))}
    assert signal.getsignal(signal.SIGINT) is not signal.SIG_IGN     # here: untouched


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="prctl is Linux's")
def test_workers_end_with_a_parent_killed_outright(tmp_path):
    """A parent killed by SIGKILL (a CI job's timeout, the out-of-memory killer) runs no
    shutdown: its pool's workers sat blocked on their pipes for good.  Now the kernel ends
    them with it (``workers.quiet_worker``, PR_SET_PDEATHSIG): a process makes a pool of
    two the way furncheck's pools are made (``pool_options``), its workers busy, and is
    killed; both are gone within ten seconds."""
    import os
    import signal

    workers: list[int] = []
    script = tmp_path / "parent.py"
    script.write_text(
        "import multiprocessing, os, sys, time\n"
        "from furncheck.workers import pool_options, process_pool\n"
        "def busy(_):\n"
        "    time.sleep(120)\n"
        "def pid(_):\n"
        "    time.sleep(0.5)\n"
        "    return os.getpid()\n"
        "with process_pool(max_workers=2, mp_context=multiprocessing.get_context('fork'),\n"
        "                  **pool_options()) as pool:\n"
        "    pids = set(pool.map(pid, range(2)))\n"
        "    print(' '.join(map(str, sorted(pids))), flush=True)\n"
        "    list(pool.map(busy, range(2)))\n")
    parent = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE,
                              text=True)
    try:
        workers = [int(word) for word in parent.stdout.readline().split()]
        assert workers
        parent.send_signal(signal.SIGKILL)
        parent.wait(timeout=30)
        deadline = time.monotonic() + 10.0
        alive = workers
        while alive and time.monotonic() < deadline:
            time.sleep(0.1)
            alive = [pid for pid in workers if _running(pid)]
        assert not alive
    finally:
        parent.kill()
        parent.wait()
        parent.stdout.close()
        for pid in workers:
            try:
                os.kill(pid, signal.SIGKILL)        # a failing run leaves none behind
            except OSError:
                pass


def _running(pid: int) -> bool:
    """Whether process ``pid`` runs (a zombie, reaped by init soon, does not)."""
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def test_the_workers_are_at_most_the_usable_cpus(tmp_path, monkeypatch):
    """``workers.usable_cpus``: the CPUs of the process's affinity, at most a container's
    quota rounded up: the least cgroup v2 'cpu.max' of the process's own cgroup (named in
    /proc/self/cgroup) and those above it ('150000 100000' is 1.5 CPUs, so 2; 'max', a
    zero period or a negative quota is none), else cgroup v1's quota and period (-1:
    none); ``local_jobs`` caps --jobs at it and defaults to it."""
    from furncheck import workers

    root, own = tmp_path / "cgroup", tmp_path / "cgroup" / "ci.slice" / "job-7"
    own.mkdir(parents=True)
    self_file = tmp_path / "self"
    self_file.write_text("0::/ci.slice/job-7\n")
    monkeypatch.setattr(workers, "CGROUP_ROOT", str(root))
    monkeypatch.setattr(workers, "CGROUP_SELF", str(self_file))
    monkeypatch.setattr(workers.os, "sched_getaffinity", lambda pid: {0, 1, 2, 3, 4, 5},
                        raising=False)
    assert workers.usable_cpus() == 6                       # no cgroup files: affinity
    (root / "ci.slice" / "cpu.max").write_text("150000 100000\n")    # on a parent
    assert workers.usable_cpus() == 2
    assert (workers.local_jobs(None), workers.local_jobs(40), workers.local_jobs(1)) == (2, 2, 1)
    (own / "cpu.max").write_text("100000 100000\n")                 # and on its own
    assert workers.usable_cpus() == 1
    for text in ("max 100000", "5 0", "-5 100000", "junk"):
        (own / "cpu.max").write_text(text + "\n")
        (root / "ci.slice" / "cpu.max").write_text(text + "\n")
        assert workers.usable_cpus() == 6, text
    (root / "cpu").mkdir()
    (root / "cpu" / "cpu.cfs_quota_us").write_text("300000\n")
    (root / "cpu" / "cpu.cfs_period_us").write_text("100000\n")
    assert workers.usable_cpus() == 3
    (root / "cpu" / "cpu.cfs_quota_us").write_text("-1\n")
    assert workers.usable_cpus() == 6
    monkeypatch.setattr(workers.os, "sched_getaffinity", lambda pid: {3}, raising=False)
    assert workers.local_jobs(40) == 1


def test_jobs_beyond_the_usable_cpus_start_no_more_workers(tmp_path, monkeypatch):
    """--jobs 40 where 2 CPUs may be used: the pool is made of 2 workers (40 on 2 CPUs
    were slower than 2), and the entries are the same."""
    from concurrent.futures import ProcessPoolExecutor

    from furncheck import workers

    made = []

    class Recorded(ProcessPoolExecutor):
        def __init__(self, max_workers=None, **kwargs):
            made.append(max_workers)
            super().__init__(max_workers=max_workers, **kwargs)

    monkeypatch.setattr(workers, "usable_cpus", lambda: 2)
    monkeypatch.setattr("concurrent.futures.ProcessPoolExecutor", Recorded)
    monkeypatch.setattr(batch, "PARALLEL_AFTER", 0.0)
    monkeypatch.setattr(batch, "entry_of", lambda path, *args: batch.Entry(True, False, path))
    paths = write(tmp_path, *[f"valid{i}.yaml" for i in range(12)])
    pieces = [entry.piece for entry in batch.entries(paths, "json", 40)]
    assert pieces == paths and made == [2]


def test_a_small_catalog_is_checked_in_one_process(calls, tmp_path):
    """Checking the fake's designs takes microseconds: no worker is started, every file
    is checked here."""
    paths = write(tmp_path, *[f"valid{i:02d}.yaml" for i in range(40)])
    assert run("validate", *paths, "--jobs", "2").exit_code == 0
    assert calls == paths


def test_a_slow_catalog_goes_to_workers(calls, tmp_path, monkeypatch):
    """Designs of 30 ms of CPU each: after PARALLEL_AFTER (0.1 s, about 4 designs after
    the first) the 15 left would take 0.45 s more, so they go to workers: the parent
    checks only some of the 20 files, and the report is the one of a single process."""
    paths = write(tmp_path, *[f"valid{i:02d}.yaml" for i in range(20)])
    fake = sys.modules["furncheck.check"]
    fast = fake.check_file

    def slow(path, model=None):
        start = time.process_time()
        while time.process_time() - start < 0.03:
            pass
        return fast(path, model)

    monkeypatch.setattr(fake, "check_file", slow)
    two = run("validate", *paths, "--jobs", "2", "--format", "json", "--no-cache")
    assert 2 <= len(calls) < 20 and calls == paths[:len(calls)]
    monkeypatch.setattr(batch, "PARALLEL_AFTER", 1e9)
    calls.clear()
    one = run("validate", *paths, "--jobs", "2", "--format", "json", "--no-cache")
    assert calls == paths
    assert one.stdout == two.stdout


def test_cli_start_up_imports_nothing_heavy():
    code = (f"import sys; sys.path.insert(0, {str(ROOT)!r}); "
            f"sys.path.insert(0, {str(ROOT / 'tests')!r}); import test_cli; "
            "print(sorted(m for m in ('numpy', 'scipy', 'furncheck.check') if m in sys.modules))")
    output = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                            check=True, cwd=ROOT).stdout
    assert output.strip() == "[]"


def test_a_closed_pipe_at_exit_is_not_printed_anything_else_is(capsys, monkeypatch):
    """``cli.main._quiet_closed_pipe``, the console script's ``sys.unraisablehook`` at
    exit: a closed file descriptor raised where nothing can catch it (CPython 3.11's
    process pools waking their manager threads at exit) prints nothing; any other
    unraisable exception is printed as Python prints it."""
    import errno
    import gc
    import sys

    from furncheck.cli.main import _quiet_closed_pipe

    class Raising:
        def __init__(self, error):
            self.error = error

        def __del__(self):
            raise self.error

    monkeypatch.setattr(sys, "unraisablehook", _quiet_closed_pipe)
    Raising(OSError(errno.EBADF, "Bad file descriptor"))
    gc.collect()
    assert capsys.readouterr().err == ""
    Raising(ValueError("something else"))
    gc.collect()
    assert "ValueError: something else" in capsys.readouterr().err


def test_the_console_script_installs_the_exit_hook(monkeypatch):
    """``cli.main.run`` (the console script) leaves ``_quiet_closed_pipe`` as
    ``sys.unraisablehook`` for the interpreter's exit, whatever the command did."""
    import signal
    import sys

    from furncheck.cli import main as cli_main

    def done(**_):
        raise SystemExit(0)

    monkeypatch.setattr(cli_main, "main", done)
    monkeypatch.setattr(sys, "unraisablehook", sys.__unraisablehook__)
    monkeypatch.setattr(signal, "signal", lambda *_: None)    # the test's own stay
    with pytest.raises(SystemExit):
        cli_main.run()
    assert sys.unraisablehook is cli_main._quiet_closed_pipe


def test_a_read_only_file_system_is_said_as_such(calls, tmp_path, monkeypatch):
    """-o into a folder on a file system mounted read-only (a CI runner's checkout) says
    'read-only file system', as writing would, not 'permission denied' (os.access finds
    both alike; statvfs tells them apart: faked here, a mount needs privileges)."""
    import os
    import types

    (valid,) = write(tmp_path, "valid.yaml")
    folder = tmp_path / "mounted"
    folder.mkdir()
    real_access, real_statvfs = os.access, os.statvfs
    monkeypatch.setattr(os, "access", lambda path, mode, **kw: False
                        if str(path).startswith(str(folder)) else real_access(path, mode, **kw))
    monkeypatch.setattr(os, "statvfs", lambda path: types.SimpleNamespace(
        f_flag=os.ST_RDONLY) if str(path).startswith(str(folder)) else real_statvfs(path))
    result = run("validate", valid, "-o", str(folder / "report.json"))
    assert result.exit_code == 2
    assert result.stderr == f"furncheck: cannot write the report to {folder / 'report.json'}: " \
                            "read-only file system\n"
    assert calls == []
