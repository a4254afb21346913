"""The model's helical mesh stiffness against the independent 3D finite-element reference of
benchmarks/fe_helical_stiffness.py (stored in benchmarks/fe_helical_stiffness.json; issue 50
item 6, last part).

The pair: tests/test_loaded_teeth.py's helical one (z = 25/75, m_n = 3 mm, α_n = 20°,
β = 15°, b = 20 mm, 6000 N tangential, aligned, unmodified), whose mesh stiffness the model
puts 21 % above ISO 6336-1's c_γα. ε_α = 1.63 and ε_β = 0.55: two or three lines carry
everywhere, so the model reports no single-pair stiffness; the FE's c' is that of one line
wholly in the zone of action carrying the whole load alone.

The reference level is the medium mesh, computed on a 16-core machine in 2 minutes (the
benchmark's docstring has the command; stored with the light, light_fine_layers and coarse
levels: coarse to medium 0.3 %, the z-layers halved 0.01 %). Tolerance of the model against FE: 8 %, from
the FE's own convergence (coarse to medium section, and the z-layers halved, each within
2 %; the plane strain of the sections puts the medium one within 1 % of a converged one)
and the spur reference's agreement with the model (single-pair stiffness +2.9 %,
tests/test_face_load_fe.py), with the helical lines' oblique load on the slices, which the
spur pair does not test, given as much again. The model meets it: 16.51 against 15.31
(+7.8 %), with its gear bodies bending out of their plane (analytic.gear_body.flexure_green:
the load's axial part and the loads' face positions on a Mindlin plate) and its teeth
shearing along the face as walls under the axial part (analytic.tooth_wall); +9.0 %
without the walls, +32 % without the axial load path (which takes 15-19 % off the FE) and
+57 % before the bodies' coupling of the teeth in plane (chord_green).

The geometry and a smoke run of the FE tooling on the tiny level are checked here too.
"""

from __future__ import annotations

import importlib.util
import json
import math
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
STORED_PATH = ROOT / "benchmarks" / "fe_helical_stiffness.json"
STORED = json.loads(STORED_PATH.read_text()) if STORED_PATH.exists() else {"fe": {}}
REFERENCE = STORED.get("reference", "medium")


def benchmark():
    spec = importlib.util.spec_from_file_location(
        "fe_helical_stiffness", ROOT / "benchmarks" / "fe_helical_stiffness.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def reference(level: str | None = None, variant: str = "coupled") -> dict:
    level = level or REFERENCE
    if level not in STORED["fe"]:
        pytest.skip(f"benchmarks/fe_helical_stiffness.json has no {level!r} level (it holds "
                    f"{sorted(STORED['fe'])}): the FE reference is computed on a 16-core "
                    "machine by benchmarks/fe_helical_stiffness.py --levels light "
                    "light_fine_layers coarse medium")
    return STORED["fe"][level][variant]


@pytest.fixture(scope="module")
def fe():
    """The reference level's coupled results (skips where the JSON lacks it); listed before
    `model` so that a skip spares the model's run."""
    return reference()


@pytest.fixture(scope="module")
def bench():
    return benchmark()


@pytest.fixture(scope="module")
def pair(bench):
    return bench.the_pair()


@pytest.fixture(scope="module")
def model(bench):
    return bench.model_results()


def test_the_contact_lines_follow_the_helicoids(bench, pair):
    """On each member's turning section a fixed transverse line of action meets the flank at
    the roll the contact line gives (dρ/dz = σ·tan β_b, numerically from the screwed
    flank), the next tooth (+pitch) meets it one base pitch further (tooth_of), the flank's
    3D normal leans sin β_b axially and the gear's line is the pinion's complement."""
    geo = bench.geometry(pair, "tiny")
    sin_b = math.sin(pair.pinion.base_helix_angle)
    for name in ("pinion", "gear"):
        flank, rolls, zone = geo.member(name)
        rb = flank.base
        k = int(np.argmin(np.abs(flank.roll - flank.roll_range[0] - 2.5)))
        p, r = flank.flank[k], float(np.hypot(*flank.flank[k]))
        _, normal, n3, _, _ = flank.at(np.array([flank.roll[k]]))
        assert abs(abs(n3[0, 2]) - sin_b) < 1e-3
        # the base tangent point of the point's normal line: the fixed line of action
        tau = [a for a in (math.atan2(p[1], p[0]) + s * math.acos(rb / r) for s in (1, -1))
               if abs(np.cross(np.append(p - rb * np.array([math.cos(a), math.sin(a)]), 0),
                               np.append(normal[0], 0))[2]) < 1e-3][0]
        e = np.array([math.cos(tau), math.sin(tau)])

        def meet(turn):
            c, s = math.cos(turn), math.sin(turn)
            val = flank.flank @ np.array([[c, s], [-s, c]]) @ e - rb
            j = np.flatnonzero(np.sign(val[:-1]) != np.sign(val[1:]))[0]
            t = val[j] / (val[j] - val[j + 1])
            return flank.roll[j] + t * (flank.roll[j + 1] - flank.roll[j])

        slope = (meet(flank.twist * 4.0) - meet(-flank.twist * 4.0)) / 8.0
        assert slope == pytest.approx(flank.sigma * flank.tan_base_helix, rel=1e-4)
        assert flank.tooth_of(meet(flank.pitch) - meet(0.0)) == 1
    assert geo.pinion.sigma == -geo.gear.sigma
    z = np.linspace(-10, 10, 5)
    assert np.allclose(geo.pinion_roll(3, z) + geo.gear_roll(3, z), geo.action)
    assert STORED.get("transverse_contact_ratio", 1.63) == pytest.approx(1.63, abs=0.01)


def test_the_fe_tooling_runs_and_balances_on_the_tiny_level(bench, pair):
    """Smoke check of tests/fe_pair_helical.py (about 15 s): both members on the tiny level
    (0.4/1.5 mm elements, 4 mm layers and strips): the work-conjugate compliance reciprocal
    (Maxwell-Betti), the centre-line one within 15 % of it (a centre-line read under a
    load at another height is no work-conjugate pair: 7 % at the light level between
    neighbouring segments near the tip), the positions' line loads
    carry F_n, two or three lines at each, the body's coupling of the teeth softening the
    mesh (coupled below uncoupled), c' below the mesh stiffness."""
    pytest.importorskip("skfem")
    import fe_pair_helical as fh

    geo = bench.geometry(pair, "tiny")
    spec = dict(bench.LEVELS["tiny"])
    spec.pop("strip")
    members = {name: fh.member_compliance(geo, name, log=lambda *_: None, **spec)
               for name in ("pinion", "gear")}
    for m in members.values():
        assert np.abs(m.surface - m.surface.T).max() < 1e-9 * np.abs(m.surface).max()
        assert np.abs(m.matrix - m.matrix.T).max() < 0.15 * np.abs(m.matrix).max()
    load = bench.normal_load(pair)
    coupled = fh.HelicalPair(geo, members["pinion"], members["gear"]).stiffness(load)
    uncoupled = fh.HelicalPair(geo, members["pinion"], members["gear"],
                               coupled=False).stiffness(load)
    for p in coupled["positions"]:
        assert sum(p["line_loads_N"].values()) == pytest.approx(load, rel=1e-9)
        assert 2 <= len(p["line_loads_N"]) <= 3
    assert coupled["mesh_stiffness"] < 0.9 * uncoupled["mesh_stiffness"]
    assert 10.0 < coupled["single_stiffness"] < coupled["mesh_stiffness"] < 25.0


def test_the_fe_reference_is_converged_to_2_percent(fe):
    """Mesh convergence of the FE's mesh stiffness: the coarse section against the medium
    (the reference) and the light section's z-layers halved (2 to 1 mm), each within 2 %
    (c_γα and c'); plane strain of the sections puts the medium one within 1 % of a
    converged one (0.5 % pinion, 0.6 % gear, the coarse 1.1 and 1.2 %)."""
    ref = fe
    pairs = [(STORED["fe"]["coarse"]["coupled"], ref)] if "coarse" in STORED["fe"] else []
    if {"light", "light_fine_layers"} <= set(STORED["fe"]):
        pairs.append((STORED["fe"]["light"]["coupled"],
                      STORED["fe"]["light_fine_layers"]["coupled"]))
    assert pairs
    for name, v in STORED.get("plane_strain", {}).items():
        if "medium" in v["levels"]:
            assert 0.0 < v["levels"]["medium"]["stiffer_than_converged"] < 0.01, name
    for a, b in pairs:
        assert a["mesh_stiffness"] == pytest.approx(b["mesh_stiffness"], rel=0.02)
        assert a["single_stiffness"] == pytest.approx(b["single_stiffness"], rel=0.02)


def test_the_models_helical_mesh_stiffness_is_the_fes_within_8_percent(fe, model):
    """The model's mean mesh stiffness over the cycle (its c_γα counterpart) against the
    FE's mean over its positions (both evenly over one cycle): 16.51 N/(mm·µm) against
    15.31 (+7.8 %; +9.0 % without the tooth's wall under the load's axial part, +32 %
    without the bodies' flexure, +57 % without their coupling of the teeth in plane); per
    position the model's 15.7-17.6 against the FE's 14.3-16.4. With the FE's transverse
    compliances and the model's axial increment the pair is the FE's within 0.6 %
    (tests/test_gear_body.py): what is left is the transverse slices' own, stiffer than
    the FE's under the load's transverse part. Held to 8 % either way."""
    assert model["mesh_stiffness"] == pytest.approx(fe["mesh_stiffness"], rel=0.08)


def test_the_teeths_coupling_takes_a_fifth_off_and_the_uncoupled_fe_is_isos(fe, model):
    """The FE without the compliance between different pairs' lines ("uncoupled", each
    pair's teeth deflecting alone) 19.15 N/(mm·µm), within 10 % of ISO 6336-1's c_γα
    (19.82): the coupling takes 20 % off. ISO's c_γα is itself 29 % above the FE's."""
    uncoupled = reference(variant="uncoupled")
    assert 0.70 < fe["mesh_stiffness"] / uncoupled["mesh_stiffness"] < 0.90
    assert uncoupled["mesh_stiffness"] == pytest.approx(model["iso_mesh_stiffness"], rel=0.10)


def test_the_fe_under_the_loads_transverse_part_is_converged():
    """The FE with the load's axial part dropped (what transverse slices see, the counterpart
    of the model's in-plane part: tests/test_gear_body.py holds the model's axial increment
    to the difference): medium level 18.87 N/(mm·µm), light 19.30, within 3 %."""
    transverse = reference("medium_transverse", "coupled")
    light = reference("light_transverse", "coupled")
    assert light["mesh_stiffness"] == pytest.approx(transverse["mesh_stiffness"], rel=0.03)


def test_the_two_load_paths_each_take_a_sixth_off_the_fe(fe):
    """The shortfall taken apart on the reference level (mesh stiffness, N/(mm·µm)):
    - the load's axial part (sin β_b = 0.243 of F_n along the axis, which a transverse
      slice does not carry: the tooth and the gear body, on a bore at half the root radius,
      bending out of their plane; far more on the 75-tooth gear, whose centre-line
      deflection under a whole line's load it raises 44 % against the pinion's 12 % on the
      light level): uncoupled 22.45 without it, 19.15 with it (-14.7 %); c' 14.41 and
      12.05 (-16.4 %);
    - the bodies' coupling of different pairs' teeth (light level: a neighbouring line moves
      0.21 (pinion) and 0.46 (gear) of the loaded line's centre-line deflection under the
      load's transverse part; the rim's torsion between the bore and the root circle is 44 %
      and 28 % of that):
      transverse part alone 22.45 uncoupled, 18.87 coupled (-16 %); with the axial part
      19.15 and 15.31 (-20 %).
    Each takes 12-22 % off: neither is within the 8 % the model is held to, and the model
    has both (tests/test_gear_body.py: with the FE's own compliance of each line and the
    model's between lines the pair is the FE's coupled one within 0.8 %; with the FE's
    transverse compliances and the model's axial increment, its full one within 0.6 %)."""
    transverse = {v: reference("medium_transverse", v) for v in ("coupled", "uncoupled")}
    full = {v: reference(variant=v) for v in ("coupled", "uncoupled")}
    axial = full["uncoupled"]["mesh_stiffness"] / transverse["uncoupled"]["mesh_stiffness"]
    assert 0.78 < axial < 0.88
    assert 0.78 < fe["single_stiffness"] / transverse["coupled"]["single_stiffness"] < 0.88
    for v in (transverse, full):
        assert 0.78 < v["coupled"]["mesh_stiffness"] / v["uncoupled"]["mesh_stiffness"] < 0.88


def test_only_the_fe_has_a_single_pair_stiffness_and_it_is_isos_within_15_percent(fe, model):
    """No position of this pair has one line alone (ε_γ = 2.18): the model reports no c';
    the FE's (one line wholly in the zone carrying F_n alone, its largest over the
    positions) against ISO 6336-1's c' (13.45, the spur value scaled by cos β): 12.05
    (-10.4 %)."""
    assert model["single_stiffness"] is None
    assert fe["single_stiffness"] == pytest.approx(model["iso_single_stiffness"], rel=0.15)
