"""``fretwear materials``: print the wear-coefficient database (SPEC §5) as a table or JSON."""

from __future__ import annotations

import json

import click


@click.command("materials")
@click.option("--contact", "contact_type", metavar="TYPE",
              help="Only this contact type (TUBE_BAV, GRAPPE_ALESAGE, ...).")
@click.option("--law", metavar="LAW", help="Only this law (ARCHARD, KWU_EPRI, EDF_MZ).")
@click.option("--database", "databases", multiple=True, metavar="CSV",
              type=click.Path(exists=True, dir_okay=False),
              help="A coefficient CSV of your own that extends/overrides the built-in table "
                   "(repeatable; later files win).")
@click.option("--json", "as_json", is_flag=True,
              help="Print JSON (one record per coefficient, and the material codes) instead.")
def command(contact_type: str | None, law: str | None, databases: tuple[str, ...],
            as_json: bool) -> None:
    """The wear-coefficient database: coefficients per contact type, material pair and law.

    Values are SI: Archard K [Pa⁻¹]; EDF_MZ A [m³/(s·W^b)], b [1], n [s⁻¹], S [m³/s]. An empty
    obstacle cell means the seed gives no obstacle coefficient for that pair.
    """
    from fretwear.database import load_database, materials, summary

    table = load_database(list(databases) or None)
    boxes = summary(table, contact_type=contact_type, law=law)
    used = set(boxes.mobile_material) | set(boxes.obstacle_material)
    codes = materials()
    codes = codes[codes.code.isin(used)]
    if as_json:
        keys = set(zip(boxes.contact_type, boxes.mobile_material, boxes.obstacle_material,
                       boxes.law, strict=True))
        rows = table[[k in keys for k in zip(table.contact_type, table.mobile_material,
                                             table.obstacle_material, table.law, strict=True)]]
        click.echo(json.dumps({"coefficients": rows.to_dict(orient="records"),
                               "materials": codes.to_dict(orient="records")},
                              ensure_ascii=False, indent=1))
        return

    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    console = Console()
    title = "Wear coefficients" + "".join(
        f" · {x}" for x in (contact_type and contact_type.upper(), law and law.upper()) if x)
    grid = Table(title=title, show_lines=False)
    for name, style in (("contact", "bold"), ("mobile", "cyan"), ("obstacle", "cyan"),
                        ("law", ""), ("mobile coefficients", "green"),
                        ("obstacle coefficients", "green"), ("source", "dim")):
        grid.add_column(name, style=style or None, overflow="fold")
    for r in boxes.itertuples():
        source = r.source if r.origin == "built-in" else f"{r.source} [{r.origin}]"
        cells = (r.contact_type, r.mobile_material, r.obstacle_material, r.law, r.mobile or "-",
                 r.obstacle or "-", source)
        grid.add_row(*(escape(str(c)) for c in cells))   # "[bib5]" is not rich markup
    console.print(grid)
    legend = Table(title="Material codes", show_header=True)
    for name in ("code", "name", "AFNOR"):
        legend.add_column(name)
    for r in codes.itertuples():
        legend.add_row(escape(r.code), escape(r.name), escape(r.afnor or "-"))
    if len(codes):
        console.print(legend)
