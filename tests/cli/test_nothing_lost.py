"""Nothing the user gave is lost, and every summary says its units (issue 15).

An output equal to an input (history, restart table, database, obstacle table, case file) is
refused before anything is computed; a restart table (ETAT_INIT) is replaced by its
continuation only with --force; the obstacle's input and output DISCRET options have names that
cannot be taken for each other (the old one-letter pair is refused with the new names); errors
name the user's path, never the atomic writer's temporary file; summaries print the units read
and --units fixes a history exported in mm; printed tables are not wrapped at 80 columns in a
file.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from fretwear.cli import main
from fretwear.errors import InputError
from fretwear.io import read_history, write_history
from fretwear.io.atomic import atomic_path
from fretwear.table.files import write_wear_table

EXAMPLES = Path(__file__).parents[2] / "examples"


@pytest.fixture
def make_case(tmp_path, grappe_case):
    """``make_case(history, extra="")``: the small case with its [obstacle] section."""
    def make(history, extra=""):
        return grappe_case(tmp_path / "case.toml", history, obstacle=True, extra=extra)
    return make


@pytest.fixture
def history(tmp_path):
    return write_history(read_history(EXAMPLES / "data" / "oscillator_gap.csv"),
                         tmp_path / "h.csv")


def _bytes(path):
    return Path(path).read_bytes()


def test_run_refuses_an_output_equal_to_an_input(tmp_path, history, capsys, make_case):
    case = make_case(history)
    before = _bytes(history)
    assert main(["run", str(case), "-q", "-o", str(history)]) == 2
    err = capsys.readouterr().err
    assert f"output -o {str(history)!r} is the history file" in err
    assert "writing it would destroy an input" in err
    assert _bytes(history) == before
    assert main(["run", str(case), "-q", "-o", str(case)]) == 2
    assert "is the case file" in capsys.readouterr().err
    database = tmp_path / "mine.csv"
    database.write_text("contact_type,mobile_material,obstacle_material,law,parameter,value,"
                        "unit\nTUBE_BAV,I690TT,A405,ARCHARD,COEF_USURE,3e-15,1/Pa\n")
    assert main(["run", str(case), "-q", "--database", str(database), "-o",
                 str(database)]) == 2
    assert "is the coefficient database" in capsys.readouterr().err


def test_restart_table_is_replaced_only_with_force(tmp_path, history, capsys, make_case):
    first = tmp_path / "first.csv"
    assert main(["run", str(make_case(history)), "-q", "-o", str(first)]) == 0
    case = make_case(history, extra=f'[restart]\ntable = "{first}"\n')
    before = _bytes(first)
    assert main(["run", str(case), "-q", "-o", str(first)]) == 2
    err = capsys.readouterr().err
    assert "is the restart table (ETAT_INIT)" in err and "add --force" in err
    assert _bytes(first) == before
    assert main(["run", str(case), "-q", "-o", str(first), "--force"]) == 0
    assert _bytes(first) != before  # the continued table (rows at 6000 and 10000 h)


def test_obstacle_refuses_outputs_equal_to_inputs(tmp_path, history, capsys, make_case):
    table = tmp_path / "wear.csv"
    assert main(["run", str(make_case(history)), "-q", "-o", str(table)]) == 0
    before = _bytes(table)
    common = ["obstacle", "--table", str(table), "--mobile-radius", "4.85e-3",
              "--wall-thickness", "0.47e-3", "--width", "20e-3", "--step", "5",
              "--resolution", "1", "-q"]
    assert main([*common, "--gap", "0.4e-3", "-o", str(table)]) == 2
    assert "is the wear table (--table)" in capsys.readouterr().err
    assert _bytes(table) == before
    discret = tmp_path / "new.txt"
    assert main([*common, "--gap", "0.4e-3", "--write-discret", str(discret)]) == 0
    before = _bytes(discret)
    assert main([*common, "--obstacle-table", str(discret), "--write-discret",
                 str(discret)]) == 2
    assert "output --write-discret" in capsys.readouterr().err
    assert _bytes(discret) == before


@pytest.mark.parametrize("old, new", [("--discrete", "--obstacle-table"),
                                      ("--discret", "--write-discret")])
def test_obstacle_old_option_names_are_refused_with_the_new_ones(tmp_path, capsys, old, new):
    target = tmp_path / "x.txt"
    assert main(["obstacle", "--table", "t.csv", old, str(target)]) == 2
    err = capsys.readouterr().err
    assert f"{old} was renamed {new}" in err and f"use {new} {target}" in err
    assert not target.exists()


def test_units_are_printed_and_units_option_fixes_a_mm_file(tmp_path, capsys, make_case):
    si = read_history(EXAMPLES / "data" / "oscillator_gap.csv")
    mm = write_history(si.replace(dy=si.dy * 1e3, dz=si.dz * 1e3, vt1=si.vt1 * 1e3,
                                  vt2=si.vt2 * 1e3), tmp_path / "mm.csv")
    assert main(["power", str(mm)]) == 0
    out = capsys.readouterr().out
    assert "UnitsWarning" in out or "plausibility limit" in out
    assert "units read: time [s], normal_force [N]" in out and "vt1 [m/s]" in out
    assert main(["power", str(mm), "--units", "length=mm,velocity=mm/s"]) == 0
    out = capsys.readouterr().out
    assert "plausibility limit" not in out and "vt1 [mm/s]" in out and "dy [mm]" in out
    case = make_case(mm)
    assert main(["run", str(case)]) == 0
    out = capsys.readouterr().out
    assert "units read: time [s]" in out and "plausibility limit" in out
    assert main(["run", str(case), "--units", "length=mm,velocity=mm/s"]) == 0
    out = capsys.readouterr().out
    assert "vt1 [mm/s]" in out and "plausibility limit" not in out


def test_errors_name_the_users_path_not_the_temporary_file(tmp_path):
    target = tmp_path / "out.parquet"

    with pytest.raises(InputError) as err, atomic_path(target) as tmp:
        raise OSError(28, f"No space left on device: {tmp}", str(tmp))
    assert str(target) in str(err.value) and ".tmp" not in str(err.value)
    assert not list(tmp_path.iterdir())  # no temporary file left behind
    folder = tmp_path / "folder.csv"
    folder.mkdir()
    with pytest.raises(InputError, match=r"output '.*folder.csv' is a directory"):
        write_wear_table(__import__("pandas").DataFrame({"instant": [1.0]}), folder)
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(InputError, match=r"cannot write the output '.*file/sub/out.csv'"):
        write_wear_table(__import__("pandas").DataFrame({"instant": [1.0]}),
                         blocker / "sub" / "out.csv")


def test_tables_are_not_wrapped_in_a_file(tmp_path):
    """Run as a user does, output redirected to a file, no COLUMNS: no table wrapped at 80."""
    env = {k: v for k, v in os.environ.items() if k != "COLUMNS"}
    out = tmp_path / "out.txt"
    with open(out, "w") as handle:
        subprocess.run([sys.executable, "-c", "import sys; from fretwear.cli import main; "
                        "sys.exit(main(['materials']))"], stdout=handle, env=env, check=True)
    lines = out.read_text().splitlines()
    table = [ln for ln in lines if ln.startswith("│")]
    assert table and max(len(ln) for ln in table) > 80
    assert all(ln.endswith("│") for ln in table)  # one line per row: nothing wrapped


def test_report_refuses_to_overwrite_an_input(tmp_path, history, capsys, make_case):
    pytest.importorskip("jinja2")
    case = make_case(history)
    before = _bytes(history)
    assert main(["report", str(case), "-o", str(history)]) == 2
    assert "is the history file" in capsys.readouterr().err
    assert _bytes(history) == before
