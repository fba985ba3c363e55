"""Print the demo contact history as Code_Aster would: ``examples/data/shock_N12.tab``.

The file is what the export recipe of ``docs/code_aster.md`` gives for one shock point of a
DYNA_VIBRA computation: an IMPR_TABLE ``FORMAT='TABLEAU'`` print with ``FORMAT_R='E16.9'`` of a
table holding the node (``NOEUD``), the instant (``INST``) and the shock's internal variables
``VINT1`` (FN), ``VINT2``/``VINT3`` (FT1/FT2), ``VINT5``/``VINT6`` (local DY/DZ of node 1),
``VINT10``-``VINT12`` (VN, VT1, VT2) and ``VINT13`` (stick flag). It is written by fretwear from
the first second of ``examples/data/oscillator_gap.csv`` (``make_example_history.py``), not by
Code_Aster: the layout follows Code_Aster's ``Objects/table_py.py`` (``ReprTable``: a ``#``
and dashes header, the title, the column names, one line per row).

Usage::

    python examples/make_aster_shock_table.py        # writes examples/data/shock_N12.tab
"""

from __future__ import annotations

import argparse
from pathlib import Path

import pandas as pd

from fretwear.io import read_history
from fretwear.io.atomic import atomic_write

HERE = Path(__file__).parent
#: Internal variable of a DIS_CHOC shock (Code_Aster) -> fretwear channel (theory §1).
VINT = {"VINT1": "normal_force", "VINT2": "ft1", "VINT3": "ft2", "VINT5": "dy", "VINT6": "dz",
        "VINT10": "vn", "VINT11": "vt1", "VINT12": "vt2", "VINT13": "stick"}


def main(source: Path = HERE / "data" / "oscillator_gap.csv",
         output: Path = HERE / "data" / "shock_N12.tab", duration: float = 1.0) -> Path:
    """Write the first ``duration`` seconds [s] of ``source`` as the IMPR_TABLE print."""
    h = read_history(source)
    h = h.window(float(h.time[0]), float(h.time[0]) + duration)
    frame = pd.DataFrame({"NOEUD": "N12", "INST": h.time,
                          **{k: getattr(h, ch) for k, ch in VINT.items()}})
    lines = ["#", "#" + "-" * 80,
             "#ASTER 16.04.00 CONCEPT TABCHOC CALCULE LE 23/11/2026 A 12:00:00 DE TYPE",
             "#TABLE_SDASTER",
             " ".join(f"{c:<16}" for c in frame.columns).rstrip()]
    for row in frame.itertuples(index=False):
        cells = [f"{row[0]:<16}"] + [f"{float(v):16.9E}" for v in row[1:]]
        lines.append(" ".join(cells))
    with atomic_write(output, "w", encoding="utf-8") as handle:
        handle.write("\n".join(lines) + "\n")
    return output


def cli(argv: list[str] | None = None) -> None:
    """The command line: options, then :func:`main`."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--source", type=Path, default=HERE / "data" / "oscillator_gap.csv",
                        help="the history to print (default: the demo history)")
    parser.add_argument("--output", type=Path, default=HERE / "data" / "shock_N12.tab",
                        help="the table written (default: examples/data/shock_N12.tab)")
    parser.add_argument("--duration", type=float, default=1.0,
                        help="seconds printed from the start of the history (default: 1)")
    args = parser.parse_args(argv)
    print(main(args.source, args.output, args.duration))


if __name__ == "__main__":
    cli()
