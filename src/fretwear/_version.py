"""fretwear's version, in the lowest layer so that any module may record it (provenance)."""

__version__ = "0.1.0"
