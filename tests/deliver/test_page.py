"""The compile report page: built from a small hand-made manifest (what each section shows,
escaping, sections left out when their data is missing, PNGs embedded, written whole), and
the page of a real compile opened in headless Chromium (no console error, the chosen method
in its title and heading, one chart point per candidate, every picture decoded, nothing
fetched from the network), with a screenshot."""

import copy
import html
import os
import re
import shutil
import struct
import zlib
from pathlib import Path

import pytest

from phongfx.deliver.page import REPORT_NAME, candidate_points, report_html, write_report

CONTRACT = {"method": "fig7", "scene": "tiny", "space": "eye space", "quantize": "round half up",
            "stream": "one vector per visible pixel",
            "inputs": [{"field": "a", "format": "1.11", "lanes": 1, "light": None, "meaning": "the pixel's place",
                        "normalized_by": None, "ports": ["in_a"], "quantity": "a", "rate": "pixel", "space": None,
                        "unit_vector": None}],
            "materials": [], "lights": [],
            "outputs": [{"format": "8.0", "meaning": "the display level", "port": "out_r", "quantity": "r",
                         "reference": "true Phong"}],
            "notes": ["No material port."]}
#: A manifest as ``phongfx compile`` writes one, cut down to what the page reads.
MANIFEST = {
    "manifest_version": 2, "scene": "tiny", "path": "../tiny.toml", "cost_model": "ecp5-proxy", "search": "certified",
    "requirement": {"max_error_levels": 1.0, "against": "phong", "mpixels_per_second": 30.0, "clock_mhz": None},
    "evaluation": {"frames": 1, "domain_samples": 2000, "points_measured": 40},
    "chosen": "fig7", "module": "tiny_fig7", "block": "shader", "tie": None, "hint": None, "refused": None,
    "rejected": {"schlick": "Schlick's unit computes only the specular term"},
    "methods": {
        "fig7": {"feasible": True, "params": {"vec_frac": 11, "k": 4}, "max": 1.0, "mean": 0.0507,
                 "cost": {"cost": 28595, "unit": "LUT-eq", "pixel_rate_mpx": 34.81, "clock_mhz": 34.81,
                          "clock_source": "proxy", "met": True, "architecture": {"pipeline": 0, "interval": 1},
                          "architectures_priced": 10}},
        "blinn": {"feasible": False, "params": {"vec_frac": 18}, "max": 9.0, "mean": 0.3,
                  "why": ["its own float form is itself 7.96 levels from true Phong"],
                  "default": {"max": 9.0, "cost": {"cost": 23231, "unit": "LUT-eq"}}}},
    "widths": {"vec_frac": 11, "k": 4}, "latency": 20,
    "cost": {"cost": 28595, "unit": "LUT-eq", "clock_path": "a → b"},
    "error": {"max": 1.0, "mean": 0.0507, "frames_max": 1.0, "domain_max": 1.0, "domain_points": 4048},
    "timing": {"architecture": {"pipeline": 0, "interval": 1, "share": True}, "clock_mhz": 34.81,
               "clock_source": "proxy", "pixel_rate_mpx": 34.81, "requirement_mpx": 30.0, "met": True,
               "latency": 20, "latency_ns": 574.56},
    "default_widths": {"max": 6.0, "cost": {"cost": 26638, "unit": "LUT-eq"}},
    "conventional_baseline": {"why_not": "not among the methods considered"},
    "certificate": {"certified": True, "bound_levels": 1.4963, "method": "interval", "seconds": 5.6, "why": "",
                    "parts": {"rounding": 0.7309, "approximation": 0.2655, "output": 0.5}},
    "witness": {"error_levels": 1, "unrounded": 0.9796, "found_by": "local search (10,000 fresh domain points)",
                "replay": "phongfx certify DIR --replay"},
    "rtl_check": {"frame": 0, "backend": "verilator-fast", "pixels": 592, "cycles": 941, "mismatches": 0,
                  "stalls": 0.2, "reset_at_cycle": 296},
    "error_png_white_levels": 2.0,
    "pictures": {"error": "worst channel's error", "frames": "the r, g, b codes"},
    "top": {"module": "tiny_fig7_top", "file": "verilog/tiny_fig7_top.v", "latency": 20, "interval": 1,
            "ports": [{"name": "in_a", "direction": "input", "width": 12, "signed": False, "format": "1.11",
                       "field": "a", "lane": None, "offset": 0}]},
    "contract": CONTRACT}


def _png(path, width=3, height=2):
    """A tiny grey RGB PNG at ``path``."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    rows = b"".join(b"\x00" + b"\x80" * 3 * width for _ in range(height))
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
                     + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))
    return path


def _text(page):
    """The page's visible text, tags removed and entities decoded, for reading values."""
    return html.unescape(re.sub(r"<[^>]+>", " ", re.sub(r"<(style|svg)\b.*?</\1>", " ", page, flags=re.S)))


def test_the_page_shows_the_requirement_the_choice_the_certificate_and_the_ports():
    page = report_html(MANIFEST)
    assert "<title>tiny: fig7 chosen: phongfx compile report</title>" in page
    assert "<h1>tiny: fig7 chosen</h1>" in page
    text = " ".join(_text(page).split())
    for shown in ("requirement ≤ 1 level against true Phong", "cost LUT-eq 28,595",
                  "Speed: 34.8 Mpixel/s at 34.8 MHz (proxy) (met)", "certified ≤ 1.496 levels (interval)",
                  "0 mismatches in 592 pixels", "widths vec_frac 11, k 4",
                  "default widths max 6 levels, LUT-eq 26,638 (misses the requirement)",
                  "against conventional Phong not among the methods considered",
                  "blinn infeasible vec_frac 18 9 levels", "its own float form is itself 7.96 levels",
                  "schlick Schlick's unit computes only the specular term", "part: rounding 0.7309",
                  "found by local search (10,000 fresh domain points)", "phongfx certify DIR --replay",
                  "in_a input 12 1.11 a 0", "Stream: one vector per visible pixel.", "No material port."):
        assert shown in text, shown
    # the chosen row of the candidates and of the pixel-rate tables is marked
    assert page.count('<tr class="chosen">') == 2


def test_every_candidate_is_a_chart_point_an_infeasible_one_at_its_defaults():
    points, left = candidate_points(MANIFEST)
    assert [(p.label, p.kind, p.x, p.y) for p in points] == [("fig7", "chosen", 28595.0, 1.0),
                                                             ("blinn (defaults)", "infeasible", 23231.0, 9.0)]
    assert left == []
    page = report_html(MANIFEST)
    chart = re.search(r'<svg id="cost-error".*?</svg>', page, re.S).group(0)
    assert re.findall(r'<g class="point" data-label="([^"]*)" data-kind="(\w+)"', chart) == [
        ("blinn (defaults)", "infeasible"), ("fig7", "chosen")]  # the chosen one drawn last, on top
    assert "cost (LUT-eq, ecp5-proxy)" in chart and "max error (display levels)" in chart
    assert "requirement 1" in chart and 'class="reference"' in chart
    # the pixel-rate chart: the one costed method at its architecture, the rate asked as a line
    speed = re.search(r'<svg id="pixel-rate".*?</svg>', page, re.S).group(0)
    assert re.findall(r'data-label="([^"]*)"', speed) == ["fig7 (depth 0, interval 1)"]
    assert "asked 30" in speed


def test_text_from_the_manifest_is_escaped():
    data = copy.deepcopy(MANIFEST)
    data["scene"] = "<script>alert(1)</script>"
    data["methods"]["blinn"]["why"] = ['a "quoted" <b>reason</b> & more']
    page = report_html(data)
    assert "<script>" not in page and "<b>reason</b>" not in page
    assert "&lt;script&gt;alert(1)&lt;/script&gt;: fig7 chosen" in page
    assert "a &quot;quoted&quot; &lt;b&gt;reason&lt;/b&gt; &amp; more" in page


def test_a_missing_optional_section_is_left_out():
    data = {k: v for k, v in MANIFEST.items()
            if k not in ("certificate", "witness", "rtl_check", "timing", "top", "contract", "tie")}
    data["methods"] = {"fig7": {k: v for k, v in MANIFEST["methods"]["fig7"].items() if k != "cost"}}
    page = report_html(data)
    text = " ".join(_text(page).split())
    assert "not certified (--sampled" in text and "RTL check: not run (--no-check)" in text
    for gone in ('id="ports"', 'id="contract"', 'id="pixel-rate"', 'id="pictures"', "Witness", "<svg", "<b>tie</b>"):
        assert gone not in page, gone
    assert "Not on the chart (no finite cost and error): fig7." in text
    assert "None" not in text  # a missing value is no "None" in a cell


def test_a_compile_that_chooses_nothing_says_why():
    data = {k: MANIFEST[k] for k in ("scene", "requirement", "methods", "rejected", "cost_model", "search")}
    data.update(chosen=None, certificate=None, witness=None,
                hint={"text": ["the best any method reaches is 6 levels: --max-error 6 accepts it"]})
    data["methods"] = {"blinn": MANIFEST["methods"]["blinn"]}
    page = report_html(data)
    assert "<h1>tiny: no design chosen</h1>" in page
    text = " ".join(_text(page).split())
    assert "No design meets the requirement (≤ 1 level against true Phong) on the scene tiny." in text
    assert "hint: the best any method reaches is 6 levels: --max-error 6 accepts it" in text
    assert 'id="chosen"' not in page and 'id="certificate"' not in page and 'id="candidates"' in page


def test_the_folder_s_pictures_are_embedded_with_their_captions(tmp_path):
    _png(tmp_path / "error" / "sheet.png")
    _png(tmp_path / "error" / "frame_000.png")
    _png(tmp_path / "frames" / "frame_000.png", 4, 4)
    _png(tmp_path / "frames" / "frame_001.png", 4, 4)
    page = report_html(MANIFEST, tmp_path)
    sources = re.findall(r'<img alt="([^"]*)" src="data:image/png;base64,([A-Za-z0-9+/=]+)"', page)
    # the error sheet alone (it holds every frame); no frames sheet: each frame
    assert [alt for alt, _ in sources] == ["error/sheet.png", "frames/frame_000.png", "frames/frame_001.png"]
    text = _text(page)
    assert "error/sheet.png: worst channel's error" in text and "white = 2 levels or more" in text
    (tmp_path / "frames" / "frame_001.png").write_text("not a picture")
    with pytest.raises(ValueError, match=r"frame_001\.png: not a PNG"):
        report_html(MANIFEST, tmp_path)


def test_the_page_is_written_whole(tmp_path, monkeypatch):
    path = write_report(tmp_path / REPORT_NAME, MANIFEST)
    assert Path(path).read_text(encoding="utf-8") == report_html(MANIFEST)
    # a failure while building leaves the previous page as it was, and no temporary file
    import phongfx.deliver.page as report
    monkeypatch.setattr(report, "report_html", lambda data, folder=None: 1 / 0)
    with pytest.raises(ZeroDivisionError):
        write_report(tmp_path / REPORT_NAME, MANIFEST)
    assert sorted(os.listdir(tmp_path)) == [REPORT_NAME]


# ---------------------------------------------------------------- in a browser

CHROMIUM, CHROMEDRIVER = "/usr/bin/chromium", "/usr/bin/chromedriver"
#: An environment variable naming a file the page's screenshot is copied to (to look at it:
#: the test's own goes into its temporary folder).
SCREENSHOT = "PHONGFX_REPORT_SCREENSHOT"


@pytest.fixture(scope="module")
def browser():
    """Headless Debian Chromium driven by Debian's chromedriver through Selenium, both at
    fixed paths so that Selenium Manager never runs (it would download a driver); skipped
    where either or Selenium is missing (``make`` installs them)."""
    missing = [path for path in (CHROMIUM, CHROMEDRIVER) if not os.access(path, os.X_OK)]
    if missing:
        pytest.skip(f"{' and '.join(missing)} not installed; apt-get install chromium chromium-driver")
    webdriver = pytest.importorskip("selenium.webdriver", reason="selenium is not installed (pip install selenium; "
                                                                 "make installs it)")
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for argument in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                     "--window-size=1200,900"):
        options.add_argument(argument)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(service=Service(executable_path=CHROMEDRIVER), options=options)
    yield driver
    driver.quit()


@pytest.mark.needs_verilator
def test_a_compiled_folder_s_page_in_chromium(tiny_compiled, browser, tmp_path):
    import json

    out = tiny_compiled.out
    assert tiny_compiled.code == 0, tiny_compiled.stderr
    assert f"report: {out}/report.html\n" in tiny_compiled.stdout
    data = json.loads((out / "manifest.json").read_text())
    page = out / REPORT_NAME
    assert page.read_text(encoding="utf-8") == report_html(data, out)  # written after the final manifest
    browser.get(page.as_uri())
    assert [entry for entry in browser.get_log("browser") if entry["level"] == "SEVERE"] == []
    chosen = data["chosen"]
    assert browser.title.startswith(f"{data['scene']}: {chosen} chosen")
    assert browser.find_element("css selector", "h1").text == f"{data['scene']}: {chosen} chosen"
    labels = browser.execute_script(
        "return Array.from(document.querySelectorAll('svg#cost-error g.point')).map(g => g.dataset.label)")
    assert sorted(labels) == sorted(name if r["feasible"] else f"{name} (defaults)"
                                    for name, r in data["methods"].items())
    images = browser.execute_script(
        "return Array.from(document.images).map(i => [i.alt, i.complete, i.naturalWidth])")
    assert [alt for alt, _, _ in images] == ["error/sheet.png", "frames/sheet.png"]
    assert all(complete and width > 0 for _, complete, width in images), images
    remote = browser.execute_script(
        "return Array.from(document.querySelectorAll('*')).flatMap(e => Array.from(e.attributes))"
        ".filter(a => /^\\s*(https?:)?\\/\\//i.test(a.value) || /url\\(\\s*['\"]?(https?:)?\\/\\//i.test(a.value))"
        ".map(a => a.name + '=' + a.value)")
    assert remote == []
    fetched = browser.execute_script("return performance.getEntriesByType('resource').map(r => r.name)")
    assert [name for name in fetched if not name.startswith(("data:", "file:"))] == []
    assert "RTL check" in browser.find_element("css selector", "body").text
    height = browser.execute_script("return document.body.scrollHeight")
    browser.set_window_size(1200, min(height + 40, 12000))
    shot = tmp_path / "report.png"
    assert browser.save_screenshot(str(shot)) and shot.stat().st_size > 10_000
    if os.environ.get(SCREENSHOT):
        shutil.copyfile(shot, os.environ[SCREENSHOT])
