"""Figures of fretwear (PNG and SVG). Only this package imports matplotlib (Agg backend).

* :mod:`fretwear.plotting.wear`: service-life wear table (volumes and depths against time,
  sector power and depth on polar plots).
"""
