"""The command line's last net (issue 15): no Python traceback reaches the user.

User errors (fretwear errors) exit 2 with the message; running out of memory exits 2 with
advice; any other exception is a bug of fretwear: exit 3, one line asking for a report, and the
traceback only with FRETWEAR_DEBUG=1.
"""

from __future__ import annotations

import pytest
from click.testing import CliRunner

import fretwear.workflows.case_files as case_files
from fretwear.cli import INTERNAL_ERROR, main


def _run(argv):
    runner = CliRunner()
    with runner.isolation() as streams:
        code = main(argv)
    return code, streams[1].getvalue().decode()


@pytest.fixture
def case(tmp_path):
    path = tmp_path / "c.toml"
    path.write_text('[power]\nvalue_W = 0.01\n[law]\nmobile = { COEF_USURE = 1e-14 }\n'
                    '[geometry]\ncontact_type = "TUBE_ALESAGE"\nmobile_radius_m = 0.01\n'
                    'obstacle_width_m = 0.02\n[time]\ninstants = [1.0]\nunit = "h"\n')
    return path


def test_a_bug_is_exit_3_without_traceback(case, monkeypatch):
    def broken(*args, **kwargs):
        raise TypeError("unsupported operand")

    monkeypatch.setattr(case_files, "wear_table_from_case", broken)
    monkeypatch.delenv("FRETWEAR_DEBUG", raising=False)
    code, err = _run(["run", str(case), "-q"])
    assert code == INTERNAL_ERROR == 3
    assert "Traceback" not in err
    assert "internal error (a bug of fretwear, please report it" in err
    assert "TypeError: unsupported operand" in err and "FRETWEAR_DEBUG=1" in err
    monkeypatch.setenv("FRETWEAR_DEBUG", "1")
    with pytest.raises(TypeError, match="unsupported operand"):
        _run(["run", str(case), "-q"])


def test_out_of_memory_is_a_user_error(case, monkeypatch):
    def huge(*args, **kwargs):
        raise MemoryError

    monkeypatch.setattr(case_files, "wear_table_from_case", huge)
    code, err = _run(["run", str(case), "-q"])
    assert code == 2 and "out of memory" in err and "Traceback" not in err
