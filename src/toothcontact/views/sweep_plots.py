"""Matplotlib figures of a sweep: maps and response curves of its figures over its inputs,
histograms, the Sobol indices and tornado of a tolerance study, the Harris map and the
optimisation's history; drawn and written as a case's (style)."""

from __future__ import annotations

import math
import textwrap
from pathlib import Path

import numpy as np
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Rectangle

from . import style as look
from .style import SERIES, WARNING

# ---------------------------------------------------------------------------------------
# sweeps

#: the figures a sweep's plots show, the first present being the primary one (the
#: tornado's and the response curves'), with their axis labels
SWEEP_FIGURES = {
    "bem_max_p_max_MPa": "largest loaded pressure (MPa)",
    "flank_pressure_max_MPa": "largest active-flank pressure (MPa)",
    "max_p_max_MPa": "largest Hertz pressure (MPa)",
    "max_edge_pressure_MPa": "largest edge pressure (MPa)",
    "loaded_transmission_error_peak_to_peak_um": "loaded TE peak to peak (µm)",
    "loaded_transmission_error_peak_to_peak_urad": "loaded TE peak to peak (µrad)",
    "transmission_error_peak_to_peak_um": "unloaded TE peak to peak (µm)",
    "transmission_error_peak_to_peak_urad": "unloaded TE peak to peak (µrad)",
    "worst_face_edge_margin_mm": "worst face-edge margin (mm)",
}


#: the grid fields a Harris map reads as the load (x) and as the relief (one curve each)
LOAD_FIELDS = ("load.torque", "load.tangential_load")
RELIEF_WORD = "relief"


def sweep_figures(rows: list[dict], stats: dict, out_dir: str | Path) -> list[Path]:
    """A sweep's figures from its table (`rows`, samples.parquet's records) and statistics
    (sweep.json's, which name its title, grid and toleranced inputs):
    - histograms.png: each figure of SWEEP_FIGURES present, with P5, P50 and P95;
    - tornado.png: each toleranced input's total and first Sobol index for the primary
      figure (Saltelli's design), else its rank correlation;
    - response.png: the primary figure's median and P5-P95 band over each numeric grid axis;
    - map.png: over the first two numeric grid axes (crown × slope: the robustness map) the
      primary figure's median, the region loaded at a face end outlined;
    - harris.png: loaded TE peak to peak over the load, one curve per relief (Harris's map),
      when the grid varies a load and a relief;
    - optimisation.png: the objective of every design tried, and the path of the design.
    The primary figure is the first of SWEEP_FIGURES the samples report; the curves and
    maps draw the statistics' groups (per axis level, per grid point: P5/P50/P95)."""
    out = Path(out_dir)
    title = stats.get("title", "sweep")
    ok = [r for r in rows if r.get("status") == "ok"]
    present = [k for k in SWEEP_FIGURES if np.isfinite(look.column(ok, k)).any()]
    # a transmission error once: in µm where the samples give it, else in µrad
    present = [k for k in present if not (k.endswith("_urad") and k[:-5] + "_um" in present)]
    if not present:
        return []
    written = [_sweep_histograms(ok, stats, present, title, out / "histograms.png")]
    primary = present[0]
    sobol = stats.get("sobol", {}).get("indices", {})
    ranks = {f: stats.get("sensitivity", {}).get(f, {}).get(primary)
             for f in stats.get("inputs", [])}
    if any(primary in sobol.get(f, {}) for f in stats.get("inputs", [])):
        written.append(_sweep_sobol({f: sobol[f][primary] for f in sobol
                                     if primary in sobol[f]}, primary, title,
                                    out / "tornado.png"))
    elif any(rho is not None for rho in ranks.values()):
        intervals = {f: stats.get("sensitivity_interval", {}).get(f, {}).get(primary)
                     for f in ranks}
        written.append(_sweep_tornado({f: r for f, r in ranks.items() if r is not None},
                                      intervals, stats.get("sensitivity_draws"), primary,
                                      title, out / "tornado.png"))
    response = stats.get("response", {})
    axes = [f for f in stats.get("grid", []) if f in response]
    if axes:
        written.append(_sweep_response(response, axes, primary, title, out / "response.png"))
    points = stats.get("grid_points", [])
    if len(axes) >= 2:
        written.append(_sweep_map(points, axes[:2], primary, title, out / "map.png"))
    load = next((f for f in axes if f in LOAD_FIELDS), None)
    relief = next((f for f in axes if RELIEF_WORD in f), None)
    te = next((f"loaded_transmission_error_peak_to_peak_{unit}" for unit in ("um", "urad")
               if f"loaded_transmission_error_peak_to_peak_{unit}" in present), None)
    if load and relief and te:
        written.append(_sweep_harris(points, load, relief, te, title, out / "harris.png"))
    if stats.get("optimise", {}).get("history"):
        written.append(_sweep_optimisation(stats["optimise"], title,
                                           out / "optimisation.png"))
    return written


def _median_at(points: list[dict], figure: str, **inputs) -> float:
    """The figure's median at the grid points with the given inputs (the first such point
    that reports it; NaN where none does)."""
    for point in points:
        if all(point["inputs"].get(k) == v for k, v in inputs.items()):
            value = point["percentiles"].get(figure, {}).get("P50")
            if value is not None:
                return value
    return math.nan


def _axis_levels(points: list[dict], field: str) -> np.ndarray:
    return np.unique([p["inputs"][field] for p in points
                      if isinstance(p["inputs"].get(field), float)])


def _sweep_map(points, axes, primary, title, path) -> Path:
    """The primary figure's median over a grid of two axes (the first grid point of each
    pair of their values; a cell without answers is blank); the cells where half or more
    of the samples are loaded at a face end hatched and outlined."""
    xs, ys = (_axis_levels(points, f) for f in axes)
    median = np.array([[_median_at(points, primary, **{axes[0]: x, axes[1]: y}) for x in xs]
                       for y in ys])
    ended = np.array([[next((p.get("end_loading", 0.0) for p in points
                             if p["inputs"].get(axes[0]) == x and p["inputs"].get(axes[1]) == y),
                            0.0) for x in xs] for y in ys])
    fig = look.figure(4.6)
    ax = fig.add_subplot()
    mesh = ax.pcolormesh(xs, ys, median, shading="nearest", cmap="viridis")
    fig.colorbar(mesh, ax=ax, label=f"median {SWEEP_FIGURES[primary]}")
    xe, ye = _cell_edges(xs), _cell_edges(ys)
    for i, j in zip(*np.nonzero(ended >= 0.5)):
        ax.add_patch(Rectangle((xe[j], ye[i]), xe[j + 1] - xe[j], ye[i + 1] - ye[i],
                               fill=False, hatch="//", edgecolor="w", linewidth=0.0))
    if (ended >= 0.5).any():
        ax.legend(handles=[Patch(facecolor="0.5", hatch="//", edgecolor="w",
                                 label="loaded at a face end in half the samples or more")],
                  fontsize="small", loc="upper right")
    ax.set_xlabel(f"{axes[0]} (core units: mm, N, MPa, rad)")
    ax.set_ylabel(f"{axes[1]} (core units)")
    fig.suptitle(textwrap.fill(f"{title} (median at each grid point)", 90))
    return look.save(fig, path)


def _cell_edges(centres: np.ndarray) -> np.ndarray:
    """The edges of cells around sorted centres (midway; the end cells symmetric), as
    pcolormesh's 'nearest' shading draws them."""
    if centres.size == 1:
        return np.array([centres[0] - 0.5, centres[0] + 0.5])
    mid = (centres[1:] + centres[:-1]) / 2
    return np.concatenate([[2 * centres[0] - mid[0]], mid, [2 * centres[-1] - mid[-1]]])


def _sweep_harris(points, load, relief, te, title, path) -> Path:
    """Harris's map: loaded TE peak to peak (the median at each grid point) against the
    load, one curve per relief."""
    fig = look.figure(4.2)
    ax = fig.add_subplot()
    loads = _axis_levels(points, load)
    for k, level in enumerate(_axis_levels(points, relief)):
        te_at = np.array([_median_at(points, te, **{load: x, relief: level}) for x in loads])
        ax.plot(loads, te_at, "o-", color=SERIES[k % len(SERIES)], label=f"{level * 1e3:g} µm")
    ax.set_xlabel(f"{load} (core units: N, N·mm)")
    ax.set_ylabel(SWEEP_FIGURES[te])
    ax.set_ylim(bottom=0)
    ax.legend(fontsize="small", title=relief, title_fontsize="small")
    fig.suptitle(textwrap.fill(f"{title} (median at each grid point)", 90))
    return look.save(fig, path)


def _sweep_optimisation(opt, title, path) -> Path:
    """The objective of each design the optimiser tried (feasible filled, infeasible open,
    the best starred) and each design variable against the evaluation."""
    history = opt["history"]
    n = [h["evaluation"] for h in history]
    fig = look.figure(2.8 + 2.0 * len(opt["variables"]))
    grid = fig.add_gridspec(1 + len(opt["variables"]), 1,
                            height_ratios=[1.6] + [1.0] * len(opt["variables"]))
    ax = fig.add_subplot(grid[0])
    objective = np.array([h["objective"] for h in history], dtype=float)
    feasible = np.array([h["feasible"] for h in history])
    ax.plot(n, objective, "-", color="0.6", linewidth=0.8)
    ax.plot(np.array(n)[feasible], objective[feasible], "o", color=SERIES[0],
            label="feasible")
    ax.plot(np.array(n)[~feasible], objective[~feasible], "o", mfc="none", color=SERIES[2],
            label="infeasible")
    best = opt["best"]
    if best["feasible"]:
        ax.plot([best["evaluation"]], [best["objective"]], "*", ms=14, color="k",
                label="best feasible design")
    else:
        ax.plot([best["evaluation"]], [best["objective"]], "*", ms=14, mfc="none",
                mec=WARNING, mew=1.5, label="best tried: no design met the constraints")
    ax.set_ylabel(_statistic_label(opt["objective"]))
    ax.legend(fontsize="small")
    for k, variable in enumerate(opt["variables"]):
        axv = fig.add_subplot(grid[k + 1], sharex=ax)
        values = [float(str(h["design"][variable["field"]]).split()[0]) for h in history]
        axv.plot(n, values, "o-", color=SERIES[1], markersize=4)
        unit = str(history[0]["design"][variable["field"]]).partition(" ")[2]
        axv.set_ylabel(f"{variable['field']}" + (f"\n({unit})" if unit else ""))
    fig.axes[-1].set_xlabel("evaluation (one sweep over the samples each)")
    fig.suptitle(textwrap.fill(f"{title}: optimisation ({opt['evaluations']} designs; "
                               f"constraints: " + (", ".join(
                                   f"{_statistic_label(c['statistic'])} ≤ {c['max']:g}"
                                   for c in opt["constraints"]) or "none") + ")", 90))
    return look.save(fig, path)


def _statistic_label(text: str) -> str:
    """A sweep statistic as a reader names it: 'P95 bem_max_p_max_MPa' -> 'P95 of the
    largest loaded pressure (MPa)', 'end_loading' -> 'probability of loading at a face end'."""
    from ..sweep.spec import PROBABILITIES
    from .labels import label

    if text in PROBABILITIES:
        return {"edge_loading": "probability of edge loading",
                "end_loading": "probability of loading at a face end"}[text]
    name, _, figure = text.partition(" ")
    return f"{name} of the {SWEEP_FIGURES.get(figure) or label(figure)}"


def _sweep_sobol(indices: dict, primary: str, title: str, path) -> Path:
    """Each toleranced input's total (bar) and first (dark bar) Sobol index of the primary
    figure, with their 95 % bootstrap half-widths."""
    order = sorted(indices, key=lambda f: indices[f]["ST"])
    fig = look.figure(1.5 + 0.55 * len(order))
    ax = fig.add_subplot()
    at = np.arange(len(order))
    ax.barh(at + 0.2, [indices[f]["ST"] for f in order], 0.4,
            xerr=[indices[f]["ST_conf"] for f in order], color=SERIES[0], label="total")
    ax.barh(at - 0.2, [indices[f]["S1"] for f in order], 0.4,
            xerr=[indices[f]["S1_conf"] for f in order], color=SERIES[2], label="first order")
    ax.set_yticks(at, order)
    ax.set_xlim(0.0, 1.05)
    ax.set_xlabel(f"Sobol index of the {SWEEP_FIGURES[primary]} (share of its variance)")
    ax.legend(fontsize="small")
    fig.suptitle(textwrap.fill(f"{title}: sensitivity to the toleranced inputs", 90))
    return look.save(fig, path)


def _sweep_histograms(rows, stats, keys, title, path) -> Path:
    """Each figure's histogram with its P5, P50 and P95; under a load spectrum one
    histogram and median per load level (the levels' figures differ: pooled, they make
    one histogram with a median between its humps) and the time-weighted percentiles."""
    columns = 2 if len(keys) > 1 else 1
    lines = math.ceil(len(keys) / columns)
    fig = look.figure(2.6 * lines + 0.9)
    fig.suptitle(textwrap.fill(f"{title}: {len(rows)} samples answered", 90))
    spectrum = stats.get("spectrum")
    levels = ([("all samples", 1.0, np.ones(len(rows), bool))] if not spectrum
              else _spectrum_levels(rows, spectrum))
    quantiles = (stats.get("time_weighted") or stats).get("percentiles", {})
    for i, key in enumerate(keys):
        ax = fig.add_subplot(lines, columns, i + 1)
        every = look.column(rows, key)
        for j, (text, share, chosen) in enumerate(levels):
            values = every[chosen & np.isfinite(every)]
            colour = SERIES[j % len(SERIES)]
            # each level's own bins: the levels' figures may lie far apart
            bins = min(30, max(5, values.size // 3))
            ax.hist(values, bins=bins, color=colour, alpha=0.55 if spectrum else 1.0,
                    label=f"{spectrum['field']} = {text} ({share:.0%} of the time)"
                    if spectrum else None)
            if spectrum and values.size:
                ax.axvline(float(np.median(values)), color=colour, linewidth=1.6)
        for q, style in (("P5", ":"), ("P50", "-"), ("P95", ":")):
            at = quantiles.get(key, {}).get(q)
            if at is not None:
                ax.axvline(at, color="k", linestyle=style, linewidth=1.0,
                           label=f"{q} over the operating time" if spectrum else q)
        ax.set_xlabel(SWEEP_FIGURES[key])
        ax.set_ylabel("samples")
    handles, labels = fig.axes[0].get_legend_handles_labels()
    if spectrum:
        handles.append(Line2D([], [], color="0.3", linewidth=1.6))
        labels.append("a level's median (its colour)")
    fig.legend(handles, labels, loc="outside lower center", fontsize="small", frameon=False,
               ncol=2 if spectrum else 3)
    return look.save(fig, path)


def _spectrum_levels(rows: list[dict], spectrum: dict) -> list[tuple[str, float, np.ndarray]]:
    """Per load level of a spectrum: its text, its share of the time and which rows ran
    at it. The sampler runs the levels in their order, so the rows' values in their order
    of appearance are the levels'; where a level has no answered sample, the levels are
    named by their values (core units) and shares by the rows' time shares."""
    column = look.column(rows, f"input:{spectrum['field']}")
    values = list(dict.fromkeys(v for v in column.tolist() if math.isfinite(v)))
    if len(values) == len(spectrum["levels"]):
        return [(str(text), share, column == value)
                for text, share, value in zip(spectrum["levels"], spectrum["shares"], values)]
    shares = look.column(rows, "time_share")
    total = float(np.nansum(shares)) or 1.0
    return [(f"{value:g}", float(np.nansum(shares[column == value])) / total, column == value)
            for value in values]


def _sweep_tornado(ranks: dict, intervals: dict, draws: int | None, primary: str,
                   title: str, path) -> Path:
    """Each toleranced input's rank correlation with the primary figure, with its 95 %
    interval where the draws allow one (sweep.statistics.spearman_interval); the number of
    draws it rests on in the axis label."""
    order = sorted(ranks, key=lambda f: abs(ranks[f]))
    fig = look.figure(1.7 + 0.45 * len(order))
    ax = fig.add_subplot()
    values = [ranks[f] for f in order]
    bounds = [intervals.get(f) for f in order]
    errors = np.array([[v - b[0], b[1] - v] if b else [0.0, 0.0]
                       for v, b in zip(values, bounds)]).T
    ax.barh(order, values, color=[SERIES[0] if v >= 0 else SERIES[2] for v in values],
            xerr=errors if any(bounds) else None, capsize=4, ecolor="k")
    ax.axvline(0.0, color="k", linewidth=0.8)
    ax.set_xlim(-1.0, 1.0)
    basis = (f"; {draws} draws per point" if draws else "") + (
        ", 95 % intervals" if any(bounds) else
        ": too few for an interval, read it as a hint" if draws else "")
    ax.set_xlabel(textwrap.fill(f"Spearman rank correlation with the "
                                f"{SWEEP_FIGURES[primary]}{basis}", 90))
    fig.suptitle(textwrap.fill(f"{title}: sensitivity to the toleranced inputs", 90))
    return look.save(fig, path)


def _sweep_response(response, axes, primary, title, path) -> Path:
    """The primary figure's median and P5-P95 band at each level of each grid axis (over
    the other inputs)."""
    fig = look.figure(2.8 * len(axes) + 0.6)
    fig.suptitle(textwrap.fill(f"{title}: {SWEEP_FIGURES[primary]} over the grid", 90))
    for i, field in enumerate(axes):
        ax = fig.add_subplot(len(axes), 1, i + 1)
        levels = [g for g in response[field] if primary in g["percentiles"]]
        x = [g["value"] for g in levels]
        q = [g["percentiles"][primary] for g in levels]
        ax.fill_between(x, [v["P5"] for v in q], [v["P95"] for v in q], color=SERIES[0],
                        alpha=0.25, label="P5-P95 over the other inputs")
        ax.plot(x, [v["P50"] for v in q], "o-", color=SERIES[0], label="median")
        ax.set_xlabel(f"{field} (core units: mm, N, MPa, rad)")
        ax.set_ylabel(SWEEP_FIGURES[primary])
        ax.legend(fontsize="small")
    return look.save(fig, path)
