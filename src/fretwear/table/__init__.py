"""The wear table: its schema, how it is built from a wear case, restarts, and its files.

- :mod:`fretwear.table.schema`: every column's native name, Code_Aster name, unit and meaning
  (:data:`COLUMNS`; the obstacle profile's :data:`PROFILE_COLUMNS`), :func:`to_aster_names`,
  :func:`from_aster_names`, and :data:`FLOAT_FORMAT`, the one format of reals in text files;
- :mod:`fretwear.table.case`: :class:`WearCase`, the validated description of one contact's
  wear computation, with each coefficient's source (:class:`Coefficient`), made of the frozen
  values of :mod:`fretwear.table.case_values` (:class:`Wall`, :class:`PowerWindow`,
  :class:`Restart`); :mod:`fretwear.table.keywords`: :data:`KEYWORDS`, the keywords of a
  wear computation documented once;
- :mod:`fretwear.table.build`: :func:`wear_table_from_case`, the service-life table of a case
  (theory §3, §7), and :func:`wear_table_columns`, its columns without the DataFrame;
  :mod:`fretwear.table.core`: :func:`wear_table`, the same from keywords;
- :mod:`fretwear.table.restart`: the initial state of a restart (ETAT_INIT) and the tube
  replacement (TUBE_NEUF);
- :mod:`fretwear.table.limit`: the depth as a fraction of the wall, the instant of the limit;
- :mod:`fretwear.table.files`: :func:`read_wear_table` and :func:`write_wear_table` (CSV,
  Parquet, Code_Aster text tables), :func:`read_profile_table` and :func:`write_profile_table`
  (the obstacle update's profile), each file with the provenance header of
  :mod:`fretwear.table.provenance` (version, date, law, coefficients and their sources).
"""

from fretwear.table.build import wear_table_columns, wear_table_from_case
from fretwear.table.case import Coefficient, WearCase
from fretwear.table.case_values import PowerWindow, Restart, Wall
from fretwear.table.core import wear_table
from fretwear.table.depth import DepthModel
from fretwear.table.depth_build import (
    carried_case,
    model_from_table,
    models_from_table,
    table_case,
)
from fretwear.table.depth_rows import EarlierRows
from fretwear.table.files import (
    read_profile_table,
    read_wear_table,
    write_profile_table,
    write_wear_table,
)
from fretwear.table.keywords import KEYWORDS
from fretwear.table.limit import DEFAULT_DEPTH_LIMIT
from fretwear.table.replace import replace_tube
from fretwear.table.restart import InitialState, initial_state
from fretwear.table.schema import (
    COLUMNS,
    FLOAT_FORMAT,
    GLOBAL_COLUMNS,
    PROFILE_COLUMNS,
    SECTOR_COLUMNS,
    WALL_COLUMNS,
    WALL_SECTOR_COLUMNS,
    from_aster_names,
    to_aster_names,
)

__all__ = [
    "COLUMNS",
    "DEFAULT_DEPTH_LIMIT",
    "Coefficient",
    "DepthModel",
    "EarlierRows",
    "FLOAT_FORMAT",
    "GLOBAL_COLUMNS",
    "PROFILE_COLUMNS",
    "SECTOR_COLUMNS",
    "WALL_COLUMNS",
    "WALL_SECTOR_COLUMNS",
    "InitialState",
    "KEYWORDS",
    "PowerWindow",
    "Restart",
    "Wall",
    "WearCase",
    "carried_case",
    "from_aster_names",
    "initial_state",
    "model_from_table",
    "models_from_table",
    "read_profile_table",
    "read_wear_table",
    "replace_tube",
    "table_case",
    "to_aster_names",
    "wear_table",
    "wear_table_columns",
    "wear_table_from_case",
    "write_profile_table",
    "write_wear_table",
]
