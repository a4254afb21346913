"""Matplotlib figures of a case's result: the mesh cycle, ease-off maps, the load
distribution, the K-chart, the path of contact, mesh loads and lubrication (the design
studies' charts are design_charts', a sweep's sweep_plots'), and figures_for, which writes
every one that applies.

Each function takes plain data (a result document as written to result.json, or arrays) and
an output path, draws on its own figure (look.figure) and writes it whole (look.save),
returning the path. Units: mm, µm, µrad, MPa, N, N·m, rad as the labels say."""

from __future__ import annotations

import math
import textwrap
from pathlib import Path

import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Patch
from matplotlib.ticker import MaxNLocator

from . import style as look
from .design_charts import crown_design_chart, worm_efficiency_vs_temperature, worm_efficiency_vs_torque
from .style import SERIES, TE_LEAST_SPAN, WARNING

# ---------------------------------------------------------------------------------------
# 1. mesh cycle


def mesh_cycle(result: dict, path: str | Path) -> Path:
    """The contact over the mesh cycle of a contact case (result['positions']).

    Four panels: transmission error (the gear's lag as a length in µm at the result's
    transmission_error_arm, else in µrad; loaded beside unloaded where solved, each about its
    own mean, the axis at least TE_LEAST_SPAN tall) over roll angle (deg); peak contact
    pressure (MPa: the loaded solution's where solved, Hertz's dotted beside it), the
    ellipse semi-axes a and b (mm, log scale) and the worst edge margin
    (mm, zero line = edge of the flank, edge contact in the warning colour) per tooth pair
    over roll angle. For a spline (kind "spline", 'pair' = tooth index, every tooth at each
    position) the last three panels run over the tooth index, one series per position.
    Missing values (None, NaN: a line contact has no edge margin) are left out."""
    rows = result.get("positions") or []
    if not rows:
        raise ValueError("mesh_cycle: the result has no 'positions' (no contact analysis)")
    by_tooth = result.get("kind") == "spline"
    roll, pair = look.column(rows, "roll_deg"), look.column(rows, "pair")
    p_max = look.column(rows, "p_max_MPa")
    a, b, margin = look.column(rows, "a_mm"), look.column(rows, "b_mm"), look.column(rows, "edge_margin_mm")
    # a pair kept only for the loaded contact (rigid_contact false) has no Hertz contact
    touching = np.array([r.get("rigid_contact", True) for r in rows], bool)
    p_max, a, b = (np.where(touching, column, np.nan) for column in (p_max, a, b))
    edge = np.array([bool(r.get("edge_contact")) for r in rows])
    line = np.array([r.get("contact_model") in ("line", "area") for r in rows])

    if by_tooth:
        x, group, x_label = pair, roll, "tooth index"
    else:
        x, group, x_label = roll, pair, f"{_driver(result)} roll angle (deg)"

    def label(g: float) -> str:
        return f"roll {g:g}°" if by_tooth else (f"pair {int(g):+d}" if g else "pair 0")

    pair_legend = ("" if by_tooth else
                   "wheel teeth: the next (+1) meshes one start's pitch of worm roll later"
                   if result.get("kind") == "worm" else
                   "tooth pairs: 0 the pair in mid-mesh at roll 0; +1, +2 one, two pitches "
                   "further through the mesh, −1, −2 behind")

    steps = np.diff(np.unique(x[np.isfinite(x)]))
    step = float(np.min(steps)) if len(steps) else 0.0
    groups = list(np.unique(group[np.isfinite(group)]))

    fig = look.figure(7.4)
    (ax_te, ax_p), (ax_ab, ax_m) = fig.subplots(2, 2)
    fig.suptitle(look.title(result, "Mesh cycle", 110), fontsize=11)

    # transmission error: one value per position, unloaded and (where solved) loaded, each
    # about its own mean (a loaded TE's mean is the mesh's compliance, hundreds of µrad; its
    # ripple is what excites the mesh), in µm where the analysis gave them as a length
    rolls = np.unique(roll[np.isfinite(roll)])
    first = [np.nonzero(roll == r)[0][0] for r in rolls]
    unit = "µm" if "transmission_error_um" in rows[0] else "µrad"
    suffix = "um" if unit == "µm" else "urad"
    for name, column, style, colour in (
            ("unloaded", f"transmission_error_{suffix}", "o-", "black"),
            ("loaded", f"loaded_transmission_error_{suffix}", "s-", WARNING)):
        values = look.column(rows, column)[first]
        if not np.isfinite(values).any():
            continue
        mean, digits = float(np.nanmean(values)), 3 if unit == "µm" else 2
        ax_te.plot(rolls, values - mean, style, color=colour, ms=4, lw=1.2,
                   label=f"{name}: mean {mean:.{digits}f} {unit}, peak to peak "
                         f"{np.nanmax(values) - np.nanmin(values):.{digits}f} {unit}")
    ax_te.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), frameon=False)
    arm = (result.get("summary") or {}).get("transmission_error_arm_mm")
    driven = "wheel" if result.get("kind") == "worm" else "gear"
    ax_te.set(title=f"Transmission error ({driven} lag"
                    + (f" × r = {arm:.4g} mm)" if arm and unit == "µm" else ")"),
              xlabel="roll angle (deg)" if by_tooth else x_label,
              ylabel=f"TE about its mean ({unit})")
    look.least_span(ax_te, np.concatenate([np.asarray(line.get_ydata(), float)
                                       for line in ax_te.get_lines()] or [np.array([])]),
                TE_LEAST_SPAN[unit])
    look.plain_axis(ax_te.yaxis)
    loaded_p = np.where(touching | (look.column(rows, "bem_load_N") > 0),
                        look.column(rows, "bem_p_max_MPa"), np.nan)
    has_loaded = np.isfinite(loaded_p).any()

    handles = []
    for i, g in enumerate(groups):
        colour = SERIES[i % len(SERIES)]
        sel = group == g
        xs = x[sel]
        if has_loaded:
            ax_p.plot(*look.gapped(xs, loaded_p[sel], step), "o-", color=colour, ms=4, lw=1.2)
            ax_p.plot(*look.gapped(xs, p_max[sel], step), ":", color=colour, lw=1.0)
        else:
            ax_p.plot(*look.gapped(xs, p_max[sel], step), "o-", color=colour, ms=4, lw=1.2)
        ax_ab.plot(*look.gapped(xs, a[sel], step), "o-", color=colour, ms=4, lw=1.2)
        ax_ab.plot(*look.gapped(xs, b[sel], step), "s--", color=colour, ms=3.5, lw=1.2)
        ax_m.plot(*look.gapped(xs, margin[sel], step), "o-", color=colour, ms=4, lw=1.2)
        handles.append(Line2D([], [], color=colour, marker="o", ms=4, label=label(g)))

    ax_p.set(title="Peak pressure: loaded (—), Hertz (···)" if has_loaded
             else "Peak contact pressure (Hertz)", xlabel=x_label, ylabel="p_max (MPa)")
    ax_ab.set(title="Contact ellipse semi-axes", xlabel=x_label,
              ylabel="semi-axis a (solid), b (dashed) (mm)")
    if np.any(np.isfinite(a) & (a > 0)) or np.any(np.isfinite(b) & (b > 0)):
        ax_ab.set_yscale("log")
        look.plain_log(ax_ab.yaxis)
        look.labelled_log_limits(ax_ab)
    ax_m.axhline(0.0, color="black", ls="--", lw=1.0)
    ax_m.set(title="Worst edge margin", xlabel=x_label,
             ylabel="edge margin (mm), < 0 = edge loading")

    style = [Line2D([], [], color="0.3", marker="o", ms=4, ls="-", label="a (long semi-axis)"),
             Line2D([], [], color="0.3", marker="s", ms=3.5, ls="--", label="b (short semi-axis)"),
             Line2D([], [], color="black", ls="--", lw=1.0, label="edge of the flank (margin 0)")]
    if line.any():
        ax_ab.plot(x[line], a[line], "D", mfc="none", mec="black", ms=8, mew=1.0)
        style.append(Line2D([], [], color="black", marker="D", mfc="none", ls="none", ms=7,
                            label="line contact (a = half its length)"))
    if edge.any():
        y_edge = np.where(np.isfinite(margin[edge]), margin[edge], 0.0)
        ax_m.plot(x[edge], y_edge, "X", color=WARNING, ms=9, mec="black", mew=0.5, zorder=5)
        style.append(Line2D([], [], color=WARNING, marker="X", mec="black", mew=0.5, ls="none",
                            ms=9, label="edge contact"))
    if np.isfinite(margin).any():
        worst = int(np.nanargmin(margin))
        margins = rows[worst].get("edge_margins_mm") or {}
        finite = {k: look.num(v) for k, v in margins.items() if math.isfinite(look.num(v))}
        name = min(finite, key=finite.get) if finite else "worst"
        lo_x, hi_x = np.nanmin(x), np.nanmax(x)
        right = x[worst] <= 0.5 * (lo_x + hi_x)
        ax_m.annotate(f"worst: {name} {margin[worst]:.3f} mm", (x[worst], margin[worst]),
                      xytext=(14 if right else -14, -16 if margin[worst] < 0 else 12),
                      textcoords="offset points", ha="left" if right else "right",
                      va="center", fontsize=8, arrowprops={"arrowstyle": "-", "color": "0.4"},
                      bbox={"boxstyle": "round,pad=0.2", "fc": "white", "ec": "0.6", "alpha": 0.9})
        ax_m.margins(y=0.18)
    lo, hi = ax_m.get_ylim()  # keep the edge (margin 0) in view
    pad = 0.08 * (max(hi, 0.0) - min(lo, 0.0))
    ax_m.set_ylim(min(lo, -pad), max(hi, pad))
    for ax in (ax_te, ax_p, ax_ab, ax_m):
        ax.grid(True, alpha=0.3)
    entries = handles + style
    fig.legend(handles=entries, loc="outside lower center",
               ncol=min(len(entries), max(4, math.ceil(len(entries) / 2))), fontsize=8,
               frameon=False, title=pair_legend or None, title_fontsize=8)
    return look.save(fig, path)


# ---------------------------------------------------------------------------------------
# 2. ease-off map


#: ease-off contours start this fraction of the map's range above its least separation
EASE_OFF_FLOOR = 0.02


def ease_off_map(face_mm, radius_mm, separation_um, path: str | Path,
                 approach_um: float | None = None, title: str = "Ease-off: flank separation",
                 member: str = "pinion") -> Path:
    """Map of the separation (ease-off) of a flank pair over the flank.

    face_mm: face position from mid-face (mm, positive toward end B), length nx;
    radius_mm: radius on the `member` (mm), length ny; separation_um: (ny, nx) separation (µm),
    NaN where there is no flank (left blank). approach_um: draws the contour
    separation = approach (µm), the rigid contact pattern at that approach."""
    x = np.asarray(face_mm, dtype=float).ravel()
    y = np.asarray(radius_mm, dtype=float).ravel()
    z = np.asarray(separation_um, dtype=float)
    if z.shape != (len(y), len(x)):
        raise ValueError(f"separation_um has shape {z.shape}; expected (len(radius_mm), "
                         f"len(face_mm)) = ({len(y)}, {len(x)})")
    if not np.isfinite(z).any():
        raise ValueError("separation_um has no finite value")
    field = np.ma.masked_invalid(z)

    fig = look.figure(5.2)
    ax = fig.subplots()
    mesh = ax.pcolormesh(x, y, field, shading="nearest", cmap="viridis")
    lo, hi = float(field.min()), float(field.max())
    handles = []
    if hi > lo:
        # no level within EASE_OFF_FLOOR of the least: there the map is flat and a contour
        # traces its round-off as islands
        floor = lo + EASE_OFF_FLOOR * (hi - lo)
        levels = [v for v in MaxNLocator(8).tick_values(lo, hi) if floor < v < hi]
        if levels:
            lines = ax.contour(x, y, field, levels=levels, colors="white", linewidths=0.6,
                               alpha=0.7)
            ax.clabel(lines, fmt="%g", fontsize=7)
    if approach_um is not None:
        if lo < approach_um < hi:
            ax.contour(x, y, field, levels=[approach_um], colors=WARNING, linewidths=2.0)
            text = f"rigid contact pattern: separation = approach {approach_um:g} µm"
        else:
            text = f"approach {approach_um:g} µm: outside the field's range, no contour"
        handles.append(Line2D([], [], color=WARNING, lw=2.0, label=text))
    imin = np.unravel_index(np.nanargmin(z), z.shape)
    ax.plot(x[imin[1]], y[imin[0]], "+", color="white", ms=10, mew=1.5)
    handles.append(Line2D([], [], color="black", marker="+", ls="none", ms=9, mew=1.5,
                          label=f"least separation {lo:.3g} µm at ({x[imin[1]]:.2f}, "
                                f"{y[imin[0]]:.2f}) mm" + (
                                    "\n(the contact search holds each position's least at "
                                    "0; below 0 is the map's own sampling of it)" if lo < 0
                                    else "")))
    if not np.isfinite(z).all():
        handles.append(Patch(facecolor="white", edgecolor="0.5", label="blank: no flank"))
    colorbar = fig.colorbar(mesh, ax=ax, pad=0.02)
    colorbar.set_label("separation (µm)")
    ax.set(title="\n".join(textwrap.wrap(title, 90)),
           xlabel="face position from mid-face (mm, + toward end B)",
           ylabel=f"{member} radius (mm)")
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=1,
              fontsize=8, frameon=False)
    return look.save(fig, path)


def load_distribution(result: dict, path: str | Path) -> Path:
    """The mesh's line load along the face over the cycle (the result's load_distribution
    section): a map of the load per mm of face (N/mm) by face position and roll angle,
    each position's largest marked, and beside it the position's K_Hβ (its largest over
    the mean W/b), the worst marked, and the cycle's K_Hβ (ISO 6336-1 Method A: the
    summary's) as a dashed line."""
    section = result["load_distribution"]
    face = np.asarray(section["face_mm"], float)
    rolls = np.asarray(section["roll_deg"], float)
    lines = np.asarray(section["line_load_N_per_mm"], float)
    factors = np.asarray(section["K_H_beta"], float)
    fig = look.figure(5.2)
    ax, side = fig.subplots(1, 2, sharey=True, gridspec_kw={"width_ratios": [4, 1]})
    mesh = ax.pcolormesh(face, rolls, lines, shading="nearest", cmap="viridis")
    ax.plot(face[np.argmax(lines, axis=1)], rolls, "+", color="black", ms=8, mew=1.2,
            label="largest line load of the position")
    colorbar = fig.colorbar(mesh, ax=side, pad=0.08)
    colorbar.set_label("line load (N/mm of face)")
    ax.set(xlabel="face position from mid-face (mm, + toward end B)",
           ylabel=f"{_driver(result)} roll angle (deg)")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.14), fontsize=8, frameon=False)
    side.plot(factors, rolls, "o-", color=WARNING, ms=3, lw=1.0)
    worst = int(np.argmax(factors))
    side.plot(factors[worst], rolls[worst], "s", color="black", ms=6)
    side.axvline(1.0, color="0.6", lw=0.8)
    cycle = (result.get("summary") or {}).get("K_H_beta")
    if cycle is not None:
        side.axvline(cycle, color="black", lw=1.0, ls="--")
    side.set(xlabel="K_Hβ of each position", title=f"worst {factors[worst]:.3f}"
             + (f"\ncycle (ISO A) {cycle:.3f}" if cycle is not None else ""))
    fig.suptitle(look.title(result, "Load distribution along the face over the mesh cycle", 95),
                 fontsize=10)
    return look.save(fig, path)


#: a K-chart trace spanning less than this (µm) is drawn on this span about its value
K_CHART_LEAST_SPAN_UM = 2.0


def k_chart(result: dict, path: str | Path) -> Path:
    """The K-chart of both members (the result's k_chart section): each member's profile
    trace at mid-face over its diameter and its lead trace at mid-profile over the face,
    the drop along the normal in µm (material removed), as made: crowns, slopes, twist,
    reliefs, topography and the tip edge together."""
    section = result["k_chart"]
    names = [n for n in ("pinion", "gear") if section.get(n)]
    fig = look.figure(2.5 * len(names) + 0.9)
    axes = np.atleast_2d(fig.subplots(len(names), 2))
    for row, name in zip(axes, names):
        trace = section[name]
        profile, lead = row
        profile.plot(trace["profile_um"], trace["profile_diameter_mm"], color=SERIES[0])
        profile.set(xlabel="drop along the normal (µm)", ylabel="diameter (mm)",
                    title=f"{name}: profile at mid-face")
        lead.plot(trace["lead_face_mm"], trace["lead_um"], color=SERIES[1])
        lead.set(xlabel="face position from mid-face (mm, + toward end B)",
                 ylabel="drop along the normal (µm)",
                 title=f"{name}: lead at d = {trace['lead_diameter_mm']:.2f} mm")
        lead.invert_yaxis()               # material removed downward, as a K-chart plots it
        for ax, values, set_limits in ((profile, trace["profile_um"], profile.set_xlim),
                                       (lead, trace["lead_um"], lead.set_ylim)):
            low, high = min(values), max(values)
            if high - low < K_CHART_LEAST_SPAN_UM:        # an unmodified trace: a flat line
                middle = 0.5 * (low + high)
                span = 0.5 * K_CHART_LEAST_SPAN_UM
                set_limits(*((middle + span, middle - span) if ax is lead
                             else (middle - span, middle + span)))
            look.plain_axis(ax.xaxis)
            look.plain_axis(ax.yaxis)
            ax.grid(True, lw=0.4, color="0.85")
    fig.suptitle(look.title(result, "K-chart: the modifications as made", 95), fontsize=10)
    return look.save(fig, path)


def path_of_contact(result: dict, path: str | Path) -> Path:
    """The loaded flank pressure along the path of contact: each contact's largest pressure
    on the active flank (flank_p_max_MPa) at its place on the driver's profile (its contact
    diameter), per tooth pair, so that the pairs taking over from each other draw one path;
    beside it ISO 6336-2's σ_H and σ_H0 of the rating and each member's permissible σ_HP."""
    rows = result["positions"]
    rating = {f["key"]: f["value"] for f in (result.get("rating") or {}).get("figures", [])}
    fig = look.figure(4.2)
    ax = fig.subplots()
    pairs = sorted({r["pair"] for r in rows})
    for k, pair in enumerate(pairs):
        mine = sorted((r for r in rows if r["pair"] == pair and r.get("flank_p_max_MPa")
                       and r.get("contact_radius_pinion_mm")),
                      key=lambda r: r["contact_radius_pinion_mm"])
        if mine:
            ax.plot([2.0 * r["contact_radius_pinion_mm"] for r in mine],
                    [r["flank_p_max_MPa"] for r in mine], "o-", ms=3, lw=1.2,
                    color=SERIES[k % len(SERIES)], label=f"tooth pair {pair}")
    for key, text, style in (("sigma_H_MPa", "ISO 6336-2 σ_H", "--"),
                             ("sigma_H0_MPa", "σ_H0 (nominal)", ":"),
                             ("sigma_HP_pinion_MPa", "σ_HP of the pinion", "-."),
                             ("sigma_HP_gear_MPa", "σ_HP of the gear", (0, (1, 4)))):
        if rating.get(key) is not None:
            ax.axhline(rating[key], color="black", lw=1.0, ls=style,
                       label=f"{text} {rating[key]:.0f} MPa")
    ax.set(xlabel=f"contact diameter on the {_driver(result)} (mm)",
           ylabel="largest pressure on the active flank (MPa)")
    look.plain_axis(ax.yaxis)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=3, fontsize=8,
              frameon=False)
    fig.suptitle(look.title(result, "Flank pressure along the path of contact against ISO's "
                                    "σ_H", 95), fontsize=10)
    return look.save(fig, path)


def mesh_loads(result: dict, path: str | Path) -> Path:
    """What the loaded contact decides over the mesh cycle (a result whose positions carry
    load_share): each tooth pair's share of its position's load, the mesh stiffness per
    position (the load_distribution section's, with ISO 6336-1's c_γα beside it), the
    transmission error's mesh harmonics (summary te_harmonics_um and
    unloaded_te_harmonics_um, µm) and the largest principal shear below each contact (MPa;
    the cycle's largest marked with its depth); a spline's over the tooth index, a series a
    position. A panel whose data the result lacks says so."""
    rows = result["positions"]
    summary = result.get("summary") or {}
    roll, pair = look.column(rows, "roll_deg"), look.column(rows, "pair")
    share = look.column(rows, "load_share")
    shear = look.column(rows, "subsurface_shear_max_MPa")
    # a spline's teeth all carry at every position: over the tooth index, one series a
    # position (as mesh_cycle draws it)
    by_tooth = result.get("kind") == "spline"
    x, group = (pair, roll) if by_tooth else (roll, pair)
    x_label = "tooth index" if by_tooth else f"{_driver(result)} roll angle (deg)"

    def label(g: float) -> str:
        return f"roll {g:g}°" if by_tooth else (f"pair {int(g):+d}" if g else "pair 0")

    fig = look.figure(6.4)
    (ax_share, ax_stiff), (ax_te, ax_shear) = fig.subplots(2, 2)
    groups = sorted(set(group[np.isfinite(share)]))
    for i, g in enumerate(groups):
        on = (group == g) & np.isfinite(share)
        ax_share.plot(x[on], share[on], "o-", ms=3, lw=1.0, color=SERIES[i % len(SERIES)],
                      label=label(g))
    ax_share.set(xlabel=x_label, ylabel="share of the load", title="Load sharing",
                 ylim=(-0.05, 1.05))
    if groups:
        ax_share.legend(fontsize=7, loc="best")
    section = result.get("load_distribution") or {}
    stiffness = section.get("mesh_stiffness_N_per_mm_um")
    if by_tooth:
        _tooth_loads(ax_stiff, ax_te, x, group, share, summary, label)
    elif stiffness:
        k = np.array([look.num(v) for v in stiffness])
        ax_stiff.plot(section["roll_deg"], k, "o-", ms=3, lw=1.0, color=SERIES[0],
                      label="the loaded contact's secant stiffness")
        iso = summary.get("iso_mesh_stiffness_N_per_mm_um")
        if iso is not None:
            ax_stiff.axhline(iso, color="0.4", ls="--", lw=1.0, label=f"ISO 6336-1 c_γα {iso:.1f}")
        ax_stiff.legend(fontsize=7, loc="best")
        ax_stiff.set(ylabel="N/(mm·µm)", xlabel=f"{_driver(result)} roll angle (deg)")
    else:
        ax_stiff.text(0.5, 0.5, "no mesh stiffness for this kind", ha="center", va="center",
                      transform=ax_stiff.transAxes)
    if not by_tooth:
        ax_stiff.set_title("Mesh stiffness per mm of face")
        _te_harmonics(ax_te, summary)
    on = np.isfinite(shear)
    for i, g in enumerate(sorted(set(group[on]))):
        here = on & (group == g)
        ax_shear.plot(x[here], shear[here], "o-", ms=3, lw=1.0,
                      color=SERIES[i % len(SERIES)])
    if on.any():
        depth = summary.get("subsurface_shear_depth_mm")
        k = int(np.nanargmax(np.where(on, shear, -np.inf)))
        ax_shear.plot(x[k], shear[k], "s", color="black", ms=6,
                      label=f"largest {shear[k]:.0f} MPa, {1e3 * depth:.0f} µm deep"
                      if depth is not None else "largest")
        ax_shear.legend(fontsize=7, loc="lower center")
    else:
        ax_shear.text(0.5, 0.5, "not computed ([analysis] subsurface)", ha="center",
                      va="center", transform=ax_shear.transAxes)
    ax_shear.set(xlabel=x_label, ylabel="(σ1 − σ3)/2 (MPa)",
                 title="Largest shear below each contact")
    fig.suptitle(look.title(result, "Loads over the mesh cycle", 95), fontsize=10)
    return look.save(fig, path)


def _te_harmonics(ax_te, summary: dict) -> None:
    """The loaded and unloaded transmission error's mesh harmonics as bars (µm)."""
    loaded, unloaded = summary.get("te_harmonics_um"), summary.get("unloaded_te_harmonics_um")
    width = 0.38
    for offset, values, name, colour in ((-width / 2, unloaded, "unloaded", "black"),
                                         (width / 2, loaded, "loaded", SERIES[0])):
        if values:
            orders = np.arange(1, len(values) + 1)
            ax_te.bar(orders + offset, values, width, color=colour, label=name)
            for o, v in zip(orders, values):
                ax_te.annotate(f"{v:.3g}", (o + offset, v), ha="center", va="bottom",
                               fontsize=6)
    if loaded or unloaded:
        ax_te.legend(fontsize=7)
        ax_te.set_xticks(np.arange(1, max(len(loaded or []), len(unloaded or [])) + 1))
    ax_te.set(xlabel="mesh order (× tooth-mesh frequency)", ylabel="amplitude (µm)",
              title="Transmission error harmonics")


def _tooth_loads(ax_loads, ax_factor, tooth, roll, share, summary: dict, label) -> None:
    """A spline's load per tooth over the mean (its share of the position's load times the
    number of teeth), a series a position, and each position's tooth load factor (the
    summary's tooth_loads) as bars with the worst marked."""
    teeth = int(np.nanmax(tooth)) + 1 if np.isfinite(tooth).any() else 0
    for i, g in enumerate(sorted(set(roll[np.isfinite(share)]))):
        on = (roll == g) & np.isfinite(share)
        ax_loads.plot(tooth[on], share[on] * teeth, "o-", ms=3, lw=1.0,
                      color=SERIES[i % len(SERIES)], label=label(g))
    ax_loads.axhline(1.0, color="0.4", ls="--", lw=1.0, label="the mean")
    ax_loads.set(xlabel="tooth index", ylabel="tooth load over the mean",
                 title="Load per tooth")
    ax_loads.legend(fontsize=7, loc="best")
    rows = [r for r in summary.get("tooth_loads") or [] if r.get("tooth_load_factor")]
    if rows:
        factors = [r["tooth_load_factor"] for r in rows]
        ax_factor.bar([f"{r['roll_deg']:.3g}°" for r in rows], factors, color=SERIES[0])
        worst = int(np.argmax(factors))
        ax_factor.bar([f"{rows[worst]['roll_deg']:.3g}°"], [factors[worst]], color=WARNING,
                      label=f"worst {factors[worst]:.3f}")
        ax_factor.legend(fontsize=7)
    ax_factor.set(xlabel="roll angle of the position", ylabel="largest over mean tooth load",
                  title="Tooth load factor")


def lubrication(result: dict, path: str | Path) -> Path:
    """The lubricated contact over the mesh cycle (analyses.lubrication's keys on the
    positions): sliding and sum speeds, the specific film λ (1 and the case's λ_GFP marked
    where given), the flash and contact temperatures and the power lost per contact, a
    series a tooth pair, over the driver's roll."""
    rows = result["positions"]
    summary = result.get("summary") or {}
    roll, pair = look.column(rows, "roll_deg"), look.column(rows, "pair")
    x_label = f"{_driver(result)} roll angle (deg)"
    fig = look.figure(6.4)
    (ax_speed, ax_film), (ax_heat, ax_loss) = fig.subplots(2, 2)
    panels = ((ax_speed, ("sliding_velocity_m_per_s", "sum_velocity_m_per_s"),
               ("sliding", "sum"), "m/s", "Sliding and sum speeds"),
              (ax_film, ("lambda",), ("λ",), "h_min / mean Ra", "Specific film thickness λ"),
              (ax_heat, ("flash_temperature_K",), ("flash",), "K", "Flash temperature"),
              (ax_loss, ("power_loss_W",), ("loss",), "W", "Power lost per contact"))
    for ax, keys, names, unit, title in panels:
        for j, (key, name) in enumerate(zip(keys, names)):
            values = look.column(rows, key)
            for i, g in enumerate(sorted(set(pair[np.isfinite(values)]))):
                on = (pair == g) & np.isfinite(values)
                order = np.argsort(roll[on])
                ax.plot(roll[on][order], values[on][order], "o-" if j == 0 else "s--", ms=3,
                        lw=1.0, color=SERIES[i % len(SERIES)],
                        label=f"{name}, pair {int(g):+d}" if g else f"{name}, pair 0")
        ax.set(xlabel=x_label, ylabel=unit, title=title)
        if ax.get_legend_handles_labels()[0]:     # a panel with no value has no legend
            ax.legend(fontsize=6, loc="best")
    ax_film.axhline(1.0, color="0.4", ls=":", lw=1.0)
    if summary.get("S_lambda") is not None:
        ax_film.axhline(summary["lambda_min"] / summary["S_lambda"], color="crimson", ls="--",
                        lw=1.0, label="λ_GFP")
        ax_film.legend(fontsize=6, loc="best")
    if summary.get("mesh_power_loss_W") is not None:
        ax_loss.set_title(f"Power lost per contact (mesh {summary['mesh_power_loss_W']:.0f} W, "
                          f"η {100 * summary['mesh_efficiency']:.2f} %)", fontsize=9)
    fig.suptitle(look.title(result, "The lubricated contact over the mesh cycle", 95), fontsize=10)
    return look.save(fig, path)


# ---------------------------------------------------------------------------------------
# 3. dispatch


def _driver(result: dict) -> str:
    """The name of a result's driving member: worm, spline hub or pinion."""
    return {"worm": "worm", "spline": "hub"}.get(result.get("kind"), "pinion")


def figures_for(result: dict, out_dir: str | Path) -> list[Path]:
    """Every figure that applies to a result document, written into `out_dir`:
    mesh_cycle.png (any result with 'positions'), ease_off.png (a result with an 'ease_off'
    section: face_mm, radius_mm, separation_um, optional approach_um), crown_design.png
    (kind crown_design), load_distribution.png (a result with a 'load_distribution' section),
    k_chart.png (a result with a 'k_chart' section), path_of_contact.png (a spur or helical
    pair's loaded flank pressures), mesh_loads.png (a result whose positions carry a loaded
    contact's load_share),
    lubrication.png (positions with the lubricated contact's lambda),
    worm_efficiency_temperature.png and worm_efficiency_torque.png
    (kind worm_efficiency, with conditions / an anti-rattle spring). [] when none applies
    (hertz, spline_crown)."""
    out = Path(out_dir)
    kind = result.get("kind")
    written = []
    if result.get("positions"):
        written.append(mesh_cycle(result, out / "mesh_cycle.png"))
    ease = result.get("ease_off")
    if isinstance(ease, dict) and {"face_mm", "radius_mm", "separation_um"} <= ease.keys():
        written.append(ease_off_map(
            ease["face_mm"], ease["radius_mm"],
            np.array([[look.num(v) for v in row] for row in ease["separation_um"]]),
            out / "ease_off.png", approach_um=ease.get("approach_um"),
            title=look.title(result, f"Ease-off: separation on the {ease.get('member', 'pinion')} "
                                 "flank"), member=ease.get("member", "pinion")))
    if result.get("load_distribution"):
        written.append(load_distribution(result, out / "load_distribution.png"))
    if result.get("k_chart"):
        written.append(k_chart(result, out / "k_chart.png"))
    if any(r.get("flank_p_max_MPa") for r in result.get("positions") or []) and \
            kind == "spur":
        written.append(path_of_contact(result, out / "path_of_contact.png"))
    if any(r.get("load_share") is not None for r in result.get("positions") or []):
        written.append(mesh_loads(result, out / "mesh_loads.png"))
    if any(r.get("lambda") is not None for r in result.get("positions") or []):
        written.append(lubrication(result, out / "lubrication.png"))
    if kind == "crown_design":
        written.append(crown_design_chart(result, out / "crown_design.png"))
    if kind == "worm_efficiency":
        if any(r.get("temperature_C") is not None for r in result.get("efficiency") or []):
            written.append(worm_efficiency_vs_temperature(
                result, out / "worm_efficiency_temperature.png"))
        if result.get("misalignment"):
            written.append(worm_efficiency_vs_torque(result, out / "worm_efficiency_torque.png"))
    return written
