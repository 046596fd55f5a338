"""The ``furncheck`` command group, and ``run``, the console script ``furncheck`` and
``python -m furncheck`` (``main`` as a process of its own)."""

from __future__ import annotations

import contextlib
import errno
import gc
import importlib
import os
import signal
import sys
from types import FrameType

import click

from furncheck import __version__, exitcodes

COMMANDS = {"validate": ("furncheck.cli.validate", "validate"),
            "suggest": ("furncheck.cli.suggest", "suggest"),
            "range": ("furncheck.cli.range", "range_command")}
"""Each command's module and function, imported when the command is run (or listed by
--help): a run imports only its own command's options and checks."""

DEBUG_VARIABLE = "FURNCHECK_DEBUG"
"""Set (to anything), an internal error shows its traceback before its one line (exit
code 2 either way)."""


class _OneLine(click.ClickException):
    """A usage error, or an internal error (a bug), as one line on stderr (contract
    section 4: one line per problem, never a traceback), exit code 2."""

    exit_code = exitcodes.BAD_INPUT

    def show(self, file=None) -> None:
        click.echo(self.message, err=True)


class _Terminated(BaseException):
    """Raised by the console script's SIGTERM handler (``run``) wherever the run is: it
    unwinds as Ctrl-C does (an ``-o`` file's temporary copy removed, worker pools shut
    down), not caught by the library's ``except Exception``."""


class _Interrupted(click.ClickException):
    """A run stopped by SIGINT or SIGTERM: one line on stderr, exit code 128 + the
    signal's number (``exitcodes.signalled``: 130, 143), which no finished run gives, so
    that a CI step that lets exit 1 (invalid designs) pass does not take an incomplete
    report for a finished one (click's own 'Aborted!' exits 1)."""

    def __init__(self, number: int):
        super().__init__(f"furncheck: interrupted ({signal.Signals(number).name}); the "
                         "report is incomplete")
        self.exit_code = exitcodes.signalled(number)

    def show(self, file=None) -> None:
        click.echo(self.message, err=True)


def _stop(number: int, frame: FrameType | None) -> None:
    """The console script's handler of SIGINT and SIGTERM: the first one unwinds the run
    (``_Interrupted``); from then on both are left to their default action, so that a
    second one (a CI's SIGTERM 7.5 s after its SIGINT) ends the process at once, never
    inside the unwinding."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if number == signal.SIGINT:
        raise KeyboardInterrupt
    raise _Terminated(number)


@contextlib.contextmanager
def _said_when_stopped():
    """A run stopped by Ctrl-C or SIGTERM (``_stop``) where it was: ``_Interrupted``, one
    line and exit 128 + the signal's number."""
    try:
        yield
    except KeyboardInterrupt:
        raise _Interrupted(signal.SIGINT) from None
    except _Terminated:
        raise _Interrupted(signal.SIGTERM) from None


def _one_line(error: click.UsageError) -> click.UsageError | _OneLine:
    """``error`` as one line: the command, click's message and where help is, e.g.
    "furncheck validate: no such option '--bogus'. Did you mean '--jobs'? (see 'furncheck
    validate --help')".  A bare ``furncheck`` keeps showing its help."""
    if isinstance(error, click.exceptions.NoArgsIsHelpError):
        return error
    path = error.ctx.command_path if error.ctx is not None else "furncheck"
    message = " ".join(error.format_message().split())
    message = message[:1].lower() + message[1:].rstrip(".")
    return _OneLine(f"{path}: {message} (see '{path} --help')")


class _Commands(click.Group):
    """The command group, its usage errors (an unknown option or command, a missing
    argument, a value of the wrong type) one line each instead of click's usage block,
    and so are an OSError (the machine's words) and any other exception (a bug).  Its
    commands are imported by name when asked for (``COMMANDS``)."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        return sorted(COMMANDS)

    def get_command(self, ctx: click.Context, name: str) -> click.Command | None:
        if name not in COMMANDS:
            return None
        module, function = COMMANDS[name]
        return getattr(importlib.import_module(module), function)

    def make_context(self, *args, **kwargs):
        try:
            with _said_when_stopped():  # while the options are read: said as in a run
                return super().make_context(*args, **kwargs)
        except click.UsageError as error:
            raise _one_line(error) from None

    def invoke(self, ctx: click.Context):
        try:
            with _said_when_stopped():
                return super().invoke(ctx)
        except click.UsageError as error:
            raise _one_line(error) from None
        except (click.exceptions.ClickException, click.exceptions.Exit, click.Abort,
                SystemExit, EOFError, BrokenPipeError):
            raise                       # click's own handling (EOF: 'Aborted!'; a closed pipe)
        except OSError as error:        # the machine's, not a bug: a full disk, a pipe
            _traceback_if_debugging()
            raise _OneLine(f"furncheck: {error.strerror or error}") from None
        except Exception as error:      # a bug: one line and exit 2, not a traceback
            _traceback_if_debugging()
            said = " ".join(str(error).split())
            raise _OneLine(f"furncheck: internal error: {type(error).__name__}: {said} "
                           f"(a bug: please report it with the design; {DEBUG_VARIABLE}=1 "
                           "shows the traceback)") from None


def _traceback_if_debugging() -> None:
    """With FURNCHECK_DEBUG set, the traceback of the error being handled on stderr (the
    one line and exit code 2 follow as without it: re-raised, it exited 1, which a CI step
    that lets invalid designs pass took for a finished run)."""
    if os.environ.get(DEBUG_VARIABLE):
        import traceback

        traceback.print_exc()


@click.group("furncheck", cls=_Commands, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, "--version", prog_name="furncheck",
                      message="%(prog)s %(version)s")
def main() -> None:
    """Check nail-jointed plank furniture designs for durability and stability.

    validate: verdicts on design files; suggest: ranked changes that make an invalid
    design valid; range: valid interval of each design DOF.
    Exit codes: 0 all designs valid (or done), 1 some design invalid (validate), 2
    unreadable, ill-formed or too big input, a usage error, or a Dask cluster
    (--scheduler) that cannot be used; 130 or 143 interrupted (SIGINT, SIGTERM).
    """


def run() -> None:
    """The console script: ``main`` as a process of its own, exiting with its code.

    When the command is done, every object still alive is frozen (``gc.freeze``), so the
    interpreter's last collection on the way out skips them: they are about to be
    dropped, and walking numpy's and furncheck's objects once more cost about 20 ms of a
    140 ms check of the stool (``benchmarks/bench_catalog.py``).  Files and streams are
    closed or flushed before this, and atexit handlers (worker pools, temporary folders,
    a Dask client) still run; what it skips is finalizing garbage cycles, which Python
    does not promise at exit either.  SIGTERM (a CI's cancel) stops the run as Ctrl-C
    does (``_Interrupted``: exit 143), and a second signal ends it at once (``_stop``).
    At the end it leaves ``_quiet_closed_pipe`` as ``sys.unraisablehook`` for the exit.
    ``main`` called in a process that goes on (the tests' CliRunner) does none of this."""
    signal.signal(signal.SIGINT, _stop)
    signal.signal(signal.SIGTERM, _stop)
    try:
        main(prog_name="furncheck")
    finally:
        gc.freeze()
        sys.unraisablehook = _quiet_closed_pipe


def _quiet_closed_pipe(unraisable) -> None:
    """``sys.unraisablehook`` for the interpreter's exit: a closed file descriptor (EBADF)
    raised where nothing can catch it is not printed; anything else is, as Python prints
    it.  CPython 3.11's process pools wake their finished manager threads once more at
    exit, through a pipe that a worker pool's shutdown may have closed just before, and
    the 'Exception ignored in: <module 'threading'>' traceback it prints (seen about once
    in 60 batch runs on a loaded machine, after the report and with the right exit code)
    would be the only traceback a user ever sees; every pool is shut down before the
    command returns."""
    error = unraisable.exc_value
    if isinstance(error, OSError) and error.errno == errno.EBADF:
        return
    sys.__unraisablehook__(unraisable)


if __name__ == "__main__":  # pragma: no cover
    run()
