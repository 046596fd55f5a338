"""The README's command examples say what the tool prints now.

Each fenced block of README.md whose lines start with ``$ furncheck`` is one or more
commands, each followed by what it prints.  Those that read only files of this
repository (the catalog in ``designs/``, ``benchmarks/``) and write none are run here, and
their printed lines must appear in the output in the same order: a README line may leave
lines out between two shown ones (a cut list, "..."), and one ending in "..." stands for
any line that begins with the text before it.  A number or a phrase that the tool no
longer prints fails the test (found by a newcomer's check: a range end, 80.068 where the
tool printed 79.703, and a suggestion's missing "; to fit, shorten ..." had drifted).
"""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest
from click.testing import CliRunner

from furncheck.cli.main import main

ROOT = Path(__file__).resolve().parents[1]
ELIDED = "..."
WRITING = {"--out", "-o", "--html", "--cache-dir"}
"""Options that write files: examples with them are not run here."""


def _examples() -> list[tuple[int, list[str], list[str]]]:
    """(README line, the command's arguments after ``furncheck``, the lines it is shown
    to print) of every example that reads only existing repository files and writes
    none."""
    lines = (ROOT / "README.md").read_text(encoding="utf-8").splitlines()
    found, block = [], None
    for number, line in enumerate(lines, start=1):
        if line.startswith("```"):
            block = [] if block is None else None
            continue
        if block is None:
            continue
        if line.startswith("$ furncheck "):
            args = shlex.split(line[len("$ furncheck "):])
            found.append((number, args, []))
            block.append(found[-1])
        elif line.startswith("$ "):
            block.append(None)                  # another program's command: not ours
        elif block and block[-1] is not None:
            block[-1][2].append(line)
    return [(number, args, shown) for number, args, shown in found
            if shown and _runnable(args)]


def _runnable(args: list[str]) -> bool:
    """Whether the example reads only files that exist here and writes none."""
    if WRITING & set(args):
        return False
    paths = [a for a in args[1:] if not a.startswith("-") and re.search(r"\.(ya?ml|json)$", a)]
    return bool(paths) and all((ROOT / path).is_file() for path in paths) \
        and not any(a in (".", "-") for a in args)


def _matches(shown: str, printed: str) -> bool:
    if shown.endswith(ELIDED) and shown.strip() != ELIDED:
        return printed.startswith(shown[:-len(ELIDED)].rstrip()) or \
            printed.rstrip() == shown[:-len(ELIDED)].rstrip()
    return printed.rstrip() == shown.rstrip()


EXAMPLES = _examples()


def test_the_readme_has_examples_to_run():
    """The collector finds the README's runnable examples (a change of its fences or
    prompts would otherwise leave this file testing nothing)."""
    commands = [" ".join(args) for _, args, _ in EXAMPLES]
    assert len(EXAMPLES) >= 5, commands
    assert any(c.startswith("suggest designs/table-racking.yaml") for c in commands)
    assert any(c.startswith("range designs/shelf-cantilever.yaml") for c in commands)


@pytest.mark.parametrize("line, args, shown", EXAMPLES,
                         ids=[f"README-{line}" for line, _, _ in EXAMPLES])
def test_a_readme_example_prints_what_it_shows(monkeypatch, tmp_path, line, args, shown):
    monkeypatch.chdir(ROOT)
    monkeypatch.setenv("FURNCHECK_CACHE_DIR", str(tmp_path / "cache"))
    printed = CliRunner().invoke(main, args).stdout.splitlines()
    at = 0
    for wanted in shown:
        if wanted.strip() == ELIDED:
            continue
        while at < len(printed) and not _matches(wanted, printed[at]):
            at += 1
        assert at < len(printed), (f"README line {line}: `furncheck {' '.join(args)}` no "
                                   f"longer prints, in this order:\n{wanted}\n"
                                   f"It prints:\n" + "\n".join(printed))
        at += 1
