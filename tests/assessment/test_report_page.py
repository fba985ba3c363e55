"""The assessment's HTML page (``fretwear assess --report``, issue 26, point 6) in a real
headless browser, as tests/report/test_report.py checks the single-contact report: every
figure decodes (naturalWidth > 0 after the load event), the key numbers are in the text, no
network; at 1280 px the figures, tables and paragraphs do not overlap one another and nothing
is wider than the window (bounding boxes read by a probe script), and the screenshot decodes
as a 1280 px wide PNG."""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import zlib

import pandas as pd
import pytest
import synthetic

from fretwear.assessment import LogisticPOD, SizingModel
from fretwear.assessment.growth import FactorNodes
from fretwear.assessment.outage import assess
from fretwear.report.assessment import render_assessment_report, write_assessment_report

PROBE = """<script>window.addEventListener("load", function () {
  var imgs = Array.from(document.images);
  var boxes = Array.from(document.querySelectorAll("figure, table, p, h2")).map(function (e) {
    var r = e.getBoundingClientRect();
    return [e.tagName + "#" + (e.id || ""), r.left, r.top, r.right, r.bottom]; });
  var out = document.createElement("pre"); out.id = "fretwear-probe";
  out.textContent = JSON.stringify({images: imgs.length,
    broken: imgs.filter(function (i) { return !i.complete || i.naturalWidth === 0; }).length,
    width: document.documentElement.scrollWidth, window: window.innerWidth, boxes: boxes});
  document.body.appendChild(out);
});</script>"""


@pytest.fixture(scope="module")
def result():
    powers = [0.02, 0.05, 0.08, 0.11, 0.03, 0.06, 0.09, 0.12, 0.04]
    tubes = [(r, c) for r in (1, 2, 3) for c in (1, 2, 3)]
    insp = pd.DataFrame({"contact": ["c7", "c8", "c2"], "instant": [10.0, 10.0, 10.0],
                         "depth": [3.0e-4, 3.6e-4, None], "result": ["", "", "NDD"]})
    return assess(synthetic.bundle(powers, tubes), insp, interval=2.0,
                  sizing=SizingModel(0.0, 1.0, 5e-5), pod=LogisticPOD.from_depths(1.5e-4, 3e-4),
                  posterior=FactorNodes([0.0], [1.0], contact_sigma=0.3))


def _browser() -> str:
    for name in ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable"):
        if shutil.which(name):
            return shutil.which(name)
    pytest.skip("no headless browser: `apt-get install -y chromium`")


def test_key_numbers_and_no_network(result):
    html = render_assessment_report(result)
    b = result.bundle
    assert f"{b['p_any']:.3g}" in html and f"{b['longest_interval']:.3g}" in html
    for tube in b["plugging"] + b["inspection_sample"]:
        assert tube in html
    assert html.count("data:image/png;base64,") == 6
    assert not re.search(r"""(src|href)\s*=\s*["'](https?:|//|file:)""", html)
    assert "<link" not in html


def test_provenance_gives_the_technique_in_engineering_units(result):
    """A new user read SizingModel(sigma=5e-05) in metres and the POD as beta0/beta1: the
    page gives the sizing error and a50/a90 in mm, units named (fails before). Oracle: the
    fixture's inputs, 5e-5 m, 1.5e-4 m and 3e-4 m, are 0.05, 0.15 and 0.3 mm."""
    html = render_assessment_report(result)
    assert "sizing error σ = 0.05 mm" in html
    assert "a50 = 0.15 mm, a90 = 0.3 mm" in html
    assert "SizingModel(" not in html and "beta0" not in html


def _overlaps(boxes):
    out = []
    for i, a in enumerate(boxes):
        for b in boxes[i + 1:]:
            if min(a[3], b[3]) - max(a[1], b[1]) > 1 and min(a[4], b[4]) - max(a[2], b[2]) > 1:
                out.append((a[0], b[0]))
    return out


def test_renders_at_1280_px_without_broken_figures_or_overlap(result, tmp_path):
    page = write_assessment_report(result, tmp_path / "report.html")
    probe = tmp_path / "probe.html"
    probe.write_text(page.read_text(encoding="utf-8").replace("</body>", PROBE + "</body>"),
                     encoding="utf-8")
    base = [_browser(), "--headless", "--no-sandbox", "--disable-gpu",
            "--disable-dev-shm-usage", "--window-size=1280,2000", "--hide-scrollbars"]
    out = subprocess.run([*base, "--virtual-time-budget=20000", "--dump-dom", probe.as_uri()],
                         capture_output=True, text=True, timeout=180)
    found = re.search(r'<pre id="fretwear-probe">([^<]*)</pre>', out.stdout)
    assert found, f"the page did not load in the browser: {out.stderr[-2000:]}"
    data = json.loads(found.group(1).replace("&quot;", '"'))
    assert data["images"] == 6 and data["broken"] == 0, data
    assert data["width"] <= data["window"] == 1280
    assert _overlaps(data["boxes"]) == []
    shot = tmp_path / "shot.png"
    subprocess.run([*base, f"--screenshot={shot}", page.as_uri()], capture_output=True,
                   timeout=180)
    png = shot.read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert int.from_bytes(png[16:20], "big") == 1280     # IHDR width
    assert zlib.crc32(png[12:29]) == int.from_bytes(png[29:33], "big")  # IHDR intact


def test_the_summary_names_the_sample_and_prints_tiny_probabilities_as_a_floor(result):
    """A new user's trial: the summary said "Next inspection sample (1 tube(s), 90 % of the
    risk)." without the tube (the terminal named it), and probabilities like 1.4e-229 were
    printed as results."""
    html = render_assessment_report(result)
    summary = html.split('<h2 id="summary">')[1].split('<h2 id="inputs">')[0]
    sample = result.bundle["inspection_sample"]
    assert sample and f"of the risk): {', '.join(sample[:20])}" in summary
    from fretwear.assessment.summary import probability_text

    assert probability_text(1.4e-229) == "< 1e-06" and probability_text(0.0963) == "0.0963"
