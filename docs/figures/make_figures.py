"""Draw every figure of docs/geometry.md: one per contact type, plus the frustum rule.

Run from the repository root: ``.venv/bin/python docs/figures/make_figures.py`` (all figures) or
``... make_figures.py TUBE_BAV frustum`` (some). Every curve is computed by fretwear itself (no
hand-drawn data); the sections are to scale except where the depth or the clearance is
exaggerated, which each title says. PNGs are written atomically next to this script.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

from fretwear.geometry import contact_geometry
from fretwear.geometry._shapes import lens_area, lens_half_chord, sagitta
from fretwear.geometry.enco import Tube3Enco, Tube4Enco
from fretwear.geometry.grappe_notch import NOTCH_LAWS, notch_depth_limit
from fretwear.geometry.tube_alesage import tilted_lunule_volume
from fretwear.plotting._common import pyplot, save_figure

plt = pyplot()
HERE = Path(__file__).resolve().parent
MM = 1e3
MM3 = 1e9


def _save(fig, name: str) -> Path:
    (target,) = save_figure(fig, HERE, Path(name).stem, formats=("png",))
    plt.close(fig)
    return target


def _circle(ax, cx, cy, r, **style):
    phi = np.linspace(0, 2 * np.pi, 721)
    ax.plot(cx + r * np.cos(phi), cy + r * np.sin(phi), **style)


def figure_tube_bav() -> Path:
    """Section of a tube worn flat by a bar, and depth against volume (straight and tilted)."""
    radius, width = 9.525e-3, 12.7e-3
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
    depth = 2.0e-3  # exaggerated
    _circle(ax1, 0, 0, radius * MM, color="k")
    x = math.sqrt(2 * radius * depth - depth**2)
    t = np.linspace(-x, x, 200)
    ax1.fill_between(t * MM, (radius - depth) * MM, np.sqrt(radius**2 - t**2) * MM,
                     color="tab:red", alpha=0.5, label="worn (exact segment)")
    ax1.plot(t * MM, (radius - depth + (x**2 - t**2) / (2 * radius)) * MM, "b--",
             label="parabolic section used")
    ax1.axhspan((radius - depth) * MM, (radius - depth + 4e-3) * MM, color="0.85",
                label="anti-vibration bar", zorder=0)
    ax1.annotate("", xy=(0, radius * MM), xytext=(0, (radius - depth) * MM),
                 arrowprops={"arrowstyle": "<->"})
    ax1.text(0.3, (radius - depth / 2) * MM, "D", va="center")
    ax1.set_aspect("equal")
    ax1.set_xlim(-11, 11)
    ax1.set_ylim(-11, 13)
    ax1.set_title("TUBE_BAV section (depth exaggerated)")
    ax1.set_xlabel("mm")
    ax1.legend(loc="lower center", fontsize=8)
    volume = np.geomspace(1e-12, 1e-7, 200)
    for tilt in (0.0, 0.5, 2.0):
        g = contact_geometry("TUBE_BAV", mobile_radius=radius, obstacle_width=width,
                             tilt_angle=tilt)
        ax2.loglog(volume * MM3, g.depth_from_volume(volume)[0] * MM, label=f"θ = {tilt:g}°")
        if tilt:
            reach = width * math.radians(tilt)
            ax2.plot(g.volume_from_depth(reach)[0] * MM3, reach * MM, "ko", ms=4)
    ax2.set_xlabel("worn volume V_m + V_o [mm³]")
    ax2.set_ylabel("depth D [mm]")
    ax2.set_title("R_m = 9.525 mm, l = 12.7 mm (dots: D = lθ)")
    ax2.grid(True, which="both", alpha=0.3)
    ax2.legend()
    return _save(fig, "geometry_tube_bav.png")


def figure_tube_tube() -> Path:
    """Two crossing tubes: plan view of the wedge flats, and depth against volume."""
    radius = 9.525e-3
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
    angle = math.radians(12.0)  # exaggerated
    span = np.array([-40.0, 40.0])
    ax1.fill_between(span, -radius * MM, radius * MM, color="tab:blue", alpha=0.3,
                     label="mobile tube")
    direction = np.array([math.cos(angle), math.sin(angle)])
    normal = np.array([-direction[1], direction[0]])
    corners = [s * 40 * direction + n * radius * MM * normal for s in (-1, 1) for n in (-1, 1)]
    poly = np.array([corners[0], corners[2], corners[3], corners[1]])
    ax1.fill(poly[:, 0], poly[:, 1], color="tab:orange", alpha=0.3, label="obstacle tube")
    ax1.set_aspect("equal")
    ax1.set_title("TUBE_TUBE plan view (angle exaggerated: 12°)")
    ax1.text(20, -8, "θ", fontsize=12)
    ax1.legend(loc="upper left", fontsize=8)
    ax1.set_xlabel("mm")
    volume = np.geomspace(1e-12, 1e-7, 200)
    for tilt in (1.0, 5.0, 20.0):
        g = contact_geometry("TUBE_TUBE", mobile_radius=radius, tilt_angle=tilt)
        ax2.loglog(volume * MM3, g.depth_from_volume(volume)[0] * MM, label=f"θ = {tilt:g}°")
    ax2.set_xlabel("worn volume of one tube [mm³]")
    ax2.set_ylabel("its depth [mm]")
    ax2.set_title("d = (1/(2R))^(1/5)·(15θV/8)^(2/5), R = 9.525 mm")
    ax2.grid(True, which="both", alpha=0.3)
    ax2.legend()
    return _save(fig, "geometry_tube_tube.png")


def _lunule_sketch(ax, rm, ro, dm, do, centre_sign=1.0, label=True):
    """Draw bore, offset mobile, lens and the interface arc (mobile towards +y or −y)."""
    depth = dm + do
    c = ro - rm + depth
    x = float(lens_half_chord(rm, ro, depth))
    s_r = float(sagitta(rm, x)) - dm
    r = (s_r**2 + x**2) / (2 * s_r)
    apex = ro + do
    t = np.linspace(-x, x, 300)
    mobile = c + np.sqrt(rm**2 - t**2)
    bore = np.sqrt(ro**2 - t**2)
    interface = apex - r + np.sqrt(r**2 - t**2)
    k = centre_sign
    ax.fill_between(t * MM, k * interface * MM, k * mobile * MM, color="tab:red", alpha=0.6,
                    label="mobile worn (V_m/l)" if label else None)
    ax.fill_between(t * MM, k * bore * MM, k * interface * MM, color="tab:orange", alpha=0.6,
                    label="obstacle worn (V_o/l)" if label else None)
    _circle(ax, 0, k * c * MM, rm * MM, color="tab:blue", lw=1)
    return x, r


def figure_tube_alesage() -> Path:
    """Tube in a hole: two opposite lunules (exaggerated), and depth against volume."""
    rm, ro, width = 9.525e-3, 9.7e-3, 20e-3
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.8))
    sketch_ro = 12e-3  # sketch only: a larger clearance makes the lunules visible
    _circle(ax1, 0, 0, sketch_ro * MM, color="k", label="hole R_o (sketch: 12 mm)")
    for sign in (1.0, -1.0):
        _lunule_sketch(ax1, rm, sketch_ro, 0.8e-3, 0.4e-3, sign, label=sign > 0)
    _circle(ax1, 0, 0, (rm - 0.6e-3) * MM, color="0.5", ls=":", lw=1,
            label="uniform wear (no R_o)")
    ax1.set_aspect("equal")
    ax1.set_title("TUBE_ALESAGE: both ends of the stroke\n(clearance exaggerated)")
    ax1.legend(loc="center", fontsize=7)
    ax1.set_xlabel("mm")
    volume = np.geomspace(1e-12, 1e-6, 200)
    uniform = contact_geometry("TUBE_ALESAGE", mobile_radius=rm, obstacle_width=width)
    ax2.loglog(volume * MM3, uniform.depth_from_volume(volume)[0] * MM, "k:",
               label="uniform (no R_o)")
    for tilt in (0.0, 0.5, 2.0):
        g = contact_geometry("TUBE_ALESAGE", mobile_radius=rm, obstacle_radius=ro,
                             obstacle_width=width, tilt_angle=tilt)
        v = volume[volume <= g.max_volume]
        ax2.loglog(v * MM3, g.depth_from_volume(v)[0] * MM, label=f"lunules, θ = {tilt:g}°")
    ax2.axhline(uniform_limit := float(contact_geometry(
        "TUBE_ALESAGE", mobile_radius=rm, obstacle_radius=ro, obstacle_width=width).max_depth)
        * MM, color="0.6", lw=0.8)
    ax2.text(2e-3, uniform_limit * 1.1, "lens range limit", fontsize=8)
    ax2.set_xlabel("V_m [mm³] (V_o = 0)")
    ax2.set_ylabel("d_m [mm]")
    ax2.set_title("R_m = 9.525 mm, R_o = 9.7 mm, l = 20 mm")
    ax2.grid(True, which="both", alpha=0.3)
    ax2.legend(fontsize=8)
    return _save(fig, "geometry_tube_alesage.png")


def figure_grappe_alesage() -> Path:
    """Rod in a guide bore: the lunule system (x, r, d_m, d_o), and the split of the depth."""
    rm, ro, width = 4.85e-3, 5.25e-3, 10e-3
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
    dm, do = 0.6e-3, 0.3e-3
    sketch_ro = 6.5e-3  # sketch only: a larger clearance makes the lunule visible
    x, r = _lunule_sketch(ax1, rm, sketch_ro, dm, do)
    _circle(ax1, 0, 0, sketch_ro * MM, color="k", label="bore R_o (sketch: 6.5 mm)")
    y_chord = math.sqrt(sketch_ro**2 - x**2) * MM
    ax1.plot([-x * MM, x * MM], [y_chord] * 2, "k--", lw=0.8)
    ax1.text(0, y_chord - 0.6, "chord 2x", ha="center", fontsize=8)
    ax1.text(-3.0, -1.0, f"common arc r = {r * MM:.2f} mm\n"
             f"d_m = {dm * MM:g} mm, d_o = {do * MM:g} mm", fontsize=8)
    ax1.set_aspect("equal")
    ax1.set_title("GRAPPE_ALESAGE lunule (not to scale)")
    ax1.legend(loc="lower center", fontsize=7)
    ax1.set_xlabel("mm")
    g = contact_geometry("GRAPPE_ALESAGE", mobile_radius=rm, obstacle_radius=ro,
                         obstacle_width=width)
    volume = np.linspace(0, 0.45, 200) * g.max_volume
    for ratio in (0.0, 0.5, 1.0):
        dm_v, do_v = g.depth_from_volume(volume, ratio * volume)
        line, = ax2.plot(volume * MM3, dm_v * MM, label=f"d_m, V_o = {ratio:g}·V_m")
        if ratio:
            ax2.plot(volume * MM3, do_v * MM, "--", color=line.get_color(),
                     label=f"d_o, V_o = {ratio:g}·V_m")
    ax2.set_xlabel("V_m [mm³]")
    ax2.set_ylabel("depth [mm]")
    ax2.set_title("R_m = 4.85 mm, R_o = 5.25 mm, l = 10 mm")
    ax2.grid(True, alpha=0.3)
    ax2.legend(fontsize=8)
    return _save(fig, "geometry_grappe_alesage.png")


def figure_frustum() -> Path:
    """The frustum rule of tilted traces against the exact wedge integral (lens sections)."""
    rm, ro, width, tilt = 9.525e-3, 9.7e-3, 20e-3, math.radians(0.5)
    reach = width * tilt
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    z = np.linspace(0, width, 50)
    for d, style in ((0.6 * reach, "tab:blue"), (2.5 * reach, "tab:red")):
        ax1.plot(z * MM, -np.maximum(d - tilt * z, 0) * MM, color=style,
                 label=f"D = {d / reach:.1f}·lθ")
    ax1.set_xlabel("position along the mobile's axis z [mm]")
    ax1.set_ylabel("depth of the trace [mm]")
    ax1.set_title("Tilted trace: depth D − θz over the width l")
    ax1.legend()
    ax1.grid(True, alpha=0.3)
    depth = np.geomspace(1e-9, 1.6e-3, 120)
    frustum = tilted_lunule_volume(depth, rm, ro, width, tilt)
    # exact wedge integral (1/θ)∫A(u)du over the trace's depths, by the trapezoid rule on a fine
    # grid of the lens area
    exact = []
    for d in depth:
        u = np.linspace(max(d - reach, 0.0), d, 4001)
        exact.append(np.trapezoid(lens_area(rm, ro, u), u) / tilt)
    ax2.semilogx(depth / reach, frustum / np.array(exact))
    ax2.axhline(5 / 6, color="0.5", ls=":", label="5/6 (sections ∝ $D^{3/2}$)")
    ax2.set_xlabel("D / (lθ)")
    ax2.set_ylabel("frustum rule / exact wedge volume")
    ax2.set_title("frustum rule (theory §6) vs exact wedge (TUBE_ALESAGE lens)")
    ax2.grid(True, which="both", alpha=0.3)
    ax2.legend()
    return _save(fig, "geometry_frustum.png")



# ---------------------------------------------------------------- broached holes, notches
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


def _broached_plate(ax, lobes: int, r_o: float, half_opening_deg: float, title: str) -> None:
    """The plate around a broached hole of ``lobes`` lobes (lands on the circle r_o), drawn on
    square hidden axes."""
    square = 2.2
    ax.add_patch(plt.Rectangle((-square, -square), 2 * square, 2 * square, color="0.7",
                               zorder=-1))
    _lobed_hole(ax, lobes, r_o, half_opening_deg, 20.0, 0.45)
    count = {3: "three", 4: "four"}[lobes]
    ax.text(-2.1, -2.1, f"plate: lands on the circle $R_o$, {count} lobes", fontsize=8)
    ax.set_xlim(-square, square)
    ax.set_ylim(-square, square)
    ax.set_aspect("equal")
    ax.set_axis_off()
    ax.set_title(title)


def figure_tube_3_enco() -> Path:
    """Sketch: trefoil hole with the tube on an isthmus edge, and the worn section at the edge."""
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(10.5, 5.0))
    # -- left: trefoil hole, tube pushed towards the edge of a land
    r_o, r_m = 1.0, 0.93
    _broached_plate(ax0, 3, r_o, 28.0, "TUBE_3_ENCO: tube on an isthmus edge (sketch)")
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
    ax1.text(0.3, ro - 0.08, "lobe (empty)\nbeyond the flank", fontsize=8)
    ax1.text(0.02, ro + 1.3 * depth, "lobe side: triangle\n"
             r"$\approx \frac{1}{2}D^2\tan\alpha_i$", fontsize=8)
    ax1.set_xlim(-half, half)
    ax1.set_ylim(ro - 0.3, top)
    ax1.set_xlabel("across the contact (depth exaggerated)")
    ax1.set_yticks([])
    ax1.legend(loc="lower center", fontsize=7)
    ax1.set_title("worn section at the edge")
    return _save(fig, "geometry_tube_3_enco.png")


def _enco_relation(ax) -> None:
    """V_m(d_m) of TUBE_3_ENCO and TUBE_4_ENCO for a 3/4-inch tube, with and without tilt."""
    dims = {"mobile_radius": 9.525e-3, "obstacle_radius": 9.75e-3, "obstacle_width": 30e-3,
            "isthmus_angle": 30.0}
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
    ax.text(limit * 1e3, 5, "range limit:\nchord at the\ntube's axis ", fontsize=8, va="bottom",
            ha="right")
    ax.set_xlabel("mobile depth $d_m$ [mm] (obstacle not worn)")
    ax.set_ylabel("mobile volume $V_m$ [mm³]")
    ax.set_title("$R_m$ = 9.525 mm, $R_o$ = 9.75 mm, $l$ = 30 mm, "
                 r"$\alpha_i$ = 30° (dots: $d = l\theta$)", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)


def figure_tube_4_enco() -> Path:
    """Sketch: quatrefoil hole, the tube bearing on the two edges of a lobe; V(d) of both types."""
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11.5, 5.0),
                                   gridspec_kw={"width_ratios": [1.0, 1.25]})
    r_o, r_m, half_opening, protrusion = 1.0, 0.93, 28.0, 0.04
    _broached_plate(ax0, 4, r_o, half_opening,
                    "TUBE_4_ENCO: tube on the two edges of a lobe (sketch)")
    beta = math.radians(half_opening)
    # the tube, pushed towards the lobe at 90°, reaches both of its edges (r_o sin β, r_o cos β)
    # and (−r_o sin β, r_o cos β) by the same protrusion: centre on the lobe's axis
    centre_y = r_o * math.cos(beta) - math.sqrt((r_m - protrusion) ** 2
                                                - (r_o * math.sin(beta)) ** 2)
    ax0.add_patch(plt.Circle((0.0, centre_y), r_m, fill=False, color="tab:blue", lw=1.6))
    ax0.plot(0.0, centre_y, "+", color="tab:blue")
    for sign in (-1.0, 1.0):
        ex, ey = sign * r_o * math.sin(beta), r_o * math.cos(beta)
        ax0.plot(ex, ey, "o", color="tab:red", ms=4)
        ax0.annotate("", (ex, ey), (0.0, 1.85),
                     arrowprops={"arrowstyle": "->", "color": "tab:red"})
    ax0.text(0.0, 1.9, "two isthmus edges: each carries half of $V_m$ and $V_o$",
             color="tab:red", ha="center", fontsize=8)
    ax0.text(0.0, -0.15, "tube $R_m$", color="tab:blue", ha="center")
    _enco_relation(ax1)
    ax1.set_title("TUBE_3_ENCO (one edge) and TUBE_4_ENCO (two edges)\n"
                  + ax1.get_title(), fontsize=9)
    return _save(fig, "geometry_tube_4_enco.png")


def _guide_card(ax, x0: float, notches: int, rod: float, bore: float) -> None:
    """Schematic guide card around x0 [mm]: bore, ``notches`` slots opening it, the rod."""
    side, slot_width, slot_depth = 7.5, 3.0, 2.2
    ax.add_patch(plt.Rectangle((x0 - side, -side), 2 * side, 2 * side, color="0.7", zorder=0))
    ax.add_patch(plt.Circle((x0, 0.0), bore, color="white", zorder=1))
    for sign in (1.0, -1.0)[:notches]:
        y = bore - 0.5 if sign > 0 else -bore - slot_depth + 0.5
        ax.add_patch(plt.Rectangle((x0 - slot_width / 2, y), slot_width, slot_depth,
                                   color="white", zorder=1))
    ax.add_patch(plt.Circle((x0, 0.0), rod, fill=False, color="tab:blue", lw=1.5, zorder=2))
    ax.text(x0, 0.0, f"rod\n⌀ {2 * rod:g} mm", color="tab:blue", ha="center", va="center",
            fontsize=8, zorder=3)
    ax.text(x0, -side - 1.2, f"{notches} notch{'es' if notches > 1 else ''}: "
            f"GRAPPE_{notches}_ENCO", ha="center", fontsize=8)


def figure_grappe_notch() -> Path:
    """Guide cards with one / two notches (schematic), and the notch cubics of both types."""
    fig, (ax0, ax) = plt.subplots(1, 2, figsize=(12.0, 4.6),
                                  gridspec_kw={"width_ratios": [1.1, 1.0]})
    _guide_card(ax0, -8.5, 1, 4.85, 5.25)
    _guide_card(ax0, 8.5, 2, 4.85, 5.25)
    ax0.set_xlim(-16.5, 16.5)
    ax0.set_ylim(-9.5, 8.0)
    ax0.set_aspect("equal")
    ax0.set_axis_off()
    ax0.set_title("Guide card, bore ⌀ 10.5 mm, worn height $l$ along the rod\n"
                  "(schematic: Code_Aster R7.20.01 gives no drawing of the notch)",
                  fontsize=9)
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
                    (d_max + 0.5, p_max + 2.0), fontsize=7,
                    arrowprops={"arrowstyle": "->", "lw": 0.6})
    ax.set_xlabel("rod depth $d_m$ [mm]")
    ax.set_ylabel("$V_m/l$ [mm²]")
    ax.set_title("Notch cubics (9.7 mm rod, 10.5 mm card): dotted = beyond the range (NaN)",
                 fontsize=9)
    ax.set_ylim(0, 58)
    ax.set_xlim(0, 5.0)
    ax.legend(fontsize=8, loc="upper left")
    ax.grid(alpha=0.3)
    return _save(fig, "geometry_grappe_notch.png")


#: Figure of each contact type (both notch types share one), and of the frustum rule.
FIGURES = {
    "TUBE_BAV": figure_tube_bav,
    "TUBE_ALESAGE": figure_tube_alesage,
    "TUBE_3_ENCO": figure_tube_3_enco,
    "TUBE_4_ENCO": figure_tube_4_enco,
    "TUBE_TUBE": figure_tube_tube,
    "GRAPPE_ALESAGE": figure_grappe_alesage,
    "GRAPPE_1_ENCO": figure_grappe_notch,
    "GRAPPE_2_ENCO": figure_grappe_notch,
    "frustum": figure_frustum,
}


def main(names: list[str]) -> None:
    """Draw the figures named (keys of FIGURES), all of them when none is named."""
    unknown = [name for name in names if name not in FIGURES]
    if unknown:
        raise SystemExit(f"unknown figure(s) {unknown}; choose among {list(FIGURES)}")
    done = set()
    for name in names or FIGURES:
        function = FIGURES[name]
        if function not in done:
            done.add(function)
            print(function())


if __name__ == "__main__":
    main(sys.argv[1:])
