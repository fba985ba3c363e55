"""Figures of docs/geometry_enco.md: broached-hole (TUBE_3_ENCO, TUBE_4_ENCO) and guide-card
notch (GRAPPE_1_ENCO, GRAPPE_2_ENCO) contacts.

Run from the repository root:  .venv/bin/python docs/figures/make_enco_figures.py
Writes docs/figures/enco_isthmus.png, enco_relation.png and grappe_notch.png (atomically).
The curves are computed by fretwear itself; the sketches exaggerate the depths for legibility.
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from fretwear.geometry.enco import Tube3Enco, Tube4Enco  # noqa: E402
from fretwear.geometry.grappe_notch import NOTCH_LAWS, notch_depth_limit  # noqa: E402
from fretwear.io.atomic import atomic_path  # noqa: E402

HERE = Path(__file__).resolve().parent


def _save(fig, name: str) -> Path:
    path = HERE / name
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=130, bbox_inches="tight", format="png")
    plt.close(fig)
    return path


def _lobed_hole(ax, lobes: int, r_land: float, half_opening_deg: float, alpha_deg: float,
                depth_lobe: float) -> None:
    """Outline of a broached hole: land arcs of radius r_land, lobes bounded by two flanks
    leaning by α_i over the lobe and an outer arc."""
    points = []
    for k in range(lobes):
        centre = 2.0 * math.pi * k / lobes
        beta = math.radians(half_opening_deg)
        nxt = 2.0 * math.pi * (k + 1) / lobes
        # land from this lobe's trailing edge to the next lobe's leading edge
        phi = np.linspace(centre + beta, nxt - beta, 60)
        points += list(zip(r_land * np.cos(phi), r_land * np.sin(phi), strict=True))
        # next lobe: leading flank, outer arc, trailing flank
        e1, e2 = nxt - beta, nxt + beta
        a = math.radians(alpha_deg)
        # flank from edge e1 leaning towards the lobe centre (angle increases towards nxt)
        f1 = (r_land * math.cos(e1) + depth_lobe * math.cos(e1 + a),
              r_land * math.sin(e1) + depth_lobe * math.sin(e1 + a))
        f2 = (r_land * math.cos(e2) + depth_lobe * math.cos(e2 - a),
              r_land * math.sin(e2) + depth_lobe * math.sin(e2 - a))
        points.append(f1)
        t1, t2 = math.atan2(f1[1], f1[0]), math.atan2(f2[1], f2[0])
        if t2 < t1:
            t2 += 2.0 * math.pi
        rad = math.hypot(*f1)
        phi = np.linspace(t1, t2, 40)
        points += list(zip(rad * np.cos(phi), rad * np.sin(phi), strict=True))
        points.append(f2)
    xs, ys = zip(*points, strict=True)
    ax.fill(xs + (xs[0],), ys + (ys[0],), color="white", zorder=0)
    ax.plot(xs + (xs[0],), ys + (ys[0],), color="0.3", lw=1.0)


def figure_isthmus() -> Path:
    """Sketch: trefoil hole with the tube on an isthmus edge, and the worn section at the edge."""
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(10.5, 5.0))
    # -- left: trefoil hole, tube pushed towards the edge of a land
    r_o, r_m = 1.0, 0.93
    square = 2.2
    ax0.add_patch(plt.Rectangle((-square, -square), 2 * square, 2 * square, color="0.7",
                                zorder=-1))
    _lobed_hole(ax0, 3, r_o, 28.0, 20.0, 0.45)
    edge = math.radians(120.0 - 28.0)  # leading edge of the lobe at 120°
    offset = r_o - r_m + 0.04
    centre = (offset * math.cos(edge), offset * math.sin(edge))
    ax0.add_patch(plt.Circle(centre, r_m, fill=False, color="tab:blue", lw=1.6))
    ax0.plot(*centre, "+", color="tab:blue")
    ex, ey = r_o * math.cos(edge), r_o * math.sin(edge)
    ax0.plot(ex, ey, "o", color="tab:red", ms=4)
    ax0.annotate("isthmus edge", (ex, ey), (0.9, 1.75), color="tab:red",
                 arrowprops={"arrowstyle": "->", "color": "tab:red"})
    ax0.text(0.0, -0.1, "tube $R_m$", color="tab:blue", ha="center")
    ax0.text(-2.1, -2.1, "plate: lands on the circle $R_o$, three lobes", fontsize=8)
    ax0.set_xlim(-square, square)
    ax0.set_ylim(-square, square)
    ax0.set_aspect("equal")
    ax0.set_axis_off()
    ax0.set_title("TUBE_3_ENCO: tube on an isthmus edge (sketch)")

    # -- right: zoom at the edge, worn section = half lens + flank triangle
    rm, ro, depth, alpha = 1.0, 1.25, 0.1, 50.0
    c = ro - rm + depth
    half = 0.75
    t = np.linspace(-half, half, 3001)
    tube = c + np.sqrt(np.maximum(rm**2 - t**2, 0.0))
    bore = np.sqrt(ro**2 - t**2)
    cot = 1.0 / math.tan(math.radians(alpha))
    flank = ro + t * cot
    lower = np.where(t <= 0.0, bore, np.maximum(bore, flank))
    top = ro + 0.2
    material_top = np.where(t <= 0.0, top, np.where(flank < top, top, np.nan))
    ax1.fill_between(t, lower, material_top, color="0.75", zorder=0, label="plate")
    worn = tube > lower
    ax1.fill_between(t, np.where(worn, lower, np.nan), np.where(worn, tube, np.nan),
                     color="tab:orange", alpha=0.8, label="worn section $S'(D)/2$")
    ax1.plot(t, tube, color="tab:blue", lw=1.5, label="tube, pushed by $D$")
    ax1.plot(t, bore, ":", color="0.3", lw=0.8, label="bore circle $R_o$")
    ft = np.linspace(0.0, 0.2 * math.tan(math.radians(alpha)), 10)
    ax1.plot(ft, ro + ft * cot, color="0.2", lw=1.0)
    ax1.plot([0, 0], [ro, top], "--", color="0.3", lw=0.8)
    ax1.annotate("", (0.0, ro + depth), (0.0, ro),
                 arrowprops={"arrowstyle": "<->", "color": "k", "lw": 0.8})
    ax1.text(-0.02, ro + 0.5 * depth, "$D$", ha="right", va="center")
    ax1.text(0.03, ro + 0.175, r"$\alpha_i$", fontsize=10)
    ax1.text(-0.7, ro + 0.16, "land side: half lens $S(D)/2$", fontsize=8)
    ax1.text(0.2, ro + 0.14, "lobe side (empty) beyond the flank;\n"
             r"worn triangle $\approx \frac{1}{2}D^2\tan\alpha_i$", fontsize=8)
    ax1.set_xlim(-half, half)
    ax1.set_ylim(ro - 0.3, top)
    ax1.set_xlabel("across the contact (depth exaggerated)")
    ax1.set_yticks([])
    ax1.legend(loc="lower center", fontsize=7)
    ax1.set_title("worn section at the edge")
    return _save(fig, "enco_isthmus.png")


def figure_relation() -> Path:
    """V_m(d_m) of TUBE_3_ENCO and TUBE_4_ENCO for a 3/4-inch tube, with and without tilt."""
    dims = {"mobile_radius": 9.525e-3, "obstacle_radius": 9.75e-3, "obstacle_width": 30e-3,
            "isthmus_angle": 30.0}
    fig, ax = plt.subplots(figsize=(7.0, 4.5))
    for cls, style in ((Tube3Enco, "-"), (Tube4Enco, "--")):
        for tilt, color in ((0.0, "tab:blue"), (0.5, "tab:orange"), (2.0, "tab:green")):
            g = cls(**dims, tilt_angle=tilt)
            depth = np.linspace(0.0, g.max_depth, 400)
            volume = g.volume_from_depth(depth)[0]
            ax.plot(depth * 1e3, volume * 1e9, style, color=color,
                    label=f"{cls.contact_type}, θ = {tilt:g}°")
            if tilt:
                reach = dims["obstacle_width"] * math.radians(tilt)
                ax.plot(reach * 1e3, g.volume_from_depth(reach)[0] * 1e9, "o", color=color,
                        ms=4)
    limit = Tube3Enco(**dims).max_depth
    ax.axvline(limit * 1e3, color="0.4", lw=0.8, ls=":")
    ax.text(limit * 1e3, 5, " range limit:\n chord at the\n tube's axis", fontsize=8, va="bottom",
            ha="right")
    ax.set_xlabel("mobile depth $d_m$ [mm] (obstacle not worn)")
    ax.set_ylabel("mobile volume $V_m$ [mm³]")
    ax.set_title("Broached hole, $R_m$ = 9.525 mm, $R_o$ = 9.75 mm, $l$ = 30 mm, "
                 r"$\alpha_i$ = 30° (dots: $d = l\theta$)", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    return _save(fig, "enco_relation.png")


def figure_notch() -> Path:
    """The notch cubics: rising branch used, maximum, falling branch not used."""
    fig, ax = plt.subplots(figsize=(7.0, 4.2))
    d = np.linspace(0.0, 3.6, 400)
    for (name, law), color in zip(NOTCH_LAWS.items(), ("tab:blue", "tab:orange"), strict=True):
        a, b, c = law["coefficients"]
        p = ((a * d + b) * d + c) * d
        d_max = notch_depth_limit(name) * 1e3
        rising = d <= d_max
        ax.plot(d[rising], p[rising], color=color, label=f"{name}: {a:g}d³ + {b:g}d² + {c:g}d")
        ax.plot(d[~rising], p[~rising], ":", color=color)
        p_max = ((a * d_max + b) * d_max + c) * d_max
        ax.plot(d_max, p_max, "o", color=color, ms=4)
        ax.annotate(f"max {p_max:.2f} mm² at {d_max:.4f} mm", (d_max, p_max),
                    (d_max + 0.15, p_max + 3.0), fontsize=7,
                    arrowprops={"arrowstyle": "->", "lw": 0.6})
    ax.set_xlabel("rod depth $d_m$ [mm]")
    ax.set_ylabel("$V_m/l$ [mm²]")
    ax.set_title("Guide-card notch (9.7 mm rod, 10.5 mm card): dotted = beyond the range (NaN)",
                 fontsize=9)
    ax.set_ylim(0, 55)
    ax.set_xlim(0, 4.4)
    ax.legend(fontsize=8, loc="upper left")
    ax.grid(alpha=0.3)
    return _save(fig, "grappe_notch.png")


if __name__ == "__main__":
    for make in (figure_isthmus, figure_relation, figure_notch):
        print(make())
