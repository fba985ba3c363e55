"""One policy for a history window given with a plain wear power: ignored with a warning naming
the keywords (fretwear.table.wear_table, as Code_Aster's POST_USURE does with PUIS_USURE and
INST_INIT/INST_FIN/NB_BLOC, U4.84.05), refused in a case file (a declaration that cannot
apply)."""

from __future__ import annotations

import warnings

import pytest

from fretwear.errors import UnusedKeywordWarning
from fretwear.history import ContactHistory
from fretwear.table import wear_table

KEYWORDS = dict(contact_type="TUBE_ALESAGE", instants=[1.0, 2.0],
                dimensions={"mobile_radius": 0.01, "obstacle_width": 0.02},
                coefficients={"COEF_USURE": 1e-14}, time_scale=3.6e3)


@pytest.mark.parametrize("window, named", [
    ({"t_start": 5.0}, "t_start"),
    ({"t_end": 9.0, "blocks": 4}, "t_end, blocks"),
])
def test_window_with_a_plain_power_is_ignored_and_named(window, named):
    with pytest.warns(UnusedKeywordWarning, match=f"wear_table: {named} window the history"):
        table = wear_table(0.01, **window, **KEYWORDS)
    # ignored: the table is that of the power alone, V = K·P·t (Archard)
    assert table["volume_mobile"].tolist() == [1e-14 * 0.01 * 3.6e3, 1e-14 * 0.01 * 7.2e3]


def test_no_warning_without_window_or_with_a_history():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        wear_table(0.01, **KEYWORDS)
        h = ContactHistory(time=[0.0, 1e-3, 2e-3], normal_force=[10.0, 10.0, 10.0],
                           vt1=[0.1, 0.1, 0.1], vt2=[0.0, 0.0, 0.0])
        wear_table(h, t_start=0.0, t_end=2e-3, **KEYWORDS)


def test_case_file_refuses_a_window_with_a_power(tmp_path):
    from fretwear.errors import KeywordError
    from fretwear.workflows.case_files import case_arguments, load_case

    (tmp_path / "c.toml").write_text(
        '[power]\nvalue_W = 0.01\nt_start_s = 1.0\n[law]\nmobile = { COEF_USURE = 1e-14 }\n'
        '[geometry]\ncontact_type = "TUBE_ALESAGE"\nmobile_radius_m = 0.01\n'
        'obstacle_width_m = 0.02\n[time]\ninstants = [1, 2]\nunit = "hour"\n')
    with pytest.raises(KeywordError, match=r"\[power\] t_start_s apply to a history"):
        case_arguments(load_case(tmp_path / "c.toml"))
