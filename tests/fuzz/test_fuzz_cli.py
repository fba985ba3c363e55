"""Fuzz the command line's argv (issue 15): every input ends in exit code 0, 1 or 2, never a
traceback.

argv = a subcommand, then tokens drawn from that command's options and from values that are
good (a small history, case, wear table), damaged, missing, directories, or odd (nan, -1, 1e308,
'', text). ``fretwear.cli.main`` runs inside click's CliRunner isolation; an exception escaping
it, a 'Traceback' on stderr, an unexpected exit code or an example over 20 s fails the test.
"""

from __future__ import annotations

import contextlib
import functools
import itertools
import os

import click
from click.testing import CliRunner
from fuzzhelpers import examples, no_hang, small_history, workdir
from hypothesis import given
from hypothesis import strategies as st

from fretwear.cli import cli, main
from fretwear.errors import FretwearError
from fretwear.io import write_history

_COUNTER = itertools.count()


@functools.lru_cache(maxsize=1)
def files(write_case) -> dict[str, str]:
    """The files the argv refer to; ``write_case``: the grappe_case fixture (tests/conftest)."""
    d = workdir() / "cli"
    d.mkdir(exist_ok=True)
    history = write_history(small_history(n=60), d / "h.csv")
    damaged = d / "damaged.csv.gz"
    damaged.write_bytes(b"\x1f\x8b\x08\x00garbage")
    case = write_case(d / "case.toml", history, obstacle=True)
    broken = d / "broken.toml"
    broken.write_text("[law\nname = 'ARCHARD'\n")
    table = d / "wear.csv"
    main(["run", str(case), "-q", "-o", str(table)])
    return {"history": str(history), "damaged": str(damaged), "case": str(case),
            "broken": str(broken), "table": str(table), "dir": str(d),
            "missing": str(d / "missing.csv")}


def _out(suffix: str) -> str:
    return str(workdir() / "cli" / f"out{next(_COUNTER)}{suffix}")


FILES = ["history", "damaged", "case", "broken", "table", "dir", "missing"]
ODD_VALUES = ["nan", "inf", "-1", "0", "1e308", "", "abc", "-", "1,2", "10", "0.5", "mm",
              "length=mm", "fn=x", "=", "time=ms,force=kN", "select=NOEUD=N1"]
OPTIONS = {
    "power": ["--sectors", "--blocks", "--t-start", "--t-end", "--threshold", "--force-threshold",
              "--rest-time", "--format", "--units", "--column", "--read-option", "--chunk-size",
              "--json", "--level"],
    "run": ["-o", "--aster-names", "--aster-format", "--database", "-q", "--wall-thickness",
            "--depth-limit", "--units", "--force"],
    "obstacle": ["--table", "--instant", "--mobile-radius", "--wall-thickness", "--width",
                 "--gap", "--bore-radius", "--plane-gap", "--orientation", "--shape",
                 "--perforation", "--resolution", "--step", "-o", "--format", "-q",
                 "--obstacle-table", "--write-discret", "--discrete", "--discret", "--units"],
    "materials": ["--contact", "--law", "--database", "--json"],
    "iterate": ["-o", "-n", "--no-plot", "-q"],
}
FIRST = {"power": ["history", "damaged", "missing", "dir"], "run": ["case", "broken", "missing"],
         "obstacle": ["case", "broken", "missing", None], "materials": [None],
         "iterate": ["broken", "missing", "dir"]}


@st.composite
def argv(draw):
    command = draw(st.sampled_from(sorted(OPTIONS)))
    out = [command]
    first = draw(st.sampled_from(FIRST[command]))
    if first is not None:
        out.append(f"@{first}")
    for _ in range(draw(st.integers(0, 5))):
        option = draw(st.sampled_from(OPTIONS[command] + ["--bogus", "-x"]))
        out.append(option)
        kind = draw(st.sampled_from(["odd", "file", "out", "none"]))
        if kind == "odd":
            out.append(draw(st.sampled_from(ODD_VALUES)))
        elif kind == "file":
            out.append("@" + draw(st.sampled_from(FILES)))
        elif kind == "out":
            out.append("@out" + draw(st.sampled_from([".csv", ".tab", ".parquet", ".xyz", ""])))
    return out


@contextlib.contextmanager
def _inside(folder):
    """Run in ``folder``: an odd value taken as a relative output path lands there."""
    here = os.getcwd()
    os.chdir(folder)
    try:
        yield
    finally:
        os.chdir(here)


def _resolve(token: str, write_case) -> str:
    """A placeholder ``@name`` -> the file's path (``@out.csv`` -> a fresh output path)."""
    if not token.startswith("@"):
        return token
    if token.startswith("@out"):
        return _out(token[4:])
    return files(write_case)[token[1:]]


@examples(80)
@given(args=argv())
def test_command_line_never_shows_a_traceback(args, grappe_case):
    runner = CliRunner()
    resolved = [_resolve(a, grappe_case) for a in args]
    with runner.isolation() as streams, no_hang(), _inside(workdir()):
        try:
            code = main(resolved)
        except SystemExit as exc:  # click's own exits
            code = exc.code
    stderr = streams[1].getvalue().decode(errors="replace")
    assert "Traceback" not in stderr, stderr
    assert code in (0, 1, 2), (code, stderr)
    if code == 2 and stderr.startswith("fretwear: error:"):
        # main() also turns a bare ValueError into exit 2: the library must raise fretwear
        # errors, so the same argv run without main's net raises one (or a click error)
        with runner.isolation(), no_hang(), _inside(workdir()):
            try:
                cli.main(args=resolved, prog_name="fretwear", standalone_mode=False)
            except (FretwearError, click.ClickException, click.exceptions.Exit,
                    click.exceptions.Abort):
                pass
