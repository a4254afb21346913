"""Typed records of one analysed case for the Python API: what result.json holds, with the
positions and the summary as tables (pandas DataFrames, from the [sweep] extra) that a
study stacks, one row per contact or per case.

    from toothcontact.runner import analyse_record
    result = analyse_record("cases/spur_crowned_20_60.toml")
    result.summary["bem_max_p_max_MPa"]             # MPa
    result.positions.to_dataframe()                 # a row per mesh position and tooth pair
    pandas.concat([r.summary.to_dataframe() for r in results])   # a row per case

Column names are result.json's keys (their units in their suffixes: _mm, _MPa, _urad, _um);
a nested entry (edge_margins_mm per edge) becomes one column per entry,
'edge_margins_mm.pinion_tip'."""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import dataclass


def _flat(entries: Mapping, prefix: str = "") -> dict:
    """One level of keys: a nested mapping's entries as 'key.entry' (lists stay whole)."""
    out = {}
    for key, value in entries.items():
        if isinstance(value, Mapping):
            out.update(_flat(value, f"{prefix}{key}."))
        else:
            out[f"{prefix}{key}"] = value
    return out


def _frame(rows: list[dict], index: list | None = None):
    import pandas

    return pandas.DataFrame.from_records([_flat(r) for r in rows], index=index)


@dataclass(frozen=True)
class Check:
    """A check of the result: its name, whether it passed, the detail (numbers) and its
    kind ("design", "solver", "source", ...)."""

    name: str
    ok: bool
    detail: str
    kind: str = "design"


@dataclass(frozen=True)
class Positions:
    """The contact over the mesh cycle: a row per mesh position and tooth pair (result.json's
    `positions`)."""

    rows: tuple[dict, ...]

    def __len__(self) -> int:
        return len(self.rows)

    def __iter__(self) -> Iterator[dict]:
        return iter(self.rows)

    def to_dataframe(self):
        """The rows as a pandas DataFrame, nested entries flattened (see the module)."""
        return _frame(list(self.rows))


@dataclass(frozen=True)
class Summary(Mapping):
    """The case's summary figures (result.json's `summary`), by key."""

    case: str
    values: dict

    def __getitem__(self, key: str):
        return self.values[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self.values)

    def __len__(self) -> int:
        return len(self.values)

    def to_dataframe(self):
        """One row, indexed by the case's name, nested entries flattened."""
        return _frame([self.values], index=[self.case])


@dataclass(frozen=True)
class CaseResult:
    """One analysed case: its name, kind and title, the summary, the positions, the checks
    and notes, and the whole result document (as result.json holds it)."""

    case: str
    kind: str
    title: str
    summary: Summary
    positions: Positions
    checks: tuple[Check, ...]
    notes: tuple[str, ...]
    document: dict

    @classmethod
    def from_document(cls, document: dict) -> CaseResult:
        summary = document.get("summary") if isinstance(document.get("summary"), dict) else {}
        return cls(document["case"], document["kind"], document.get("title") or document["case"],
                   Summary(document["case"], dict(summary)),
                   Positions(tuple(document.get("positions") or ())),
                   tuple(Check(c["name"], bool(c["ok"]), c["detail"], c.get("kind", "design"))
                         for c in document.get("checks", [])),
                   tuple(document.get("notes") or ()), document)

    @property
    def failed_checks(self) -> tuple[Check, ...]:
        """The design checks that failed (edge loading, a stress over its limit, ...)."""
        return tuple(c for c in self.checks if not c.ok and c.kind == "design")

    @property
    def passed(self) -> bool:
        """Whether every design check passed (the command line's exit 0)."""
        return not self.failed_checks
