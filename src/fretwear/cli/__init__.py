"""The ``fretwear`` command line: thin subcommands that parse, call one library function, write.

Each subcommand lives in its own module ``fretwear.cli.<name>`` exposing a click command called
``command``; they are imported only when used.
"""

from __future__ import annotations

import importlib
import os
import sys

import click

from fretwear import __version__
from fretwear.errors import FretwearError

#: Exit code of an unexpected exception (a bug), told apart from a user error (2).
INTERNAL_ERROR = 3
#: Exit code of an interrupt (Ctrl-C): 128 + SIGINT, as a shell reports a process it stopped.
INTERRUPTED = 130

SUBCOMMANDS: dict[str, str] = {
    "power": "Wear power, block and sector powers and contact statistics of a history.",
    "materials": "The wear-coefficient database as a table.",
    "run": "Run a case file: the service-life wear table.",
    "obstacle": "Update the obstacle's clearance profile from a wear table.",
    "iterate": "Coupled loop dynamics -> wear -> obstacle update -> dynamics.",
    "bundle": "Every contact of a tube bundle from a manifest, on Dask.",
    "simulate": "A bundle's contact histories from its description (flow to wear), on Dask.",
    "calibrate": "Calibrate the wear coefficients on inspected depths; forecast every contact.",
    "report": "Run a case and write one HTML report with its uncertainty.",
    "assess": "The outage decision of a bundle: plugging, next inspection, operating interval.",
}


class LazyGroup(click.Group):
    """A click group importing each subcommand module on demand."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        return list(SUBCOMMANDS)

    def get_command(self, ctx: click.Context, name: str) -> click.Command | None:
        if name not in SUBCOMMANDS:
            return None
        module = importlib.import_module(f"fretwear.cli.{name}")
        return module.command

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        with formatter.section("Commands"):
            formatter.write_dl(list(SUBCOMMANDS.items()))


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="fretwear")
def cli() -> None:
    """fretwear: fretting-wear analysis of impact-sliding contacts (SI units inside)."""


#: Line width of the printed tables when the output is a file or a pipe (rich would wrap them at
#: 80 columns): as wide as their content.
WIDE_COLUMNS = 10_000


def main(argv: list[str] | None = None) -> int:
    """Console-script entry point; returns the exit code.

    When standard output is not a terminal (a file, a pipe) and ``COLUMNS`` is not set, tables
    are printed at their full width instead of being wrapped at 80 columns.
    """
    wide = "COLUMNS" not in os.environ and not sys.stdout.isatty()
    if wide:
        os.environ["COLUMNS"] = str(WIDE_COLUMNS)
    try:
        return _main(argv)
    finally:
        if wide:
            os.environ.pop("COLUMNS", None)


def _main(argv: list[str] | None) -> int:
    try:
        # without standalone mode, click returns the code of a command's ctx.exit(code)
        code = cli.main(args=argv, prog_name="fretwear", standalone_mode=False)
    except click.exceptions.Exit as exc:
        return int(exc.exit_code)
    except click.ClickException as exc:
        exc.show()
        return exc.exit_code
    except click.exceptions.Abort as exc:
        # click turns Ctrl-C (KeyboardInterrupt) into Abort, the interrupt as its cause
        if isinstance(exc.__cause__, KeyboardInterrupt):
            return _interrupted(exc.__cause__)
        click.echo("Aborted.", err=True)
        return 1
    except KeyboardInterrupt as exc:  # outside click's own handling
        return _interrupted(exc)
    except Exception as exc:  # noqa: BLE001 - turn library errors into a clean message
        # fretwear's errors name the culprit and the fix: exit 2. A ValueError of another
        # library escaped the guard layer: a bug of fretwear, exit 3 (issue 29)
        if isinstance(exc, FretwearError | FileNotFoundError):
            click.echo(f"fretwear: error: {exc}", err=True)
            return 2
        if isinstance(exc, MemoryError):
            click.echo("fretwear: error: out of memory; reduce the input (a chunk size, a "
                       "number of sectors, an angular resolution) or use a larger machine",
                       err=True)
            return 2
        if os.environ.get("FRETWEAR_DEBUG"):
            raise
        click.echo(f"fretwear: internal error (a bug of fretwear, please report it with the "
                   f"command): {type(exc).__name__}: {exc}; set FRETWEAR_DEBUG=1 to see where",
                   err=True)
        return INTERNAL_ERROR
    return code if isinstance(code, int) else 0


def _interrupted(exc: KeyboardInterrupt) -> int:
    """One line for an interrupt (the command's own message when it gave one), and its code."""
    click.echo(f"fretwear: {exc}" if str(exc) else "fretwear: interrupted", err=True)
    return INTERRUPTED


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
