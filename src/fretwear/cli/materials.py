"""``fretwear materials``: print the wear-coefficient database (theory §5) as a table or JSON."""

from __future__ import annotations

import json
import re

import click
from rich.console import Console
from rich.markup import escape
from rich.table import Table

from fretwear.database import REFERENCES, load_database, materials, summary
from fretwear.geometry import CONTACT_TYPES
from fretwear.laws import WEAR_LAWS


def _short_source(source: str, origin: str) -> str:
    """The reference tags of a built-in row (``[bib5] [bib6]``), the full source of a user row."""
    if origin != "built-in":
        return f"{source} [{origin}]"
    refs = re.findall(r"\[bib\d+\]", source)
    return " ".join(dict.fromkeys(refs)) or source


def _coefficients_help() -> str:
    """Each law's user coefficients as symbol [SI unit], from the law registry."""
    return "; ".join(
        f"{law.name} " + ", ".join(f"{law.symbols.get(p, p)} [{law.units[p]}]"
                                   for p in law.parameters if p in law.aster_keywords)
        for law in WEAR_LAWS.values())


_HELP = f"""The wear-coefficient database: coefficients per contact type, material pair and law.

One row per (contact type, mobile material, obstacle material, law). Values are SI:
{_coefficients_help()}. "-" in the obstacle column is an empty box of the reference tables (no
obstacle coefficient). The built-in values are the coefficient tables of Code_Aster's POST_USURE
reference manual (R7.20.01 §3); the material codes used are listed after the table.
"""


@click.command("materials", help=_HELP)
@click.option("--contact", "contact_type", metavar="TYPE",
              help=f"Only this contact type ({', '.join(CONTACT_TYPES)}); any case.")
@click.option("--law", metavar="LAW", help=f"Only this law ({', '.join(WEAR_LAWS)}); any case.")
@click.option("--database", "databases", multiple=True, metavar="CSV",
              type=click.Path(exists=True, dir_okay=False),
              help="A coefficient CSV of your own that extends/overrides the built-in table "
                   "(repeatable; later files win; format in docs/laws.md).")
@click.option("--json", "as_json", is_flag=True,
              help="Print JSON (one record per coefficient, SI values, with source and origin, "
                   "and the material codes) instead.")
def command(contact_type: str | None, law: str | None, databases: tuple[str, ...],
            as_json: bool) -> None:
    """``fretwear materials``: the database as a table or JSON (help text: :data:`_HELP`)."""
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
    console = Console()
    ct = contact_type.strip().upper() if contact_type else None
    lw = law.strip().upper() if law else None
    if boxes.empty:
        scope = table if ct is None else table[table.contact_type == ct]
        boxes_per_law = scope.drop_duplicates(
            ["contact_type", "mobile_material", "obstacle_material", "law"]).law.value_counts()
        have = ", ".join(f"{name} ({n} material pairs)" for name, n in boxes_per_law.items())
        wear_law = WEAR_LAWS.get(lw)
        given = [] if wear_law is None or (table.law == lw).any() else [
            f"{p} ({wear_law.aster_keywords[p]})" for p in wear_law.required
            if p in wear_law.aster_keywords]
        console.print(escape(
            f"No {lw or ''} coefficients{f' for {ct}' if ct else ''} in the database"
            + (f"; {ct or 'it'} has: {have}." if have else ".")
            + (f" The database has no {lw} values at all: give {', '.join(given)} "
               "explicitly." if given else "")
            + " Add your own with --database your.csv."), highlight=False)
        return
    title = "Wear coefficients" + "".join(f" · {x}" for x in (ct, lw) if x)
    empty = (boxes.obstacle == "").any()
    grid = Table(title=title,
                 caption="- : no obstacle coefficient (an empty box)" if empty else None)
    columns = [("contact", "bold", "contact_type")] if ct is None else []
    columns += [("mobile", "cyan", "mobile_material"), ("obstacle", "cyan", "obstacle_material")]
    columns += [("law", None, "law")] if lw is None else []
    columns += [("mobile coefficients", "green", "mobile"),
                ("obstacle coefficients", "green", "obstacle"), ("source", "dim", "source")]
    for name, style, _ in columns:
        grid.add_column(name, style=style, overflow="fold")
    for r in boxes.to_dict(orient="records"):
        r = {**r, "source": _short_source(r["source"], r["origin"]),
             "mobile": r["mobile"].replace("  ", "\n") or "-",     # one parameter per line
             "obstacle": r["obstacle"].replace("  ", "\n") or "-"}
        grid.add_row(*(escape(str(r[key])) for _, _, key in columns))   # "[bib5]" is not markup
    console.print(grid)
    notes = [f"{ref} {text}" for ref, text in REFERENCES.items()
             if any(ref in s for s in boxes.source[boxes.origin == "built-in"])]
    if (boxes.origin == "built-in").any():
        notes.insert(0, "Built-in values: the coefficient tables of Code_Aster's POST_USURE "
                        "reference manual (R7.20.01 §3), verbatim; [bibN] is its bibliography "
                        "number.")
    if {"GRAPPE_1_ENCO", "GRAPPE_2_ENCO"} & set(boxes.contact_type[boxes.origin == "built-in"]):
        notes.append("GRAPPE_1_ENCO and GRAPPE_2_ENCO share one table in the reference.")
    for note in notes:
        console.print(escape(note), style="dim", highlight=False)
    legend = Table(title="Material codes")
    for name in ("code", "name", "AFNOR"):
        legend.add_column(name)
    for r in codes.itertuples():
        legend.add_row(escape(r.code), escape(r.name), escape(r.afnor or "-"))
    for code in sorted(used - set(codes.code)):
        legend.add_row(escape(code), "(not a built-in code: from your file)", "-")
    console.print(legend)
