"""A wear table read back from a file fretwear wrote is drawn as the table in memory: the
limit line, the restart and the title come from the wear case the file carries (issue 25,
point 3; before, a table read back had no attrs wall, origin or law to draw them from)."""

import pytest
from matplotlib.figure import Figure

from fretwear.plotting import plot_wear_table
from fretwear.table import read_wear_table, wear_table, write_wear_table

KW = {"contact_type": "TUBE_BAV", "time_scale": 3.15576e7, "wall_thickness": 1.09e-3,
      "dimensions": {"mobile_radius": 9.525e-3, "obstacle_width": 12.7e-3},
      "coefficients": {"COEF_USURE": 9.2e-15}, "name": "R12C40 AVB3", "time_unit": "year"}


def _drawn(fig):
    axis = fig.axes[1]
    return (fig._suptitle.get_text(), axis.get_xlabel(),
            sorted(t.get_text() for t in axis.get_legend().get_texts()),
            sorted(t.get_text() for t in axis.texts))


@pytest.mark.parametrize("suffix", ["csv", "parquet"])
def test_the_figure_of_a_file_equals_the_figure_in_memory(suffix, tmp_path):
    first = wear_table(0.01, instants=[0.0, 10.0], **KW)
    table = wear_table(0.01, instants=[5.0, 12.0], initial_state=first, **KW)
    back = read_wear_table(write_wear_table(table, tmp_path / f"t.{suffix}"))
    here, there = (plot_wear_table(t, ax=Figure()) for t in (table, back))
    assert _drawn(there) == _drawn(here)
    title, xlabel, legend, notes = _drawn(there)
    assert title == "R12C40 AVB3: TUBE_BAV ARCHARD" and xlabel == "instant [year]"
    assert "limit 40 % of the wall" in legend and "restart" in notes
