"""The confidence interval of the power in ``fretwear power`` and the ``run`` summary.

Oracle: scipy.stats.t.interval on the block powers the command reports (an independent
computation of the batch-means interval).
"""

import json
from pathlib import Path

import numpy as np
import pytest
from scipy import stats

from fretwear.cli import main

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
HISTORY = EXAMPLES / "data" / "oscillator_gap.csv"


def test_power_json_interval_matches_student(capsys):
    assert main(["power", str(HISTORY), "--blocks", "12", "--sectors", "4", "--level", "0.9",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    blocks = np.array(out["blocks"])
    low, high = stats.t.interval(0.9, 11, loc=blocks.mean(), scale=stats.sem(blocks))
    iv = out["confidence_interval"]
    assert iv["estimate"] == pytest.approx(out["total"], rel=1e-12)
    assert (iv["estimate"] - iv["half_width"], iv["high"]) == pytest.approx((low, high),
                                                                           rel=1e-12)
    assert iv["count"] == 12 and iv["level"] == 0.9
    assert len(out["sector_confidence_intervals"]) == 4
    sector = np.array(out["block_sectors"])[:, 2]
    assert out["sector_confidence_intervals"][2]["half_width"] == pytest.approx(
        stats.t.ppf(0.95, 11) * stats.sem(sector), rel=1e-12)


def test_power_table_prints_the_interval(capsys):
    assert main(["power", str(HISTORY), "--blocks", "12"]) == 0
    text = capsys.readouterr().out
    assert "P = 0.00200 ± 0.00066 W (95 %)" in text


def test_one_block_prints_no_interval(capsys):
    assert main(["power", str(HISTORY), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["confidence_interval"] is None


def test_run_summary_prints_the_interval_and_its_warning(capsys):
    assert main(["run", str(EXAMPLES / "tube_bav.toml")]) == 0
    text = capsys.readouterr().out
    assert "P = 0.0020 ± 0.0011 W (95 %)  (batch means over 4 blocks)" in text
    assert "ConfidenceWarning: oscillator_gap: only 4 blocks" in text  # named like the others
