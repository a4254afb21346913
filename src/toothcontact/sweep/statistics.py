"""What a sweep's table says: per output figure its percentiles over the samples that
answered (P5, P50, P95, P99), the probability of edge loading with its Wilson score
interval (95 %), and for each toleranced input its Spearman rank correlation with each
figure (the sensitivity ranking: a monotone influence, whatever its shape), taken within
each grid point (where the grid holds the other inputs still: the draws are the same at
every point) and averaged over the grid points."""

from __future__ import annotations

import math

import numpy as np

#: the percentiles reported per figure
PERCENTILES = (5, 50, 95, 99)
#: the normal quantile of the two-sided 95 % interval
Z95 = 1.959963984540054
#: the summary's count of edge-loaded contacts (the loaded contact's), else of contacts a
#: face end cuts (the rigid analysis's): a sample is edge-loaded where it is above zero
EDGE_KEYS = ("edge_loaded_contacts", "edge_contacts")


def summarise(rows: list[dict], inputs: list[str], grid: list[str] = ()) -> dict:
    """The sweep's statistics (see the module) from its records; `inputs`: the toleranced
    fields, `grid`: the varied ones (their columns are `input:FIELD`)."""
    ok = [r for r in rows if r.get("status") == "ok"]
    figures = sorted({k for r in ok for k, v in r.items()
                      if k != "sample" and not k.startswith("input:")
                      and isinstance(v, float) and not isinstance(v, bool)})
    out = {"samples": len(rows), "ok": len(ok), "failed": len(rows) - len(ok),
           "failures": {r["sample"]: r["status"] for r in rows if r.get("status") != "ok"},
           "percentiles": {}, "sensitivity": {}}
    for key in figures:
        values = np.array([r[key] for r in ok if isinstance(r.get(key), float)])
        if values.size:
            out["percentiles"][key] = {f"P{q}": float(np.percentile(values, q))
                                       for q in PERCENTILES}
    edge = next((k for k in EDGE_KEYS if any(k in r for r in ok)), None)
    if edge is not None:
        hits = sum((r.get(edge) or 0) > 0 for r in ok)
        out["edge_loading"] = {"key": edge, "samples": len(ok), "edge_loaded": hits,
                               "probability": hits / len(ok) if ok else None,
                               "interval_95": wilson(hits, len(ok))}
    points: dict[tuple, list[dict]] = {}
    for r in ok:
        points.setdefault(tuple(r.get(f"input:{f}") for f in grid), []).append(r)
    for field in inputs:
        column = f"input:{field}"
        if not ok or not all(isinstance(r.get(column), float) for r in ok):
            continue
        ranks = {}
        for key in figures:
            rhos = [rho for group in points.values()
                    if (rho := _spearman(np.array([r[column] for r in group]),
                                         [r.get(key) for r in group])) is not None]
            if rhos:
                ranks[key] = float(np.mean(rhos))
        out["sensitivity"][field] = ranks
    return out


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
