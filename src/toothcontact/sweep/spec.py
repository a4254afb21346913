"""The sweep file (`kind = "sweep"`): a base case (a bundled name or a path relative to the
sweep file) and what varies: `[[vary]]` grids (a dotted field path and values, or from/to
in `steps`) and `[[tolerance]]` distributions (normal by `mean` and `std` or a ±3σ `band`,
uniform or triangular by `low`, `high` and `mode`), drawn `samples` times per grid point
with `seed` by `sampling` (random, Latin hypercube or scrambled Sobol, scipy.stats.qmc; or
Saltelli's design for Sobol indices, SALib), each draw a loaded analysis (`method =
"monte_carlo"`) or taken on a surrogate fitted to a few dozen (`"surrogate"`, with a
`[surrogate]` table); a `[spectrum]` of load levels with time
shares; `set` fields fixed in every sample; an `[optimise]` table of design variables
sized over the tolerance samples. Every quantity is text with a unit, as in a case.
Validation errors are CaseErrors naming the field."""

from __future__ import annotations

from typing import Literal

from pydantic import Field, field_validator, model_validator

from ..case import Model


class Vary(Model):
    """A grid axis: the field's `values`, or `from` .. `to` in `steps` equal steps."""

    field: str = Field(description="a dotted field path of the base case, e.g. 'load.torque'")
    also: list[str] = Field([], description="more fields set to the same values, e.g. the "
                                            "gear's relief beside the pinion's")
    values: list[str | bool | int | float] = Field([], description="the values, with units")
    start: str | float | None = Field(None, alias="from")
    to: str | float | None = None
    steps: int | None = Field(None, ge=2, le=1000, description="points from `from` to `to`")

    @model_validator(mode="after")
    def _one_way(self):
        ranged = (self.start, self.to, self.steps)
        if self.values and any(v is not None for v in ranged):
            raise ValueError(f"{self.field}: give values or from/to/steps, not both")
        if not self.values and any(v is None for v in ranged):
            raise ValueError(f"{self.field}: give values, or all of from, to and steps")
        return self


#: the fields a flank tolerance class sets the band of: (member, modification) -> the
#: tolerance of ISO 1328-1:2013 it takes (analytic.iso1328.FlankTolerances' field)
CLASS_TOLERANCES = {(member, modification): tolerance
                    for member in ("pinion", "gear")
                    for modification, tolerance in (("helix_slope", "helix_slope"),
                                                    ("profile_slope", "profile_slope"))}


class Tolerance(Model):
    """A toleranced input: normal (`mean` with `std`, or a ±3σ `band`), uniform (`low`,
    `high`) or triangular (`low`, `mode`, `high`); a member's helix or profile slope may
    instead take its band from `iso1328_class` (ISO 1328-1:2013's f_HβT or f_HαT of the
    member: ±3σ of a normal about `mean`, default 0, or the range of a uniform)."""

    field: str = Field(description="a dotted field path of the base case")
    distribution: Literal["normal", "uniform", "triangular"]
    mean: str | float | None = None
    std: str | float | None = None
    band: str | float | None = Field(None, description="±3σ half-width of a normal")
    low: str | float | None = None
    high: str | float | None = None
    mode: str | float | None = None
    iso1328_class: int | None = Field(
        None, ge=1, le=11, description="flank tolerance class (ISO 1328-1:2013, 1-11) "
                                       "giving a helix or profile slope's band")

    @property
    def class_tolerance(self) -> str | None:
        """The ISO 1328-1 tolerance a class gives this field (see CLASS_TOLERANCES)."""
        member, _, rest = self.field.partition(".")
        modification, _, key = rest.partition(".")
        return CLASS_TOLERANCES.get((member, modification)) if key == "amount" else None

    @model_validator(mode="after")
    def _parameters(self):
        given = {k for k in ("mean", "std", "band", "low", "high", "mode")
                 if getattr(self, k) is not None}
        if self.iso1328_class is not None:
            if self.class_tolerance is None:
                raise ValueError(f"{self.field}: iso1328_class sets the band of "
                                 + " or ".join(sorted({f"pinion.{m}.amount" for _, m in
                                                       CLASS_TOLERANCES}))
                                 + " (or the gear's)")
            if self.distribution == "triangular" or not given <= {"mean"}:
                raise ValueError(f"{self.field}: with iso1328_class give a normal (an "
                                 "optional mean) or a uniform distribution and no spread: "
                                 "the class gives it; given: "
                                 + ", ".join([self.distribution, *sorted(given)]))
            return self
        needed = {"normal": [{"mean", "std"}, {"mean", "band"}], "uniform": [{"low", "high"}],
                  "triangular": [{"low", "mode", "high"}]}[self.distribution]
        if given not in needed:
            raise ValueError(f"{self.field}: a {self.distribution} tolerance takes "
                             + " or ".join(", ".join(sorted(n)) for n in needed)
                             + f"; given: {', '.join(sorted(given)) or 'nothing'}")
        return self


class Spectrum(Model):
    """A load spectrum: a grid axis whose `levels` run for the given time `shares`
    (fractions of the operating time, summing to 1); the sweep's statistics are then also
    weighted by time."""

    field: str = Field(description="the load's dotted field, e.g. 'load.torque'")
    levels: list[str | float] = Field(min_length=1, description="the load levels, with units")
    shares: list[float] = Field(min_length=1, description="each level's share of the time")

    @model_validator(mode="after")
    def _shares(self):
        if len(self.shares) != len(self.levels):
            raise ValueError(f"{self.field}: {len(self.shares)} shares for "
                             f"{len(self.levels)} levels; give one share per level")
        if any(not (0.0 < s <= 1.0) for s in self.shares) or abs(sum(self.shares) - 1) > 1e-6:
            raise ValueError(f"{self.field}: shares {self.shares} must be in (0, 1] and sum "
                             "to 1")
        return self


#: the statistics an objective or a constraint may name over a figure, and the
#: probabilities it may name alone: of edge loading at any flank edge, and at a face end
STATISTICS = ("P5", "P50", "P95", "P99", "mean")
PROBABILITIES = ("edge_loading", "end_loading")


def _statistic(text: str) -> str:
    name, _, figure = text.partition(" ")
    if text not in PROBABILITIES and (name not in STATISTICS or not figure.strip()):
        raise ValueError(f"{text!r} is not a statistic; give {' or '.join(PROBABILITIES)}, "
                         f"or one of {', '.join(STATISTICS)} and a figure of the case's "
                         "summary, e.g. 'P95 bem_max_p_max_MPa'")
    return text


class DesignVariable(Model):
    """A design variable of an optimisation: a dotted field between `low` and `high`."""

    field: str = Field(description="a dotted field path of the base case")
    low: str | float
    high: str | float


class Constraint(Model):
    """An optimisation constraint: a statistic (see Optimise.objective) at most `max`."""

    statistic: str = Field(description="'edge_loading' or 'end_loading' (probabilities) or "
                                       "'P95 FIGURE', ...")
    max: float = Field(allow_inf_nan=False, description="the statistic's largest allowed "
                                                        "value, a finite number")

    _known = field_validator("statistic")(_statistic)


class Optimise(Model):
    """Design variables sized over the sweep's samples: minimise `objective` (a statistic
    over the samples: 'P5|P50|P95|P99|mean FIGURE', or 'edge_loading', the probability of
    edge loading, 'end_loading' at a face end) subject to each constraint, by
    scipy.optimize (COBYQA) from the middle of the bounds, in at most `evaluations`
    sweeps."""

    variables: list[DesignVariable] = Field(min_length=1, alias="variable")
    objective: str
    constraints: list[Constraint] = Field([], alias="constraint")
    evaluations: int = Field(20, ge=2, le=500, description="sweeps the optimiser may run")

    _known = field_validator("objective")(_statistic)


class Surrogate(Model):
    """How a surrogate study (`method = "surrogate"`, sweep.surrogate) samples and when it
    stops: `initial` loaded samples (a Latin hypercube), `batch` more a round where the
    leave-one-out error is largest, until each figure's error is within `tolerance` (a
    fraction of its range) or `max_samples` are analysed (per grid point)."""

    figures: list[str] = Field([], description="the summary figures studied (default: "
                                               "bem_max_p_max_MPa and max_end_load_ratio)")
    initial: int = Field(20, ge=4, le=2000, description="loaded samples of the first design")
    batch: int = Field(8, ge=1, le=500, description="loaded samples added a round")
    max_samples: int = Field(120, ge=4, le=5000, description="the most loaded samples")
    tolerance: float = Field(0.03, gt=0.0, lt=1.0,
                             description="each figure's leave-one-out RMS error allowed, as a "
                                         "fraction of its range over the samples")

    @model_validator(mode="after")
    def _budget(self):
        if self.max_samples < self.initial:
            raise ValueError(f"max_samples ({self.max_samples}) must be at least initial "
                             f"({self.initial})")
        return self


class SweepSpec(Model):
    """A sweep file (see the module)."""

    kind: Literal["sweep"]
    title: str | None = None
    base: str = Field(description="a bundled case name or a case file, relative to the sweep")
    samples: int = Field(1, ge=1, le=100000, description="tolerance samples per grid point")
    seed: int = Field(0, ge=0)
    sampling: Literal["random", "latin_hypercube", "sobol", "saltelli"] = "latin_hypercube"
    method: Literal["monte_carlo", "surrogate"] = Field(
        "monte_carlo", description="monte_carlo: every draw a loaded analysis; surrogate: "
                                   "the draws taken on a surrogate fitted to a few dozen "
                                   "loaded samples (sweep.surrogate)")
    surrogate: Surrogate | None = None
    set: dict[str, str | bool | int | float] = Field(
        {}, description="fields set in the base case for every sample (dotted path: value)")
    vary: list[Vary] = []
    tolerance: list[Tolerance] = []
    spectrum: Spectrum | None = None
    optimise: Optimise | None = None

    @property
    def axes(self) -> list[Vary]:
        """The grid's axes: the spectrum's levels (first, slowest), then each [[vary]]."""
        levels = [Vary(field=self.spectrum.field, values=self.spectrum.levels)] \
            if self.spectrum else []
        return levels + list(self.vary)

    @model_validator(mode="after")
    def _fields_once(self):
        fields = [f for v in self.axes for f in [v.field, *v.also]] + list(self.set) \
            + [t.field for t in self.tolerance] \
            + [v.field for v in (self.optimise.variables if self.optimise else [])]
        twice = sorted({f for f in fields if fields.count(f) > 1})
        if twice:
            raise ValueError(f"{twice[0]}: varied or toleranced twice; give each field once")
        if not self.axes and not self.tolerance:
            raise ValueError("nothing varies: give [[vary]], [[tolerance]] or [spectrum] tables")
        if self.surrogate is not None and self.method != "surrogate":
            raise ValueError("[surrogate] is read only with method = 'surrogate'")
        if self.method == "surrogate":
            if not self.tolerance:
                raise ValueError("method: 'surrogate' fits the [[tolerance]] inputs: give "
                                 "one or more")
        if self.sampling == "saltelli" and len(self.tolerance) < 2:
            raise ValueError("sampling: 'saltelli' (Sobol indices) needs two or more "
                             "[[tolerance]] inputs")
        return self
