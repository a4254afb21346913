"""The sweep file (`kind = "sweep"`): a base case (a bundled name or a path relative to the
sweep file) and what varies: `[[vary]]` grids (a dotted field path and values, or from/to
in `steps`) and `[[tolerance]]` distributions (normal by `mean` and `std` or a ±3σ `band`,
uniform or triangular by `low`, `high` and `mode`), drawn `samples` times per grid point
with `seed` by `sampling` (random, Latin hypercube or scrambled Sobol, scipy.stats.qmc).
Every quantity is text with a unit, as in a case. Validation errors are CaseErrors naming
the field."""

from __future__ import annotations

from typing import Literal

from pydantic import Field, model_validator

from ..case import Model


class Vary(Model):
    """A grid axis: the field's `values`, or `from` .. `to` in `steps` equal steps."""

    field: str = Field(description="a dotted field path of the base case, e.g. 'load.torque'")
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


class Tolerance(Model):
    """A toleranced input: normal (`mean` with `std`, or a ±3σ `band`), uniform (`low`,
    `high`) or triangular (`low`, `mode`, `high`)."""

    field: str = Field(description="a dotted field path of the base case")
    distribution: Literal["normal", "uniform", "triangular"]
    mean: str | float | None = None
    std: str | float | None = None
    band: str | float | None = Field(None, description="±3σ half-width of a normal")
    low: str | float | None = None
    high: str | float | None = None
    mode: str | float | None = None

    @model_validator(mode="after")
    def _parameters(self):
        given = {k for k in ("mean", "std", "band", "low", "high", "mode")
                 if getattr(self, k) is not None}
        needed = {"normal": [{"mean", "std"}, {"mean", "band"}], "uniform": [{"low", "high"}],
                  "triangular": [{"low", "mode", "high"}]}[self.distribution]
        if given not in needed:
            raise ValueError(f"{self.field}: a {self.distribution} tolerance takes "
                             + " or ".join(", ".join(sorted(n)) for n in needed)
                             + f"; given: {', '.join(sorted(given)) or 'nothing'}")
        return self


class SweepSpec(Model):
    """A sweep file (see the module)."""

    kind: Literal["sweep"]
    title: str | None = None
    base: str = Field(description="a bundled case name or a case file, relative to the sweep")
    samples: int = Field(1, ge=1, le=100000, description="tolerance samples per grid point")
    seed: int = Field(0, ge=0)
    sampling: Literal["random", "latin_hypercube", "sobol"] = "latin_hypercube"
    vary: list[Vary] = []
    tolerance: list[Tolerance] = []

    @model_validator(mode="after")
    def _fields_once(self):
        fields = [v.field for v in self.vary] + [t.field for t in self.tolerance]
        twice = sorted({f for f in fields if fields.count(f) > 1})
        if twice:
            raise ValueError(f"{twice[0]}: varied or toleranced twice; give each field once")
        if not fields:
            raise ValueError("nothing varies: give [[vary]] or [[tolerance]] tables")
        return self
