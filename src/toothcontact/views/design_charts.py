"""Matplotlib charts of the design studies: seed 003's crown design chart (kind
crown_design) and the worm-set efficiency charts over temperature and torque (kind
worm_efficiency); views.plots.figures_for writes them with a case's other figures.

Each function takes a result document as written to result.json and an output path,
draws on its own figure (look.figure) and writes it whole (look.save), returning the path.
Units: mm, mrad, MPa, N·m, °C as the labels say."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from matplotlib.legend_handler import HandlerTuple

from . import style as look
from .style import DESIGN, SERIES

# ---------------------------------------------------------------------------------------
# 1. crown design chart (seed 003)


def crown_design_curves(result: dict) -> dict:
    """The crown design chart's curves as the analysis computed them (result['crown_chart'],
    analytic.crown.design_chart), as arrays (NaN where a rule has no radius), with the
    chosen crown's radius, centre and face width."""
    chart = result["crown_chart"]
    return {"theta": np.asarray(chart["theta_rad"], float),
            "edge_radius_mm": {end: np.array([look.num(r) for r in radii])
                               for end, radii in chart["edge_radius_mm"].items()},
            "stress_radius_mm": look.num(chart["stress_radius_mm"]),
            "reference_stress_MPa": chart["reference_stress_MPa"],
            "reference": chart["reference"], "design_radius_mm": result["crown"]["radius_mm"],
            "design_stress_MPa": chart["design_stress_MPa"], "slope_A": chart["slope_A"],
            "slope_B": chart["slope_B"], "center_from_B_mm": result["crown"]["center_from_B_mm"],
            "face_width_mm": chart["face_width_mm"], "edge_clearance_mm": chart["edge_clearance_mm"],
            "full": chart["full"]}


def crown_design_chart(result: dict, path: str | Path) -> Path:
    """Seed 003's crown design chart: crown radius R (mm, log scale) against the total slope
    theta (misalignment + deflection, mrad).

    The edge rule (eq 13, R·theta + a = room to the face end) bounds R from above, per face
    end for an off-centre crown; the stress rule (crowned Hertz stress = allowable, or the chosen
    design's stress when the case gives none) bounds it from below. The chosen crown
    (result['crown']) is marked at the case's slope_A (and slope_B)."""
    curves = crown_design_curves(result)
    theta_mrad = 1e3 * curves["theta"]
    R = curves["design_radius_mm"]
    fig = look.figure(5.6)
    ax = fig.subplots()
    colours = {"A": SERIES[0], "B": SERIES[2]}
    full = curves["full"]
    F, c = curves["face_width_mm"], curves["center_from_B_mm"]
    clearance = curves["edge_clearance_mm"]
    less = f" − {clearance:g}" if clearance else ""
    for end, radii in curves["edge_radius_mm"].items():
        if full:
            text = f"edge rule (eq 13): R·θ + a = F/2{less} = {F / 2 - clearance:.2f} mm"
        elif end == "A":
            text = f"edge rule, end A: R·θ + a = F − c{less} = {F - c - clearance:.2f} mm"
        else:
            text = f"edge rule, end B: R·θ + a = c{less} = {c - clearance:.2f} mm"
        ax.plot(theta_mrad, radii, color=colours[end], lw=2.0, label=text)
    R_min = curves["stress_radius_mm"]
    slopes = [("A", curves["slope_A"])] if full else [("A", curves["slope_A"]),
                                                     ("B", curves["slope_B"])]
    if curves["reference"] == "allowable":
        text = (f"stress rule: σ_c = allowable {curves['reference_stress_MPa']:.0f} MPa"
                if math.isfinite(R_min) else "stress rule: no crown radius meets the allowable")
        blocked = [end for end, slope in slopes if math.isfinite(R_min) and R_min > float(
            np.interp(slope, curves["theta"], curves["edge_radius_mm"][end]))]
        if blocked:
            text += (f"\n(above the edge rule at θ_{', θ_'.join(blocked)}: no radius meets both"
                     + ("" if full else " with this crown centre") + ")")
    else:
        text = ("stress reference: σ_c of the chosen design, "
                f"{curves['reference_stress_MPa']:.0f} MPa (no allowable_stress given)")
    if math.isfinite(R_min):
        ax.axhline(R_min, color=SERIES[1], lw=2.0, ls="--", label=text)
        if full:
            upper = curves["edge_radius_mm"]["A"]
            ax.fill_between(theta_mrad, R_min, upper, where=upper >= R_min, color=SERIES[1],
                            alpha=0.12, lw=0, label="both rules met")
    else:
        ax.plot([], [], color=SERIES[1], lw=2.0, ls="--", label=text)

    for end, slope in slopes:
        ax.plot(1e3 * slope, R, "*", ms=18, color=DESIGN, mec="black", mew=1.0, zorder=6,
                clip_on=False)
        ax.annotate(f"θ_{end} = {1e3 * slope:.3g} mrad", (1e3 * slope, R), xytext=(10, 10),
                    textcoords="offset points", fontsize=8)
    uncrowned = (result.get("uncrowned") or {}).get("agma_stress_MPa")
    design_label = (f"chosen crown: R = {R:.4g} mm, c = {c:.4g} mm from B, "
                    f"σ_c = {curves['design_stress_MPa']:.0f} MPa")
    if uncrowned is not None:
        design_label += f"\n(uncrowned AGMA eq 3: {uncrowned:.0f} MPa)"
    ax.plot([], [], "*", ms=14, color=DESIGN, mec="black", ls="none", label=design_label)

    if math.isfinite(R_min) and curves["reference"] == "allowable":
        for end, radii in curves["edge_radius_mm"].items():  # largest slope within both rules
            above = np.nonzero(np.isfinite(radii) & (radii >= R_min))[0]
            if len(above) and above[-1] + 1 < len(radii):
                i = above[-1]
                t = np.interp(R_min, radii[i:i + 2][::-1], theta_mrad[i:i + 2][::-1])
                ax.plot(t, R_min, "o", ms=8, mfc="white", mec=colours[end], mew=2.0, zorder=5,
                        label=f"largest slope within both rules{'' if full else ' at end ' + end}: "
                              f"{t:.3g} mrad")
    ax.set_yscale("log")
    look.plain_log(ax.yaxis)
    finite = [v for r in curves["edge_radius_mm"].values() for v in r[np.isfinite(r)]]
    span = [R] + ([R_min] if math.isfinite(R_min) else []) + finite
    ref = max(R, R_min) if math.isfinite(R_min) else R
    ax.set_ylim(0.6 * min(span), 1.6 * min(max(span), 10.0 * ref))
    ax.set_xlim(0.0, theta_mrad[-1])
    ax.grid(True, which="both", alpha=0.3)
    ax.set(xlabel="total slope θ, misalignment + deflection (mrad = mm/m)",
           ylabel="crown radius R (mm)",
           title=look.title(result, ("Full" if full else "Off-centre") + " crown design chart"))
    ax.legend(loc="upper center", fontsize=8, bbox_to_anchor=(0.5, -0.13), ncol=1,
              frameon=False)
    return look.save(fig, path)


# ---------------------------------------------------------------------------------------
# 2-3. worm set efficiency


def worm_efficiency_vs_temperature(result: dict, path: str | Path) -> Path:
    """Worm set efficiency over lubricant temperature (seed 000, DIN 3996 with Y_VISC).

    Top: computed eta_total, eta_z, eta_kim (and eta_wheel_driving when not self-locking)
    per result['efficiency'] row as lines over temperature_C (°C); the source's published
    eta_total and eta_z (inputs.conditions) as points, hollow where the result's checks
    found the published column inconsistent. Bottom: mean friction mu_zm, computed and
    published."""
    rows = [r for r in result.get("efficiency") or [] if r.get("temperature_C") is not None]
    if not rows:
        raise ValueError("worm_efficiency_vs_temperature: no efficiency rows with a temperature")
    published = [{"temperature": r["temperature_C"], **{k: v for k, v in r.items()
                                                        if k.startswith("published_")}}
                 for r in rows]
    order = np.argsort([r["temperature_C"] for r in rows])
    rows = [rows[i] for i in order]
    T = look.column(rows, "temperature_C")
    fig = look.figure(6.6)
    ax, ax_mu = fig.subplots(2, 1, sharex=True, height_ratios=(2.2, 1.0))
    failed = [c["name"] for c in result.get("checks") or [] if not c.get("ok")]
    series = [("eta_total", "η_total = η_z·η_spindle", SERIES[0], "-", "o"),
              ("eta_z", "η_z, tooth, worm driving (DIN 3996)", SERIES[1], "-", "s"),
              ("eta_kim", "η, seed 001 eq (2), same μ_zm", SERIES[2], ":", None),
              ("eta_wheel_driving", "η_z', wheel driving (0 = self-locking)", SERIES[3], "-.",
               None)]
    handles, labels, extra = [], [], []
    for key, text, colour, ls, marker in series:
        values = look.column(rows, key)
        if not np.isfinite(values).any() or (key == "eta_wheel_driving" and not np.any(values > 0)):
            continue
        (line,) = ax.plot(T, values, ls, color=colour, lw=1.8)
        entry, label = [line], f"{text}: computed"
        pts = [(c["temperature"], c[f"published_{key}"]) for c in published
               if c.get(f"published_{key}") is not None] if marker else []
        if pts:
            t, v = np.array(pts).T
            bad = np.array([any(f"published {key.replace('eta_total', 'eta_tot')}" in n
                                and f"at {tt:g} °C" in n for n in failed) for tt in t])
            (good,) = ax.plot(t[~bad], v[~bad], marker, color=colour, ms=7, mec="black", mew=0.6,
                              ls="none")
            entry.append(good)
            label += " (line), published (points)"
            if bad.any():
                (hollow,) = ax.plot(t[bad], v[bad], marker, mfc="white", mec=colour, ms=8,
                                    mew=1.6, ls="none")
                name = text.split(" =")[0].split(",")[0]
                extra.append((hollow, f"published {name} that the source's own columns "
                                      + "contradict (see checks)"))
        handles.append(tuple(entry))
        labels.append(label)
    handles += [h for h, _ in extra]
    labels += [t for _, t in extra]
    ax.set(ylabel="efficiency (–)", title=look.title(result, "Worm set efficiency over temperature"))
    ax.legend(handles, labels, fontsize=8, loc="center right",
              handler_map={tuple: HandlerTuple(ndivide=None)})
    ax.grid(True, alpha=0.3)

    ax_mu.plot(T, look.column(rows, "mu_zm"), "-", color=SERIES[4], lw=1.8,
               label="computed μ_zm = μ_0T·Y_S·Y_G·Y_W·Y_R·Y_VISC")
    pts = [(c["temperature"], c["published_mu_zm"]) for c in published
           if c.get("published_mu_zm") is not None]
    if pts:
        t, v = np.array(pts).T
        ax_mu.plot(t, v, "D", color=SERIES[4], mec="black", mew=0.6, ms=6, ls="none",
                   label="published μ_zm")
    ax_mu.set(xlabel="lubricant temperature (°C)", ylabel="mean friction μ_zm (–)")
    ax_mu.legend(fontsize=8, loc="upper right")
    ax_mu.grid(True, alpha=0.3)
    return look.save(fig, path)


def worm_torque_curves(result: dict) -> dict:
    """Seed 001's anti-rattle-spring model over output torque as the analysis computed it
    (result['anti_rattle_curve']: N·m, N, mm), as arrays."""
    curve = result.get("anti_rattle_curve")
    if not curve:
        raise ValueError("worm_torque_curves: the result has no anti-rattle spring curve")
    return {**{key: np.asarray(curve[key], float) for key in
               ("output_torque_Nm", "spring_force_N", "misalignment_mm", "normal_load_N")},
            "eta_aligned": np.full(len(curve["output_torque_Nm"]), curve["eta_aligned"]),
            "mu_zm": curve["mu_zm"]}


def worm_efficiency_vs_torque(result: dict, path: str | Path) -> Path:
    """Worm set efficiency against output torque with and without the anti-rattle spring's
    misalignment (seed 001), with the shaft-end misalignment (mm) and the loads (N) below.

    With the case's [contact] (seed 001's pressure-dependent friction) the rows carry both
    efficiencies, eta_kim_aligned and eta_kim, drawn with the constant-mu curve for
    reference. Without it: eq (2) at the case's mu_zm; seed 001 lets the tilt act only
    through the friction law mu = c·p^n, so at a constant mu_zm both are the same curve, and
    the chart says so."""
    rows = result.get("misalignment") or []
    if not rows:
        raise ValueError("worm_efficiency_vs_torque: the result has no 'misalignment' rows")
    curves = worm_torque_curves(result)
    Tq = curves["output_torque_Nm"]
    T_rows = look.column(rows, "output_torque_Nm")
    fig = look.figure(7.4)
    ax_eta, ax_x, ax_f = fig.subplots(3, 1, sharex=True, height_ratios=(1.3, 1.0, 1.0))
    fig.suptitle(look.title(result, "Worm set efficiency over output torque", 110), fontsize=11)

    eta_tilted = look.column(rows, "eta_kim")
    mu = curves["mu_zm"]
    if "eta_kim_aligned" in rows[0]:
        # seed 001's full chain: pressure (eq 19) -> mu = c·p^n -> eq (2), per torque (no
        # efficiency without output torque)
        on = T_rows > 0
        ax_eta.plot(T_rows[on], look.column(rows, "eta_kim_aligned")[on], "o-", color=SERIES[0],
                    lw=1.8, ms=5, label="without misalignment: μ(p) at the tooth load (eqs 19, 2)")
        ax_eta.plot(T_rows[on], eta_tilted[on], "s-", color=SERIES[2], lw=1.8, ms=5,
                    label="with the spring's preload and tilt: μ(p) on the total load")
        ax_eta.plot(Tq, curves["eta_aligned"], "--", color="0.5", lw=1.0,
                    label=f"constant μ = {mu:.3g} (eq 2)")
    elif np.isfinite(eta_tilted).any():
        ax_eta.plot(Tq, curves["eta_aligned"], "-", color=SERIES[0], lw=1.8,
                    label=f"without misalignment: seed 001 eq (2), μ = {mu:.3g}")
        ax_eta.plot(T_rows, eta_tilted, "o-", color=SERIES[2], lw=1.8, ms=5,
                    label="with the spring's misalignment")
    else:
        ax_eta.plot(Tq, curves["eta_aligned"], "-", color=SERIES[0], lw=1.8,
                    label="with and without misalignment: seed 001 eq (2) at constant "
                          f"μ = {mu:.3g}")
        ax_eta.text(0.01, 0.06, "seed 001 lets the shaft tilt act only through μ = c·p^n; the "
                    "case gives a constant μ,\nso the two curves coincide",
                    transform=ax_eta.transAxes, fontsize=8, color="0.25")
    if "eta_kim_aligned" not in rows[0]:
        ax_eta.plot(T_rows, np.interp(T_rows, Tq, curves["eta_aligned"]), "o", color=SERIES[0],
                    ms=5, ls="none", label="torques of the case")
    look.plain_axis(ax_eta.yaxis)
    lo, hi = ax_eta.get_ylim()
    if hi - lo < 0.02:
        mid = 0.5 * (lo + hi)
        ax_eta.set_ylim(mid - 0.03, mid + 0.02)
    ax_eta.set(ylabel="efficiency (–)")
    ax_eta.legend(fontsize=8, loc="lower right")

    x = curves["misalignment_mm"]
    ax_x.plot(Tq, x, "-", color=SERIES[2], lw=1.8,
              label="shaft-end misalignment x (eq 21), left axis")
    ax_x.plot(T_rows, look.column(rows, "misalignment_mm"), "o", color=SERIES[2], ms=5, ls="none",
              label="the case's torques (result)")
    ax_x.axhline(0.0, color="black", lw=0.8, ls="--")
    if np.any(np.diff(np.sign(x)) != 0):
        zero = float(np.interp(0.0, x, Tq)) if np.all(np.diff(x) > 0) else math.nan
        if math.isfinite(zero):
            ax_x.annotate(f"aligned at {zero:.2f} N·m", (zero, 0.0), xytext=(8, -16),
                          textcoords="offset points", fontsize=8)
    ax_x.set(ylabel="misalignment x (mm)")
    # the spring force is proportional to x (eq 21): its scale on the right, same curve
    force = curves["spring_force_N"]
    i = int(np.argmax(np.abs(x)))
    if x[i] != 0.0:
        ax_s = ax_x.twinx()
        ax_s.set_ylim(*(np.array(ax_x.get_ylim()) * force[i] / x[i]))
        ax_s.plot(T_rows, look.column(rows, "spring_force_N"), "x", color="black", ms=6,
                  ls="none")
        ax_s.set_ylabel("spring force F_ARS (N)")
        ax_x.plot([], [], "x", color="black", ms=6, ls="none",
                  label="spring force F_ARS (eq 20) of the result, right axis")
    ax_x.legend(fontsize=8, loc="upper left")

    ax_f.plot(Tq, curves["normal_load_N"], "-", color=SERIES[3], lw=1.8,
              label="tooth normal load F_n (eq 3)")
    ax_f.plot(T_rows, look.column(rows, "normal_load_N"), "o", color=SERIES[3], ms=5, ls="none",
              label="the case's torques (result)")
    ax_f.set(xlabel="output (wheel) torque (N·m)", ylabel="normal load (N)")
    ax_f.legend(fontsize=8, loc="upper left")
    for ax in (ax_eta, ax_x, ax_f):
        ax.grid(True, alpha=0.3)
    ax_f.set_xlim(0.0, Tq[-1])
    return look.save(fig, path)
