"""``fretwear power HISTORY``: wear power, block and sector powers, contact statistics.

Thin: parse the options, call :func:`fretwear.power.wear_power` (streaming the file chunk by
chunk), print a table or JSON. Library errors are reported by the ``fretwear`` entry point.
"""

from __future__ import annotations

import json
import math
import warnings

import click

from fretwear.statistics import STATISTICS_UNITS


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


def _fmt(value, unit: str = "") -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    if isinstance(value, int):
        return f"{value}"
    return f"{value:.6g}" + (f" {unit}" if unit and unit != "1" else "")


def _print_table(result, caught: list[str]) -> None:
    from rich.console import Console
    from rich.table import Table

    console = Console()
    head = Table(title=f"Wear power of {result.name or 'history'}", show_header=False)
    head.add_column("quantity")
    head.add_column("value", justify="right")
    head.add_row("window", f"[{result.t_start:.6g}, {result.t_end:.6g}] s")
    head.add_row("duration T", _fmt(result.duration, "s"))
    head.add_row("wear power P", _fmt(result.total, "W"))
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
        for col in ("sector", "from [deg]", "to [deg]", "power [W]", "share"):
            sectors.add_column(col, justify="right")
        for j, p in enumerate(result.sectors):
            share = f"{p / result.total:.1%}" if result.total > 0 else "-"
            sectors.add_row(str(j + 1), _fmt(result.sector_edges[j]),
                            _fmt(result.sector_edges[j + 1]), _fmt(p), share)
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
    for message in caught:
        console.print(f"[yellow]warning:[/yellow] {message}", highlight=False)


@click.command(name="power")
@click.argument("history", type=click.Path(exists=True, dir_okay=True))
@click.option("--sectors", "sectors", metavar="N|e1,e2,...",
              help="Number of equal angular sectors, or their edges in degrees (-180 ... 180).")
@click.option("--blocks", type=click.IntRange(min=1), default=1, show_default=True,
              help="Number of equal blocks of the window (stationarity check).")
@click.option("--t-start", type=float, default=None, help="Window start [s] (default: first).")
@click.option("--t-end", type=float, default=None, help="Window end [s] (default: last).")
@click.option("--threshold", type=float, default=0.1, show_default=True,
              help="Stationarity threshold on the relative spread of the block powers.")
@click.option("--force-threshold", type=float, default=0.0, show_default=True,
              help="Contact / impact force threshold [N] of the statistics.")
@click.option("--rest-time", type=float, default=0.0, show_default=True,
              help="Minimum rest [s] below the force threshold between two impacts.")
@click.option("--format", "format_", default=None,
              help="File format (csv, parquet, hdf5, netcdf, npz, aster ...); default: guessed.")
@click.option("--chunk-size", type=click.IntRange(min=2), default=1_000_000, show_default=True,
              help="Samples read per chunk (memory bound).")
@click.option("--json", "as_json", is_flag=True, help="Print JSON (SI units) instead of tables.")
def command(history, sectors, blocks, t_start, t_end, threshold, force_threshold, rest_time,
            format_, chunk_size, as_json):
    """Wear power P = (1/T)∫Fn·|Vt|dt of HISTORY, per block and per sector, with statistics."""
    from fretwear.power import wear_power

    options = {} if format_ is None else {"format": format_}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = wear_power(history, t_start=t_start, t_end=t_end, blocks=blocks,
                            sectors=_parse_sectors(sectors), stationarity_threshold=threshold,
                            force_threshold=force_threshold, minimum_rest_time=rest_time,
                            chunk_size=chunk_size, **options)
    messages = [str(w.message) for w in caught]
    if as_json:
        payload = result.to_dict()
        payload["warnings"] = messages
        payload["units"] = {"total": "W", "blocks": "W", "sectors": "W", "block_edges": "s",
                            "sector_edges": "deg", "t_start": "s", "t_end": "s",
                            "duration": "s", "spread": "1", "statistics": STATISTICS_UNITS}
        click.echo(json.dumps(payload, indent=2))
    else:
        _print_table(result, messages)
