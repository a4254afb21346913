"""What an analysis returns: named sections of numbers (keys carry their unit), the checks
a reviewer must see and notes (result.json), and what stays in memory for the pictures."""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class Check:
    """A pass/fail statement about the result. kind "design": about the design (a failed one
    is flagged at the top of the report and exits the run with 1); "source": whether the
    result reproduces the numbers a source prints, or those numbers agree with each other (a
    misprint, or the case's reading of the source, is not the design's); "method": a
    self-check of the method (two routes to the same number);
    "solver": whether a solver answered everywhere (a failed one leaves the results
    incomplete: its rows say why, and the run exits with 4); "rigid": the rigid pattern's
    edge margins where the loaded contact's verdicts decide (shown, not flagged)."""

    name: str
    ok: bool
    detail: str
    kind: str = "design"

    def as_dict(self) -> dict:
        return {"name": self.name, "ok": bool(self.ok), "detail": self.detail, "kind": self.kind}


@dataclass
class Result:
    """What an analysis found: sections, checks and notes go to result.json; `cycle` (a
    contact.cycle.ContactCycle, for contact cases), `loaded` (contact.edge_loads.LoadedContact
    or None per cycle row) and `parts` (the members it generated: gearset's GearPair,
    SplinePair or WormSet) stay in memory for the pictures."""

    sections: dict = field(default_factory=dict)
    checks: list[Check] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    cycle: object = None
    loaded: list | None = None
    parts: object = None

    def as_dict(self) -> dict:
        return {**self.sections, "checks": [c.as_dict() for c in self.checks],
                "notes": self.notes}
