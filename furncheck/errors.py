"""Errors a user can cause, typed and carrying their data.

They are turned into one line at the edge (the CLI, the reporters); the library never
prints.  ``str(error)`` is that line: ``file:line: key.path: message``.
"""

from __future__ import annotations


class FurncheckError(Exception):
    """Base class of every error furncheck raises on purpose."""


class DesignError(FurncheckError):
    """A design file that cannot be read or is ill-formed.

    file : the path as the user gave it
    key  : key path inside the document, e.g. ``planks[1].size`` ('' for the whole file)
    line : 1-based line in the file (YAML, or JSON syntax errors), or None
    message : what is wrong, in words
    """

    def __init__(self, file: str, key: str, line: int | None, message: str):
        self.file = file
        self.key = key
        self.line = line
        self.message = message
        self.more: tuple[DesignError, ...] = ()     # the file's other problems, in order
        super().__init__(self.one_line())

    def one_line(self) -> str:
        where = self.file if self.line is None else f"{self.file}:{self.line}"
        return f"{where}: {self.key}: {self.message}" if self.key else f"{where}: {self.message}"

    def lines(self) -> list[str]:
        """One line per problem of the file (contract section 4): this one, then
        ``more`` (``str(error)`` is this one's line alone)."""
        return [problem.one_line() for problem in (self, *self.more)]


class DesignTooBig(DesignError):
    """A design whose check would need more memory than furncheck allows itself, refused
    before any solve: the dense system of its grounded planks' displacements
    (``statics.condense``) would have ``unknowns`` rows and columns, more than ``limit``
    (``of_unknowns``), or its planks' boxes meet in more pairs than the geometry compares
    (``of_pairs``)."""

    def __init__(self, file: str, detail: str, size: int, limit: int):
        self.size = size            # the unknowns, or the pairs
        self.limit = limit
        super().__init__(file, "", None, f"too big to check: {detail}")

    @classmethod
    def of_unknowns(cls, file: str, unknowns: int, limit: int) -> DesignTooBig:
        nodes, most = unknowns // 6, limit // 6
        return cls(file, f"its ground contacts sit on {nodes} nodes, a dense contact "
                         f"system of {unknowns} unknowns (furncheck takes at most {limit}, "
                         f"{most} nodes: about 1 GB of memory)", unknowns, limit)

    @classmethod
    def of_pairs(cls, file: str, pairs: int, planks: int, limit: int) -> DesignTooBig:
        return cls(file, f"its {planks} planks meet or overlap in {pairs} pairs, each "
                         f"compared face by face (furncheck takes at most {limit}: about "
                         "500 MB of memory; planks drawn on top of one another?)", pairs,
                   limit)


class MechanismError(FurncheckError):
    """The statics system has no unique solution: some planks are free to move.

    planks : ids of the planks that form the free part
    """

    def __init__(self, planks: tuple[str, ...], message: str):
        self.planks = tuple(planks)
        self.message = message
        super().__init__(message)


class DofError(FurncheckError):
    """An unknown or malformed DOF name given on the command line."""

    def __init__(self, name: str, message: str):
        self.name = name
        self.message = message
        super().__init__(f"{name}: {message}")


class ClusterError(FurncheckError):
    """A Dask cluster (``--scheduler ADDRESS``) that cannot be used: Dask not installed,
    the scheduler not reachable, no worker answering, or workers running other furncheck
    code (their results could differ from a local run's)."""
