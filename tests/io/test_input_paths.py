"""Every input path through the guard layer (issue 29, point 4): the inspections reader of
``calibrate``, bundle manifests, named pipes, the grid posterior at log-likelihoods ~ -1e19,
``blocks`` bounded, and the CLI's exit code of a non-fretwear ValueError. Each case: a fretwear
error naming the user's file (or value) and the fix, in bounded time and memory."""

from __future__ import annotations

import math
import os
import threading
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from fretwear.errors import FretwearError, InputError
from fretwear.uncertainty.calibration import read_inspections

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
BASE = ('[law]\nmobile = { COEF_USURE = 1e-14 }\n[geometry]\ncontact_type = "TUBE_BAV"\n'
        'mobile_radius_m = 9.525e-3\nobstacle_width_m = 12.7e-3\n[time]\ninstants = [1]\n'
        'unit = "year"\n')


# ----------------------------------------------------------------------------- inspections
@pytest.mark.parametrize("content, words", [
    (b"instant,depth_mm\n1,0.3\n\xe9\n", "not UTF-8"),
    (b"", "is empty"),
    (b"# only a comment\n\n", "is empty"),
    (b"instant,depth_mm\n1,0.3,5\n", "line 2: 3 cells"),
    (b"instant,depth_mm,depth_mm\n1,0.3,0.4\n", "'depth_mm' is given twice"),
    (b"instant,depth_mm\n" + b"9" * 400 + b",0.3\n", "line 2, row 1: instant must be a finite"),
    (b"instant,depth_mm\n1,0.3\x00\n", "binary data"),
])
def test_a_bad_inspection_file_is_a_fretwear_error_naming_it(tmp_path, content, words):
    path = tmp_path / "insp.csv"
    path.write_bytes(content)
    with pytest.raises(FretwearError) as info:
        read_inspections(path)
    assert str(path) in str(info.value) and words in str(info.value), str(info.value)


def test_a_utf16_inspection_file_with_its_bom_is_read(tmp_path):
    path = tmp_path / "insp.csv"
    path.write_bytes("instant;depth_mm\n1;0,3\n".encode("utf-16"))
    assert read_inspections(path)["depth"].tolist() == [pytest.approx(3e-4)]


# ----------------------------------------------------------------------------- manifests
def _run(tmp_path, manifest):
    from fretwear.bundle import run_bundle

    case = tmp_path / "base.toml"
    case.write_text(BASE)
    return run_bundle(manifest, case, scheduler="serial")


def test_a_utf16_toml_manifest_is_read(tmp_path):
    path = tmp_path / "m.toml"
    path.write_bytes('[[contacts]]\ncontact = "A"\n"power.value_W" = 1e-3\n'.encode("utf-16"))
    assert _run(tmp_path, path).stats["done"] == 1


def test_a_nul_byte_and_a_link_loop_in_path_cells_fail_their_contacts_only(tmp_path):
    os.symlink(tmp_path / "loop1", tmp_path / "loop2")
    os.symlink(tmp_path / "loop2", tmp_path / "loop1")
    path = tmp_path / "m.csv"
    path.write_bytes(b"contact,history,power.value_W\nA,a\x00b.csv,\nB,loop1,\nC,,1e-3\n")
    result = _run(tmp_path, path)
    errors = result.errors.set_index("contact")["message"]
    assert "not a valid file name" in errors["A"]
    assert "loop of symbolic links" in errors["B"]
    assert result.stats["done"] == 1


def test_a_400_digit_instant_fails_its_contact_with_a_fretwear_error(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text(f'[[contacts]]\ncontact = "A"\n"power.value_W" = 1e-3\n'
                    f'"time.instants" = [{"1" * 400}]\n')
    errors = _run(tmp_path, path).errors
    assert errors["error"].tolist() == ["InputError"]
    assert "beyond the float range" in errors["message"].iloc[0]


def test_a_list_in_tube_row_names_the_key(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text('[[contacts]]\ncontact = "A"\n"power.value_W" = 1e-3\ntube_row = [1, 2]\n')
    with pytest.raises(InputError, match=r"tube_row = \[1, 2\] is not one value"):
        _run(tmp_path, path)


# ----------------------------------------------------------------------------- pipes
@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="named pipes are POSIX")
@pytest.mark.parametrize("what", ["case", "history", "inspections", "manifest"])
@pytest.mark.parametrize("writer", [False, True])
def test_a_named_pipe_is_refused_without_blocking(tmp_path, what, writer):
    """A FIFO given as a file is refused at once, with or without a writer (without one the
    reader blocked forever; with one done before the reader opened it, its data was lost and
    the reader blocked too)."""
    from fretwear.bundle import read_manifest
    from fretwear.io import read_history
    from fretwear.workflows.case_files import load_case

    fifo = tmp_path / "pipe.csv"
    os.mkfifo(fifo)
    if writer:  # a writer waiting for its reader: released below
        threading.Thread(target=lambda: open(fifo, "w").close(), daemon=True).start()
    call = {"case": load_case, "history": read_history, "inspections": read_inspections,
            "manifest": read_manifest}[what]
    start = time.perf_counter()
    try:
        with pytest.raises(InputError, match="named pipe"):
            call(fifo)
    finally:
        if writer:  # give the waiting writer a reader, so that its thread ends
            fd = os.open(fifo, os.O_RDONLY | os.O_NONBLOCK)
            time.sleep(0.05)
            os.close(fd)
    assert time.perf_counter() - start < 5.0


@pytest.mark.parametrize("special", ["/dev/zero", "/dev/null"])
def test_a_device_is_refused(special):
    if not os.path.exists(special):
        pytest.skip(f"no {special}")
    with pytest.raises(InputError, match="not a regular file"):
        read_inspections(special)


# ----------------------------------------------------------------------------- grid posterior
def test_the_grid_posterior_at_log_likelihoods_of_minus_1e19(tmp_path):
    """Two inspections no factor fits and a measurement sigma of 1e-10: the log-likelihood is
    ~ -1e19 (an IndexError before). The posterior concentrates at the least-squares factor,
    which for TUBE_TUBE (ln d = a_i + 2/5 ln f) is exp(mean_i(ln(y_i/d_i)) / 0.4)."""
    from fretwear.uncertainty import calibrate
    from fretwear.workflows.case_files import load_case, run_case

    text = (EXAMPLES / "tube_tube.toml").read_text(encoding="utf-8")
    case = tmp_path / "tt.toml"
    case.write_text(text.replace('obstacle = { COEF_USURE = 1.0e-12 }', ""))
    table = run_case(load_case(case)).table
    d1 = dict(zip(table["instant"], table["depth_mobile"], strict=True))
    insp = tmp_path / "insp.csv"
    insp.write_text("instant,depth_mm\n0.5,0.6\n1.0,0.3\n")
    result = calibrate(table, insp, method="grid", measurement_sigma=1e-10)
    expected = math.exp((math.log(0.6e-3 / d1[0.5]) + math.log(0.3e-3 / d1[1.0])) / 2 / 0.4)
    assert result.posterior.median == pytest.approx(expected, rel=2e-3)


# ----------------------------------------------------------------------------- blocks
def test_blocks_are_bounded_before_any_allocation(tmp_path):
    from fretwear.history import ContactHistory
    from fretwear.power import PowerAccumulator, wear_power

    with pytest.raises(InputError, match="4831838208"):
        PowerAccumulator(t_start=0.0, t_end=1.0, blocks=4831838208)
    h = ContactHistory(time=np.linspace(0, 1, 11), normal_force=np.ones(11),
                       vt1=np.ones(11), vt2=np.zeros(11))
    # blocks inside one interval are the window's (the integrand is piecewise linear): allowed
    assert wear_power(h, blocks=20).blocks.size == 20


def test_a_case_file_with_huge_blocks_exits_2_naming_them(tmp_path, capsys):
    from fretwear.cli import main

    text = (EXAMPLES / "tube_bav.toml").read_text(encoding="utf-8")
    case = tmp_path / "c.toml"
    history = (EXAMPLES / "data" / "oscillator_gap.csv").resolve()
    assert "blocks = 4 " in text
    text = text.replace("blocks = 4 ", "blocks = 4831838208 ", 1)
    case.write_text(text.replace('"data/oscillator_gap.csv"', f'"{history}"'))
    assert main(["run", str(case), "-o", str(tmp_path / "w.tab")]) == 2
    assert "4831838208" in capsys.readouterr().err


# ----------------------------------------------------------------------------- CLI exit code
def test_a_non_fretwear_value_error_is_a_bug_exit_3(monkeypatch, capsys):
    import fretwear.cli.materials as materials_cli
    from fretwear.cli import INTERNAL_ERROR, main

    def broken(*args, **kwargs):
        raise ValueError("a library's raw message")

    monkeypatch.setattr(materials_cli, "summary", broken)
    assert main(["materials"]) == INTERNAL_ERROR == 3
    assert "internal error" in capsys.readouterr().err
    assert pd.isna(np.nan)


def test_a_400_digit_length_in_a_manifest_fails_its_contact(tmp_path):
    """Found by the deep fuzz run (FRETWEAR_FUZZ_SCALE=20): geometry.mobile_radius_m given a
    400-digit integer raised an OverflowError out of run_bundle."""
    path = tmp_path / "m.toml"
    path.write_text(f'[[contacts]]\ncontact = "A"\n"power.value_W" = 1e-3\n'
                    f'"geometry.mobile_radius_m" = {"1" * 400}\n'
                    f'[[contacts]]\ncontact = "B"\n"power.value_W" = 1e-3\n')
    result = _run(tmp_path, path)
    assert result.errors["contact"].tolist() == ["A"]
    assert "beyond the range of numbers" in result.errors["message"].iloc[0]
