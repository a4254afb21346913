"""The samples of a sweep: every grid point of the `[[vary]]` axes (their product, the first
axis slowest) times `samples` draws of the `[[tolerance]]` inputs (the same draws at every
grid point: common random numbers, so grid points differ by the grid alone). Draws are
points of the unit cube from scipy.stats.qmc (Latin hypercube, scrambled Sobol) or numpy's
generator, or Saltelli's design for Sobol indices (SALib: `samples` base points, samples ×
(inputs + 2) draws), seeded by the sweep's seed, mapped through each distribution's
inverse CDF; the same seed gives the same samples on any machine. With a load spectrum
each sample stands for its level's time share over the draws. Each sample is the base
case's table with the fields set (values as text with the unit they were given in) and is
validated as a case before anything runs."""

from __future__ import annotations

import copy
import itertools
import math
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..case import CaseError, CaseInfo, parse_case, shown
from .spec import SweepSpec, Tolerance, Vary


@dataclass(frozen=True)
class Sample:
    """One sample: its number (from 0), the varied inputs as set (field -> text), the case
    table that results and that table parsed (case.CaseInfo: what a worker analyses)."""

    sample: int
    inputs: dict
    raw: dict
    case: CaseInfo
    time_share: float | None = None


def plan(spec: SweepSpec, base: dict, folder: Path | None = None, source: str = "sweep",
         design: dict | None = None, unit_cube: np.ndarray | None = None,
         first: int = 0) -> list[Sample]:
    """The sweep's samples, each validated as a case (a CaseError names the sample, the
    field and the value). `base`: the base case's table as read; `folder`: where the files
    it names are found (the base case's folder); `design`: fields set in every sample
    (field -> text; an optimiser's design variables); `unit_cube`: the toleranced inputs'
    CDF values to draw at (m, inputs; a surrogate's design) instead of the sweep's own;
    `first`: the first sample's number."""
    from .. import units

    ureg = units.registry()
    fixed = _with(base, spec.set)
    axes = [_grid(axis, ureg, f"{source}: vary[{i}]") for i, axis in enumerate(spec.axes)]
    draws = _draws(spec, ureg, source, unit_cube)
    shares = dict(zip(map(repr, spec.spectrum.levels), spec.spectrum.shares)) \
        if spec.spectrum else None
    out = []
    for point in itertools.product(*axes) if axes else [()]:
        share = shares[repr(point[0])] / len(draws) if shares else None
        for draw in draws:
            inputs = dict(design or {})
            inputs.update({field: value for axis, value in zip(spec.axes, point)
                           for field in (axis.field, *axis.also)})
            inputs.update(draw)
            number = first + len(out)
            raw = _with(fixed, inputs)
            try:
                case = parse_case(raw, source=f"{source}: sample {number}", base=folder)
            except CaseError as exc:
                raise CaseError(f"{exc} (set by the sweep: "
                                + ", ".join(f"{k} = {v!r}" for k, v in inputs.items())
                                + ")") from None
            out.append(Sample(number, inputs, raw, case, share))
    return out


def with_class_bands(spec: SweepSpec, base: dict, folder: Path | None = None,
                     source: str = "sweep") -> SweepSpec:
    """The spec with each `iso1328_class` tolerance's band set from its member's size in
    the base case (with the sweep's `set`): f_HβT or f_HαT of ISO 1328-1:2013
    (analytic.iso1328), as a normal's ±3σ band about `mean` (default 0) or a uniform's
    range. A member outside the standard's scope is a CaseError."""
    import math

    from .. import units
    from ..analytic import iso1328

    ureg = units.registry()
    classed = [t for t in spec.tolerance if t.iso1328_class is not None]
    if not classed:
        return spec
    case = parse_case(_with(base, spec.set), source=f"{source}: base", base=folder)
    resolved = []
    for j, t in enumerate(spec.tolerance):
        if t.iso1328_class is None:
            resolved.append(t)
            continue
        where = f"{source}: tolerance[{j}] ({t.field})"
        if getattr(case, "kind", None) != "spur":
            raise CaseError(f"{where}: iso1328_class needs a spur or helical base case, "
                            f"not {getattr(case, 'kind', '?')!r}")
        name = t.field.partition(".")[0]
        member = getattr(case, name)
        teeth = abs(case.teeth[0 if name == "pinion" else 1])
        size = dict(reference_diameter=teeth * case.module_mm / math.cos(case.helix_angle),
                    normal_module=case.module_mm,
                    face_width=member.face_width or case.face_width)
        beyond = iso1328.out_of_scope(teeth=teeth, helix_angle=case.helix_angle, **size)
        if beyond:
            raise CaseError(f"{where}: the {name} lies outside the formulae's scope, which "
                            "the standard forbids extrapolating: " + "; ".join(beyond))
        tolerance = getattr(iso1328.flank_tolerances(t.iso1328_class, **size),
                            t.class_tolerance)
        mean = in_unit(t.mean if t.mean is not None else "0 um", "um", ureg, f"{where}.mean",
                       "a length")
        resolved.append(t.model_copy(update=dict(mean=f"{mean!r} um", band=f"{tolerance!r} um")
                                     if t.distribution == "normal" else
                                     dict(low=f"{mean - tolerance!r} um",
                                          high=f"{mean + tolerance!r} um")))
    return spec.model_copy(update={"tolerance": resolved})


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


def quantity(text, ureg, where: str):
    """A sweep's number with its unit (a bare number dimensionless) as a pint quantity: the
    number and the unit read apart, so that an offset unit (degC, degF) reads as a
    temperature; a CaseError naming `where` for no number, an unknown unit, a control
    character or a number that is not finite."""
    from ..units import split

    if isinstance(text, bool) or not isinstance(text, (str, int, float)):
        raise CaseError(f"{where}: {shown(text)} is not a number with a unit")
    if isinstance(text, str):
        parts = split(text) if text.isprintable() else None
        if parts is None:
            raise CaseError(f"{where}: {shown(text)} is not a number with a unit")
        magnitude, unit = parts[0], parts[1].replace("^", "**")
    else:
        magnitude, unit = float(text), ""
    if not math.isfinite(magnitude):
        raise CaseError(f"{where}: {shown(text)} is not a finite number")
    try:
        return ureg.Quantity(magnitude, unit or "dimensionless")
    except Exception:        # noqa: BLE001 - pint raises many kinds; the message names it
        raise CaseError(f"{where}: {shown(text)}: unknown unit {unit!r}") from None


def as_text(magnitude: float, unit) -> str | float:
    """A sampled value as the case reads it: a bare number where it was given bare, else a
    number with its unit (a milliradian is dimensionless to pint, but not a bare number)."""
    return float(magnitude) if str(unit) == "dimensionless" else f"{float(magnitude)!r} {unit:~}"


def _grid(axis: Vary, ureg, where: str) -> list:
    """The axis's values: as given, or `steps` equal steps from `from` to `to` in the unit
    of `from`."""
    if axis.values:
        return list(axis.values)
    start = quantity(axis.start, ureg, f"{where}.from")
    end = in_unit(axis.to, start.units, ureg, f"{where}.to", f"from ({axis.start!r})")
    return [as_text(m, start.units) for m in np.linspace(start.magnitude, end, axis.steps)]


def in_unit(text, unit, ureg, where: str, whose: str, spread: bool = False) -> float:
    """The magnitude of `text` in `unit`; a CaseError where it is of another dimension.
    spread: `text` is a difference (a standard deviation, a band): in an offset unit (degC,
    degF) a difference of temperatures, 5 degC as 5 K."""
    value = quantity(text, ureg, where)
    if spread:
        value, unit = _as_difference(value, ureg), _as_difference(ureg.Quantity(1.0, unit),
                                                                  ureg).units
    try:
        return float(value.to(unit).magnitude)
    except Exception:        # noqa: BLE001 - a dimensionality error of pint
        raise CaseError(f"{where}: {shown(text)} is not in the unit of {whose}") from None


def _as_difference(value, ureg):
    """A quantity in an offset unit (degC, degF) as the same number of its differences
    (delta_degC, delta_degF); any other as it is."""
    if value.units in (ureg.degC, ureg.degF):
        return ureg.Quantity(value.magnitude, f"delta_{value.units}")
    return value


def _draws(spec: SweepSpec, ureg, source: str, unit_cube: np.ndarray | None = None
           ) -> list[dict]:
    """`samples` draws of the toleranced inputs (field -> text), or those at the points
    `unit_cube` of their CDFs where given, or one empty draw."""
    if not spec.tolerance:
        return [{} for _ in range(spec.samples)] if spec.axes else [{}]
    if unit_cube is None:
        unit_cube = unit_draws(spec)
    columns = [_inverse(t, unit_cube[:, j], ureg, f"{source}: tolerance[{j}]")
               for j, t in enumerate(spec.tolerance)]
    return [{t.field: column[i] for t, column in zip(spec.tolerance, columns)}
            for i in range(len(unit_cube))]


def unit_draws(spec: SweepSpec) -> np.ndarray:
    """The sweep's draws as points of its toleranced inputs' CDFs (samples, inputs)."""
    return _unit_cube(spec.sampling, spec.samples, len(spec.tolerance), spec.seed)


def _unit_cube(sampling: str, n: int, d: int, seed: int) -> np.ndarray:
    """n points in [0, 1)^d (Saltelli's design: n × (d + 2) points, SALib's order, first
    and total indices), strictly inside (a normal's inverse CDF is finite there)."""
    from scipy.stats import qmc

    if sampling == "saltelli":
        points = saltelli_design(n, d, seed)
    elif sampling == "random":
        points = np.random.default_rng(seed).random((n, d))
    elif sampling == "latin_hypercube":
        points = qmc.LatinHypercube(d=d, seed=seed).random(n)
    else:
        with warnings.catch_warnings():       # balance needs a power of two; any n works
            warnings.simplefilter("ignore", UserWarning)
            points = qmc.Sobol(d=d, scramble=True, seed=seed).random(n)
    tiny = np.finfo(float).eps
    return np.clip(points, tiny, 1.0 - tiny)


def saltelli_problem(d: int) -> dict:
    """SALib's problem of d inputs on the unit cube (the inverse CDFs map them after)."""
    return {"num_vars": d, "names": [f"x{j}" for j in range(d)], "bounds": [[0.0, 1.0]] * d}


def saltelli_design(n: int, d: int, seed: int) -> np.ndarray:
    """Saltelli's scheme for first and total Sobol indices (SALib.sample.sobol): n base
    points, n × (d + 2) rows."""
    from SALib.sample import sobol

    with warnings.catch_warnings():       # SALib prefers n a power of two; any n works
        warnings.simplefilter("ignore")
        return sobol.sample(saltelli_problem(d), n, calc_second_order=False, seed=seed)


def _inverse(tolerance: Tolerance, u: np.ndarray, ureg, where: str) -> list:
    """The tolerance's values at the unit-interval points u: its inverse CDF, in the unit
    of its first parameter."""
    from scipy import stats

    t = tolerance
    key = "mean" if t.distribution == "normal" else "low"
    first = getattr(t, key)
    unit = quantity(first, ureg, f"{where}.{key}").units

    def number(name, spread: bool = False):
        return in_unit(getattr(t, name), unit, ureg, f"{where}.{name}", repr(first), spread)

    if t.distribution == "normal":
        key = "std" if t.std is not None else "band"
        spread = number(key, spread=True) / (1.0 if key == "std" else 3.0)
        if not spread > 0:
            raise CaseError(f"{where}.{key}: {shown(getattr(t, key))} must be greater than "
                            "zero (the normal's spread)")
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
    return [as_text(v, unit) for v in values]
