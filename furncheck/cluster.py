"""Work on a Dask cluster: ``--scheduler ADDRESS`` (``pip install 'furncheck[dask]'``).

``connect`` opens a client to the scheduler at ADDRESS and makes sure that its workers run
the same furncheck code as this process (``cache.source_fingerprint``): otherwise their
results could differ from a local run's, and the run stops with one line (``ClusterError``).

``validate``: this process reads each design file (the workers need not see its file
system; a missing or unreadable file gets its error entry here, as ``check_file`` words
it), and the workers check the bytes (``check.check_data``, the same steps as
``check_file``) and make the report entries in the run's format, so the report is written
here as it would be by ``--jobs``: in input order, as the entries come, and byte-identical
to a local run.  Files go in tasks of TASK_FILES consecutive designs, at most
WINDOW_PER_THREAD tasks per worker thread outstanding, so memory stays flat over a large
catalog.  With the result cache, the cache stays here: stored designs are not sent, and
the workers send back the checked designs' results to be stored.

``range``: the DOFs' searches are independent, so their shares (as ``--jobs`` deals them)
go to the workers with the design; each worker prepares the design's search once
(``RangeFinder``) and searches its shares.

A task that fails on the cluster (a worker lost, a result that cannot travel) gives error
entries for its designs, and the batch goes on; a range whose share failed ends the run
with one line.  Dask's nanny starts workers with one BLAS thread (its
``distributed.nanny.pre-spawn-environ``), as the command line runs numpy.
"""

from __future__ import annotations

import functools
import threading
from collections import deque
from collections.abc import Iterator
from typing import TYPE_CHECKING

from furncheck.errors import ClusterError, DesignError

if TYPE_CHECKING:
    from furncheck.cache import ResultCache
    from furncheck.design.model import Design
    from furncheck.report.entries import Entry

CONNECT_SECONDS = 10
"""How long to try to reach the scheduler (Dask retries a refused connection until then)."""

CONNECT_GRACE = 5
"""Seconds beyond CONNECT_SECONDS before a connection that hangs is given up."""

WORKER_SECONDS = 60
"""How long to wait for a worker to join and take the first task (a cluster still
starting its workers, or one with none)."""

TASK_FILES = 16
"""Designs per task: a task costs a few ms of scheduling, a small design ~5 ms to check."""

WINDOW_PER_THREAD = 4
"""Tasks outstanding per worker thread: enough to keep every thread busy while the
report is written here, few enough that memory does not grow with the catalog."""


def connect(address: str):
    """A ``dask.distributed.Client`` of the scheduler at ``address`` whose workers run this
    furncheck; ClusterError (one line for the user) when there is none such."""
    try:
        from dask.distributed import Client
        from distributed.comm import resolve_address
    except ImportError:
        raise ClusterError("--scheduler needs Dask: pip install 'furncheck[dask]'") from None
    try:        # a malformed address refused before a client exists (none left to close)
        resolved = resolve_address(address)
    except (OSError, ValueError) as error:
        raise ClusterError(f"not a Dask scheduler address: {address} "
                           f"({_first_line(error)})") from None
    port = _port(resolved)
    if port is not None and not 0 < port < 65536:     # else a connection waits and fails
        raise ClusterError(f"not a Dask scheduler address: {address} (port {port} is not "
                           f"between 1 and 65535)")
    client = _opened(Client, address)
    try:
        client.wait_for_workers(1, timeout=WORKER_SECONDS)
        theirs = client.submit(_worker_fingerprint, pure=False).result(timeout=WORKER_SECONDS)
    except TimeoutError:
        client.close()
        raise ClusterError(f"no worker of the Dask scheduler at {address} took a task "
                           f"within {WORKER_SECONDS} s") from None
    except Exception as error:  # noqa: BLE001 - whatever the worker could not do
        client.close()
        raise ClusterError(f"the workers of the Dask scheduler at {address} cannot run "
                           f"furncheck: {type(error).__name__}: {_first_line(error)}") from None
    from furncheck import cache

    if theirs != cache.source_fingerprint():
        client.close()
        raise ClusterError(f"the workers of the Dask scheduler at {address} run other "
                           f"furncheck code than this command (install the same version "
                           f"there): their results could differ")
    return client


def _opened(client_class, address: str):
    """A client of the scheduler at ``address``, or ClusterError.  Opened in a thread of
    its own, waited for at most CONNECT_SECONDS and a little more: a server there that
    is not a Dask scheduler may accept the connection and never answer (Dask's own
    timeout does not cover its handshake), or answer with what Dask cannot read."""
    outcome: list = []

    def open_client() -> None:
        try:
            outcome.append(client_class(address, timeout=CONNECT_SECONDS,
                                        set_as_default=False))
        except BaseException as error:  # noqa: BLE001 - reported by the caller's thread
            outcome.append(error)

    opener = threading.Thread(target=open_client, name="furncheck-connect", daemon=True)
    opener.start()
    opener.join(CONNECT_SECONDS + CONNECT_GRACE)
    if not outcome:
        raise ClusterError(f"cannot reach the Dask scheduler at {address}: no answer "
                           f"within {CONNECT_SECONDS} s (is it a Dask scheduler?)")
    if isinstance(outcome[0], BaseException):
        error = outcome[0]
        if isinstance(error, (MemoryError, OverflowError)):
            # it answered, but with what Dask reads as a frame of exbibytes: no scheduler
            raise ClusterError(f"cannot reach the Dask scheduler at {address}: what "
                               f"answered there is no Dask scheduler (its reply could not "
                               f"be read: {type(error).__name__})")
        raise ClusterError(f"cannot reach the Dask scheduler at {address}: "
                           f"{type(error).__name__}: {_first_line(error)}")
    return outcome[0]


def _port(address: str) -> int | None:
    """The port of a resolved TCP-like Dask address ('tcp://host:port'), None for another
    kind (an in-process 'inproc://' one) or none given."""
    from distributed.comm.addressing import parse_address, parse_host_port

    scheme, location = parse_address(address)
    if scheme not in ("tcp", "tls", "ws", "wss"):
        return None
    try:
        return parse_host_port(location)[1]
    except ValueError:
        return None


def _worker_fingerprint() -> str:
    """On a worker: its furncheck's ``source_fingerprint``."""
    from furncheck import cache

    return cache.source_fingerprint()


def _first_line(error: BaseException) -> str:
    text = str(error).strip()
    return text.splitlines()[0] if text else type(error).__name__


def worker_threads(client) -> int:
    """The threads of the cluster's workers, all together (at least 1)."""
    return max(1, sum(client.nthreads().values()))


# --- validate -----------------------------------------------------------------------------

def cluster_entries(client, items: list[tuple[str, str | None]], fmt: str,
                    model: str | None, cache: ResultCache | None = None) -> Iterator[Entry]:
    """The entries of every (path, cache key) of ``items``, in order, checked by the
    cluster's workers (module docstring); with a ``cache``, each result stored under its
    key as it comes back."""
    tasks = [items[k:k + TASK_FILES] for k in range(0, len(items), TASK_FILES)]
    window = WINDOW_PER_THREAD * worker_threads(client)
    pending: deque = deque()
    for task in tasks:
        pending.append(_submit(client, task, fmt, model, cache is not None))
        while len(pending) >= window:
            yield from _finished(pending.popleft(), fmt, model, cache)
    while pending:
        yield from _finished(pending.popleft(), fmt, model, cache)


def _submit(client, task: list[tuple[str, str | None]], fmt: str, model: str | None,
            keep_reports: bool):
    """(task, per path its bytes and format or None, the future of the workers' part)."""
    from furncheck.design.load import read_design_file

    documents = []
    for path, _ in task:
        try:
            documents.append((path, *read_design_file(path)))
        except DesignError:     # its error entry is made here (``_finished``)
            documents.append(None)
    sent = [document for document in documents if document is not None]
    future = client.submit(_check_documents, sent, fmt, model, keep_reports, pure=False) \
        if sent else None
    return task, documents, future


def _finished(submitted, fmt: str, model: str | None,
              cache: ResultCache | None) -> Iterator[Entry]:
    """The entries of a submitted task, in order, when its future is done."""
    from furncheck.batch import entry_of, entry_of_report
    from furncheck.scan import error_report

    task, documents, future = submitted
    done: list = []
    failed = None
    if future is not None:
        try:
            done = future.result()
        except Exception as error:  # noqa: BLE001 - a lost worker, a result that cannot travel
            failed = (f"internal error: a task on the Dask cluster failed "
                      f"({type(error).__name__}: {_first_line(error)})")
        future.release()
    results = iter(done)
    for (path, key), document in zip(task, documents):
        if document is None:            # unreadable here: worded as check_file words it
            yield entry_of(path, fmt, model)
            continue
        if failed is not None:
            yield entry_of_report(error_report(path, failed), fmt)
            continue
        entry, report = next(results)
        if cache is not None and report is not None and cache.store(path, key, report):
            cache.put_piece(key, fmt, (entry.valid, entry.error, entry.piece))
        yield entry


def _check_documents(documents: list[tuple[str, bytes, str]], fmt: str, model: str | None,
                     keep_reports: bool) -> list[tuple[Entry, object]]:
    """On a worker: per (path, bytes, format) its entry in ``fmt``, and its report when
    ``keep_reports`` (for the cache of the process that asked)."""
    from furncheck.batch import entry_of_report, guarded
    from furncheck.check import check_data

    out = []
    for path, data, document_format in documents:
        report = guarded(path, functools.partial(check_data, data, path, document_format,
                                                 model))
        out.append((entry_of_report(report, fmt), report if keep_reports else None))
    return out


# --- range --------------------------------------------------------------------------------

def cluster_ranges(client, design: Design, locked: tuple[str, ...],
                   shares: list[list]) -> list[tuple[list, int]]:
    """Per share of DOFs, (its ranges, the full checks they took), searched on the
    cluster's workers; the design goes to every worker once (``scatter``)."""
    sent = client.scatter(design, broadcast=True)
    futures = [client.submit(_ranges_of_share, sent, locked, share, pure=False)
               for share in shares]
    try:
        return client.gather(futures)
    except Exception as error:  # noqa: BLE001 - a lost worker, a result that cannot travel
        raise ClusterError(f"a range search on the Dask cluster failed: "
                           f"{type(error).__name__}: {_first_line(error)}") from None


_FINDERS = threading.local()
"""On a worker thread: the RangeFinder of the design it searched last, kept for its other
shares (a finder is not shared between threads: its searches keep state)."""


def _ranges_of_share(design: Design, locked: tuple[str, ...], share: list):
    from furncheck.ranges import RangeFinder

    finder = getattr(_FINDERS, "finder", None)
    if finder is None or finder.design is not design or finder.locked_names != locked:
        finder = _FINDERS.finder = RangeFinder(design, locked)
    return finder.search(share)
