"""From a validated case to its result: one module per case kind.

Each kind's analysis returns a `Result` (analyses.result): named sections of numbers (keys
carry their unit), the checks a reviewer must see (edge loading, stress over a limit, a
source's inconsistency) and notes. The contact kinds (spur, spline, worm, imported) share
what they report from a contact cycle (analyses.contact). Pure functions: nothing here
reads or writes files. A kind's module is imported when a case of that kind is analysed.
"""

from __future__ import annotations

import importlib
import warnings

from .. import case as schema
from .result import Check, Result

#: case kind -> the module (analyses.<module>) and the function that analyses it
KINDS = {
    "hertz": ("hertz", "hertz_case"),
    "crown_design": ("crown_design", "crown_design_case"),
    "worm_efficiency": ("worm_efficiency", "worm_efficiency_case"),
    "spline_crown": ("spline_crown", "spline_crown_case"),
    "spur": ("spur", "spur_geometry_case"),
    "spline": ("spline", "spline_geometry_case"),
    "worm": ("worm", "worm_geometry_case"),
    "imported": ("imported", "imported_case"),
}

__all__ = ["Check", "KINDS", "Result", "analyse"]


def analyse(case: schema.CaseInfo) -> Result:
    """Run the analysis of the case's kind; bad geometry becomes a CaseError."""
    module, function = KINDS[case.kind]
    runner = getattr(importlib.import_module(f"{__name__}.{module}"), function)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = runner(case)
    # the analyses' own warnings are notes for the reader; a numerical library's runtime
    # warnings (an overflow inside a guarded step) are not
    result.notes.extend(str(w.message) for w in caught if issubclass(w.category, UserWarning))
    result.notes.extend(_defaulted_materials(case))
    return result


def _defaulted_materials(case: schema.CaseInfo) -> list[str]:
    """Notes naming the materials the case left to their defaults (steel; the mate's)."""
    given = case.model_fields_set
    notes = []
    if "material" in type(case).model_fields and "material" not in given:
        m = case.material
        whose = " (the worm's)" if case.kind == "worm" else ""
        notes.append(f"material{whose}: none given, so steel: E = {m.E / 1e3:g} GPa, "
                     f"nu = {m.nu:g}")
    for mate in ("gear_material", "wheel_material", "sleeve_material"):
        if mate in type(case).model_fields and getattr(case, mate) is None:
            notes.append(f"{mate}: none given, so the same as material")
    return notes
