"""One regression test per defect the fuzz suite found (issue 15), with the input it found.

Each input used to end in a Python exception (a traceback for the user), a numpy overflow
warning with an infinite result, an example over 20 s or the interpreter killed for memory; each
now ends in a fretwear error naming the value and the fix.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from fuzzhelpers import small_history
from test_fuzz_cases import base_cases, obstacle_base

from fretwear.errors import FormatError, InputError, KeywordError
from fretwear.io import read_history
from fretwear.obstacle import obstacle_from_config
from fretwear.obstacle.clearance import polar_polygon
from fretwear.obstacle.profiles import discret_angles
from fretwear.workflows.aster import _F, POST_USURE
from fretwear.workflows.case_files import run_case


def _update(**changes):
    table, section, geometry = obstacle_base()
    return obstacle_from_config(dict(section, **changes), geometry=geometry).update(table)


# obstacle_base() perforates its 0.47 mm wall: the wrong option must be reported before the
# wear is computed, so no PerforationWarning precedes the error
@pytest.mark.filterwarnings("error::fretwear.errors.PerforationWarning")
def test_obstacle_step_zero_or_nan():
    """step_deg = 0 raised ZeroDivisionError; NaN a ValueError from int(round(nan))."""
    with pytest.raises(InputError, match=r"angular step \(step_deg\) = 0.0: give a number of "
                                         r"degrees from 0.05 to 120"):
        _update(step_deg=0)
    with pytest.raises(InputError, match=r"step_deg\) = nan"):
        discret_angles(float("nan"))


# obstacle_base() perforates its 0.47 mm wall: the wrong option must be reported before the
# wear is computed, so no PerforationWarning precedes the error
@pytest.mark.filterwarnings("error::fretwear.errors.PerforationWarning")
def test_obstacle_resolutions_that_ran_for_minutes():
    """resolution_deg = 1e-6 (or step_deg = 1e-4) ran for minutes, then exhausted memory."""
    with pytest.raises(InputError, match=r"resolution \(resolution_deg\) = 1e-06: give a number "
                                         r"of degrees from 0.005 to 90"):
        _update(resolution_deg=1e-6)
    with pytest.raises(InputError, match=r"step_deg\) = 0.0001"):
        _update(step_deg=1e-4)
    with pytest.raises(InputError, match=r"resolution_deg\) = 'fine'"):
        polar_polygon(lambda a, side: a * 0 + 1.0, resolution="fine")


def test_obstacle_gap_that_overflowed():
    """gap_m = 1.34e154 m: 'overflow encountered in multiply' and an infinite clearance."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(InputError, match=r"= 1.34078e\+154 m is not a plausible obstacle "
                                             r"dimension"):
            _update(gap_m=1.3407807929942597e+154)


def test_obstacle_width_that_underflowed():
    """width_m = 5e-324 m: an infinite depth profile, then scipy's ValueError."""
    with pytest.raises(InputError, match=r"= 4.94066e-324 m is not a plausible obstacle "
                                         r"dimension \(1e-9 to 1e3 m\)"):
        _update(width_m=5e-324)


def test_post_usure_width_that_overflowed():
    """LARGEUR_OBST = 5e-324 m: 'overflow encountered in divide' and infinite depths."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(InputError, match=r"LARGEUR_OBST\) = 4.94066e-324 m is not a plausible "
                                             r"contact dimension"):
            POST_USURE(LOI_USURE="ARCHARD", CONTACT="TUBE_BAV", RAYON_MOBILE=0.0111,
                       LARGEUR_OBST=5e-324, COEF_INST=31_536_000.0, PUIS_USURE=0.012,
                       MOBILE=_F(COEF_USURE=1.2e-13), INST=(1.0, 2.0))


def test_sector_count_that_exhausted_memory():
    """[sectors] count = 57241 (a typo) made the interpreter be killed for memory."""
    case = base_cases()[2]
    case["sectors"] = {"count": 57241}
    with pytest.raises(InputError, match=r"number of sectors must be from 1 to 720 .*got 57241"):
        run_case(case)


def test_code_aster_time_column_with_a_control_character(tmp_path):
    """A TABLEAU whose INST cell reads '\\x01.0E+00' leaked pandas' ValueError."""
    path = tmp_path / "h.tab"
    h = small_history(n=5)
    text = "#\n#N1\nINST FN VT1 VT2\n" + "".join(
        f"{t:.16E} {f:.16E} {a:.16E} {b:.16E}\n"
        for t, f, a, b in zip(h.time, h.normal_force, h.vt1, h.vt2, strict=True))
    path.write_text(text.replace("\n0.0000000000000000E+00", "\n\x01.0000000000000000E+00", 1))
    with pytest.raises(FormatError, match=r"h\.tab: column 'INST' is not numeric \(type K\d+; "
                                          r"row 0 holds '\\x01.0000000000000000E\+00'\)"):
        read_history(path)


def _dynamics(**changes):
    from test_fuzz_cases import dynamics_base

    from fretwear.dynamics.config import dynamics_from_config

    section = dynamics_base()
    for path, value in changes.items():
        where = section
        *parents, key = path.split(".")
        for p in parents:
            where = where[p][0] if isinstance(where[p], list) else where[p]
        where[key] = value
    return dynamics_from_config(section)


@pytest.mark.parametrize("changes, error, match", [
    # AttributeError 'str' object has no attribute 'items'
    ({"modes": ""}, KeywordError, r"\[dynamics.modes\]: expected a table of keys"),
    # ValueError from numpy: could not convert string to float
    ({"modes.damping_ratios": ["=", 0.01]}, InputError,
     r"'damping_ratios' must hold numbers .* got \['=', 0.01\]"),
    ({"modes.forcing_shapes": [4.3e16, "", 1.0]}, InputError, r"'forcing_shapes' must hold"),
    # TypeError 'int' object is not iterable
    ({"shocks": 177}, KeywordError, r"\[dynamics\] shocks = 177: give an array of tables"),
    ({"forces": "y"}, KeywordError, r"\[dynamics\] forces = 'y': give an array of tables"),
    # OverflowError: cannot convert float infinity to integer
    ({"archive_step_s": 5e-324}, InputError, r"archive_step_s = 5e-324 s: give a step > 0 "
                                             r"that archives at most 1e\+09 samples"),
])
def test_dynamics_section_values_that_leaked_python_errors(changes, error, match):
    with pytest.raises(error, match=match):
        _dynamics(**changes)


def test_discret_table_too_long_to_update(tmp_path):
    """A DISCRET table of 72001 points ran the update for 150 s (quadratic in the count)."""
    path = tmp_path / "fine.txt"
    theta = np.linspace(0.0, 360.0, 72001)
    path.write_text("# mobile_radius = 4.85e-3\nTHETA JEU\n"
                    + "".join(f"{t:.6f} 5.0e-4\n" for t in theta))
    with pytest.raises(InputError, match=r"72001 points; at most 10001 are accepted .*resample"):
        _update(type="discrete", file=str(path))
