"""Report pages (``furncheck.report.pages``): self-contained HTML for a catalog and for a
suggestion folder, their SVG views, and -- where headless Chromium is installed -- a real
browser opening them from file://.
"""

from __future__ import annotations

import json
import os
import re
import shutil
from html import escape
from pathlib import Path

import numpy as np
import pytest

from furncheck.check import check_design
from furncheck.design import load_design
from furncheck.export.colours import MARK_RGB, UTILIZATION_STOPS, utilization_rgb
from furncheck.export.projection import shaded
from furncheck.geometry import analyze
from furncheck.report.pages import (
    CatalogEntry,
    PageDesign,
    catalog_page,
    suggestion_page,
    worst_utilization,
)
from furncheck.report.svg import design_svg, plank_utilizations

CATALOG = Path(__file__).resolve().parent.parent / "designs"
ARTIFACTS = Path(os.environ.get("FURNCHECK_TEST_ARTIFACTS",
                                Path(__file__).resolve().parent.parent / ".artifacts"))

_RESOURCE = re.compile(r"""(?:\bsrc|\bhref|\baction|\bposter)\s*=\s*["']?\s*(https?:)?//"""
                       r"""|url\(\s*["']?\s*(https?:)?//|@import\s+["']?(https?:)?//""",
                       re.IGNORECASE)


def _entry(name: str, model: str = "rigid") -> CatalogEntry:
    from furncheck.design.model import with_model

    design = with_model(load_design(str(CATALOG / name)), model)
    return CatalogEntry(check_design(design, analyze(design)), design)


def test_plank_colours_are_the_pictures_scale():
    """The SVG colours a plank as the PNG views do: the utilization scale's colour lit by
    the same light.  The overloaded cantilever's post/shelf joint fails (utilization > 1),
    so both planks read at least that joint's utilization; a lift-off names its planks,
    which read the scale's failing end."""
    entry = _entry("shelf-cantilever-overloaded.yaml")
    used = plank_utilizations(entry.report, entry.design)
    joint = next(j for c in entry.report.cases for j in c.joints
                 if set(j.planks) == {"post", "shelf"})
    assert joint.utilization > 1.0
    assert used["post"] >= joint.utilization and used["shelf"] >= joint.utilization
    assert worst_utilization(used) == max(used.values())
    svg = design_svg(entry.design, used)
    fills = {(title, fill) for fill, title in re.findall(
        r'fill="(rgb\([^)]*\))"[^>]*><title>([^<]+)</title>', svg)}
    for plank in entry.design.planks:
        lit = [shaded(np.array([utilization_rgb(used[plank.id])]), np.array([normal]))[0]
               for normal in np.vstack([plank.rotation_matrix.T, -plank.rotation_matrix.T])]
        allowed = {"rgb({},{},{})".format(*(round(255 * c) for c in colour)) for colour in lit}
        drawn = {fill for title, fill in fills if title == plank.id}
        assert drawn and drawn <= allowed
    tipping = _entry("bench-tips.yaml")
    lifting = next(v for v in tipping.report.violations if v.kind == "lift-off")
    failing = UTILIZATION_STOPS[-1][0]
    used = plank_utilizations(tipping.report, tipping.design)
    for plank in lifting.where.split(","):
        assert used[plank.strip()] >= failing
    assert [c.stability for c in tipping.report.cases] == ["lift-off"]
    named = {p.strip() for p in lifting.where.split(",")}
    assert all(used[p.id] is None for p in tipping.design.planks if p.id not in named), \
        used       # its only case topples: nothing counted, grey ("not computed")


def test_svg_view_draws_each_plank_and_outlines_the_changed_ones():
    """Each plank shows at least one face and at most three (a box seen from an oblique
    view), every polygon stays inside the picture, and a changed plank is outlined in the
    'changed' mark's colour, an added one in the 'added' colour, and its 12 edges drawn
    dashed over everything (as the PNG views do: a hidden part still shows)."""
    entry = _entry("table.yaml")
    svg = design_svg(entry.design, plank_utilizations(entry.report, entry.design), 240, 180,
                     marks={"top": "changed", "apron": "added"})
    titles = re.findall(r"<title>([^<]+)</title></polygon>", svg)
    for plank in entry.design.planks:
        assert 1 <= titles.count(plank.id) <= 3
    coordinates = np.array([[float(v) for v in pair.split(",")]
                            for points in re.findall(r'points="([^"]+)"', svg)
                            for pair in points.split()])
    assert coordinates[:, 0].min() >= 0 and coordinates[:, 0].max() <= 240
    assert coordinates[:, 1].min() >= 0 and coordinates[:, 1].max() <= 180
    for plank, mark in (("top", "changed"), ("apron", "added")):
        colour = "rgb({},{},{})".format(*(round(255 * c) for c in MARK_RGB[mark]))
        assert len(re.findall(rf'stroke="{re.escape(colour)}" stroke-width="2"[^>]*>'
                              rf"<title>{plank}</title>", svg)) == titles.count(plank)
        dashed = re.findall(rf'<path d="([^"]+)" fill="none" stroke="{re.escape(colour)}" '
                            r'stroke-width="1" stroke-dasharray="2 2"/>', svg)
        assert len(dashed) == 1 and dashed[0].count("M") == 12     # its 12 edges, hidden too


def test_svg_view_draws_the_loads_of_the_case_as_arrows():
    """The loads of the case given (the pages give the governing one) are arrows, as in
    the PNG views (``export.arrows``): the overloaded cantilever's 30 kg on its shelf one
    arrow pointing down (gravity: its head below its tail in the picture), labelled
    '30 kg' in a detail view but not in a thumbnail; the bookcase's books spread on four
    shelves, three arrows each, the label once; no case, no arrows."""
    from furncheck.export.findings import governing_case

    entry = _entry("shelf-cantilever-overloaded.yaml")
    case = governing_case(entry.report)
    detail = design_svg(entry.design, None, 420, 300, case=case)
    (x0, y0, x1, y1), = [tuple(float(v) for v in found) for found in re.findall(
        r'<line x1="([^"]+)" y1="([^"]+)" x2="([^"]+)" y2="([^"]+)"', detail)]
    assert abs(x1 - x0) < 1e-6 and y1 > y0 + 20
    assert re.findall(r"<text[^>]*>([^<]+)</text>", detail) == ["30 kg"]
    thumbnail = design_svg(entry.design, None, 160, 120, case=case)
    assert thumbnail.count("<line ") == 1 and "<text" not in thumbnail
    assert "<line " not in design_svg(entry.design)
    shelves = _entry("bookshelf-18.yaml")
    case = governing_case(shelves.report)
    spread = [load for load in case.loads if load.spread]
    svg = design_svg(shelves.design, None, 420, 300, case=case)
    assert svg.count("<line ") == 3 * len(spread) + len(case.loads) - len(spread) > 3
    labels = re.findall(r"<text[^>]*>([^<]+)</text>", svg)
    assert len(labels) == len(set(labels)) and any(t.endswith("spread") for t in labels)


def test_case_table_reads_utilization_in_percent():
    """The details' case table gives the worst joint's and plank's utilization in percent,
    as the rest of the page does (``format_percent``), not as a fraction."""
    from furncheck.report.numbers import format_percent
    from furncheck.report.pages import _case_table

    entry = _entry("table.yaml", "elastic")
    table = _case_table(entry.report)
    case = entry.report.cases[0]
    assert f"{'/'.join(case.worst_joint.planks)}: {format_percent(case.worst_joint.utilization)}" \
        in table
    plank = max(case.planks, key=lambda p: p.utilization)
    assert f"{format_percent(plank.utilization)}</td>" in table


def test_svg_view_is_the_same_for_a_moved_design():
    """The view is fitted to the picture: moving the whole design changes no pixel."""
    from dataclasses import replace

    design = _entry("stool.yaml").design
    moved = replace(design, planks=tuple(
        replace(p, center=(p.center[0] + 3.0, p.center[1] - 2.0, p.center[2] + 0.5))
        for p in design.planks))
    assert design_svg(design) == design_svg(moved)


def test_catalog_page_lists_every_design_and_fetches_nothing():
    entries = [_entry(name) for name in ("table.yaml", "bench-tips.yaml", "stool.yaml")]
    page = catalog_page(entries, "three designs")
    assert page.startswith("<!DOCTYPE html>")
    for number, entry in enumerate(entries, start=1):
        assert f'href="#d{number}"' in page and f'id="d{number}"' in page
        assert entry.report.design in page
    assert page.count('<tr data-verdict="') == 3
    assert 'data-verdict="invalid"' in page and "lift-off" in page
    assert page.count("<svg") == 2 * len(entries)             # a thumbnail and a view each
    assert not _RESOURCE.search(page)
    assert "customElements" not in page                      # no viewer script needed
    # bench-tips topples: its column names that, where it read 150 %, a number no report
    # holds (its planks are drawn at the scale's failing end); it still sorts as failing
    assert '<td class="num" data-value="1.5">lift-off<' in page
    assert 'data-value="1.5">150 %' not in page


def test_suggestion_page_embeds_models_and_edits(tmp_path):
    """The page shows the input and each suggestion, their GLB models inline as data:
    URIs with the viewer script inlined, and no reference to the network; a suggestion's
    implausible proportions as the text report words them."""
    entry = _entry("bench-tips.yaml")
    glb = b"glTF-bytes"
    document = {"design": entry.report.design, "valid": False, "suggestions": [
        {"rank": 1, "kind": "continuous", "restores": ["stability"], "dofs": ["leg_r.x"],
         "advice": "Move leg_r 255 mm away from leg_l.", "design_file": "s-01.yaml",
         "score": {"implausible": ["leg_r hangs 64 % of its end past the edge of seat"]},
         "edits": [{"plank": "leg_r", "edit": "change", "fields": {"x": [300.0, 555.0]}},
                   {"plank": "foot-1", "edit": "add", "fields": {
                       "length": [None, 400.0], "width": [None, 72.0],
                       "thickness": [None, 12.0], "x": [None, 555.0], "y": [None, 0.0],
                       "z": [None, 6.0], "rx": [None, 0.0], "ry": [None, 0.0],
                       "rz": [None, 90.0]}}]}]}
    page = suggestion_page(document, PageDesign(entry.report, entry.design, glb),
                           {1: PageDesign(entry.report, entry.design, glb, ("s-01.png",))})
    assert page.count("data:model/gltf-binary;base64,") == 2
    assert "customElements" in page.split("<body>")[0]       # the viewer, inlined
    assert "Move leg_r 255 mm away from leg_l." in page
    assert "implausible proportion: leg_r hangs 64 % of its end past the edge of seat" in page
    assert "<td>leg_r</td><td>change</td><td>x</td><td>300</td><td>555</td>" in page
    assert ("<td>foot-1</td><td>add</td><td>new plank</td><td></td><td>400 x 72 x 12, "
            "centred at (555, 0, 6), turned (0, 0, 90) degrees</td>") in page
    assert 'src="s-01.png"' in page
    assert not _RESOURCE.search(page)


# --- a real browser ---------------------------------------------------------------------------

def _browser():
    """A headless Chromium driven by Selenium, or the reason there is none."""
    chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    driver_path = shutil.which("chromedriver")
    if not chromium or not driver_path:
        pytest.skip("headless Chromium and chromedriver are not installed "
                    "(Debian: apt-get install chromium chromium-driver)")
    webdriver = pytest.importorskip("selenium.webdriver")
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = chromium
    for flag in ("--headless=new", "--no-sandbox", "--use-angle=swiftshader",
                 "--enable-unsafe-swiftshader", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync", "--no-first-run",
                 "--window-size=1200,1400"):
        options.add_argument(flag)
    options.set_capability("goog:loggingPrefs", {"performance": "ALL"})
    try:
        return webdriver.Chrome(service=Service(driver_path), options=options)
    except Exception as error:  # noqa: BLE001 - a browser that cannot start here
        pytest.skip(f"headless Chromium could not start: {type(error).__name__}: {error}")


def _requests(browser) -> list[str]:
    """The URLs the page asked the network for (Chrome's performance log)."""
    urls = []
    for entry in browser.get_log("performance"):
        message = json.loads(entry["message"])["message"]
        if message.get("method") == "Network.requestWillBeSent":
            urls.append(message["params"]["request"]["url"])
    return urls


def _png_pixels(data: bytes) -> np.ndarray:
    import io

    from matplotlib import image

    return image.imread(io.BytesIO(data), format="png")


@pytest.mark.browser
def test_catalog_page_sorts_and_filters_in_chromium(tmp_path):
    entries = [_entry(name) for name in ("table.yaml", "bench-tips.yaml", "stool.yaml",
                                         "shelf-cantilever-overloaded.yaml")]
    page = tmp_path / "catalog.html"
    page.write_text(catalog_page(entries), encoding="utf-8")
    browser = _browser()
    try:
        from selenium.webdriver.common.by import By

        browser.get(page.as_uri())
        header = browser.find_elements(By.CSS_SELECTOR, "#catalog th")[2]

        def column() -> list[float]:
            return [float(row.find_elements(By.TAG_NAME, "td")[2].get_attribute("data-value"))
                    for row in browser.find_elements(By.CSS_SELECTOR, "#catalog tbody tr")]

        header.click()
        assert column() == sorted(column())
        header.click()
        assert column() == sorted(column(), reverse=True)
        browser.find_element(By.ID, "filter").send_keys("lift-off")
        shown = [row for row in browser.find_elements(By.CSS_SELECTOR, "#catalog tbody tr")
                 if row.is_displayed()]
        assert len(shown) == 1 and "bench-tips" in shown[0].text
        ARTIFACTS.mkdir(parents=True, exist_ok=True)
        browser.save_screenshot(str(ARTIFACTS / "catalog-page.png"))
        assert all(url.startswith(("file:", "data:")) for url in _requests(browser))
    finally:
        browser.quit()


@pytest.mark.browser
def test_suggestion_page_renders_its_3d_view_in_chromium(tmp_path):
    from furncheck.export.meshes import glb_bytes

    entry = _entry("table.yaml")
    glb = glb_bytes(entry.design, entry.report)
    document = {"design": entry.report.design, "valid": True, "suggestions": []}
    page = tmp_path / "index.html"
    page.write_text(suggestion_page(document, PageDesign(entry.report, entry.design, glb), {}),
                    encoding="utf-8")
    browser = _browser()
    try:
        from selenium.webdriver.common.by import By
        from selenium.webdriver.support.ui import WebDriverWait

        browser.get(page.as_uri())
        viewer = browser.find_element(By.TAG_NAME, "model-viewer")
        WebDriverWait(browser, 60).until(
            lambda b: b.execute_script("return arguments[0].loaded === true", viewer))
        background = np.array([0xF4, 0xF4, 0xF4]) / 255

        def drawn_share(_) -> float | bool:
            """The share of the view's pixels that are not its background (the model
            fades in after loading, later on a busy machine: polled)."""
            pixels = _png_pixels(viewer.screenshot_as_png)[..., :3]
            share = float((np.abs(pixels - background).max(axis=-1) > 0.03).mean())
            return share if share > 0.02 else False   # the table covers part of the view

        assert WebDriverWait(browser, 60, poll_frequency=0.5).until(drawn_share) > 0.02
        ARTIFACTS.mkdir(parents=True, exist_ok=True)
        browser.execute_script("window.scrollTo(0, 0)")
        browser.save_screenshot(str(ARTIFACTS / "suggestion-page.png"))
        assert all(url.startswith(("file:", "data:")) for url in _requests(browser))
    finally:
        browser.quit()


def test_suggest_out_writes_the_folders_page(tmp_path):
    """``suggest --out DIR`` writes DIR/index.html: every suggestion's advice, the
    design's and each suggestion's model embedded (one GLB each), its pictures linked by
    the names written beside it, nothing fetched from the network."""
    from click.testing import CliRunner

    from furncheck.cli.main import main

    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["suggest", str(CATALOG / "bench-tips.yaml"), "--model",
                                       "rigid", "--out", str(out), "--format", "json",
                                       "--no-plots"])
    assert result.exit_code == 0, result.output
    document = json.loads(result.stdout)
    page = (out / "index.html").read_text(encoding="utf-8")
    for entry in document["suggestions"]:
        assert escape(entry["advice"]) in page
    assert page.count("data:model/gltf-binary;base64,") == 1 + len(document["suggestions"])
    for picture in re.findall(r'<img src="([^"]+)"', page):
        assert (out / picture).is_file()
    assert not _RESOURCE.search(page)


def test_the_page_lists_what_a_fix_changes_besides_planks(tmp_path):
    """Non-slip pads change no plank: the page's cut list says what they change, the
    floor's friction, from -> to, as the text and JSON do."""
    from click.testing import CliRunner
    from shop_designs import TILE_BENCH

    from furncheck.cli.main import main

    design = tmp_path / "tile-bench.yaml"
    design.write_text(TILE_BENCH, encoding="utf-8")
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["suggest", str(design), "--out", str(out),
                                       "--no-plots"])
    assert result.exit_code == 0, result.output
    page = (out / "index.html").read_text(encoding="utf-8")
    assert "<tr><td>the floor</td><td>change</td><td>friction</td><td>0.15</td>" \
           "<td>0.2</td></tr>" in page


def test_validate_html_writes_one_page_for_the_run(tmp_path):
    """``validate --html FILE`` keeps the run's report and exit code and writes one page
    with a row per design (an unreadable one included, marked 'error')."""
    from click.testing import CliRunner

    from furncheck.cli.main import main

    broken = tmp_path / "broken.yaml"
    broken.write_text("furncheck: 1\nplanks: 3\n", encoding="utf-8")
    names = [str(CATALOG / "table.yaml"), str(CATALOG / "bench-tips.yaml"), str(broken)]
    page_file = tmp_path / "catalog.html"
    with_page = CliRunner().invoke(main, ["validate", *names, "--model", "rigid", "--no-cache",
                                          "--html", str(page_file), "--format", "json"])
    without = CliRunner().invoke(main, ["validate", *names, "--model", "rigid", "--no-cache",
                                        "--format", "json"])
    assert with_page.exit_code == without.exit_code == 2
    assert with_page.stdout == without.stdout
    page = page_file.read_text(encoding="utf-8")
    assert page.count('<tr data-verdict="') == 3
    assert page.count('data-verdict="error"') == 1 and page.count('data-verdict="valid"') == 1
    assert not _RESOURCE.search(page)
    to_folder = CliRunner().invoke(main, ["validate", *names, "--html", str(tmp_path)])
    assert to_folder.exit_code == 2
    assert to_folder.stderr == (f"furncheck: cannot write the report page to {tmp_path}: it "
                                f"is a directory\n")


def test_a_toppling_case_shows_no_forces_as_if_bolted_down():
    """bench-tips (elastic) tips over: its case's joint and plank figures come from a solve
    held down to the ground (the seat 'sags' 44 mm there), which raise no violation; the
    page and the colours must not show them as overloads.  The plank the lift-off names
    reads the scale's failing end, the others no more than that."""
    from furncheck.report.pages import _case_table, worst_utilization

    entry = _entry("bench-tips.yaml", "elastic")
    (case,) = entry.report.cases
    assert case.stability == "lift-off"
    assert max(plank.utilization for plank in case.planks) > 10      # the bolted solve's
    used = plank_utilizations(entry.report, entry.design)
    assert worst_utilization(used) == 1.5
    table = _case_table(entry.report)
    assert "not counted: the design does not stand in this case" in table
    assert "sag 4" not in table and "<td>seat: " not in table
