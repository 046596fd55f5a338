"""The result cache of ``furncheck validate`` (contract section 4; ``furncheck.cache``).

Hits and misses are counted with the fake checker of ``test_cli`` (it records every file it
checks); byte identity of cached and fresh reports is checked with the real checker on the
catalog, in every report format.
"""

from __future__ import annotations

import multiprocessing
import os
import subprocess
import sys
from pathlib import Path

import pytest
from test_cli import fake_check_file, run, write

from furncheck import cache as cache_module
from furncheck.cache import ResultCache, check_with_cache
from furncheck.check import check_file
from furncheck.report import REPORTERS, render
from furncheck.result import BatchReport
from furncheck.result_codec import decode_report, encode

ROOT = Path(__file__).resolve().parents[1]
CATALOG = sorted((ROOT / "designs").glob("*.yaml"))


def entries(directory: Path) -> list[Path]:
    return sorted(path for path in directory.rglob("*") if path.is_file())


# --- hits, misses, invalidation -------------------------------------------------------------

def test_an_unchanged_file_is_not_checked_again(checked_paths, tmp_path):
    valid, bad = write(tmp_path, "valid.yaml", "bad.yaml")
    cache = tmp_path / "cache"
    first = run("validate", valid, bad, "--cache-dir", str(cache), "--format", "json")
    assert checked_paths == [valid, bad] and len(entries(cache)) == 2
    second = run("validate", valid, bad, "--cache-dir", str(cache), "--format", "json")
    assert checked_paths == [valid, bad]                      # nothing checked the second time
    assert second.stdout == first.stdout and second.exit_code == first.exit_code == 1


def test_the_default_directory_is_the_user_cache_directory(checked_paths, tmp_path, monkeypatch):
    """FURNCHECK_CACHE_DIR (set per test by conftest) is used when --cache-dir is not
    given; without it, XDG_CACHE_HOME/furncheck on Linux."""
    (valid,) = write(tmp_path, "valid.yaml")
    run("validate", valid)
    assert entries(Path(os.environ["FURNCHECK_CACHE_DIR"]))
    monkeypatch.delenv("FURNCHECK_CACHE_DIR")
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "xdg"))
    if sys.platform.startswith("linux"):
        assert cache_module.default_directory() == str(tmp_path / "xdg" / "furncheck")


def test_no_cache_neither_reads_nor_writes(checked_paths, tmp_path):
    (valid,) = write(tmp_path, "valid.yaml")
    cache = tmp_path / "cache"
    run("validate", valid, "--cache-dir", str(cache))
    run("validate", valid, "--cache-dir", str(cache), "--no-cache")
    assert checked_paths == [valid, valid]
    run("validate", str(tmp_path / "other.yaml"), "--no-cache", "--cache-dir",
        str(tmp_path / "unused"))
    assert not (tmp_path / "unused").exists()


def test_a_changed_file_option_or_code_is_checked_again(checked_paths, tmp_path, monkeypatch):
    """Each of: the file's content, --model, the path as given (reports name it), and
    furncheck's code (its version here) changes the key; changing the content back finds
    the first entry again."""
    (valid,) = write(tmp_path, "valid.yaml")
    cache = ["--cache-dir", str(tmp_path / "cache")]
    run("validate", valid, *cache)
    Path(valid).write_text("furncheck: 1\n# edited\n")
    run("validate", valid, *cache)
    run("validate", valid, "--model", "rigid", *cache)
    run("validate", valid, "--model", "elastic", *cache)
    with monkeypatch.context() as patch:
        patch.chdir(tmp_path)
        run("validate", "valid.yaml", *cache)
    with monkeypatch.context() as patch:
        patch.setattr(cache_module, "__version__", "99.0")
        run("validate", valid, *cache)
    Path(valid).write_text("furncheck: 1\n")
    run("validate", valid, *cache)                     # the first entry again
    assert checked_paths == [valid] * 4 + ["valid.yaml", valid]


def test_input_errors_are_not_cached(checked_paths, tmp_path):
    missing = str(tmp_path / "missing.yaml")
    run("validate", missing, "--cache-dir", str(tmp_path / "cache"))
    run("validate", missing, "--cache-dir", str(tmp_path / "cache"))
    assert checked_paths == [missing, missing] and not (tmp_path / "cache").exists()


# --- damaged entries and concurrency --------------------------------------------------------

@pytest.mark.parametrize("damage", ["truncate", "flip", "empty", "garbage", "other-key"])
def test_a_damaged_entry_is_ignored_and_written_again(checked_paths, tmp_path, damage):
    (valid,) = write(tmp_path, "valid.yaml")
    cache = tmp_path / "cache"
    first = run("validate", valid, "--cache-dir", str(cache), "--format", "json").stdout
    (entry,) = entries(cache)
    good = entry.read_bytes()
    damaged = {"truncate": good[:len(good) // 2],
               "flip": good[:-5] + bytes([good[-5] ^ 0x01]) + good[-4:],
               "empty": b"",
               "garbage": os.urandom(len(good)),
               "other-key": good[:20] + bytes([good[20] ^ 0xFF]) + good[21:]}[damage]
    entry.write_bytes(damaged)
    again = run("validate", valid, "--cache-dir", str(cache), "--format", "json")
    assert again.stdout == first and again.exit_code == 0
    assert checked_paths == [valid, valid]                     # checked again
    assert entry.read_bytes() == good                  # and the entry rewritten
    run("validate", valid, "--cache-dir", str(cache))
    assert checked_paths == [valid, valid]                     # a hit once more


def _write_and_read(directory: str, rounds: int) -> list[str]:
    """In a separate process: store and read back the same entries over and over; returns
    what went wrong (a read must give nothing or exactly the report stored)."""
    cache = ResultCache(directory, {"model": None})
    reports = [fake_check_file(str(Path(__file__)), None)] * 3
    problems = []
    for round_number in range(rounds):
        for index, report in enumerate(reports):
            key = cache.key(f"file-{index}.yaml", b"same content")
            cache.put(key, report)
            read = cache.get(key, report.design)
            if read is not None and read != report:
                problems.append(f"round {round_number}: a different report was read")
    return problems


def test_runs_in_parallel_leave_only_complete_entries(tmp_path):
    """Four processes write and read the same three entries 150 times each: no read gives
    a wrong report, and the three entries are complete at the end (written atomically, no
    temporary file left behind)."""
    context = multiprocessing.get_context("fork" if sys.platform != "win32" else "spawn")
    with context.Pool(4) as pool:
        outcomes = pool.starmap(_write_and_read, [(str(tmp_path), 150)] * 4)
    assert outcomes == [[]] * 4
    cache = ResultCache(str(tmp_path), {"model": None})
    assert len(entries(tmp_path)) == 3
    for index in range(3):
        key = cache.key(f"file-{index}.yaml", b"same content")
        assert cache.get(key, str(Path(__file__))) is not None


def test_an_unwritable_cache_directory_is_one_warning(checked_paths, tmp_path):
    """A file where the cache directory should be: the run's results are right, one line
    on stderr says they were not cached, the exit code is unchanged."""
    valid, bad = write(tmp_path, "valid.yaml", "bad.yaml")
    blocker = tmp_path / "not-a-folder"
    blocker.write_text("")
    result = run("validate", valid, bad, "--cache-dir", str(blocker))
    assert result.exit_code == 1
    assert result.stderr.count("results not cached") == 1
    assert "2 designs: 1 valid, 1 invalid" in result.stdout


def test_a_file_edited_during_the_check_is_not_stored_under_its_old_key(tmp_path):
    """The checker edits the file while checking it (as an editor saving mid-run would):
    the report is returned but not stored, so the next run with the old content does not
    get the result of the new one."""
    path = tmp_path / "valid.yaml"
    path.write_text("furncheck: 1\n")
    cache = ResultCache(str(tmp_path / "cache"), {"model": None})

    def check_many(paths):
        path.write_text("furncheck: 1\n# edited while checked\n")
        return [fake_check_file(p) for p in paths]

    reports = list(check_with_cache([str(path)], cache, check_many))
    assert reports[0].valid is True and not entries(tmp_path / "cache")


# --- same output as a cold run ---------------------------------------------------------------

@pytest.mark.parametrize("model", ["elastic", "rigid"])
def test_decoded_reports_render_byte_identical_in_every_format(model):
    """Every catalog design's report, encoded and decoded as the cache stores it, equals the
    original field for field (also the source lines, which equality leaves out) and renders
    to the same bytes in every format."""
    reports = tuple(check_file(str(path), model) for path in CATALOG)
    decoded = tuple(decode_report(encode(report)) for report in reports)
    assert decoded == reports
    assert [v.line for r in decoded for v in r.violations] == \
        [v.line for r in reports for v in r.violations]
    for fmt in REPORTERS:
        assert render(BatchReport(decoded), fmt) == render(BatchReport(reports), fmt)


def test_a_warm_run_prints_what_the_cold_run_printed_and_loads_no_numpy(tmp_path):
    """The command run twice over three catalog designs: the second run, all hits, writes
    the same bytes and never imports numpy (the checker is not needed)."""
    designs = [str(ROOT / "designs" / name) for name in
               ("stool.yaml", "table.yaml", "bench-tips.yaml")]
    code = ("import sys; from furncheck.cli.main import main\n"
            "try:\n    main(sys.argv[1:])\nexcept SystemExit as done:\n"
            "    print('numpy' in sys.modules, done.code, file=sys.stderr)\n")
    command = [sys.executable, "-c", code, "validate", *designs, "--format", "json",
               "--cache-dir", str(tmp_path / "cache")]
    cold = subprocess.run(command, capture_output=True, text=True, check=True)
    warm = subprocess.run(command, capture_output=True, text=True, check=True)
    assert cold.stderr.split() == ["True", "1"]
    assert warm.stderr.split() == ["False", "1"]
    assert warm.stdout == cold.stdout
