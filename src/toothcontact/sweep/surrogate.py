"""Tolerance studies on a surrogate (a sweep's `method = "surrogate"`): a space-filling
design of loaded samples, a surrogate of each studied figure fitted on them per grid point,
its cross-validated error, samples added where that error is largest until it is within
the sweep's tolerance or its budget is spent; then the Monte Carlo draws and the Sobol
indices taken on the surrogate instead of the loaded contact.

The inputs are the toleranced fields' CDF values u in the unit cube (every distribution is
uniform there, and the draws of the Monte Carlo are the same points the full sweep would
analyse: sweep.sampling's unit cube, mapped by the inverse CDFs). The design is a Latin
hypercube (scipy.stats.qmc) of `initial` points, the same at every grid point (common
random numbers, as the full sweep's).

The surrogate is scipy's RBFInterpolator: a thin-plate-spline radial basis interpolant with
a linear polynomial tail, which is kriging (a Gaussian process's posterior mean) with the
spline's generalised covariance (Matheron, "Splines and kriging: their formal
equivalence", 1981): scale-free, so it needs no length scales fitted on a few dozen points,
and scipy is a dependency already (scikit-learn's Gaussian process would add 40 MB for the
same mean; chaospy's polynomial chaos suits smooth figures, not a largest pressure that
switches between contacts). Its error is measured, not assumed: the leave-one-out residual
of every loaded sample (the interpolant refitted without it), their RMS over the figure's
range across the samples (`errors`), each sample weighted by the share of the cube nearest
to it (its Voronoi cell, counted on a scrambled Sobol set): the draws are uniform in the
cube, and the samples added where the error is largest would otherwise count their hard
region many times over. It is a pointwise error at the samples: on the stored 400-sample
Monte Carlo of the bundled spur_crown_tolerance it was 0.3-1.0 times the true RMS error at
the samples it did not see (which holds the loaded figure's own scatter between
neighbouring samples), while the percentiles drawn on the surrogate were within a fifth of
it (tests). A figure judged against a threshold (the largest end load ratio against
END_LOAD_RATIO) is also settled where no more than the tolerance of the cube lies within
twice its error of the threshold: what it decides is which side a draw falls. New samples
go where a candidate (a scrambled Sobol set) lies farthest from the design, weighted by the
leave-one-out residual of its nearest design point, `batch` a round. Predictions are held
within the values fitted (an interpolant overshoots beside a kink)."""

from __future__ import annotations

import logging
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..case import CaseError
from .optimise import nearest

log = logging.getLogger(__name__)

#: the figures studied where the sweep names none: the largest loaded pressure and the
#: largest end load ratio (a face end loaded where it exceeds END_LOAD_RATIO)
DEFAULT_FIGURES = ("bem_max_p_max_MPa", "max_end_load_ratio")
#: candidates per input for the next samples (a scrambled Sobol set)
CANDIDATES_PER_INPUT = 512
#: Saltelli's base points for the Sobol indices on the surrogate (SALib)
SOBOL_BASE = 1024


@dataclass
class Fit:
    """A figure's surrogate at one grid point: the interpolant, the leave-one-out residual
    of each design point (in the figure's unit), the share of the cube nearest each design
    point (weights summing to 1) and the figure's range over the design."""

    model: object
    residuals: np.ndarray
    weights: np.ndarray
    spread: float
    #: the least and largest value fitted: predictions are held between them (an
    #: interpolant overshoots beside a kink: a ratio of 0 and above would read -0.008)
    bounds: tuple[float, float] = (-np.inf, np.inf)

    def __call__(self, u: np.ndarray) -> np.ndarray:
        """The figure predicted at the unit-cube points u (m, d), within `bounds`."""
        return np.clip(self.model(u), *self.bounds)

    @property
    def rmse(self) -> float:
        """The leave-one-out RMS residual over the cube (the figure's unit)."""
        return float(np.sqrt(np.sum(self.weights * self.residuals ** 2)))

    @property
    def error(self) -> float:
        """The leave-one-out RMS residual over the figure's range (0 where it is constant)."""
        return self.rmse / self.spread if self.spread > 0 else 0.0


def fit(u: np.ndarray, y: np.ndarray) -> Fit:
    """The thin-plate-spline interpolant of y (n,) at the unit-cube points u (n, d), its
    leave-one-out residuals (each point's value less the interpolant fitted on the
    others) and the points' shares of the cube (cell_shares)."""
    from scipy.interpolate import RBFInterpolator

    def model(keep):
        return RBFInterpolator(u[keep], y[keep], kernel="thin_plate_spline", degree=1)

    every = np.ones(len(y), bool)
    residuals = np.empty(len(y))
    for i in range(len(y)):
        every[i] = False
        residuals[i] = y[i] - model(every)(u[i:i + 1])[0]
        every[i] = True
    return Fit(model(every), residuals, cell_shares(u), float(np.ptp(y)),
               (float(y.min()), float(y.max())))


def candidates(d: int, seed: int = 0) -> np.ndarray:
    """A scrambled Sobol set of CANDIDATES_PER_INPUT·d points of the unit cube."""
    import warnings

    from scipy.stats import qmc

    with warnings.catch_warnings():       # balance needs a power of two; any n works
        warnings.simplefilter("ignore", UserWarning)
        return qmc.Sobol(d=d, scramble=True, seed=seed).random(CANDIDATES_PER_INPUT * d)


def cell_shares(u: np.ndarray) -> np.ndarray:
    """Each point's share of the unit cube: of a scrambled Sobol set, the fraction nearest
    to it (its Voronoi cell's volume, the draws being uniform in the cube)."""
    from scipy.spatial import cKDTree

    nearest = cKDTree(u).query(candidates(u.shape[1]))[1]
    return np.bincount(nearest, minlength=len(u)) / len(nearest)


def settled(f: Fit, threshold: float | None, tolerance: float) -> bool:
    """Whether a fit meets the tolerance: its error within it, or, for a figure judged
    against `threshold`, no more than `tolerance` of the cube within twice its RMS error
    of the threshold."""
    if f.error <= tolerance:
        return True
    if threshold is None:
        return False
    near = np.abs(f(candidates(f.model.y.shape[1])) - threshold) <= 2.0 * f.rmse
    return float(near.mean()) <= tolerance


def latin_hypercube(n: int, d: int, seed: int) -> np.ndarray:
    """n points of a Latin hypercube in the open unit cube (d inputs)."""
    from scipy.stats import qmc

    tiny = np.finfo(float).eps
    return np.clip(qmc.LatinHypercube(d=d, seed=seed).random(n), tiny, 1.0 - tiny)


def next_points(u: np.ndarray, weights: np.ndarray, count: int, seed: int) -> np.ndarray:
    """`count` new points of the unit cube where the surrogate is least sure: among a
    scrambled Sobol set, greedily the candidate whose distance to the nearest design point
    times that point's weight (its largest leave-one-out residual over the figures' ranges)
    is largest; a chosen point joins the design with its nearest's weight."""
    pool = candidates(u.shape[1], seed)
    distance = np.linalg.norm(pool[:, None, :] - u[None, :, :], axis=2)
    nearest = distance.argmin(axis=1)
    reach, weight = distance[np.arange(len(pool)), nearest], weights[nearest]
    chosen = []
    for _ in range(count):
        k = int(np.argmax(reach * weight))
        chosen.append(pool[k])
        closer = np.linalg.norm(pool - pool[k], axis=1)
        nearer = closer < reach
        reach = np.where(nearer, closer, reach)
        weight = np.where(nearer, weight[k], weight)
        reach[k] = 0.0
    tiny = np.finfo(float).eps
    return np.clip(np.array(chosen), tiny, 1.0 - tiny)


@dataclass
class Study:
    """A surrogate study's state: the design (unit-cube points, shared by the grid
    points), the loaded records so far and the fits per (grid point, figure)."""

    u: np.ndarray
    records: list[dict]
    fits: dict[tuple, dict[str, Fit]]
    rounds: int
    #: whether every figure was settled (else the sample budget ran out)
    converged: bool = False


def study(analyse_points: Callable[[np.ndarray, int], list[dict]], d: int, grid: list[str],
          figures: list[str], settings, seed: int,
          thresholds: dict[str, float] | None = None) -> Study:
    """Fit the surrogates: `analyse_points(u, first)` analyses the unit-cube points u (m, d)
    at every grid point (sample numbers from `first`) and returns their records;
    `settings` the sweep's [surrogate] table. Rounds of `batch` new points until every
    figure at every grid point is settled (its error within `tolerance`, or for one of
    `thresholds` (figure -> the value it is judged against), its draws' side of it; see
    settled), or `max_samples` points are analysed. A CaseError where a figure is not one
    the samples report."""
    thresholds = thresholds or {}
    u = latin_hypercube(settings.initial, d, seed)
    records = analyse_points(u, 0)
    rounds = 1
    while True:
        fits = _fits(u, records, grid, figures)
        worst = {f: max(fit_[f].error for fit_ in fits.values()) for f in figures}
        log.info("surrogate, round %d: %d points, leave-one-out error %s", rounds, len(u),
                 ", ".join(f"{f} {100 * e:.1f} %" for f, e in worst.items()))
        done = all(settled(fit_[f], thresholds.get(f), settings.tolerance)
                   for fit_ in fits.values() for f in figures)
        if done or len(u) >= settings.max_samples:
            return Study(u, records, fits, rounds, done)
        weights = np.max([np.abs(fit_[f].residuals) / (fit_[f].spread or 1.0)
                          for fit_ in fits.values() for f in figures
                          if not settled(fit_[f], thresholds.get(f), settings.tolerance)],
                         axis=0)
        count = min(settings.batch, settings.max_samples - len(u))
        new = next_points(u, weights, count, seed + rounds)
        records += analyse_points(new, len(records))
        u = np.vstack([u, new])
        rounds += 1


def _fits(u: np.ndarray, records: list[dict], grid: list[str], figures: list[str]
          ) -> dict[tuple, dict[str, Fit]]:
    """Each grid point's fit of each figure over the design points that answered there
    (records in design order per grid point, as analyse_points gives them)."""
    points: dict[tuple, list[dict]] = {}
    for r in sorted(records, key=lambda r: r["sample"]):
        points.setdefault(_point(r, grid), []).append(r)
    out = {}
    for point, group in points.items():
        out[point] = {}
        for figure in figures:
            have = np.array([isinstance(r.get(figure), float) for r in group])
            if not any(figure in r for r in group):
                reported = sorted(k for k, v in group[0].items() if isinstance(v, float)
                                  and not k.startswith("input:") and k != "time_share")
                raise CaseError(f"surrogate.figures: {figure!r} is not a figure the samples "
                                f"report; {nearest(figure, reported)}")
            if have.sum() < u.shape[1] + 2:
                raise CaseError(f"surrogate: only {int(have.sum())} of {len(group)} samples "
                                f"at {dict(zip(grid, point))} report {figure}: too few to "
                                "fit (see the samples' status in samples.parquet)")
            y = np.array([r[figure] for r, h in zip(group, have) if h])
            found = fit(u[: len(group)][have], y)
            if not have.all():          # the points that did not answer: no residual, no share
                for name in ("residuals", "weights"):
                    full = np.zeros(len(group))
                    full[have] = getattr(found, name)
                    setattr(found, name, full)
            out[point][figure] = found
    return out


def _point(record: dict, grid: list[str]) -> tuple:
    return tuple(record.get(f"input:{f}") for f in grid)


def draws_on(found: Study, draws: np.ndarray, inputs: list[str], grid: list[str],
             shares: dict | None, end_ratio: float) -> list[dict]:
    """The Monte Carlo's records on the surrogate: per grid point and draw (unit-cube
    points `draws`), each studied figure predicted, the toleranced inputs as their CDF
    values (a rank correlation is the same on them), the grid's values, a time share under
    a load spectrum (`shares`: grid point -> its level's share, over the draws) and, where
    the largest end load ratio is studied, end_loaded_contacts 1 or 0 at `end_ratio`."""
    out = []
    for point, fits in found.fits.items():
        predicted = {f: m(draws) for f, m in fits.items()}
        for i in range(len(draws)):
            record = {"sample": len(out), "status": "ok",
                      **{f"input:{g}": v for g, v in zip(grid, point)},
                      **{f"input:{f}": float(draws[i, j]) for j, f in enumerate(inputs)},
                      **{f: float(v[i]) for f, v in predicted.items()}}
            if "max_end_load_ratio" in predicted:
                record["end_loaded_contacts"] = float(record["max_end_load_ratio"] > end_ratio)
            if shares is not None:
                record["time_share"] = shares[point] / len(draws)
            out.append(record)
    return out


def sobol_on(found: Study, inputs: list[str], seed: int, point: np.ndarray | None = None
             ) -> dict:
    """Each toleranced input's first and total Sobol index per studied figure on the
    surrogate (SALib.analyze.sobol on Saltelli's design of SOBOL_BASE points; at the
    design `point` where the surrogate has design variables too), averaged over the grid
    points; the shape of sweep.statistics' Sobol indices."""
    import warnings

    from SALib.analyze import sobol

    from .sampling import saltelli_design, saltelli_problem

    d = len(inputs)
    design = saltelli_design(SOBOL_BASE, d, seed)
    if point is not None:
        design = np.hstack([design, np.tile(point, (len(design), 1))])
    per_point = []
    for fits in found.fits.values():
        found_here = {}
        for figure, f in fits.items():
            y = f(design)
            if np.ptp(y) > 0:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore", UserWarning)
                    found_here[figure] = sobol.analyze(saltelli_problem(d), y,
                                                       calc_second_order=False, seed=seed)
        per_point.append(found_here)
    figures = sorted({k for p in per_point for k in p})
    indices: dict = {field: {} for field in inputs}
    for figure in figures:
        got = [p[figure] for p in per_point if figure in p]
        for j, field in enumerate(inputs):
            indices[field][figure] = {name: float(np.mean([g[name][j] for g in got]))
                                      for name in ("S1", "S1_conf", "ST", "ST_conf")}
    return {"grid_points": len(per_point), "of": len(per_point), "indices": indices,
            "on": f"the surrogate ({SOBOL_BASE} Saltelli base points)"}


#: a design's re-check agrees with the surrogate where its loaded samples' RMS difference
#: from the surrogate is within this many times the stated error (or the tolerance, if
#: larger): a RMS of a few dozen samples scatters by a third about the true one
RECHECK_FACTOR = 2.0


def recheck(found: Study, analyse: Callable[[np.ndarray, int], list[dict]],
            point: np.ndarray, grid: list[str], settings, seed: int) -> dict:
    """A design found on the surrogate checked by the loaded contact: `initial` loaded
    samples of the tolerances at the design `point` (a Latin hypercube; `analyse(u,
    first)` analyses them at every grid point), each figure's RMS difference from the
    surrogate's value there, over its range, against the stated leave-one-out error
    (`agrees` where within RECHECK_FACTOR times it, or the tolerance if larger)."""
    figures = list(next(iter(found.fits.values())))
    inputs = found.u.shape[1] - len(point)
    u = latin_hypercube(settings.initial, inputs, seed + 1)
    records = analyse(u, 0)
    points: dict[tuple, list[dict]] = {}
    for r in sorted(records, key=lambda r: r["sample"]):
        points.setdefault(_point(r, grid), []).append(r)
    cube = np.hstack([u, np.tile(point, (len(u), 1))])
    errors, rmse = {}, {}
    for figure in figures:
        worst = 0.0
        for where, group in points.items():
            fit_ = found.fits[where][figure]
            have = [isinstance(r.get(figure), float) for r in group]
            loaded = np.array([r[figure] for r, h in zip(group, have) if h])
            predicted = fit_(cube[: len(group)][np.array(have)])
            rms = float(np.sqrt(np.mean((loaded - predicted) ** 2))) if loaded.size else 0.0
            worst = max(worst, rms)
            errors[figure] = max(errors.get(figure, 0.0),
                                 rms / fit_.spread if fit_.spread > 0 else 0.0)
        rmse[figure] = worst
    stated = {f: max(fits[f].error for fits in found.fits.values()) for f in figures}
    return {"samples": settings.initial, "grid_points": len(points),
            "ok": sum(r.get("status") == "ok" for r in records), "rmse": rmse,
            "errors": errors, "stated_errors": stated,
            "agrees": all(errors[f] <= RECHECK_FACTOR * max(stated[f], settings.tolerance)
                          for f in figures)}


def summary(found: Study, settings, figures: list[str]) -> dict:
    """What the study says of itself: the loaded samples per grid point, the rounds, the
    tolerance, whether every figure met it, and per figure its error (leave-one-out RMS over
    the range, the worst grid point's), that RMS in the figure's unit and the range."""
    errors = {f: max(fits[f].error for fits in found.fits.values()) for f in figures}
    return {"model": "thin-plate-spline radial basis interpolant, linear tail "
                     "(scipy.interpolate.RBFInterpolator) on the inputs' CDF values",
            "design": "Latin hypercube, then points added where the leave-one-out error "
                      "is largest",
            "loaded_samples": len(found.u), "grid_points": len(found.fits),
            "rounds": found.rounds, "tolerance": settings.tolerance,
            "max_samples": settings.max_samples,
            "converged": found.converged,
            "errors": errors,
            "rmse": {f: max(fits[f].rmse for fits in found.fits.values()) for f in figures},
            "ranges": {f: max(fits[f].spread for fits in found.fits.values())
                       for f in figures}}


def check_figures(figures: list[str], optimise, where: str = "optimise") -> None:
    """Before any sample runs: a CaseError where an [optimise] statistic needs a figure
    the surrogate does not study (`end_loading` needs max_end_load_ratio; `edge_loading`,
    a count of contacts at any edge, has no smooth figure a surrogate can hold)."""
    if optimise is None:
        return
    named = [("objective", optimise.objective)] + [
        (f"constraint[{i}].statistic", c.statistic) for i, c in enumerate(optimise.constraints)]
    for field, text in named:
        if text == "edge_loading":
            raise CaseError(f"{where}.{field}: 'edge_loading' is not drawn on a surrogate "
                            "(a count of edge contacts is no smooth figure); give "
                            "'end_loading', or method = 'monte_carlo'")
        needed = "max_end_load_ratio" if text == "end_loading" else text.partition(" ")[2].strip()
        if needed not in figures:
            raise CaseError(f"{where}.{field}: {text!r} needs {needed!r} among the surrogate's "
                            f"figures ([surrogate] figures: {', '.join(figures)})")
