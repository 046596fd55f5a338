"""``--scheduler ADDRESS``: validate and range on a Dask cluster (``furncheck.cluster``).

A LocalCluster of two worker processes (one thread each) stands for a real cluster: the
workers are separate interpreters that import furncheck themselves, receive the designs'
bytes and send back report entries (validate) or DOF ranges (range).  The output must be
byte-identical to a local run's, whatever the cluster.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
from click.testing import CliRunner

from furncheck.cli.main import main as cli

distributed = pytest.importorskip("distributed", reason="the dask extra is not installed")

DESIGNS = Path(__file__).resolve().parent.parent / "designs"


@pytest.fixture(scope="module")
def scheduler():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=":0")   # any free port: runs may overlap
    try:
        yield cluster.scheduler_address
    finally:
        cluster.close()


def _run(*args: str):
    return CliRunner().invoke(cli, list(args), catch_exceptions=False)


@pytest.fixture()
def catalog(tmp_path):
    """The bundled catalog, a design file that does not parse and a missing path."""
    folder = tmp_path / "catalog"
    shutil.copytree(DESIGNS, folder)
    (folder / "broken.yaml").write_text("furncheck: 1\nplanks: [\n")
    return [str(folder), str(tmp_path / "missing.yaml")]


@pytest.mark.parametrize("fmt", ["json", "text"])
def test_validate_on_the_cluster_writes_the_local_report(scheduler, catalog, fmt):
    local = _run("validate", *catalog, "--format", fmt, "--no-cache", "--jobs", "1")
    remote = _run("validate", *catalog, "--format", fmt, "--no-cache", "--scheduler", scheduler)
    assert local.exit_code == remote.exit_code == 2       # the broken and the missing file
    assert remote.stdout == local.stdout
    if fmt == "json":
        designs = json.loads(remote.stdout)["reports"]
        assert len(designs) == len(list(DESIGNS.rglob("*.yaml"))) + 2
        errors = sorted(d["name"] for d in designs if "error" in d)
        assert errors == ["broken", "missing"]


def test_cluster_results_fill_the_cache_of_this_process(scheduler, tmp_path):
    """Checked on the cluster, stored here: a second, local run reads every design back
    from the cache (none checked: the checker is broken for that run) with the same
    report."""
    cache = str(tmp_path / "cache")
    first = _run("validate", str(DESIGNS), "--format", "json", "--cache-dir", cache,
                 "--scheduler", scheduler)
    stored = list(Path(cache).rglob("*"))
    assert any(path.is_file() for path in stored)
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr("furncheck.batch.check_one", lambda *_: pytest.fail("checked again"))
        second = _run("validate", str(DESIGNS), "--format", "json", "--cache-dir", cache,
                      "--jobs", "1")
    assert second.exit_code == first.exit_code == 1
    assert second.stdout == first.stdout


def test_range_on_the_cluster_gives_the_local_ranges(scheduler):
    design = str(DESIGNS / "stool.yaml")
    local = _run("range", design, "--format", "json", "--jobs", "1")
    remote = _run("range", design, "--format", "json", "--scheduler", scheduler)
    assert remote.exit_code == local.exit_code == 0
    assert remote.stdout == local.stdout
    assert len(json.loads(remote.stdout)["ranges"]) >= 16   # shared among the workers


def test_workers_running_other_code_are_refused(scheduler, monkeypatch):
    """The workers' fingerprint is computed there from their own source; this process's is
    made to differ, as after an upgrade on one side only."""
    import furncheck.cache

    real = furncheck.cache.source_fingerprint
    monkeypatch.setattr(furncheck.cache, "source_fingerprint", lambda: real() + "-changed")
    result = CliRunner().invoke(cli, ["validate", str(DESIGNS / "stool.yaml"),
                                      "--scheduler", scheduler])
    assert result.exit_code == 2
    assert "run other furncheck code" in result.stderr
    assert result.stderr.count("\n") == 1 and "Traceback" not in result.stderr


@pytest.mark.parametrize(("address", "words"), [
    ("nonsense-address", "not a Dask scheduler address: nonsense-address"),
    ("foo://1.2.3.4:5", "unknown address scheme"),
    ("tcp://127.0.0.1:99999", "not a Dask scheduler address: tcp://127.0.0.1:99999 (port "
                              "99999 is not between 1 and 65535)"),
])
def test_a_bad_address_is_one_line_and_exit_2(address, words):
    result = CliRunner().invoke(cli, ["range", str(DESIGNS / "stool.yaml"),
                                      "--scheduler", address])
    assert result.exit_code == 2
    assert words in result.stderr and result.stderr.count("\n") == 1


def test_an_unreachable_scheduler_is_one_line_and_exit_2(monkeypatch):
    import socket

    import furncheck.cluster as cluster

    monkeypatch.setattr(cluster, "CONNECT_SECONDS", 1)
    with socket.socket() as unused:             # a port that nothing listens on
        unused.bind(("127.0.0.1", 0))
        port = unused.getsockname()[1]
    result = CliRunner().invoke(cli, ["validate", str(DESIGNS / "stool.yaml"),
                                      "--scheduler", f"tcp://127.0.0.1:{port}"])
    assert result.exit_code == 2
    assert result.stderr.startswith(
        f"furncheck: cannot reach the Dask scheduler at tcp://127.0.0.1:{port}")
    assert result.stderr.count("\n") == 1


def test_without_dask_the_option_says_what_to_install(monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "dask.distributed", None)
    result = CliRunner().invoke(cli, ["validate", str(DESIGNS / "stool.yaml"),
                                      "--scheduler", "tcp://127.0.0.1:8786"])
    assert result.exit_code == 2
    assert result.stderr == ("furncheck: --scheduler needs Dask: "
                             "pip install 'furncheck[dask]'\n")


def test_the_scheduler_comes_from_the_environment(monkeypatch):
    monkeypatch.setenv("FURNCHECK_SCHEDULER", "nonsense-address")
    result = CliRunner().invoke(cli, ["validate", str(DESIGNS / "stool.yaml")])
    assert result.exit_code == 2 and "nonsense-address" in result.stderr


def test_a_failed_task_gives_error_entries_and_the_batch_goes_on(tmp_path):
    """A task lost on the cluster (here: a client whose every second task fails) gives its
    designs error entries saying so; the other tasks' designs keep their verdicts, in
    order, and an unreadable file still gets its own error."""
    from furncheck import cluster

    class Future:
        def __init__(self, value, error):
            self.value, self.error = value, error

        def result(self):
            if self.error:
                raise RuntimeError("worker tcp://10.0.0.9:4000 lost\nmore")
            return self.value

        def release(self):
            pass

    class Client:
        submitted = 0

        def nthreads(self):
            return {"w": 1}

        def submit(self, function, *args, pure=True):
            Client.submitted += 1
            return Future(function(*args), Client.submitted % 2 == 0)

    paths = [str(DESIGNS / "stool.yaml")] * (cluster.TASK_FILES + 2) + [str(tmp_path / "x.yaml")]
    entries = list(cluster.cluster_entries(Client(), [(p, None) for p in paths], "text", None))
    assert len(entries) == len(paths)
    first, second = entries[:cluster.TASK_FILES], entries[cluster.TASK_FILES:-1]
    assert all(entry.valid is False and not entry.error for entry in first)
    assert all(entry.error for entry in second)
    assert "a task on the Dask cluster failed (RuntimeError: worker tcp://10.0.0.9:4000 " \
           "lost)" in second[0].piece
    assert "no such file" in entries[-1].piece


def test_a_server_that_never_answers_is_one_line_and_exit_2(monkeypatch):
    """Something listens at the address but is no Dask scheduler: it accepts the
    connection and says nothing (Dask's own timeout does not cover the handshake)."""
    import socket

    import furncheck.cluster as cluster

    monkeypatch.setattr(cluster, "CONNECT_SECONDS", 1)
    monkeypatch.setattr(cluster, "CONNECT_GRACE", 1)
    with socket.socket() as silent:
        silent.bind(("127.0.0.1", 0))
        silent.listen()
        port = silent.getsockname()[1]
        result = CliRunner().invoke(cli, ["validate", str(DESIGNS / "stool.yaml"),
                                          "--scheduler", f"tcp://127.0.0.1:{port}"])
    assert result.exit_code == 2
    assert result.stderr == (f"furncheck: cannot reach the Dask scheduler at "
                             f"tcp://127.0.0.1:{port}: no answer within 1 s (is it a Dask "
                             f"scheduler?)\n")


def test_a_server_that_answers_as_no_dask_scheduler_is_one_line_and_exit_2(monkeypatch):
    """Something at the address answers, but not as Dask does (an SSH banner and bytes
    that Dask reads as a frame length of exbibytes): one line saying so, where it said
    'MemoryError: Unable to allocate 2.82 EiB'."""
    import socket
    import threading

    import furncheck.cluster as cluster

    monkeypatch.setattr(cluster, "CONNECT_SECONDS", 2)
    monkeypatch.setattr(cluster, "CONNECT_GRACE", 1)
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen()
    port = server.getsockname()[1]

    def banner() -> None:
        while True:
            try:
                connection, _ = server.accept()
            except OSError:
                return
            with connection:
                connection.sendall(b"SSH-2.0-OpenSSH_9.6\r\n" + b"\xff" * 64)

    threading.Thread(target=banner, daemon=True).start()
    try:
        result = CliRunner().invoke(cli, ["validate", str(DESIGNS / "stool.yaml"),
                                          "--scheduler", f"tcp://127.0.0.1:{port}"])
    finally:
        server.close()
    assert result.exit_code == 2
    assert result.stderr.count("\n") == 1
    assert result.stderr == (f"furncheck: cannot reach the Dask scheduler at "
                             f"tcp://127.0.0.1:{port}: what answered there is no Dask "
                             f"scheduler (its reply could not be read: MemoryError)\n")


def test_a_scheduler_without_workers_is_one_line_and_exit_2(monkeypatch):
    import furncheck.cluster as cluster

    monkeypatch.setattr(cluster, "WORKER_SECONDS", 1)
    with distributed.LocalCluster(n_workers=0, processes=False,
                                  dashboard_address=":0") as empty:
        result = CliRunner().invoke(cli, ["validate", str(DESIGNS / "stool.yaml"),
                                          "--scheduler", empty.scheduler_address])
    assert result.exit_code == 2
    assert result.stderr == (f"furncheck: no worker of the Dask scheduler at "
                             f"{empty.scheduler_address} took a task within 1 s\n")
