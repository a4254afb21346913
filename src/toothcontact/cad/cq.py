"""The generated solids as CadQuery objects, to go on with in CadQuery's own API: a bore,
a hub, a keyway (optional extra: `pip install toothcontact[cadquery]`; the solids are the
same OCP shapes `export` writes, wrapped, not rebuilt)."""

from __future__ import annotations

from pathlib import Path


def workplanes(case_or_path) -> dict:
    """Each part of a spur, spline or worm case (a validated case, or the path of a case
    file) as a `cadquery.Workplane` holding its solid, by part name (pinion/gear,
    hub/sleeve, worm/wheel). Units mm; each part in its own frame: axis on z, mid-face at
    z = 0, tooth 0 on +x."""
    try:
        import cadquery
    except ImportError:
        raise ImportError("CadQuery objects need the cadquery package: "
                          "pip install 'toothcontact[cadquery]'") from None
    from .parts import build_parts

    case = case_or_path
    if isinstance(case_or_path, (str, Path)):
        from ..case import load_case

        case, _ = load_case(Path(case_or_path))
    return {name: cadquery.Workplane("XY").add(cadquery.Shape.cast(body.solid))
            for name, body in build_parts(case).items()}
