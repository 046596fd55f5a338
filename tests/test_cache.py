"""The result cache of ``furncheck validate`` (contract section 4; ``furncheck.cache``).

Hits and misses are counted with the fake checker of ``test_cli`` (it records every file it
checks); byte identity of cached and fresh reports is checked with the real checker on the
catalog, in every report format.
"""

from __future__ import annotations

import base64
import hashlib
import multiprocessing
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from test_cli import fake_check_file, run, write

from furncheck import cache as cache_module
from furncheck.cache import ResultCache
from furncheck.check import check_file
from furncheck.report import REPORTERS, render
from furncheck.result import BatchReport
from furncheck.result_codec import decode_report, encode

ROOT = Path(__file__).resolve().parents[1]
CATALOG = sorted((ROOT / "designs").glob("*.yaml"))


def entries(directory: Path) -> list[Path]:
    """The result entries under ``directory`` (not the report pieces, NAME.FORMAT; not the
    folder's own '.gitignore')."""
    return sorted(path for path in (directory / cache_module.LAYOUT).rglob("*")
                  if path.is_file() and not path.suffix)


def pieces(directory: Path) -> list[Path]:
    """The report pieces (NAME.FORMAT; not the folder's CACHEDIR.TAG)."""
    return sorted(path for path in (directory / cache_module.LAYOUT).rglob("*.*")
                  if path.is_file() and path.name != "CACHEDIR.TAG")


# --- hits, misses, invalidation -------------------------------------------------------------

def test_an_unchanged_file_is_not_checked_again(checked_paths, tmp_path):
    valid, bad = write(tmp_path, "valid.yaml", "bad.yaml")
    cache = tmp_path / "cache"
    first = run("validate", valid, bad, "--cache-dir", str(cache), "--format", "json")
    assert checked_paths == [valid, bad] and len(entries(cache)) == len(pieces(cache)) == 2
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
    assert checked_paths == [missing, missing]
    assert not entries(tmp_path / "cache") and not pieces(tmp_path / "cache")


# --- damaged entries and concurrency --------------------------------------------------------

@pytest.mark.parametrize("damage", ["truncate", "flip", "empty", "garbage", "other-key"])
def test_a_damaged_entry_is_ignored_and_written_again(checked_paths, tmp_path, damage):
    """The result entry damaged (and its piece gone): checked again, both written again;
    the piece damaged: made again from the result, without a check."""
    (valid,) = write(tmp_path, "valid.yaml")
    cache = tmp_path / "cache"
    first = run("validate", valid, "--cache-dir", str(cache), "--format", "json").stdout
    (entry,), (piece,) = entries(cache), pieces(cache)
    good, good_piece = entry.read_bytes(), piece.read_bytes()

    def damaged(data: bytes) -> bytes:
        return {"truncate": data[:len(data) // 2],
                "flip": data[:-5] + bytes([data[-5] ^ 0x01]) + data[-4:],
                "empty": b"",
                "garbage": os.urandom(len(data)),
                "other-key": data[:20] + bytes([data[20] ^ 0xFF]) + data[21:]}[damage]

    entry.write_bytes(damaged(good))
    piece.unlink()
    again = run("validate", valid, "--cache-dir", str(cache), "--format", "json")
    assert again.stdout == first and again.exit_code == 0
    assert checked_paths == [valid, valid]              # checked again
    assert entry.read_bytes() == good and piece.read_bytes() == good_piece  # rewritten
    piece.write_bytes(damaged(good_piece))
    third = run("validate", valid, "--cache-dir", str(cache), "--format", "json")
    assert third.stdout == first and checked_paths == [valid, valid]   # not checked
    assert piece.read_bytes() == good_piece


@pytest.mark.parametrize("fmt", ["json", "junit", "sarif"])
@pytest.mark.parametrize("payload", [(True, False, None), (1, False, "x"),
                                     (True, False, ("x", (1, 2))), (True, 0, "x")])
def test_a_well_sealed_piece_of_another_shape_is_made_again(checked_paths, tmp_path, fmt,
                                                            payload):
    """A piece whose header and CRC are right but whose payload is not what its format's
    ``piece`` makes (a restored cache of another version, a planted file) is made again
    from the stored result, the output as before; it ended the batch with an internal
    error."""
    import marshal
    import zlib

    (valid,) = write(tmp_path, "valid.yaml")
    cache = tmp_path / "cache"
    first = run("validate", valid, "--cache-dir", str(cache), "--format", fmt)
    (piece,) = pieces(cache)
    key = piece.parent.name + piece.stem                # entries are at KEY[:2]/KEY[2:]
    header = cache_module._MARKER + bytes.fromhex(key) + fmt.encode() + b"\0"
    body = marshal.dumps(payload)
    piece.write_bytes(header + zlib.crc32(body).to_bytes(4, "big") + body)
    again = run("validate", valid, "--cache-dir", str(cache), "--format", fmt)
    assert again.stdout == first.stdout and again.exit_code == first.exit_code == 0
    assert checked_paths == [valid]                     # from the result, not checked


def test_a_symlink_in_the_cache_is_neither_read_nor_written_through(checked_paths, tmp_path):
    """An entry that is a symlink (a cache restored from an archive may hold one) is not
    followed: the file it points to stays as it was (it was overwritten with the entry:
    a write outside the cache folder), the design is checked, the link replaced by the
    entry, with the usual mode (not the target's).  A folder of the layout that is a
    link gets no entries at all."""
    (valid,) = write(tmp_path, "valid.yaml")
    cache = tmp_path / "cache"
    first = run("validate", valid, "--cache-dir", str(cache), "--format", "json")
    (entry,), (piece,) = entries(cache), pieces(cache)
    outside = tmp_path / "outside"
    outside.write_bytes(entry.read_bytes())             # a well-formed entry, elsewhere
    outside.chmod(0o4777)                               # setuid, writable by all
    mode = entry.stat().st_mode & 0o7777
    entry.unlink()
    piece.unlink()
    entry.symlink_to(outside)
    again = run("validate", valid, "--cache-dir", str(cache), "--format", "json")
    assert again.stdout == first.stdout and checked_paths == [valid, valid]  # not read
    assert not entry.is_symlink() and entry.read_bytes() == outside.read_bytes()
    assert entry.stat().st_mode & 0o7777 == mode        # not the link target's mode
    outside.write_bytes(b"mine")
    for path in entries(cache) + pieces(cache):
        path.unlink()
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    folder = entry.parent
    folder.rmdir()
    folder.symlink_to(elsewhere)
    third = run("validate", valid, "--cache-dir", str(cache), "--format", "json")
    assert third.stdout == first.stdout and checked_paths == [valid] * 3
    assert list(elsewhere.iterdir()) == [] and outside.read_bytes() == b"mine"
    # the layout's own folder a link (a CI engineer's case): no shard folder is made
    # through it, and the run says once that nothing was cached
    folder.unlink()
    layout = folder.parent
    (layout / "CACHEDIR.TAG").unlink()
    for path in layout.iterdir():
        shutil.rmtree(path)
    layout.rmdir()
    layout.symlink_to(elsewhere)
    fourth = run("validate", valid, "--cache-dir", str(cache), "--format", "json")
    assert fourth.stdout == first.stdout and list(elsewhere.iterdir()) == []
    assert fourth.stderr == (f"furncheck: results not cached: {cache}: {layout.name} is a "
                             f"symbolic link (nothing is written through one)\n")


def test_a_piece_is_reused_as_it_is_and_other_formats_use_the_result(checked_paths,
                                                                      tmp_path, monkeypatch):
    """A second run in one format reads the stored piece (the result is not even decoded);
    a run in another format makes its piece from the stored result (no check), equal to a
    run without the cache."""
    valid, bad = write(tmp_path, "valid.yaml", "bad.yaml")
    cache = ["--cache-dir", str(tmp_path / "cache")]
    first = run("validate", valid, bad, "--format", "json", *cache).stdout
    with monkeypatch.context() as patch:
        patch.setattr(cache_module, "decode_report",
                      lambda data: pytest.fail("a result was decoded"))
        assert run("validate", valid, bad, "--format", "json", *cache).stdout == first
    assert checked_paths == [valid, bad]
    for fmt in ("text", "junit", "github", "sarif"):
        cached = run("validate", valid, bad, "--format", fmt, *cache)
        assert checked_paths == [valid, bad]
        fresh = run("validate", valid, bad, "--format", fmt, "--no-cache")
        assert cached.stdout == fresh.stdout and cached.exit_code == fresh.exit_code == 1
        del checked_paths[2:]
    assert len(pieces(tmp_path / "cache")) == 2 * 5


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


def test_a_read_only_cache_warns_only_where_a_result_was_lost(checked_paths, tmp_path,
                                                              monkeypatch):
    """A CI job restores a warm cache read-only (os.access says it cannot be written): a
    run whose every result is stored already loses nothing and says nothing (it warned on
    every run), also in a format whose pieces were never stored (they are made from the
    stored results); one with a new design says once that results were not cached, in the
    words of the error writing would raise ('permission denied' here; 'read-only file
    system' on such a mount), not a made-up 'Permission denied'."""
    valid, bad = write(tmp_path, "valid.yaml", "bad.yaml")
    cache = tmp_path / "cache"
    assert run("validate", valid, bad, "--cache-dir", str(cache)).stderr == ""
    real_access = os.access
    monkeypatch.setattr(os, "access", lambda path, mode, **kw: False if str(path).startswith(
        str(cache)) else real_access(path, mode, **kw))
    warm = run("validate", valid, bad, "--cache-dir", str(cache))
    assert warm.stderr == "" and warm.exit_code == 1 and checked_paths == [valid, bad]
    other_format = run("validate", valid, bad, "--cache-dir", str(cache), "--format", "json")
    assert other_format.stderr == "" and checked_paths == [valid, bad]  # pieces made anew
    (other,) = write(tmp_path, "valid-2.yaml")
    cold = run("validate", valid, other, "--cache-dir", str(cache))
    assert cold.stderr == f"furncheck: results not cached: {cache}: permission denied\n"
    assert checked_paths == [valid, bad, other]


def test_results_checked_in_workers_count_as_lost_where_the_cache_is_unwritable(
        tmp_path, monkeypatch):
    """Worker processes get a copy of the cache, so what they could not store is counted
    where their entries come back (the warning's count): each design they checked, not
    one whose input could not be read (never stored)."""
    from furncheck import batch
    from furncheck.report.entries import Entry

    valid, bad, broken = write(tmp_path, "valid.yaml", "bad.yaml", "broken.yaml")
    cache = ResultCache(str(tmp_path / "cache"), {"model": None})
    cache.unwritable = "read-only file system"

    def in_workers(to_check, fmt, jobs, model, cache_copy):
        return iter([Entry(True, False, ""), Entry(False, False, ""), Entry(None, True, "")])

    monkeypatch.setattr(batch, "_checked", in_workers)
    assert len(list(batch.entries([valid, bad, broken], "text", 2, None, cache))) == 3
    assert cache.lost == 2


def test_a_file_edited_during_the_check_is_not_stored_under_its_old_key(tmp_path,
                                                                       monkeypatch):
    """The checker edits the file while checking it (as an editor saving mid-run would):
    the report is returned but not stored, so the next run with the old content does not
    get the result of the new one."""
    from furncheck import batch

    path = tmp_path / "valid.yaml"
    path.write_text("furncheck: 1\n")
    cache = ResultCache(str(tmp_path / "cache"), {"model": None})

    def check_one(checked: str, model: str | None = None):
        path.write_text("furncheck: 1\n# edited while checked\n")
        return fake_check_file(checked, model)

    monkeypatch.setattr(batch, "check_one", check_one)
    (entry,) = batch.entries([str(path)], "text", 1, None, cache)
    assert entry.valid is True and not list((tmp_path / "cache").rglob("*"))


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


def test_the_report_page_reads_the_results_the_run_stored(tmp_path, monkeypatch):
    """``validate --html`` draws its page from the results the run just cached (the
    streamed report keeps only its text): with a warm cache nothing is checked at all, and
    the page is byte-identical to one drawn from fresh checks (``--no-cache``)."""
    designs = [str(Path(__file__).resolve().parents[1] / "designs" / name)
               for name in ("stool.yaml", "table-slides.yaml", "shelf-cantilever.yaml")]
    fresh, cold, warm = (tmp_path / f"{name}.html" for name in ("fresh", "cold", "warm"))
    cache_dir = str(tmp_path / "cache")
    assert run("validate", *designs, "--no-cache", "--html", str(fresh)).exit_code == 1
    assert run("validate", *designs, "--cache-dir", cache_dir, "--html", str(cold)).exit_code == 1
    monkeypatch.setattr("furncheck.batch.check_one",
                        lambda *_: pytest.fail("a design was checked again"))
    assert run("validate", *designs, "--cache-dir", cache_dir, "--html", str(warm)).exit_code == 1
    assert fresh.read_bytes() == cold.read_bytes() == warm.read_bytes()


def test_an_empty_home_is_an_unset_one(monkeypatch):
    """Some CI containers run with HOME set to nothing: '~/.cache' then read '/.cache', a
    folder at the file system's root.  An empty HOME counts as unset: the user database's
    home, as Python takes it when HOME is unset; with no home known at all, the temporary
    folder."""
    import os
    import pwd

    from furncheck.cache import default_directory

    monkeypatch.delenv("XDG_CACHE_HOME", raising=False)
    monkeypatch.delenv("FURNCHECK_CACHE_DIR", raising=False)
    monkeypatch.setenv("HOME", "")
    home = pwd.getpwuid(os.getuid()).pw_dir
    assert default_directory() == os.path.join(home, ".cache", "furncheck")
    assert os.environ["HOME"] == ""                 # left as it was
    # a container's user with no passwd entry: no home anywhere; the temporary folder,
    # never a folder named '~' in the current one
    import tempfile

    monkeypatch.setattr(cache_module, "_user_database_home", lambda: None)
    assert default_directory() == os.path.join(tempfile.gettempdir(),
                                               f"furncheck-cache-{os.getuid()}")


def test_a_cache_folder_furncheck_makes_is_left_out_of_git(checked_paths, tmp_path):
    """A cache folder that furncheck makes holds a '.gitignore' of '*' (as pytest's does),
    so that 'cache-dir = ".furncheck-cache"' in a repository stays out of git status; a
    folder that existed before (a user's own, or '.') gets none."""
    (design,) = write(tmp_path, "valid.yaml")
    made = tmp_path / "made-cache"
    run("validate", str(design), "--cache-dir", str(made))
    assert (made / ".gitignore").read_text().splitlines()[-1] == "*"
    existing = tmp_path / "existing"
    existing.mkdir()
    run("validate", str(design), "--cache-dir", str(existing))
    assert not (existing / ".gitignore").exists() and any(existing.iterdir())


INIT = b"x = 1\n"
INIT_HASH = b"sha256=" + base64.urlsafe_b64encode(hashlib.sha256(INIT).digest()).rstrip(b"=")


def _install(site: Path, record: bytes, when: int, version: str = "1.0") -> None:
    """A fake distribution 'Fake_Dep' ``version`` of the module ``fakedep`` installed in
    ``site``, its RECORD ``record`` (``%(init)s`` standing for its __init__.py's hash),
    its files stamped ``when`` (pip stamps them with the time of the install)."""
    package = site / "fakedep"
    package.mkdir(parents=True, exist_ok=True)
    (package / "__init__.py").write_bytes(INIT)
    info = site / f"Fake_Dep-{version}.dist-info"
    info.mkdir()
    (info / "RECORD").write_bytes(record.replace(b"%(init)s", INIT_HASH)
                                  .replace(b"1.0.dist-info", f"{version}.dist-info".encode()))
    for path in (package / "__init__.py", info / "RECORD"):
        os.utime(path, ns=(when, when))


RECORD = (b"../../../bin/fake,sha256=%(script)s,229\n"
          b"fakedep/__init__.py,%(init)s,6\n"
          b"fakedep/__pycache__/__init__.cpython-311.pyc,,\n"
          b"fakedep/core.so,sha256=%(core)s,99\n"
          b"Fake_Dep-1.0.dist-info/INSTALLER,sha256=%(installer)s,4\n"
          b"Fake_Dep-1.0.dist-info/RECORD,,\n")


def _record(script=b"one", core=b"abc", installer=b"pip", pyc=True) -> bytes:
    record = RECORD.replace(b"%(script)s", script).replace(b"%(core)s", core) \
        .replace(b"%(installer)s", installer)
    return record if pyc else b"".join(line for line in record.splitlines(keepends=True)
                                       if b".pyc" not in line)


def test_a_dependencys_part_of_the_key_is_its_build_not_its_install(tmp_path, monkeypatch):
    """Installs of one build of a dependency, in other folders at other times, by pip or
    uv, compiled or not (CI jobs each installing afresh), give the code fingerprint the
    same part: the files of its distribution's RECORD with their hashes, but for its
    dist-info folder's (INSTALLER, REQUESTED) and those outside its folder (a console
    script, whose first line names each environment's Python).  Another build (a file's
    hash differs) gives another.  Of two dist-info folders (a stale one left by an
    upgrade) the one whose __init__.py hash is the file's counts.  Without a RECORD (a
    source tree on the path) its place and its __init__'s stamp stand for it, as before.
    (With the stamp alone, every fresh install missed every entry.)"""
    early, late = 1_000_000_000_000_000_000, 1_700_000_000_000_000_000
    _install(tmp_path / "one", _record(), early)
    _install(tmp_path / "two", _record(script=b"two", installer=b"uv", pyc=False), late)
    _install(tmp_path / "other", _record(core=b"abd"), early)
    _install(tmp_path / "stale", _record(core=b"old").replace(b"%(init)s", b"sha256=old"),
             early, version="0.9")
    _install(tmp_path / "stale", _record(), early)
    _install(tmp_path / "bare", _record(), early)
    (tmp_path / "bare" / "Fake_Dep-1.0.dist-info" / "RECORD").unlink()
    monkeypatch.setattr(cache_module, "_DEPENDENCIES", (("fakedep", "fake-dep"),))
    parts = {}
    for site in ("one", "two", "other", "stale", "bare"):
        monkeypatch.setattr(sys, "path", [str(tmp_path / site), *sys.path])
        sys.path_importer_cache.clear()
        (parts[site],) = cache_module._dependency_files()
        monkeypatch.undo()
        monkeypatch.setattr(cache_module, "_DEPENDENCIES", (("fakedep", "fake-dep"),))
    assert parts["one"] == parts["two"] == parts["stale"] != parts["other"]
    assert parts["one"].startswith("fakedep=record:")
    assert parts["bare"].startswith(f"fakedep={tmp_path / 'bare' / 'fakedep'}")
    assert "fakedep" not in sys.modules


def test_a_read_only_mount_is_said_in_one_wording(tmp_path, monkeypatch):
    """A cache on a read-only mount (a CI job's restored cache): making its folder raises
    EROFS, and the warning reads 'read-only file system' as where os.access found it out
    ('Read-only file system', the system's capital, differed from the README's words)."""
    import errno

    def refuse(*args, **kwargs):
        raise OSError(errno.EROFS, "Read-only file system")

    monkeypatch.setattr(cache_module.os, "makedirs", refuse)
    cache = ResultCache(str(tmp_path / "cache"), {"model": None})
    cache.probe()
    assert cache.unwritable == f"{tmp_path / 'cache'}: read-only file system"
    from furncheck.files import why_failed

    assert why_failed(OSError(errno.EACCES, "Permission denied")) == "permission denied"
    assert why_failed(OSError(errno.ENOSPC, "No space left on device")) == \
        "No space left on device"
