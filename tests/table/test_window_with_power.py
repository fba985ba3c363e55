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


def test_window_other_than_a_power_results_own_is_named():
    """A PowerResult source carries its own window: t_start/t_end/blocks that differ from it
    were silently ignored (the table used the result's [0, 1] s and 1 block while the caller
    asked for [0.5, 1] s in 2 blocks). Oracle: the table's power is the result's total (the
    keywords are ignored) and an UnusedKeywordWarning names them; the same window as the
    result's, or none, warns nothing."""
    import numpy as np

    from fretwear.power import wear_power

    t = np.linspace(0.0, 1.0, 2001)
    h = ContactHistory(time=t, normal_force=np.where(t > 0.5, 10.0, 1.0),
                       vt1=0.2 * np.sin(2 * np.pi * 5 * t), vt2=np.zeros_like(t))
    result = wear_power(h)
    with pytest.warns(UnusedKeywordWarning, match=r"wear_table: t_start, blocks .* PowerResult"):
        table = wear_table(result, t_start=0.5, blocks=2, **KEYWORDS)
    assert table.attrs["power"]["total"] == result.total
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        wear_table(result, **KEYWORDS)
        wear_table(result, t_start=0.0, t_end=1.0, blocks=1, **KEYWORDS)
