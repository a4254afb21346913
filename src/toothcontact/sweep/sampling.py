"""The samples of a sweep: every grid point of the `[[vary]]` axes (their product, the
first axis slowest) times `samples` draws of the `[[tolerance]]` inputs (the same draws at
every grid point: common random numbers, so grid points differ by the grid alone). Draws
are points of the unit cube from scipy.stats.qmc (Latin hypercube, scrambled Sobol) or
numpy's generator, seeded by the sweep's seed, mapped through each distribution's inverse
CDF; the same seed gives the same samples on any machine. Each sample is the base case's
table with the fields set (values as text with the unit they were given in) and is
validated as a case before anything runs."""

from __future__ import annotations

import copy
import itertools
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..case import CaseError, parse_case
from .spec import SweepSpec, Tolerance, Vary


@dataclass(frozen=True)
class Sample:
    """One sample: its number (from 0), the varied inputs as set (field -> text) and the
    case table that results."""

    sample: int
    inputs: dict
    raw: dict


def plan(spec: SweepSpec, base: dict, folder: Path | None = None,
         source: str = "sweep") -> list[Sample]:
    """The sweep's samples, each validated as a case (a CaseError names the sample, the
    field and the value). `base`: the base case's table as read; `folder`: where the files
    it names are found (the base case's folder)."""
    from .. import units

    ureg = units.registry()
    axes = [_grid(axis, ureg, f"{source}: vary[{i}]") for i, axis in enumerate(spec.vary)]
    draws = _draws(spec, ureg, source)
    out = []
    for point in itertools.product(*axes) if axes else [()]:
        for draw in draws:
            inputs = {axis.field: value for axis, value in zip(spec.vary, point)}
            inputs.update(draw)
            number = len(out)
            raw = _with(base, inputs)
            try:
                parse_case(raw, source=f"{source}: sample {number}", base=folder)
            except CaseError as exc:
                raise CaseError(f"{exc} (set by the sweep: "
                                + ", ".join(f"{k} = {v!r}" for k, v in inputs.items())
                                + ")") from None
            out.append(Sample(number, inputs, raw))
    return out


def _with(base: dict, inputs: dict) -> dict:
    """A copy of the case table with each dotted field set (tables made where missing)."""
    raw = copy.deepcopy(base)
    for field, value in inputs.items():
        *tables, key = field.split(".")
        node = raw
        for name in tables:
            node = node.setdefault(name, {})
            if not isinstance(node, dict):
                raise CaseError(f"{field}: {name} is a value in the base case, not a table")
        node[key] = value
    return raw


def _quantity(text, ureg, where: str):
    try:
        return ureg.Quantity(text) if isinstance(text, str) else ureg.Quantity(float(text))
    except Exception:        # noqa: BLE001 - pint raises many kinds; the message names it
        raise CaseError(f"{where}: {text!r} is not a number with a unit") from None


def _text(magnitude: float, unit) -> str | float:
    """A sampled value as the case reads it: a bare number where it was given bare, else a
    number with its unit (a milliradian is dimensionless to pint, but not a bare number)."""
    return float(magnitude) if str(unit) == "dimensionless" else f"{float(magnitude)!r} {unit}"


def _grid(axis: Vary, ureg, where: str) -> list:
    """The axis's values: as given, or `steps` equal steps from `from` to `to` in the unit
    of `from`."""
    if axis.values:
        return list(axis.values)
    start = _quantity(axis.start, ureg, f"{where}.from")
    end = _in_unit(axis.to, start.units, ureg, f"{where}.to", f"from ({axis.start!r})")
    return [_text(m, start.units) for m in np.linspace(start.magnitude, end, axis.steps)]


def _in_unit(text, unit, ureg, where: str, whose: str) -> float:
    """The magnitude of `text` in `unit`; a CaseError where it is of another dimension."""
    quantity = _quantity(text, ureg, where)
    try:
        return float(quantity.to(unit).magnitude)
    except Exception:        # noqa: BLE001 - a dimensionality error of pint
        raise CaseError(f"{where}: {text!r} is not in the unit of {whose}") from None


def _draws(spec: SweepSpec, ureg, source: str) -> list[dict]:
    """`samples` draws of the toleranced inputs (field -> text), or one empty draw."""
    if not spec.tolerance:
        return [{} for _ in range(spec.samples)] if spec.vary else [{}]
    unit_cube = _unit_cube(spec.sampling, spec.samples, len(spec.tolerance), spec.seed)
    columns = [_inverse(t, unit_cube[:, j], ureg, f"{source}: tolerance[{j}]")
               for j, t in enumerate(spec.tolerance)]
    return [{t.field: column[i] for t, column in zip(spec.tolerance, columns)}
            for i in range(spec.samples)]


def _unit_cube(sampling: str, n: int, d: int, seed: int) -> np.ndarray:
    """n points in [0, 1)^d, strictly inside (a normal's inverse CDF is finite there)."""
    from scipy.stats import qmc

    if sampling == "random":
        points = np.random.default_rng(seed).random((n, d))
    elif sampling == "latin_hypercube":
        points = qmc.LatinHypercube(d=d, seed=seed).random(n)
    else:
        with warnings.catch_warnings():       # balance needs a power of two; any n works
            warnings.simplefilter("ignore", UserWarning)
            points = qmc.Sobol(d=d, scramble=True, seed=seed).random(n)
    tiny = np.finfo(float).eps
    return np.clip(points, tiny, 1.0 - tiny)


def _inverse(tolerance: Tolerance, u: np.ndarray, ureg, where: str) -> list:
    """The tolerance's values at the unit-interval points u: its inverse CDF, in the unit
    of its first parameter."""
    from scipy import stats

    t = tolerance
    first = t.mean if t.distribution == "normal" else t.low
    unit = _quantity(first, ureg, where).units

    def number(name):
        return _in_unit(getattr(t, name), unit, ureg, f"{where}.{name}", repr(first))

    if t.distribution == "normal":
        spread = number("std") if t.std is not None else number("band") / 3.0
        if not spread > 0:
            raise CaseError(f"{where}: the spread must be greater than zero")
        values = stats.norm.ppf(u, loc=number("mean"), scale=spread)     # finite inside (0, 1)
    else:
        low, high = number("low"), number("high")
        if not high > low:
            raise CaseError(f"{where}: high ({t.high!r}) must exceed low ({t.low!r})")
        if t.distribution == "uniform":
            values = low + (high - low) * u
        else:
            mode = number("mode")
            if not low <= mode <= high:
                raise CaseError(f"{where}.mode: {t.mode!r} must lie between low and high")
            values = stats.triang.ppf(u, (mode - low) / (high - low), loc=low,
                                      scale=high - low)
    return [_text(v, unit) for v in values]
