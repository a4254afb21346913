"""The generated solids as CadQuery objects (cad.cq.workplanes): a user cuts a bore and a
keyway into a generated gear with CadQuery's own API and exports it; the result is a valid
solid whose volume fell by the bore and keyway's (an independent closed form), and the STEP
reads back with the same volume."""

import math

import pytest

cadquery = pytest.importorskip("cadquery")

from toothcontact.cad.cq import workplanes  # noqa: E402
from toothcontact.case import parse_case  # noqa: E402

CASE = {"kind": "spur", "teeth": [20, 60], "module": "3 mm", "pressure_angle": "20 deg",
        "face_width": "30 mm", "pinion": {"crown": {"height": "10 um"}}}


def test_a_bore_and_a_keyway_cut_into_a_generated_gear(tmp_path):
    parts = workplanes(parse_case(CASE))
    assert set(parts) == {"pinion", "gear"}
    gear = parts["gear"]
    solid = gear.val()
    assert isinstance(solid, cadquery.Shape) and solid.isValid()
    before = solid.Volume()
    bore, key_width, key_depth, face = 40.0, 12.0, 3.3, 30.0
    cut = (gear.faces(">Z").workplane().hole(bore)
           .faces(">Z").workplane().center(bore / 2, 0)
           .rect(2 * key_depth, key_width).cutBlind(-face))
    after = cut.val()
    assert after.isValid()
    # the bore's cylinder and the keyway's box beyond it (the box reaches key_depth past
    # the bore's wall: its part inside the bore, a circular segment, was already cut)
    r, w = bore / 2, key_width / 2
    chord = math.sqrt(r * r - w * w)                   # where the key's sides meet the bore
    segment = r * r * math.asin(w / r) - w * chord     # the bore's part beyond that chord
    removed = (math.pi * r * r + key_width * key_depth + key_width * (r - chord) - segment) * face
    assert before - after.Volume() == pytest.approx(removed, rel=1e-4)
    path = tmp_path / "gear_with_bore.step"
    cadquery.exporters.export(cut, str(path))
    back = cadquery.importers.importStep(str(path)).val()
    assert back.isValid() and back.Volume() == pytest.approx(after.Volume(), rel=1e-6)


def test_a_case_file_path_works_too(tmp_path):
    import tomli_w

    path = tmp_path / "pair.toml"
    path.write_bytes(tomli_w.dumps({**CASE, "export": {"teeth": 3}}).encode())
    parts = workplanes(path)
    assert all(p.val().isValid() for p in parts.values())
