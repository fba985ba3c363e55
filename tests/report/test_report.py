"""The HTML report (fretwear.report, ``fretwear report``, ``fretwear run --report``).

The page must be self-contained (no external resource), carry the inputs, every coefficient with
its source, the version, the warnings, the tables, the power's interval and the exceedance, and
render in a real headless browser with no broken image (chromium --dump-dom after the load
event, a probe script reading each image's naturalWidth).
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from fretwear import __version__
from fretwear.cli import main
from fretwear.report import analyse_case, render_report, write_report

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
BROWSERS = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")
PROBE = """<script>window.addEventListener("load", function () {
  var imgs = Array.from(document.images);
  var out = document.createElement("pre"); out.id = "fretwear-probe";
  out.textContent = JSON.stringify({images: imgs.length,
    broken: imgs.filter(function (i) { return !i.complete || i.naturalWidth === 0; }).length,
    headings: Array.from(document.querySelectorAll("h2")).map(function (h) { return h.id; })});
  document.body.appendChild(out);
});</script>"""


@pytest.fixture(scope="module")
def analysis():
    return analyse_case(EXAMPLES / "tube_bav.toml", samples=512, seed=3)


@pytest.fixture(scope="module")
def html(analysis):
    return render_report(analysis)


def test_content(analysis, html):
    attrs = analysis.case.table.attrs
    assert f"<td>{__version__}</td>" in html
    # every coefficient with its source (the database row of I600TT/Z6C13)
    source = attrs["coefficient_sources"]["mobile.coefficient"]
    assert "COEF_USURE" in html and "9.2e-15" in html
    assert source.split(" (")[0].replace("&", "&amp;") in html
    assert str(analysis.interval) in html  # P = ... ± ... W (95 %)
    assert "Probability that the global depth exceeds the limit" in html
    p = analysis.uncertainty.exceedance()["probability"].iloc[-1]
    assert f"{p:.3g}" in html
    for warning in analysis.case.warnings:
        assert warning.split(":")[0] in html
    assert html.count("data:image/png;base64,") == 4  # table, sectors, fan chart, Sobol'
    # the power's distribution in words (its unit), not a dataclass repr of 16 digits
    power = next(v for v in analysis.uncertainty.variables if v.kind == "power")
    assert f"wear power: {power.distribution}" in html and "TruncatedStudent(" not in html
    assert "The tube's global depth at each instant" in html


def test_self_contained(html):
    assert not re.search(r"""(src|href)\s*=\s*["'](https?:|//|file:)""", html)
    assert "<link" not in html


def _browser() -> str:
    for name in BROWSERS:
        path = shutil.which(name)
        if path:
            return path
    pytest.skip("no headless browser: `apt-get install -y chromium` (make test installs it "
                "when apt-get can)")


def test_renders_in_a_headless_browser_without_broken_images(html, tmp_path):
    page = tmp_path / "probe.html"
    page.write_text(html.replace("</body>", PROBE + "</body>"), encoding="utf-8")
    out = subprocess.run(
        [_browser(), "--headless", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
         "--virtual-time-budget=20000", "--dump-dom", page.as_uri()],
        capture_output=True, text=True, timeout=180)
    found = re.search(r'<pre id="fretwear-probe">([^<]*)</pre>', out.stdout)
    assert found, f"the page did not load in the browser: {out.stderr[-2000:]}"
    probe = json.loads(found.group(1).replace("&quot;", '"'))
    assert probe["images"] == 4 and probe["broken"] == 0, probe
    assert {"summary", "inputs", "coefficients", "power", "table", "uncertainty",
            "warnings"} <= set(probe["headings"])


def test_calibration_section_and_cli(tmp_path, capsys):
    inspections = tmp_path / "insp.csv"
    inspections.write_text("instant,depth_mm,measurement_sigma\n10,0.2,0.1\n")
    out = tmp_path / "r.html"
    assert main(["report", str(EXAMPLES / "tube_bav.toml"), "-o", str(out), "--samples", "256",
                 "--inspections", str(inspections), "--forecast", "30"]) == 0
    text = out.read_text(encoding="utf-8")
    assert "Calibration on inspections" in text and "Posterior predictive" in text
    assert text.count("data:image/png;base64,") == 5
    run_out = tmp_path / "run.html"
    assert main(["run", str(EXAMPLES / "tube_tube.toml"), "-q", "--report", str(run_out)]) == 0
    html = run_out.read_text(encoding="utf-8")
    assert "THROUGH THE WALL" in html
    # bad news first: the alarm opens the summary, before the wear power and the limit
    summary = html[html.index('id="summary"'):]
    assert summary.index("THROUGH THE WALL") < summary.index("Wear power") < summary.index("Limit:")


def test_write_is_atomic_and_returns_the_path(analysis, tmp_path):
    target = tmp_path / "sub" / "report.html"
    assert write_report(analysis, target) == target
    assert target.read_text(encoding="utf-8").startswith("<!DOCTYPE html>")
    assert [p.name for p in target.parent.iterdir()] == ["report.html"]


def test_sobol_table_gives_the_interval_clipped_to_0_1(analysis, html):
    """The report's Sobol' table: each index as computed, its half-width and the interval it
    gives cut to [0, 1] (the range of an index), recomputed here from sensitivity()."""
    table = analysis.uncertainty.sensitivity()
    head = "<th>variable</th><th>first</th><th>first_conf</th><th>first low</th>" \
           "<th>first high</th><th>total</th><th>total_conf</th><th>total low</th>" \
           "<th>total high</th>"
    assert head in html and "clipped to [0, 1]" in html
    for name, r in table.iterrows():
        bounds = [min(max(v, 0.0), 1.0) for v in (r["first"] - r["first_conf"],
                                                  r["first"] + r["first_conf"])]
        row = re.search(rf"<td>{re.escape(str(name))}</td>((?:<td>[^<]*</td>){{8}})", html)
        cells = [float(c) for c in re.findall(r"<td>([^<]*)</td>", row.group(1))]
        assert cells[2:4] == pytest.approx(bounds, rel=1e-3, abs=1e-12)  # 4 digits shown
        assert 0.0 <= min(cells[2:4] + cells[6:8]) and max(cells[2:4] + cells[6:8]) <= 1.0
