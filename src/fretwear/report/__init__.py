"""Reports: one case analysed end to end (wear table, power interval, Monte Carlo, calibration)
and written as one self-contained HTML page (extra ``report``: jinja2, matplotlib).

- :func:`analyse_case`: run a case file and propagate its uncertainty -> :class:`Analysis`;
- :func:`write_report` / :func:`render_report`: the HTML page of an analysis.

``fretwear report CASE.toml -o report.html`` and ``fretwear run CASE.toml --report report.html``.
"""

from fretwear.report.analysis import UNCERTAINTY_KEYS, Analysis, analyse_case
from fretwear.report.html import render_report, write_report

__all__ = ["UNCERTAINTY_KEYS", "Analysis", "analyse_case", "render_report", "write_report"]
