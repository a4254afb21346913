"""What a sweep's table says: per output figure its percentiles over the samples that
answered (P5, P50, P95, P99), the probability of edge loading with its Wilson score
interval (95 %) (at any flank edge, and at a face end), and for each toleranced input its
Spearman rank correlation with each figure (the sensitivity ranking: a monotone influence,
whatever its shape), taken within each grid point (where the grid holds the other inputs
still: the draws are the same at every point) and averaged over the grid points; with
Saltelli's design also each input's first and total Sobol indices (SALib.analyze.sobol:
Saltelli et al., Comput. Phys. Commun. 181 (2010) 259-270, table 2, estimators (b) for S1
and (f), Jansen's, for ST), likewise per grid point and averaged. Under a load spectrum
the same figures weighted by each sample's share of the operating time. Per grid point,
and per level of each numeric grid axis, P5/P50/P95 of each figure and the fractions of
samples edge- and end-loaded (the response curves and maps draw these). Each rank
correlation has its 95 % interval (spearman_interval) where the draws allow one."""

from __future__ import annotations

import math
import warnings

import numpy as np

#: the percentiles reported per figure
PERCENTILES = (5, 50, 95, 99)
#: the normal quantile of the two-sided 95 % interval
Z95 = 1.959963984540054
#: per loading flag, the summary's counts that raise it, the first a sample reports: the
#: loaded contact's edge-loaded contacts at any flank edge (tip, root, face end), at a face
#: end, or its corner contacts (a tip, root or form edge), else the rigid analysis's
#: contacts a face end cuts; a sample is so loaded where the count is above zero
FLAGS = {"edge_loading": ("edge_loaded_contacts", "edge_contacts"),
         "end_loading": ("end_loaded_contacts", "edge_contacts"),
         "corner_contact": ("corner_contacts",)}


def summarise(rows: list[dict], inputs: list[str], grid: list[str] = (),
              saltelli: bool = False) -> dict:
    """The sweep's statistics (see the module) from its records; `inputs`: the toleranced
    fields, `grid`: the varied ones (their columns are `input:FIELD`); `saltelli`: the
    draws are Saltelli's design (sweep.sampling), so Sobol indices can be had."""
    ok = [r for r in rows if r.get("status") == "ok"]
    figures = sorted({k for r in ok for k, v in r.items()
                      if k not in ("sample", "time_share") and not k.startswith("input:")
                      and isinstance(v, float) and not isinstance(v, bool)})
    out = {"samples": len(rows), "ok": len(ok), "failed": len(rows) - len(ok),
           "failures": {r["sample"]: r["status"] for r in rows if r.get("status") != "ok"},
           "percentiles": {}, "sensitivity": {}}
    out["percentiles"] = _percentiles(ok, figures, PERCENTILES)
    flags = {flag: key for flag, keys in FLAGS.items()
             if (key := next((k for k in keys if any(k in r for r in ok)), None))}
    for flag, key in flags.items():
        hits = sum((r.get(key) or 0) > 0 for r in ok)
        out[flag] = {"key": key, "samples": len(ok), "loaded": hits,
                     "probability": hits / len(ok) if ok else None,
                     "interval_95": wilson(hits, len(ok))}
    if ok and all(isinstance(r.get("time_share"), float) for r in ok):
        out["time_weighted"] = _time_weighted(ok, figures, flags)
    points: dict[tuple, list[dict]] = {}
    for r in ok:
        points.setdefault(tuple(r.get(f"input:{f}") for f in grid), []).append(r)
    if grid:
        out["grid_points"] = [_group(dict(zip(grid, point)), group, figures, flags)
                              for point, group in points.items()]
        out["response"] = _response(ok, grid, figures, flags)
    if saltelli:
        out["sobol"] = _sobol(rows, inputs, grid, figures)
    for field in inputs:
        column = f"input:{field}"
        if not ok or not all(isinstance(r.get(column), float) for r in ok):
            continue
        ranks, intervals = {}, {}
        for key in figures:
            rhos = [rho for group in points.values()
                    if (rho := _spearman(np.array([r[column] for r in group]),
                                         [r.get(key) for r in group])) is not None]
            if rhos:
                ranks[key] = float(np.mean(rhos))
                intervals[key] = spearman_interval(ranks[key], min(map(len, points.values())))
        out["sensitivity"][field] = ranks
        out.setdefault("sensitivity_interval", {})[field] = intervals
    if points:
        out["sensitivity_draws"] = min(map(len, points.values()))
    return out


#: the fewest draws for which a rank correlation gets a 95 % interval (Fisher's z is an
#: approximation for large samples: with 4 draws, a perfect ±1 arises by chance 1 time in 12)
LEAST_DRAWS = 10


def spearman_interval(rho: float, n: int) -> list[float] | None:
    """The 95 % interval of a Spearman rank correlation rho from n draws: Fisher's z with
    Bonett & Wright's variance (1 + rho²/2)/(n - 3) (Psychometrika 65 (2000) 23-28, eq 2);
    None under LEAST_DRAWS draws. At a grid of points the draws are the same at every point
    (common random numbers), so n is one point's, not their sum: the interval is not
    narrowed by the averaging."""
    if n < LEAST_DRAWS:
        return None
    z = math.atanh(max(-0.9999, min(0.9999, rho)))
    half = Z95 * math.sqrt((1.0 + rho * rho / 2.0) / (n - 3))
    return [min(rho, math.tanh(z - half)), max(rho, math.tanh(z + half))]


def _percentiles(rows: list[dict], figures: list[str], qs=PERCENTILES) -> dict:
    """{figure: {"P5": ..}} over the rows that hold the figure."""
    out = {}
    for key in figures:
        values = np.array([r[key] for r in rows if isinstance(r.get(key), float)])
        if values.size:
            out[key] = {f"P{q}": float(np.percentile(values, q)) for q in qs}
    return out


def _group(inputs: dict, rows: list[dict], figures: list[str], flags: dict) -> dict:
    """A group of samples (a grid point, or a level of one axis): its inputs, count,
    P5/P50/P95 per figure and the fraction of its samples edge- (end-) loaded."""
    return {"inputs": inputs, "samples": len(rows),
            "percentiles": _percentiles(rows, figures, (5, 50, 95)),
            **{flag: sum((r.get(key) or 0) > 0 for r in rows) / len(rows)
               for flag, key in flags.items()}}


def _response(ok: list[dict], grid: list[str], figures: list[str], flags: dict) -> dict:
    """Per numeric grid axis of more than one level: each level's group (_group) over the
    other inputs."""
    out = {}
    for field in grid:
        column = f"input:{field}"
        levels = sorted({r[column] for r in ok if isinstance(r.get(column), float)})
        if len(levels) > 1:
            out[field] = [{"value": v, **_group({field: v}, [r for r in ok
                                                             if r.get(column) == v],
                                                figures, flags)} for v in levels]
    return out


def _time_weighted(ok: list[dict], figures: list[str], flags: dict) -> dict:
    """Percentiles of each figure over the operating time (each sample weighted by its
    time share) and the share of the time spent edge- (end-) loaded, its interval a Wilson
    interval at the effective sample size (sum w)² / sum w²."""
    weights = np.array([r["time_share"] for r in ok])
    out = {"percentiles": {}}
    for key in figures:
        have = np.array([isinstance(r.get(key), float) for r in ok])
        if have.any():
            values = np.array([r[key] for r, h in zip(ok, have) if h])
            out["percentiles"][key] = {f"P{q}": weighted_percentile(values, weights[have], q)
                                       for q in PERCENTILES}
    n = int(round(weights.sum() ** 2 / (weights ** 2).sum()))
    for flag, key in flags.items():
        hit = np.array([(r.get(key) or 0) > 0 for r in ok])
        share = float(weights[hit].sum() / weights.sum())
        out[flag] = {"key": key, "time_share": share,
                     "interval_95": wilson(round(share * n), n)}
    return out


def weighted_percentile(values: np.ndarray, weights: np.ndarray, q: float) -> float:
    """The q-th percentile of values drawn with the given weights: the smallest value whose
    cumulative weight reaches q % of the total (numpy's 'inverted_cdf' with weights)."""
    return float(np.percentile(values, q, weights=weights, method="inverted_cdf"))


def _sobol(rows: list[dict], inputs: list[str], grid: list[str], figures: list[str]) -> dict:
    """Each input's first and total Sobol index per figure (SALib.analyze.sobol on
    Saltelli's design, with 95 % bootstrap half-widths), averaged over the grid points
    whose every sample answered; a figure that does not vary has none."""
    from SALib.analyze import sobol

    from .sampling import saltelli_problem

    points: dict[tuple, list[dict]] = {}
    for r in sorted(rows, key=lambda r: r["sample"]):
        points.setdefault(tuple(r.get(f"input:{f}") for f in grid), []).append(r)
    complete = [group for group in points.values()
                if all(r.get("status") == "ok" for r in group)]
    out: dict = {field: {} for field in inputs}
    for key in figures:
        found = []
        for group in complete:
            y = np.array([r.get(key) if isinstance(r.get(key), float) else np.nan
                          for r in group])
            if np.isfinite(y).all() and np.ptp(y) > 0:
                with warnings.catch_warnings():   # a block of equal values: SALib says so
                    warnings.simplefilter("ignore", UserWarning)
                    found.append(sobol.analyze(saltelli_problem(len(inputs)), y,
                                               calc_second_order=False, seed=0))
        for j, field in enumerate(inputs):
            if found:
                out[field][key] = {name: float(np.mean([f[name][j] for f in found]))
                                   for name in ("S1", "S1_conf", "ST", "ST_conf")}
    return {"grid_points": len(complete), "of": len(points), "indices": out}


def wilson(hits: int, n: int) -> list[float] | None:
    """The Wilson score interval (95 %) of a proportion hits/n; None for no trials."""
    if n == 0:
        return None
    p = hits / n
    centre = (p + Z95 ** 2 / (2 * n)) / (1 + Z95 ** 2 / n)
    half = Z95 * math.sqrt(p * (1 - p) / n + Z95 ** 2 / (4 * n * n)) / (1 + Z95 ** 2 / n)
    # at p = 0 or 1 the interval reaches 0 or 1 exactly (round-off aside)
    return [0.0 if hits == 0 else max(0.0, centre - half),
            1.0 if hits == n else min(1.0, centre + half)]


def _spearman(x: np.ndarray, y: list) -> float | None:
    """Spearman's rank correlation of x with y over the pairs where y is a number; None
    where either does not vary."""
    from scipy.stats import spearmanr

    keep = np.array([isinstance(v, float) for v in y])
    if keep.sum() < 3:
        return None
    xs, ys = x[keep], np.array([v for v in y if isinstance(v, float)])
    if np.ptp(xs) == 0 or np.ptp(ys) == 0:
        return None
    return float(spearmanr(xs, ys).statistic)
