"""``--format sarif``: a SARIF 2.1.0 log, e.g. for GitHub code scanning.

One run; ``tool.driver.rules`` holds one rule per violation kind plus ``input-error``
(always all of them, in a fixed order, so the log's shape does not depend on the batch).
Every violation and every unreadable input is one result of level ``error``, located at
the design file (``artifactLocation.uri``) and, when known, its line (``region.startLine``).
Relative paths stay relative (resolved against the repository root by code scanning);
absolute ones become ``file://`` URIs.  Each result has ``partialFingerprints``
(``FINGERPRINT``): a hash of its rule, file and what it is about -- the plank or joint
and the load case, not the line nor the numbers -- so that code scanning keeps one alert
per problem from run to run (a sag that changes, or lines added above it, is the same
alert) and tells apart the cases of one problem that share a line (a seat sagging in
three cases: three alerts, where the hash of the line's text that the upload computes
otherwise is the same for all three).
"""

from __future__ import annotations

import hashlib
import json
import os
from collections.abc import Iterable, Iterator
from pathlib import PurePath
from typing import Any
from urllib.parse import quote

from furncheck import __version__
from furncheck.files import utf8
from furncheck.report.common import INPUT_ERROR, describe_violation, input_errors
from furncheck.report.entries import Entry
from furncheck.result import VIOLATION_KINDS, BatchReport, DesignReport

SARIF_VERSION = "2.1.0"
SARIF_SCHEMA = "https://json.schemastore.org/sarif-2.1.0.json"
FINGERPRINT = "furncheck/v1"
"""The ``partialFingerprints`` key of each result (its own, not the upload's
``primaryLocationLineHash``, which code scanning computes from the line's text)."""

RULE_DESCRIPTIONS = {
    "disconnected": "A listed joint's planks do not touch or interpenetrate, a plank is "
                    "joined to no other plank, two planks miss a joint by a little (a "
                    "gap or overlap up to 20 x tolerance), or two planks are drawn through "
                    "each other (a board pasted twice).",
    "penetration": "A plank corner lies below the ground plane.",
    "floating": "Part of the assembly touches the ground nowhere, or a plank standing on "
                "its end stops just short of the floor (up to 20 x tolerance).",
    "non-durable": "A nail joint's pull or shear force per nail exceeds the nail capacity, "
                   "or a wall anchor holds more than its rating.",
    "lift-off": "No equilibrium exists with non-negative ground forces: the design "
                "topples, or a part lifts off what it rests on.",
    "sliding": "No equilibrium exists within the friction cones: the design slides, or a "
               "part slides on what it rests on.",
    "sagging": "A plank's sag, with creep, exceeds its span / sag_limit (elastic model).",
    "overstressed": "A plank's bending stress exceeds its bending strength / safety factor "
                    "(elastic model).",
    INPUT_ERROR: "The design file cannot be read or is ill-formed.",
}
"""Rule id -> one-sentence description.  Ids are the violation kinds of the contract
(``result.VIOLATION_KINDS``, every one described: a test checks)."""


def render(batch: BatchReport) -> str:
    """The batch as a SARIF 2.1.0 JSON document (indent 2, trailing newline)."""
    return "".join(document(Entry.of(report, piece(report)) for report in batch.reports))


def piece(report: DesignReport) -> tuple[str, tuple[tuple[str, int | None, str, str], ...]]:
    """(the design's path, its findings: (rule id, line, message, what it is about) of
    every problem)."""
    return report.design, tuple(_findings(report))


def is_piece(value: Any) -> bool:
    """Whether ``value`` is shaped as ``piece`` returns it (a cached piece is checked)."""
    return type(value) is tuple and len(value) == 2 and type(value[0]) is str \
        and type(value[1]) is tuple and all(
            type(finding) is tuple and len(finding) == 4 and type(finding[0]) is str
            and (finding[1] is None or type(finding[1]) is int) and type(finding[2]) is str
            and type(finding[3]) is str for finding in value[1])


def document(entries: Iterable[Entry]) -> Iterator[str]:
    """The log of ``entries``' findings.  The rules come before the results (and a rule
    unknown to this version is added when it is first met), so the log is written when
    the last entry has arrived."""
    rule_ids = list(VIOLATION_KINDS) + [INPUT_ERROR]
    results: list[dict[str, Any]] = []
    for entry in entries:
        design, findings = entry.piece
        seen: dict[str, int] = {}
        for rule_id, line, text, about in findings:
            if rule_id not in rule_ids:  # a kind this version does not know: still a rule
                rule_ids.append(rule_id)
            identity = "\0".join((rule_id, artifact_uri(design), about))
            seen[identity] = seen.get(identity, 0) + 1     # the same twice: :1, :2
            results.append(_result(rule_id, rule_ids.index(rule_id), design, line, text,
                                   _fingerprint(identity, seen[identity])))
    log = {
        "$schema": SARIF_SCHEMA,
        "version": SARIF_VERSION,
        "runs": [{
            "tool": {"driver": {
                "name": "furncheck",
                "version": __version__,
                "rules": [_rule(rule_id) for rule_id in rule_ids],
            }},
            "results": results,
        }],
    }
    yield json.dumps(log, indent=2) + "\n"


def artifact_uri(path: str) -> str:
    """A URI reference for a design path: relative stays relative, absolute -> file://;
    its bytes percent-encoded (a name that is not UTF-8 too: 'bad%FFname.yaml')."""
    pure = PurePath(path)
    if pure.is_absolute():
        return pure.as_uri()
    return quote(os.fsencode(pure.as_posix()), safe="/")


def _findings(report: DesignReport) -> list[tuple[str, int | None, str, str]]:
    """(rule id, line, message, what it is about) of every problem of one design: a
    violation is about its planks or joint and its case, an input error about its
    message (it names the key and what is wrong with it)."""
    if report.error is not None or report.valid is None:
        return [(INPUT_ERROR, line, message, message)
                for line, message in input_errors(report)]
    return [(v.kind, v.line, describe_violation(v), f"{v.where}\0{v.case or ''}")
            for v in report.violations]


def _fingerprint(identity: str, occurrence: int) -> str:
    """A result's fingerprint: 16 hex digits of the SHA-256 of its identity (rule, file,
    what it is about), and which occurrence of that identity in its file it is."""
    digest = hashlib.sha256(utf8(identity)).hexdigest()
    return f"{digest[:16]}:{occurrence}"


def _rule(rule_id: str) -> dict[str, Any]:
    description = RULE_DESCRIPTIONS.get(rule_id, f"furncheck violation '{rule_id}'.")
    return {
        "id": rule_id,
        "name": "".join(part.capitalize() for part in rule_id.split("-")),
        "shortDescription": {"text": description},
        "defaultConfiguration": {"level": "error"},
    }


def _result(rule_id: str, rule_index: int, design: str, line: int | None,
            text: str, fingerprint: str) -> dict[str, Any]:
    physical: dict[str, Any] = {"artifactLocation": {"uri": artifact_uri(design)}}
    if line is not None and line >= 1:
        physical["region"] = {"startLine": line}
    return {
        "ruleId": rule_id,
        "ruleIndex": rule_index,
        "level": "error",
        "message": {"text": text},
        "locations": [{"physicalLocation": physical}],
        "partialFingerprints": {FINGERPRINT: fingerprint},
    }
