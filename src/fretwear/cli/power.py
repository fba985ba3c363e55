"""``fretwear power HISTORY``: wear power, block and sector powers, contact statistics.

Thin: parse the options, call :func:`fretwear.power.wear_power` (streaming the file chunk by
chunk), print a table or JSON. Library errors are reported by the ``fretwear`` entry point.
"""

from __future__ import annotations

import json
import math
import warnings
from pathlib import Path

import click
from rich.console import Console
from rich.table import Table

from fretwear.cli._units import pairs, parse_units, units_line, units_option
from fretwear.errors import ConfidenceWarning
from fretwear.history import CHANNELS, DEFAULT_CHUNK_SIZE
from fretwear.io import FORMATS, units_read
from fretwear.power import wear_power
from fretwear.power.statistics import STATISTICS_UNITS


def _parse_sectors(value: str | None):
    """``"10"`` -> 10 equal sectors; ``"-180,0,180"`` -> edges [deg]."""
    if value is None:
        return None
    text = value.strip()
    try:
        if "," not in text:
            return int(text)
        return [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise click.BadParameter(
            f"{value!r}: give a number of sectors (e.g. 10) or comma-separated edges in degrees "
            "from -180 to 180 (e.g. -180,-90,0,90,180)", param_hint="--sectors") from None


def _option_value(text: str):
    """A reader option from the command line: integer, true/false, or text (``\\t`` is a tab)."""
    if text.lower() in ("true", "false"):
        return text.lower() == "true"
    try:
        return int(text)
    except ValueError:
        return text.replace("\\t", "\t")


def _history_argument(values: tuple[str, ...]):
    """One file, or a set of IMPR_FONCTION files given as FILE... or CHANNEL=FILE..."""
    keyed: dict[str, str] = {}
    plain: list[str] = []
    for value in values:
        key, sep, path = value.partition("=")
        if sep and key and not Path(value).exists():
            keyed[key] = path
        else:
            plain.append(value)
    for path in [*keyed.values(), *plain]:
        if not Path(path).is_file():
            what = "is a directory, not a file" if Path(path).is_dir() else "does not exist"
            raise click.BadParameter(f"{path!r} {what}", param_hint="HISTORY")
    if keyed and plain:
        raise click.BadParameter(
            f"mix of CHANNEL=FILE {list(keyed)} and plain files {plain}: give every function "
            "file as CHANNEL=FILE, or none", param_hint="HISTORY")
    if keyed:
        return keyed
    return plain[0] if len(plain) == 1 else plain


def _fmt(value, unit: str = "") -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    if isinstance(value, int):
        return f"{value}"
    return f"{value:.6g}" + (f" {unit}" if unit and unit != "1" else "")


def _intervals(result, level: float):
    """(interval of the total, intervals of the sectors) with >= 2 blocks, else (None, [])."""
    if len(result.blocks) < 2:
        return None, []
    return result.confidence_interval(level), result.sector_confidence_intervals(level)


def _print_table(result, caught: list[str], interval=None, sector_intervals=()) -> None:
    console = Console()
    head = Table(title=f"Wear power of {result.name or 'history'}", show_header=False)
    head.add_column("quantity")
    head.add_column("value", justify="right")
    # + 0.0: a window starting at -0.0 printed "[-0, ...]"
    head.add_row("window", f"[{result.t_start + 0.0:.6g}, {result.t_end + 0.0:.6g}] s")
    head.add_row("duration T", _fmt(result.duration, "s"))
    head.add_row("wear power P", _fmt(result.total, "W"))
    if interval is not None:
        head.add_row(f"confidence ({interval.count} blocks, batch means)", str(interval))
    head.add_row("block spread (max-min)/mean", f"{result.spread:.2%}")
    console.print(head)
    blocks = Table(title="Blocks")
    for col in ("block", "start [s]", "end [s]", "power [W]", "P_b / P"):
        blocks.add_column(col, justify="right")
    for k, p in enumerate(result.blocks):
        share = p / result.total if result.total > 0 else math.nan
        blocks.add_row(str(k + 1), _fmt(result.block_edges[k]), _fmt(result.block_edges[k + 1]),
                       _fmt(p), _fmt(share))
    console.print(blocks)
    if result.sectors is not None:
        sectors = Table(title="Angular sectors")
        names = ("sector", "from [deg]", "to [deg]", "power [W]", "share")
        if sector_intervals:
            names += (f"± [W] ({100 * sector_intervals[0].level:g} %)",)
        for col in names:
            sectors.add_column(col, justify="right")
        for j, p in enumerate(result.sectors):
            share = f"{p / result.total:.1%}" if result.total > 0 else "-"
            extra = (f"{sector_intervals[j].half_width:.2g}",) if sector_intervals else ()
            sectors.add_row(str(j + 1), _fmt(result.sector_edges[j]),
                            _fmt(result.sector_edges[j + 1]), _fmt(p), share, *extra)
        console.print(sectors)
    stats = Table(title="Contact statistics")
    stats.add_column("statistic")
    stats.add_column("value", justify="right")
    s = result.statistics
    for name, unit in STATISTICS_UNITS.items():
        if name.startswith("block_"):
            continue
        stats.add_row(name.replace("_", " "), _fmt(getattr(s, name), unit))
    console.print(stats)
    notes = [] if interval is None else list(interval.warnings)
    for message in [*caught, *notes]:
        console.print(f"[yellow]warning:[/yellow] {message}", highlight=False)


@click.command(name="power")
@click.argument("history", nargs=-1, required=True, metavar="HISTORY...")
@click.option("--sectors", "sectors", metavar="N|e1,e2,...",
              help="Number of equal angular sectors, or their edges in degrees (-180 ... 180).")
@click.option("--blocks", type=click.IntRange(min=1), default=1, show_default=True,
              help="Number of equal blocks of the window (stationarity check).")
@click.option("--t-start", type=float, default=None, help="Window start [s] (default: first).")
@click.option("--t-end", type=float, default=None, help="Window end [s] (default: last).")
@click.option("--threshold", "--stationarity-threshold", "threshold", type=float, default=0.1,
              show_default=True,
              help="Stationarity threshold on the relative spread (max-min)/mean of the block "
                   "powers [-]; above it a warning is printed.")
@click.option("--force-threshold", type=float, default=0.0, show_default=True,
              help="Contact / impact force threshold [N] of the statistics.")
@click.option("--rest-time", type=float, default=0.0, show_default=True,
              help="Minimum rest [s] below the force threshold between two impacts.")
@click.option("--format", "format_", default=None,
              help=f"File format ({', '.join(FORMATS)}); default: guessed from the content.")
@units_option
@click.option("--column", "columns", multiple=True, metavar="COLUMN=CHANNEL",
              help=f"Map a column to a channel ({', '.join(CHANNELS)}), or COLUMN=none to "
                   "ignore it; columns of a file without header "
                   "are named 0, 1, ... Repeatable.")
@click.option("--read-option", "read_options", multiple=True, metavar="KEY=VALUE",
              help="Option of the format's reader: csv delimiter/decimal/comment/header/"
                   "encoding, hdf5 group, aster index/title (a file holding several tables) "
                   "and select=NOEUD=N12 (the rows of one shock point). "
                   "Repeatable.")
@click.option("--chunk-size", type=click.IntRange(min=2), default=DEFAULT_CHUNK_SIZE,
              show_default=True,
              help="Samples read per chunk (memory bound).")
@click.option("--level", type=click.FloatRange(0.0, 1.0, min_open=True, max_open=True),
              default=0.95, show_default=True,
              help="Confidence level of the interval of the power (batch means over the "
                   "blocks; needs --blocks >= 2, ideally >= 10).")
@click.option("--json", "as_json", is_flag=True, help="Print JSON (SI units) instead of tables.")
def command(history, sectors, blocks, t_start, t_end, threshold, force_threshold, rest_time,
            format_, units, columns, read_options, chunk_size, level, as_json):
    """Wear power P = (1/T)∫Fn·|Vt|dt of HISTORY, per block and per sector, with statistics.

    HISTORY is one file (CSV, Parquet, HDF5, NetCDF, NPZ, Code_Aster IMPR_TABLE; the format is
    recognised from the content), streamed chunk by chunk, or a set of Code_Aster IMPR_FONCTION
    TABLEAU files, one per channel: FILE... (channels from the value columns' names) or
    CHANNEL=FILE... (e.g. fn=fn.txt vt1=vt1.txt vt2=vt2.txt). Output: the power [W], the block
    and sector powers [W] and the contact statistics (SI units); with --blocks >= 2 the
    confidence interval of the power, P = 0.184 ± 0.012 W (95 %), by batch means.
    """
    source = _history_argument(history)
    options = dict((k, _option_value(v)) for k, v in pairs(
        read_options, "--read-option", "KEY=VALUE (e.g. group=/shock/N12)", split=False).items())
    if format_ is not None:
        options["format"] = format_
    if units:
        options["units"] = parse_units(units)
    if columns:
        options["columns"] = {
            k: (None if v.lower() in ("none", "") else v)
            for k, v in pairs(columns, "--column", "COLUMN=CHANNEL (e.g. FN_N12=fn)").items()}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = wear_power(source, t_start=t_start, t_end=t_end, blocks=blocks,
                            sectors=_parse_sectors(sectors), stationarity_threshold=threshold,
                            force_threshold=force_threshold, minimum_rest_time=rest_time,
                            chunk_size=chunk_size, **options)
    messages = [str(w.message) for w in caught]
    read_in = units_read(source, **options)
    with warnings.catch_warnings():  # their notes travel with the intervals
        warnings.simplefilter("ignore", ConfidenceWarning)
        interval, sector_intervals = _intervals(result, level)
    if as_json:
        payload = result.to_dict()
        payload["confidence_interval"] = None if interval is None else interval.to_dict()
        payload["sector_confidence_intervals"] = [iv.to_dict() for iv in sector_intervals]
        payload["warnings"] = messages
        payload["units_read"] = read_in
        payload["units"] = {"total": "W", "blocks": "W", "sectors": "W", "block_edges": "s",
                            "sector_edges": "deg", "t_start": "s", "t_end": "s",
                            "duration": "s", "spread": "1", "statistics": STATISTICS_UNITS}
        click.echo(json.dumps(payload, indent=2))
    else:
        _print_table(result, messages, interval, sector_intervals)
        click.echo(units_line(read_in))
