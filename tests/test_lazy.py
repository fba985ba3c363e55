"""fretwear._lazy: pandas is imported at its first use, so that streaming a Parquet file with
``fretwear power`` never imports it (0.2 s of start-up), and every use of ``pd`` behaves as with
``import pandas as pd``. Checked in fresh interpreters (sys.modules is the oracle)."""

from __future__ import annotations

import subprocess
import sys

import numpy as np

from fretwear.history import ContactHistory
from fretwear.io import write_history

CHECK = """
import sys
{body}
print("pandas" in sys.modules)
"""


def _pandas_imported(body: str) -> bool:
    out = subprocess.run([sys.executable, "-c", CHECK.format(body=body)], capture_output=True,
                         text=True, check=True)
    return out.stdout.strip().splitlines()[-1] == "True"


def test_power_of_a_parquet_file_never_imports_pandas(tmp_path):
    t = np.arange(2000) * 1e-4
    h = ContactHistory(time=t, normal_force=np.maximum(0, 10 * np.sin(300 * t)),
                       vt1=0.01 * np.cos(300 * t), vt2=0 * t, dy=np.cos(t), dz=np.sin(t))
    path = write_history(h.replace(dy=1e-4 * h.dy, dz=1e-4 * h.dz), tmp_path / "h.parquet")
    assert not _pandas_imported("import fretwear.cli.power")
    assert not _pandas_imported(
        "from fretwear.cli import main\n"
        f"assert main(['power', {str(path)!r}, '--blocks', '4', '--sectors', '8']) == 0")
    # a table is pandas' job: the first use imports it
    assert _pandas_imported("from fretwear.table import wear_table\n"
                            "wear_table(0.01, contact_type='TUBE_ALESAGE', instants=[1.0], "
                            "dimensions={'mobile_radius': 0.01, 'obstacle_width': 0.02}, "
                            "coefficients={'COEF_USURE': 1e-14})")


def test_the_stand_in_behaves_as_pandas():
    import pandas

    from fretwear._lazy import LazyModule

    pd = LazyModule("pandas")
    frame = pd.DataFrame({"a": [1.0, 2.0]})
    assert isinstance(frame, pandas.DataFrame) and pd.DataFrame is pandas.DataFrame
    assert pd.concat([frame, frame], ignore_index=True)["a"].tolist() == [1.0, 2.0, 1.0, 2.0]
    assert "DataFrame" in vars(pd)  # cached after the first use


def test_geometry_imports_numba_only_when_a_kernel_is_asked():
    """fretwear._lazy.compiled_when_used: the geometry's kernels compile (and numba loads) at
    the first solve, not at import."""
    assert "False" == subprocess.run(
        [sys.executable, "-c", "import sys, fretwear.geometry; print('numba' in sys.modules)"],
        capture_output=True, text=True, check=True).stdout.strip()
    assert "True" == subprocess.run(
        [sys.executable, "-c", "import sys\nfrom fretwear.geometry._shapes import _lens_kernels\n"
         "_lens_kernels()\nprint('numba' in sys.modules)"],
        capture_output=True, text=True, check=True).stdout.strip()


def test_power_command_imports_neither_the_wear_table_nor_scipy_stats():
    """``fretwear power FILE`` never builds a table: importing its command leaves out
    fretwear.table (scipy.interpolate, scipy.optimize: about 1 s of start-up, issue 28) and
    scipy.stats (0.6-0.9 s); a case given to another command still loads (cli._units)."""
    out = subprocess.run(
        [sys.executable, "-c", "import sys, fretwear.cli.power\n"
         "print(sorted(m for m in ('fretwear.table', 'fretwear.workflows.case_files',\n"
         "                         'scipy.stats', 'scipy.interpolate') if m in sys.modules))"],
        capture_output=True, text=True, check=True).stdout.strip()
    assert out == "[]"
