"""Figures of fretwear (PNG and SVG). Only this package imports matplotlib (Agg backend).

Computation modules return data; these modules only plot it:

* :mod:`fretwear.plotting.wear`: service-life wear table (volumes and depths against time,
  sector power and depth on polar plots).
* :mod:`fretwear.plotting.obstacle`: obstacle update (new and worn clearance figure, depth
  profiles of mobile and obstacle).
* :mod:`fretwear.plotting.dynamics`: built-in dynamics and the coupled loop (time histories,
  orbit in the clearance figure, depth per cycle).
"""
