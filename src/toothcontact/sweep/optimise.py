"""Modification sizing on the sweep engine (`[optimise]`): design variables (crown height
or radius, profile crown, tip relief, ... any numeric field) set in every sample of the
sweep, an objective that is a statistic over the samples (P95 of the largest loaded
pressure, P50 of loaded TE, the probability of edge loading, ...) and constraints on
other statistics, solved by scipy.optimize's COBYQA (Ragonneau & Zhang: derivative-free,
bounds and constraints) on the variables scaled to [0, 1], from the middle of the bounds.
The samples' draws are the same for every design (common random numbers), so the
objective is a deterministic function of the design and the search sees no sampling noise.
Each design's sweep is checkpointed under OUT/optimise/<design key>, so a resumed
optimisation reruns nothing it finished."""

from __future__ import annotations

import hashlib
import math
from collections.abc import Callable
from pathlib import Path

import numpy as np

from ..case import CaseError
from .spec import PROBABILITIES, Optimise

#: COBYQA's first and last trust-region radius on the [0, 1] scaled variables
INITIAL_RADIUS, FINAL_RADIUS = 0.25, 0.01


def check_statistics(spec: Optimise, figures: dict, where: str) -> None:
    """Before any sample runs: a CaseError naming the field where the objective or a
    constraint names a figure that `figures` (the base design's record, sweep.run's
    sample_record) does not report, or a probability of edge loading where it reports no
    edge count."""
    from .statistics import FLAGS

    named = [("objective", spec.objective)] + [
        (f"constraint[{i}].statistic", c.statistic) for i, c in enumerate(spec.constraints)]
    numbers = sorted(k for k, v in figures.items() if isinstance(v, (int, float))
                     and not isinstance(v, bool) and k != "sample" and not k.startswith("input:"))
    for field, text in named:
        if text in PROBABILITIES:
            if not any(key in figures for key in FLAGS[text]):
                raise CaseError(f"{where}.{field}: {text!r}: the base design reports no edge "
                                "loading (no loaded contact or pattern): name a figure, "
                                "e.g. 'P95 " + (numbers[0] if numbers else "FIGURE") + "'")
            continue
        figure = text.partition(" ")[2].strip()
        if figure not in numbers:
            raise CaseError(f"{where}.{field}: {figure!r} is not a figure the base design "
                            f"reports; {nearest(figure, numbers)}")


#: the most figure names a message offers for one it does not know
NEAREST = 12


def nearest(name: str, known: list[str]) -> str:
    """The figures nearest `name` by spelling (at most NEAREST), as a message's end."""
    import difflib

    close = difflib.get_close_matches(name, known, n=NEAREST, cutoff=0.0)
    return (f"the nearest of the {len(known)} figures: {', '.join(close)}" if close
            else "no figures are reported")


def statistic(text: str, stats: dict, rows: list[dict], where: str) -> float:
    """The statistic `text` of a sweep ('edge_loading', 'end_loading', or 'P95 FIGURE'
    etc. over the samples that answered; time-weighted under a load spectrum); inf where no
    sample answered. A CaseError (naming `where`) for a statistic or figure the sweep has
    not."""
    weighted = stats.get("time_weighted")
    if text in PROBABILITIES:
        edge = (weighted or stats).get(text)
        if edge is None:
            raise CaseError(f"{where}: {text!r}: this sweep's samples report no edge "
                            "loading (no loaded contact or pattern)")
        value = edge["time_share"] if weighted else edge["probability"]
        return math.inf if value is None else float(value)
    name, _, figure = text.partition(" ")
    figure = figure.strip()
    ok = [r for r in rows if r.get("status") == "ok"]
    if not ok:
        return math.inf
    known = sorted((weighted or stats)["percentiles"])
    if figure not in known:
        raise CaseError(f"{where}: {figure!r} is not a figure of this sweep's samples; "
                        f"{nearest(figure, known)}")
    if name == "mean":
        values = [(r.get("time_share") or 1.0, r[figure]) for r in ok
                  if isinstance(r.get(figure), float)]
        return float(sum(w * v for w, v in values) / sum(w for w, _ in values))
    return float((weighted or stats)["percentiles"][figure][name])


def design_key(design: dict) -> str:
    """A folder name for a design (the same design, the same folder: a resumed
    optimisation finds its sweeps)."""
    text = "|".join(f"{k}={v}" for k, v in sorted(design.items()))
    return "design_" + hashlib.sha1(text.encode()).hexdigest()[:12]


def designs(spec: Optimise, where: str = "optimise") -> Callable[[np.ndarray], dict]:
    """The design at a point of the unit cube (each variable scaled to [0, 1] between its
    bounds): field -> text in the unit of its `low`. A CaseError names a bound that is no
    number with a unit, or a `high` not above `low`."""
    from .. import units
    from .sampling import as_text, in_unit, quantity

    ureg = units.registry()
    bounds = []
    for i, v in enumerate(spec.variables):
        low = quantity(v.low, ureg, f"{where}.variable[{i}].low")
        high = in_unit(v.high, low.units, ureg, f"{where}.variable[{i}].high", repr(v.low))
        if not high > low.magnitude:
            raise CaseError(f"{where}.variable[{i}]: high ({v.high!r}) must exceed low "
                            f"({v.low!r})")
        bounds.append((float(low.magnitude), high, low.units))

    def design_of(x) -> dict:
        return {v.field: as_text(lo + float(np.clip(t, 0, 1)) * (hi - lo), unit)
                for v, t, (lo, hi, unit) in zip(spec.variables, x, bounds)}

    return design_of


def optimise(spec: Optimise, evaluate: Callable[[dict, Path], tuple[dict, list[dict]]],
             out: Path, where: str = "optimise") -> dict:
    """Solve the optimisation: `evaluate(design, folder, point)` runs the sweep with the
    design's fields set (field -> text with unit; `point` the design scaled to the unit
    cube) into `folder` and returns its statistics and records. Returns the history (every
    design tried, its objective and constraints) and the best feasible design (else the
    least infeasible)."""
    from scipy.optimize import NonlinearConstraint, minimize

    design_of = designs(spec, where)
    history: list[dict] = []
    seen: dict[tuple, dict] = {}

    def evaluated(x) -> dict:
        key = tuple(np.round(np.clip(x, 0, 1), 12))
        if key not in seen:
            design = design_of(x)
            folder = out / design_key(design)
            stats, rows = evaluate(design, folder, np.clip(x, 0, 1))
            entry = {"evaluation": len(history), "design": design, "folder": folder.name,
                     "ok": stats["ok"], "failed": stats["failed"],
                     "objective": statistic(spec.objective, stats, rows,
                                            f"{where}.objective"),
                     "constraints": [statistic(c.statistic, stats, rows,
                                               f"{where}.constraint[{j}]")
                                     for j, c in enumerate(spec.constraints)]}
            entry["feasible"] = all(g <= c.max for g, c in zip(entry["constraints"],
                                                               spec.constraints))
            history.append(entry)
            seen[key] = entry
        return seen[key]

    constraints = [NonlinearConstraint(lambda x, j=j: evaluated(x)["constraints"][j],
                                       -np.inf, c.max)
                   for j, c in enumerate(spec.constraints)]
    result = minimize(lambda x: _finite(evaluated(x)["objective"]),
                      np.full(len(spec.variables), 0.5), method="COBYQA",
                      bounds=[(0.0, 1.0)] * len(spec.variables), constraints=constraints,
                      options={"maxfev": spec.evaluations, "initial_tr_radius": INITIAL_RADIUS,
                               "final_tr_radius": FINAL_RADIUS})
    feasible = [h for h in history if h["feasible"]]
    best = min(feasible, key=lambda h: h["objective"]) if feasible else min(
        history, key=lambda h: sum(max(0.0, g - c.max)
                                   for g, c in zip(h["constraints"], spec.constraints)))
    return {"objective": spec.objective,
            "constraints": [{"statistic": c.statistic, "max": c.max}
                            for c in spec.constraints],
            "variables": [{"field": v.field, "low": v.low, "high": v.high}
                          for v in spec.variables],
            "method": "COBYQA (scipy.optimize.minimize)", "message": str(result.message),
            "evaluations": len(history), "best": best, "feasible_found": bool(feasible),
            "history": history}


def _finite(value: float) -> float:
    """An objective COBYQA can take: a design where no sample answered counts as very bad
    (1e30), not as inf."""
    return value if math.isfinite(value) else 1e30
