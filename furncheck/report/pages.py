"""Report pages: one self-contained HTML file for a catalog (``validate --html``) and one
per suggested design folder (``suggest --out DIR``: ``DIR/index.html``).

Self-contained and offline: styles, scripts, pictures and the 3D models are in the page
itself (SVG views inline, PNGs and GLB models as data: URIs), so it opens from file:// with
no network.  The interactive 3D view is Google's <model-viewer> web component (Apache-2.0,
three.js inside), shipped with furncheck in ``report/static`` and inlined where a page
shows a model.
"""

from __future__ import annotations

import base64
import json
from dataclasses import dataclass
from html import escape
from importlib import resources
from typing import Any

from furncheck.design.model import Design
from furncheck.export.colours import UTILIZATION_STOPS, utilization_rgb
from furncheck.export.findings import (
    DURABILITY_COUNTS,
    changed_planks,
    governing_case,
    kinds_without_utilization,
)
from furncheck.report.numbers import format_number, format_percent
from furncheck.report.svg import design_svg, plank_utilizations
from furncheck.result import BatchReport, DesignReport

VIEWER_SCRIPT = "model-viewer-umd.min.js"
"""<model-viewer> 4.4.0 (npm @google/model-viewer, its UMD bundle with three.js r183)."""

_STYLE = """
body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;margin:1.5em;color:#222}
h1{font-size:1.4em}h2{font-size:1.15em;margin-top:2em;border-top:1px solid #ccc;
padding-top:.8em}table{border-collapse:collapse}th,td{padding:.3em .6em;
border-bottom:1px solid #e3e3e3;text-align:left;vertical-align:middle}
th.sortable{cursor:pointer;user-select:none}th.sortable:after{content:' \\2195';color:#999}
th[aria-sort=ascending]:after{content:' \\2191'}th[aria-sort=descending]:after{content:' \\2193'}
.valid{color:#17803a;font-weight:600}.invalid{color:#c62020;font-weight:600}
.error{color:#8a5a00;font-weight:600}.num{text-align:right;font-variant-numeric:tabular-nums}
.bar{display:inline-block;width:4em;height:.7em;background:#eee;margin-left:.4em}
.bar span{display:block;height:100%}.controls{margin:1em 0}.controls input{width:22em}
.small{color:#666;font-size:.9em}ul.violations li{margin:.2em 0}
.suggestion{border:1px solid #ddd;border-radius:6px;padding:.8em 1em;margin:1em 0}
.views{display:flex;gap:1em;flex-wrap:wrap;align-items:flex-start}
model-viewer{width:420px;height:320px;background:#f4f4f4}
.legend span{display:inline-block;width:1.2em;height:.8em;margin:0 .2em 0 .8em}
"""

_SORT_SCRIPT = """
function sortTable(th){const table=th.closest('table');const body=table.tBodies[0];
const index=[...th.parentNode.children].indexOf(th);
const order=th.getAttribute('aria-sort')==='ascending'?'descending':'ascending';
for(const other of th.parentNode.children){other.removeAttribute('aria-sort');}
th.setAttribute('aria-sort',order);const sign=order==='ascending'?1:-1;
const key=row=>{const cell=row.children[index];const v=cell.dataset.value??cell.textContent;
const n=parseFloat(v);return isNaN(n)?v.toLowerCase():n;};
const rows=[...body.rows].sort((a,b)=>{const x=key(a),y=key(b);
if(typeof x==='number'&&typeof y==='number')return sign*(x-y);
return sign*String(x).localeCompare(String(y));});
for(const row of rows)body.appendChild(row);}
function filterTable(){const text=document.getElementById('filter').value.toLowerCase();
const verdict=document.getElementById('verdict').value;
for(const row of document.querySelectorAll('#catalog tbody tr')){
const shown=row.textContent.toLowerCase().includes(text)&&
(verdict===''||row.dataset.verdict===verdict);row.hidden=!shown;}}
document.querySelectorAll('th.sortable').forEach(th=>th.addEventListener('click',()=>sortTable(th)));
document.getElementById('filter')?.addEventListener('input',filterTable);
document.getElementById('verdict')?.addEventListener('change',filterTable);
"""


def _verdict(report: DesignReport) -> str:
    if report.error is not None:
        return "error"
    return "valid" if report.valid else "invalid"


def worst_utilization(used: dict[str, float | None]) -> float | None:
    """The largest of the planks' utilizations (``svg.plank_utilizations``; None when
    nothing was computed)."""
    values = [u for u in used.values() if u is not None]
    return max(values) if values else None


def _css_rgb(utilization: float | None) -> str:
    return "rgb({},{},{})".format(*(round(255 * c) for c in utilization_rgb(utilization)))


def _bar(utilization: float | None) -> str:
    if utilization is None:
        return ""
    top = UTILIZATION_STOPS[-1][0]
    width = min(utilization, top) / top * 100
    return (f'<span class="bar"><span style="width:{width:.0f}%;'
            f'background:{_css_rgb(utilization)}"></span></span>')


def _legend() -> str:
    items = "".join(f'<span style="background:{_css_rgb(u)}"></span>'
                    f"{format_percent(u)}{' (the limit)' if u == 1.0 else ''}"
                    for u, _ in UTILIZATION_STOPS)
    return (f'<p class="legend small">Colour: share of capacity used {items}; '
            "grey: not computed.</p>")


def _page(title: str, body: str, viewer: bool = False) -> str:
    """A whole HTML document; the <model-viewer> script inlined when ``viewer``."""
    script = ""
    if viewer:
        code = resources.files("furncheck.report").joinpath("static", VIEWER_SCRIPT) \
            .read_text(encoding="utf-8")
        script = f"<script>{code}</script>\n"
    return (f"<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            f"<title>{escape(title)}</title>\n<style>{_STYLE}</style>\n{script}</head>\n"
            f"<body>\n{body}\n<script>{_SORT_SCRIPT}</script>\n</body>\n</html>\n")


@dataclass(frozen=True)
class CatalogEntry:
    """One design of a catalog page: its report and, when it could be read, its design
    (for the view)."""

    report: DesignReport
    design: Design | None = None


def catalog_page(entries: list[CatalogEntry], title: str = "furncheck catalog") -> str:
    """The catalog page: a sortable, filterable table (design, verdict, worst
    utilization, violations, view) and one details section per design."""
    batch = BatchReport(tuple(entry.report for entry in entries))
    summary = batch.summary
    rows, details = [], []
    for number, entry in enumerate(entries, start=1):
        report = entry.report
        verdict = _verdict(report)
        used = None if report.error is not None or entry.design is None else \
            plank_utilizations(report, entry.design)
        worst = None if used is None else worst_utilization(used)
        thumbnail = "" if entry.design is None else design_svg(
            entry.design, used, 160, 120, case=governing_case(report))
        kinds = sorted({v.kind for v in report.violations})
        count = len(report.violations)
        violations = report.error or (
            f"{count} violation{'s' if count != 1 else ''}: {', '.join(kinds)}" if kinds
            else "")
        # a design that topples, slides or does not stand as drawn is drawn at the scale's
        # failing end: the column says why rather than a percentage no report holds
        failed = sorted(kinds_without_utilization(report))
        shown = "" if worst is None else \
            ", ".join(failed) if failed else format_percent(worst)
        rows.append(
            f'<tr data-verdict="{verdict}"><td><a href="#d{number}">{escape(report.design)}'
            f'</a><br><span class="small">{escape(report.name)}</span></td>'
            f'<td class="{verdict}">{verdict}</td>'
            f'<td class="num" data-value="{-1 if worst is None else round(worst, 6)}">'
            f'{escape(shown)}{_bar(worst)}</td>'
            f'<td data-value="{count}">{escape(violations)}</td><td>{thumbnail}</td></tr>')
        details.append(_details(number, entry, used))
    body = (f"<h1>{escape(title)}</h1>\n<p>{summary['designs']} designs: "
            f'<span class="valid">{summary["valid"]} valid</span>, '
            f'<span class="invalid">{summary["invalid"]} invalid</span>, '
            f'<span class="error">{summary["errors"]} errors</span>.</p>\n{_legend()}\n'
            '<div class="controls"><input id="filter" type="search" '
            'placeholder="filter: design, violation, plank ..."> '
            '<select id="verdict"><option value="">all verdicts</option>'
            '<option value="valid">valid</option><option value="invalid">invalid</option>'
            '<option value="error">error</option></select></div>\n'
            '<table id="catalog"><thead><tr><th class="sortable">design</th>'
            '<th class="sortable">verdict</th><th class="sortable">worst utilization</th>'
            '<th class="sortable">violations</th><th>view</th></tr></thead>\n<tbody>\n'
            + "\n".join(rows) + "\n</tbody></table>\n" + "\n".join(details))
    return _page(title, body)


def _details(number: int, entry: CatalogEntry, used: dict[str, float] | None) -> str:
    report = entry.report
    verdict = _verdict(report)
    parts = [f'<h2 id="d{number}">{escape(report.name)} <span class="{verdict}">'
             f"{verdict}</span></h2>", f'<p class="small">{escape(report.design)}</p>']
    if report.error is not None:
        parts.append("".join(f"<p>{escape(problem)}</p>" for problem in report.errors))
        return "\n".join(parts)
    if entry.design is not None:
        parts.append(design_svg(entry.design, used, 420, 300, title=report.name,
                                case=governing_case(report)))
    parts.append(_violation_list(report))
    parts.append(_case_table(report))
    return "\n".join(parts)


def _violation_list(report: DesignReport) -> str:
    if not report.violations:
        return "<p>No violations.</p>"
    items = "".join(
        f"<li><b>{escape(v.kind)}</b>: {escape(v.where)}"
        f"{'' if v.case is None else f' in case {escape(repr(v.case))}'}: "
        f"{escape(v.message)}</li>" for v in report.violations)
    return f'<ul class="violations">{items}</ul>'


def _case_table(report: DesignReport) -> str:
    if not report.cases:
        return ""
    rows = []
    for case in report.cases:
        if case.stability not in DURABILITY_COUNTS:     # as if bolted down: not counted
            rows.append(f"<tr><td>{escape(case.name)}</td><td>{escape(case.stability)}</td>"
                        f"<td>-</td><td colspan=\"2\">not counted: the design does not "
                        f"stand in this case</td></tr>")
            continue
        joint = case.worst_joint
        joint_text = "" if joint is None else (
            f"{escape('/'.join(joint.planks))}: {format_percent(joint.utilization)}")
        plank = max(case.planks or (), key=lambda p: p.utilization, default=None)
        plank_text = "" if plank is None else (
            f"{escape(plank.id)}: sag {format_number(plank.sag, 3)} {escape(report.units)}, "
            f"{format_percent(plank.utilization)}")
        rows.append(f"<tr><td>{escape(case.name)}</td><td>{escape(case.stability)}</td>"
                    f"<td>{'yes' if case.durable else 'no'}</td><td>{joint_text}</td>"
                    f"<td>{plank_text}</td></tr>")
    return ("<table><thead><tr><th>case</th><th>stability</th><th>durable</th>"
            "<th>worst joint (utilization)</th><th>worst plank (sag, utilization)</th>"
            "</tr></thead><tbody>" + "".join(rows) + "</tbody></table>")


def _data_uri(data: bytes, kind: str) -> str:
    return f"data:{kind};base64,{base64.b64encode(data).decode('ascii')}"


def _model_viewer(glb: bytes | None, label: str) -> str:
    if glb is None:
        return ""
    return (f'<model-viewer src="{_data_uri(glb, "model/gltf-binary")}" '
            f'alt="{escape(label)}" camera-controls camera-orbit="-55deg 62deg auto" '
            'shadow-intensity="0.6" interaction-prompt="none"></model-viewer>')


@dataclass(frozen=True)
class PageDesign:
    """A design shown on a suggestion page: its report, the design, its GLB model (None
    where matplotlib cannot be imported) and pictures (file names relative to the page)."""

    report: DesignReport
    design: Design
    glb: bytes | None = None
    pictures: tuple[str, ...] = ()


def suggestion_page(document: dict[str, Any], original: PageDesign,
                    suggested: dict[int, PageDesign]) -> str:
    """``DIR/index.html`` of ``suggest --out DIR``: the input's verdict, violations and
    views, then each suggestion (its advice, what it restores, its edits, its views and
    force-space plots, its 3D model) from ``document``, the suggest JSON
    (``report.suggestions.render_json``, parsed)."""
    report = original.report
    verdict = _verdict(report)
    used = plank_utilizations(report, original.design)
    parts = [f"<h1>{escape(report.name)}: <span class=\"{verdict}\">{verdict}</span></h1>",
             f'<p class="small">{escape(report.design)}</p>', _legend(),
             '<div class="views">' + design_svg(original.design, used, 420, 300,
                                               title=report.name,
                                               case=governing_case(report))
             + _model_viewer(original.glb, report.name) + "</div>",
             _violation_list(report), _case_table(report)]
    suggestions = document.get("suggestions", [])
    parts.append(f"<h2>{len(suggestions)} suggestion{'s' if len(suggestions) != 1 else ''}</h2>")
    if not suggestions:
        explanation = document.get("explanation")
        parts.append("<p>No suggestion.</p>" if explanation is None else
                     f"<pre>{escape(json.dumps(explanation, indent=2))}</pre>")
    for entry in suggestions:
        rank = entry["rank"]
        shown = suggested.get(rank)
        parts.append(f'<div class="suggestion" id="s{rank}"><h3>{rank}. '
                     f"{escape(str(entry.get('advice', '')))}</h3>"
                     f"<p>Restores {escape(' and '.join(entry.get('restores', [])))}."
                     + (f" Design file: <code>{escape(str(entry['design_file']))}</code>"
                        if entry.get("design_file") else "") + "</p>")
        for reason in (entry.get("score") or {}).get("implausible") or ():
            parts.append(f'<p class="small">implausible proportion: {escape(reason)}</p>')
        parts.append(_edits_table(entry.get("edits"),
                                  _other_changes(entry, len(original.design.anchors))))
        if shown is not None:
            views = [design_svg(shown.design, plank_utilizations(shown.report, shown.design),
                                420, 300, marks=changed_planks(original.design, shown.design),
                                title=f"suggestion {rank}",
                                case=governing_case(shown.report))]
            views += [f'<a href="{escape(picture)}" title="full size"><img '
                      f'src="{escape(picture)}" alt="{escape(picture)}" width="420"></a>'
                      for picture in shown.pictures]
            views.append(_model_viewer(shown.glb, f"suggestion {rank}"))
            parts.append('<div class="views">' + "".join(views) + "</div>")
        parts.append("</div>")
    viewer = original.glb is not None or any(s.glb is not None for s in suggested.values())
    return _page(f"furncheck: {report.name}", "\n".join(parts), viewer=viewer)


def _other_changes(entry: dict[str, Any], anchors: int = 0
                   ) -> list[tuple[str, str, str, Any, Any]]:
    """Rows of what a suggestion changes besides planks (the suggest JSON's ``anchors``
    that it adds, numbered after the design's own ``anchors``, ``nails``, ``ratings``,
    ``friction`` and ``anchors_moved``): (what, edit, field, from, to); a resting joint
    nailed reads from 'resting'."""
    rows = []
    for index, added in enumerate(entry.get("anchors") or (), start=anchors):
        what = f"anchors[{index}] on {added['plank']} (wall {added['wall']})"
        rows += [(what, "add", "at", None, added["at"]),
                 (what, "add", "rating, N", None, added["capacity"])]
    rows += [(str(n["joint"]), "change", "nails", "resting" if n.get("resting")
              else n["before"], n["after"]) for n in entry.get("nails") or ()]
    rows += [(f"anchors[{r['anchor']}]", "change", "rating, N", r["before"], r["after"])
             for r in entry.get("ratings") or ()]
    if entry.get("friction"):
        rows.append(("the floor", "change", "friction", *entry["friction"]))
    rows += [(f"anchors[{m['anchor']}]", "move", "at", m["from"], m["to"])
             for m in entry.get("anchors_moved") or ()]
    return rows


def _edits_table(edits: list[dict[str, Any]] | None,
                 others: list[tuple[str, str, str, Any, Any]] = ()) -> str:
    """A cut list of the suggestion's ``edits`` (the suggest JSON's: plank, edit 'change',
    'add' or 'remove', and per field [from, to] in the file's units): a row per changed
    field, one row per added plank (its size, centre and turn, as the text report words
    it); then ``others`` (``_other_changes``), a row each."""
    if not edits and not others:
        return ""
    rows = []
    for edit in edits or ():
        plank, kind = escape(str(edit.get("plank", ""))), escape(str(edit.get("edit", "")))
        fields = edit.get("fields") or {}
        if edit.get("edit") == "add":
            rows.append(f"<tr><td>{plank}</td><td>{kind}</td><td>new plank</td><td></td>"
                        f"<td>{escape(_new_plank(fields))}</td></tr>")
            continue
        for field, values in fields.items():
            before, after = values if isinstance(values, list | tuple) and len(values) == 2 \
                else (None, values)
            rows.append(f"<tr><td>{plank}</td><td>{kind}</td><td>{escape(str(field))}</td>"
                        f"<td>{escape(_shown(before))}</td>"
                        f"<td>{escape(_shown(after))}</td></tr>")
    for what, kind, field, before, after in others:
        rows.append(f"<tr><td>{escape(what)}</td><td>{escape(kind)}</td>"
                    f"<td>{escape(field)}</td><td>{escape(_shown(before))}</td>"
                    f"<td>{escape(_shown(after))}</td></tr>")
    return ("<table><thead><tr><th>plank</th><th>edit</th><th>what</th><th>from</th>"
            "<th>to</th></tr></thead><tbody>" + "".join(rows) + "</tbody></table>")


def _new_plank(fields: dict[str, Any]) -> str:
    """'length x width x thickness, centred at (x, y, z), turned (rx, ry, rz) degrees' of
    an added plank's fields (each [None, value]); the turn left out when there is none."""
    def value(name: str):
        values = fields.get(name)
        return values[-1] if isinstance(values, list | tuple) and values else values

    def listed(names: tuple[str, ...], separator: str) -> str:
        return separator.join(_shown(value(name)) for name in names)

    text = (f"{listed(('length', 'width', 'thickness'), ' x ')}, centred at "
            f"({listed(('x', 'y', 'z'), ', ')})")
    turn = [value(name) for name in ("rx", "ry", "rz")]
    if any(isinstance(angle, int | float) and angle for angle in turn):
        text += f", turned ({listed(('rx', 'ry', 'rz'), ', ')}) degrees"
    return text


def _shown(value: Any) -> str:
    """A cut-list value as the reports write numbers ('' for none)."""
    if value is None:
        return ""
    if isinstance(value, bool) or not isinstance(value, int | float):
        return json.dumps(value)
    return format_number(float(value))
