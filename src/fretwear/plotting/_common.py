"""What every figure module shares: matplotlib on the Agg backend, atomic PNG + SVG output."""

from __future__ import annotations

from pathlib import Path


def pyplot():
    """matplotlib.pyplot on the non-interactive Agg backend (no display needed)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_figure(fig, directory, stem: str, *, dpi: int = 120,
                formats: tuple[str, ...] = ("png", "svg")) -> list[Path]:
    """Write ``fig`` as ``directory/stem.<fmt>`` for each format, atomically; return the paths."""
    from fretwear.io.atomic import atomic_path

    out = []
    for fmt in formats:
        target = Path(directory) / f"{stem}.{fmt}"
        with atomic_path(target) as tmp:
            fig.savefig(tmp, format=fmt, dpi=dpi, bbox_inches="tight")
        out.append(target)
    return out
