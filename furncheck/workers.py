"""What every worker process of furncheck's pools does first (``quiet_worker``)."""

from __future__ import annotations

import signal


def quiet_worker() -> None:
    """A pool's initializer: Ctrl-C is left to the parent process.  The terminal sends it
    to the whole process group; a worker that took it printed a KeyboardInterrupt
    traceback from inside ``multiprocessing`` after the parent's own one-line 'Aborted!'.
    Ignoring it, each worker ends with its current task when the parent shuts the pool
    down.  SIGTERM ends a worker at once, as by default (a forked worker would otherwise
    inherit the command line's handler, which unwinds the parent's run)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
