"""Writing a command's report (stdout or ``-o FILE``) and failing with one line, exit 2."""

from __future__ import annotations

import os
import sys
from collections.abc import Iterable
from typing import NoReturn

import click

from furncheck import exitcodes
from furncheck import tolerances as tol
from furncheck.files import neutral, utf8


def fail(message: str | list[str]) -> NoReturn:
    """One line on stderr (per problem, for a design file's list of them), exit code 2
    (bad input or usage)."""
    for problem in [message] if isinstance(message, str) else message:
        click.echo(neutral(f"furncheck: {problem}"), err=True)
    raise click.exceptions.Exit(exitcodes.BAD_INPUT)


def output_problem(output: str) -> str | None:
    """Why ``-o output`` cannot be written, found before any work is done, or None.  A
    missing folder on its path is no problem: it is made when the report is written
    (``make_folder``; as ``--views`` makes its folder, and pytest's ``--junitxml`` its
    report's: a CI job writes to a fresh 'reports/' folder), not before, so a run that
    fails leaves none behind."""
    if not output:          # an unset variable in a script: the path of no file
        return "an empty path names no file"
    if output.endswith(("/", os.sep)) or os.path.isdir(output):
        return "it is a directory" if os.path.isdir(output) else "it names a folder"
    parent = os.path.dirname(os.path.abspath(output))
    existing = parent
    while not os.path.exists(existing):
        existing = os.path.dirname(existing)
    if not os.path.isdir(existing):
        return f"{existing} is a file, not a folder"
    from furncheck.files import why_unwritable

    if existing != parent:
        return None if os.access(existing, os.W_OK) else \
            f"cannot make the folder {os.path.dirname(output)} ({why_unwritable(existing)})"
    if os.path.exists(output) and not os.access(output, os.W_OK):
        return why_unwritable(output)
    if not os.path.exists(output) and not os.access(parent, os.W_OK):
        return why_unwritable(parent)
    return None


def make_folder(path: str) -> None:
    """Make the missing folders on ``path``'s way (a file to write; OSError as raised)."""
    parent = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(parent):
        os.makedirs(parent, exist_ok=True)


def check_output(output: str | None, what: str = "the report") -> None:
    """Fail early if ``-o output`` (or another file: ``what`` names it) cannot be written
    ('-' and None mean stdout: closed (``>&-``), the report would be lost without a word
    and the exit code say all went well)."""
    if output is not None and output != "-":
        problem = output_problem(output)
        if problem:
            fail(f"cannot write {what} to {output}: {problem}")
    elif sys.stdout is None:
        fail(f"cannot write {what} to standard output: it is closed")


def check_not_an_input(output: str | None, inputs, what: str = "the report") -> None:
    """Fail (one line, exit 2) when ``-o output`` is one of the design files to check
    (``inputs``: their paths; '-' and None are stdout): the report would replace the
    design, an easy slip in a script that builds its argument list."""
    if output is None or output == STDIN or not os.path.exists(output):
        return
    for path in inputs:
        if isinstance(path, str) and path != STDIN and os.path.exists(path) \
                and os.path.samefile(path, output):
            fail(f"cannot write {what} to {output}: it is one of the designs to check")


def check_apart(output: str | None, other: str | None, what: str, others: str) -> None:
    """Fail (one line, exit 2) when two files a run writes are one (``validate -o r.html
    --html r.html``: the page replaced the report, which the run said it had written)."""
    if output is None or other is None or STDIN in (output, other):
        return
    same = os.path.samefile(output, other) if os.path.exists(output) \
        and os.path.exists(other) else os.path.realpath(output) == os.path.realpath(other)
    if same:            # (realpath: through a linked folder, or a link not yet pointing)
        fail(f"cannot write {what} to {output}: {others} goes there")


def write_output(document: str, output: str | None) -> None:
    """Write the report to stdout or to ``output``."""
    write_chunks([document], output)


WRITE_BLOCK = 1 << 16
"""Characters of a report gathered before they are written (a streamed report comes in
one piece per design)."""


def write_chunks(chunks: Iterable[str], output: str | None) -> None:
    """Write the report, given as consecutive pieces, to stdout or to ``output``, as the
    pieces come (in blocks of about WRITE_BLOCK characters).  ``output`` is written
    atomically: until the report is complete it holds the old one (an interrupted run
    leaves it as it was)."""
    from furncheck.files import replacing

    if output is None or output == "-":
        _write_blocks(chunks, _echo, "standard output")
        return
    try:
        make_folder(output)
        with replacing(output, durable=True) as stream:
            _write_blocks(chunks, lambda text: stream.write(utf8(text)), output)
    except OSError as error:
        fail(f"cannot write the report to {output}: {error.strerror or error}")


def _echo(text: str) -> None:
    """``text`` to standard output; what its encoding cannot take (a file name's bytes
    that are not UTF-8, as in ``files.utf8``) escaped."""
    try:
        click.echo(text, nl=False)
    except UnicodeEncodeError:
        encoding = getattr(sys.stdout, "encoding", None) or "utf-8"
        click.echo(text.encode(encoding, "backslashreplace").decode(encoding), nl=False)


def _write_blocks(chunks: Iterable[str], write, where: str) -> None:
    """``write`` the chunks joined in blocks; a failing write is one line, exit 2."""
    block: list[str] = []
    size = 0
    for chunk in chunks:
        block.append(chunk)
        size += len(chunk)
        if size >= WRITE_BLOCK:
            _write(write, "".join(block), where)
            block, size = [], 0
    if block:
        _write(write, "".join(block), where)


def _write(write, text: str, where: str) -> None:
    try:
        write(text)
    except OSError as error:
        fail(f"cannot write the report to {where}: {error.strerror or error}")


class WholeNumber(click.ParamType):
    """A whole number from ``least`` to ``most`` (None: no limit), said in words where it
    is not one ('expected a whole number of at least 1, got 'abc''), where click says
    "'abc' is not a valid integer range" or "0 is not in the range x>=1"."""

    name = "integer"

    def __init__(self, least: int, most: int | None = None):
        self.least, self.most = least, most

    def convert(self, value, param, ctx) -> int:
        if isinstance(value, int) and not isinstance(value, bool):
            number = value
        else:       # digits alone: not '1_0', '٣' or '+ 2', which int() would take
            text = str(value).strip()
            number = int(text) if text.isascii() and text.isdigit() else None
        if number is None or number < self.least or \
                (self.most is not None and number > self.most):
            self.fail(f"expected {self.wanted()}, got {value!r}", param, ctx)
        return number

    def wanted(self) -> str:
        if self.most is None:
            return f"a whole number of at least {self.least}"
        return f"a whole number from {self.least} to {self.most}"


MODEL_OPTION = click.option(
    "--model", type=click.Choice(list(tol.MODELS)), default=None,
    help="Statics model, over the files' own 'model': elastic (planks bend: contract 3a) "
         "or rigid (the paper's rigid planks).  [default: 'model' of [tool.furncheck], "
         "else the file's 'model', elastic for a file without one]")


def config_or_fail(paths, stdin_name: str | None = None):
    """``[tool.furncheck]`` for a run on ``paths`` (``furncheck.config``), standard input
    standing for the file ``stdin_name`` where it is given (``--stdin-filename``: an
    editor piping a draft from another folder gets its project's options, as the file
    would), or one line and exit 2."""
    from furncheck.config import ConfigError, load_config

    if stdin_name:
        paths = tuple(stdin_name if path == STDIN else path for path in paths)
    try:
        return load_config(paths)
    except ConfigError as error:
        fail(str(error))


STDIN = "-"
"""The PATH or DESIGN that stands for a design on standard input."""

STDIN_NAME = "<stdin>"
"""How reports name a design read from standard input without ``--stdin-filename``."""

STDIN_FILENAME_OPTION = click.option(
    "--stdin-filename", metavar="NAME", default=None,
    help="The name reports give a design read from '-' (standard input); its extension "
         "picks YAML or JSON.  [default: <stdin>, format by content]")


def stdin_document(name: str | None) -> tuple[bytes, str, str]:
    """Standard input's bytes, the name reports give them (``name``, else STDIN_NAME) and
    their format: by the name's extension, else JSON when the text starts with '{'.
    Raises DesignError when standard input is closed or cannot be read."""
    from furncheck.errors import DesignError

    source = name or STDIN_NAME
    if sys.stdin is None:                   # started with standard input closed (<&-)
        raise DesignError(source, "", None, "cannot read standard input: it is closed")
    try:
        data = sys.stdin.buffer.read()
    except (OSError, ValueError) as error:  # a bad descriptor, or a closed stream
        raise DesignError(source, "", None, "cannot read standard input: "
                          f"{getattr(error, 'strerror', None) or error}") from None
    suffix = os.path.splitext(source)[1].lower()
    fmt = {".json": "json", ".yaml": "yaml", ".yml": "yaml"}.get(suffix)
    if fmt is None:
        fmt = "json" if data.lstrip(b"\xef\xbb\xbf \t\r\n").startswith(b"{") else "yaml"
    return data, source, fmt


def check_stdin_name(stdin_name: str | None, paths) -> None:
    """Fail (one line, exit 2) when ``--stdin-filename`` is given but no design is read
    from '-': it would name nothing (a forgotten '-')."""
    if stdin_name is not None and STDIN not in paths:
        fail("--stdin-filename names the design read from '-' (standard input), and no "
             "'-' was given")


def load_or_fail(path: str, model: str | None = None, stdin_name: str | None = None,
                 fmt: str = "text", output: str | None = None):
    """The design at ``path`` (standard input for STDIN, named ``stdin_name``), in
    ``model`` when given, or one line and exit 2 when it cannot be read (with ``fmt``
    'json' a report of the error too: ``fail_as``)."""
    from furncheck.check import load_checked, load_data
    from furncheck.design.model import with_model
    from furncheck.errors import DesignError

    check_stdin_name(stdin_name, (path,))
    try:
        loaded = load_data(*stdin_document(stdin_name)) if path == STDIN else load_checked(path)
        return with_model(loaded, model)
    except DesignError as error:
        fail_as(error.file or path, error.lines(), fmt, output)


def fail_as(path: str, message: str | list[str], fmt: str, output: str | None) -> NoReturn:
    """``fail(message)``, after writing with ``fmt`` 'json' the report (to ``output``, or
    stdout) as a document of its own, ``{"design": path, "error": message}`` (the design
    and error of ``validate``'s entry for a file it cannot check), for the tools that
    read it."""
    if fmt == "json":
        import json

        problems = [message] if isinstance(message, str) else message
        document = {"design": path, "error": problems[0]}
        if len(problems) > 1:                   # as validate's entry: every problem too
            document["errors"] = problems
        write_output(json.dumps(document, indent=2) + "\n", output)
    fail(message)


def dofs_or_fail(path: str, design, names, fmt: str = "text",
                 output: str | None = None) -> tuple:
    """The named DOFs of ``design``, or one line naming the bad one and exit 2 (with
    ``fmt`` 'json' a report of the error too: ``fail_as``)."""
    from furncheck.dofs import parse_dof
    from furncheck.errors import DofError

    try:
        return tuple(parse_dof(design, name) for name in names)
    except DofError as error:
        fail_as(path, f"{path}: {error}", fmt, output)


SCHEDULER_OPTION = click.option(
    "--scheduler", metavar="ADDRESS", envvar="FURNCHECK_SCHEDULER", default=None,
    help="Do the work on the Dask cluster whose scheduler is at ADDRESS, e.g. "
         "tcp://10.0.0.5:8786 (needs the dask extra; the workers need the same furncheck); "
         "the output is the same as a local run's.  [env: FURNCHECK_SCHEDULER]")


def client_or_fail(address: str | None):
    """A Dask client of the scheduler at ``address`` (``furncheck.cluster.connect``), None
    without one, or one line and exit 2."""
    if address is None:
        return None
    from furncheck.cluster import connect
    from furncheck.errors import ClusterError

    try:
        return connect(address)
    except ClusterError as error:
        fail(str(error))
