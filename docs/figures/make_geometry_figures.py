"""Draw the figures of docs/geometry.md (one function per contact type, plus the common parts).

Run from the repository root: ``.venv/bin/python docs/figures/make_geometry_figures.py``.
Every curve is computed by fretwear itself (no hand-drawn data); the sections are to scale
except where the depth is exaggerated, which each title says. The broached-hole and notch types
have their own script, docs/figures/make_enco_figures.py.
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from fretwear.geometry import contact_geometry  # noqa: E402
from fretwear.geometry._shapes import lens_area, lens_half_chord, sagitta  # noqa: E402
from fretwear.geometry.tube_alesage import tilted_lunule_volume  # noqa: E402
from fretwear.io.atomic import atomic_path  # noqa: E402

HERE = Path(__file__).resolve().parent
MM = 1e3
MM3 = 1e9


def _save(fig, name: str) -> Path:
    target = HERE / name
    with atomic_path(target) as tmp:
        fig.savefig(tmp, dpi=120, format="png", bbox_inches="tight")
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
    ax1.set_title("TUBE_ALESAGE: the tube at both ends of its stroke (not to scale)")
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
    ax2.axhline(5 / 6, color="0.5", ls=":", label="5/6 (sections ∝ D^{3/2})")
    ax2.set_xlabel("D / (lθ)")
    ax2.set_ylabel("frustum rule / exact wedge volume")
    ax2.set_title("SPEC frustum rule vs exact wedge (TUBE_ALESAGE lens)")
    ax2.grid(True, which="both", alpha=0.3)
    ax2.legend()
    return _save(fig, "geometry_frustum.png")


FIGURES = {
    "TUBE_BAV": figure_tube_bav,
    "TUBE_TUBE": figure_tube_tube,
    "TUBE_ALESAGE": figure_tube_alesage,
    "GRAPPE_ALESAGE": figure_grappe_alesage,
    "frustum": figure_frustum,
}


def main() -> None:
    for function in FIGURES.values():
        print(function())


if __name__ == "__main__":
    main()
