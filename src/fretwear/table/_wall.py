"""The wall columns of the wear table: depth over the wall, instant of the limit.

Step 5 of :func:`~fretwear.table.wear_table_from_case`: the case's
:class:`~fretwear.table.DepthModel` (:func:`~fretwear.table.depth.case_model`: the law, the
geometry, the volumes at the origin, a restart's earlier rows, a tube replacement) inverted by
:func:`fretwear.table.limit.wall_columns`: the global depth by
:meth:`~fretwear.table.DepthModel.time_to`, each sector's by
:meth:`~fretwear.table.DepthModel.sector_time_to` (the same meaning of the time to a limit).
"""

from __future__ import annotations

import numpy as np

from fretwear.table.limit import wall_columns


# --------------------------------------------------------------------------- 5. the wall
def _wall(case, table, model):
    """The wall columns (:func:`fretwear.table.limit.wall_columns`) of ``table`` (the columns,
    or the frame of a restart): the depth over the wall and the instant of reaching the limit,
    by the case's depth ``model`` (its global depth where the case has a contact type)."""
    sectored = case.sectors is not None
    depths = (np.asarray(table["depth_mobile"], dtype=float),
              np.asarray(table["sector"], dtype=int) if sectored else None,
              np.asarray(table["depth_mobile_sector"], dtype=float) if sectored else None)
    return wall_columns(*depths, wall=case.wall.thickness, depth_limit=case.wall.limit,
                        unit=case.time_unit, stacklevel=5,
                        global_depth=model if case.contact_type is not None else None,
                        sector_depths=model if sectored else None)
