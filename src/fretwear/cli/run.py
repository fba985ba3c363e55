"""``fretwear run CASE.toml``: the service-life wear table of a case file."""

from __future__ import annotations

from pathlib import Path

import click
import numpy as np

from fretwear.case import keys_help

_HELP = f"""Run a TOML case file: wear power, wear law, depths, service-life table.

Writes the table to OUTPUT (.csv, .parquet, or .tab/.resu for a Code_Aster IMPR_TABLE file
that LIRE_TABLE reads) and prints a summary (power, block spread, sector powers, volumes and
depths at the last instant, warnings). Units: SI (m, m³, W, s; angles in degrees).

\b
Case-file keys (units in the names; docs/case_files.md):
{keys_help()}
"""

_ASTER_SUFFIXES = (".tab", ".resu", ".txt")


def write_table(table, path: Path, *, aster_names: bool = False, title: str | None = None
                ) -> Path:
    """Write a wear table atomically; the suffix chooses CSV, Parquet or a Code_Aster table."""
    from fretwear.errors import InputError
    from fretwear.io.atomic import atomic_path
    from fretwear.operator import to_aster_names

    suffix = path.suffix.lower()
    if suffix in _ASTER_SUFFIXES:
        from fretwear.io.aster import write_aster_table

        return write_aster_table(to_aster_names(table), path, format="TABLEAU",
                                 title=title or "POST_USURE fretwear", float_format="%.10E")
    frame = to_aster_names(table) if aster_names else table
    frame = frame.copy()
    frame.attrs = {}
    if suffix == ".csv":
        with atomic_path(path) as tmp:
            frame.to_csv(tmp, index=False, float_format="%.12g")
    elif suffix in (".parquet", ".pq"):
        with atomic_path(path) as tmp:
            frame.to_parquet(tmp, index=False)
    else:
        raise InputError(f"output {str(path)!r}: unknown suffix {suffix!r}; use .csv, .parquet, "
                         f"or {', '.join(_ASTER_SUFFIXES)} for a Code_Aster table")
    return path


def _summary(result, console) -> None:
    from rich.table import Table

    table = result.table
    attrs = table.attrs
    title = attrs.get("title") or "fretwear run"
    console.rule(f"[bold]{title}")
    power = result.power
    unit = attrs.get("time_unit") or f"{attrs.get('time_scale')} s"
    console.print(f"contact [bold]{attrs.get('contact_type')}[/], law [bold]{attrs.get('law')}"
                  f"[/], time unit = {unit}")
    console.print(f"wear power P = [bold]{result.total_power:.6g} W[/]")
    intensity = (attrs.get("coefficients_mobile") or {}).get("intensity")
    if intensity is not None:
        console.print(f"KWU-EPRI wear-intensity factor w = {float(intensity):.4g}")
    blocks = getattr(power, "blocks", None)
    if blocks is not None and len(blocks) > 1:
        console.print(f"block powers [W]: {', '.join(f'{b:.4g}' for b in blocks)}; spread "
                      f"(max-min)/mean = {float(power.spread):.3g}")
    last = table[table["instant"] == table["instant"].iloc[-1]]
    if "sector" in table.columns and table["sector"].notna().any():
        st = Table(title=f"sectors at instant {last['instant'].iloc[0]:g} "
                         "(P in W, V in mm³, d in mm)")
        for col in ("sector", "angles (deg)", "P", "V tube", "V obst", "d tube", "d obst"):
            st.add_column(col, justify="right")
        for _, row in last.iterrows():
            st.add_row(f"{int(row['sector'])}", f"{row['angle_start']:g}..{row['angle_end']:g}",
                       f"{row['sector_power']:.4g}",
                       f"{row['volume_mobile_cumulated'] * 1e9:.4g}",
                       f"{row['volume_obstacle_cumulated'] * 1e9:.4g}",
                       f"{row['depth_mobile_sector'] * 1e3:.4g}",
                       f"{row['depth_obstacle_sector'] * 1e3:.4g}")
        console.print(st)
    row = last.iloc[0]
    console.print(
        f"at instant {row['instant']:g}: V tube = {row['volume_mobile'] * 1e9:.4g} mm³, "
        f"V obstacle = {row['volume_obstacle'] * 1e9:.4g} mm³, depth tube = "
        f"{row['depth_mobile'] * 1e3:.4g} mm, depth obstacle = "
        f"{row['depth_obstacle'] * 1e3:.4g} mm")
    glob = table.drop_duplicates("instant")[["instant", "volume_mobile", "depth_mobile"]]
    gt = Table(title="service life (tube)")
    for col in ("instant", "V tube (mm³)", "depth tube (mm)"):
        gt.add_column(col, justify="right")
    for _, r in glob.iterrows():
        depth = r["depth_mobile"]
        gt.add_row(f"{r['instant']:g}", f"{r['volume_mobile'] * 1e9:.4g}",
                   "NaN (out of range)" if np.isnan(depth) else f"{depth * 1e3:.4g}")
    console.print(gt)
    if result.warnings:
        console.print("[yellow]warnings:[/]")
        for w in result.warnings:
            console.print(f"  - {w}", markup=False, highlight=False, style="yellow")


@click.command(help=_HELP, context_settings={"max_content_width": 100})
@click.argument("case_file", type=click.Path(exists=True, dir_okay=False, path_type=Path))
@click.option("-o", "--output", type=click.Path(dir_okay=False, path_type=Path),
              help="Write the table here: .csv, .parquet, or .tab/.resu (Code_Aster table).")
@click.option("--plot", "plot_dir", type=click.Path(file_okay=False, path_type=Path),
              help="Write PNG and SVG figures into this directory.")
@click.option("--aster-names", is_flag=True,
              help="Code_Aster column names (INST, V_USUR_TUBE, ...) in CSV/Parquet output.")
@click.option("-q", "--quiet", is_flag=True, help="No summary on the terminal.")
def command(case_file: Path, output: Path | None, plot_dir: Path | None, aster_names: bool,
            quiet: bool) -> None:
    from rich.console import Console
    from rich.progress import (
        BarColumn,
        Progress,
        SpinnerColumn,
        TaskProgressColumn,
        TextColumn,
        TimeElapsedColumn,
    )

    from fretwear.case import run_case

    console = Console(stderr=False, quiet=quiet)
    columns = (SpinnerColumn(), TextColumn("{task.description}"), BarColumn(),
               TaskProgressColumn(), TimeElapsedColumn())
    with Progress(*columns, console=Console(stderr=True, quiet=quiet), transient=True) as bar:
        task = bar.add_task("reading the case", total=None)

        def step(description: str, done: int | None = None, total: int | None = None) -> None:
            bar.update(task, description=description, completed=done or 0, total=total)

        result = run_case(case_file, progress=step)
    _summary(result, console)
    if output is not None:
        written = write_table(result.table, output, aster_names=aster_names,
                              title=result.table.attrs.get("title"))
        console.print(f"table written to [bold]{written}[/]")
    if plot_dir is not None:
        from fretwear.plotting.wear import plot_wear_table

        files = plot_wear_table(result.table, plot_dir)
        console.print(f"figures written to [bold]{plot_dir}[/]: "
                      + ", ".join(f.name for f in files))
