"""Worm sets as made (surfaces.broken, worm_gearset.worm_edges): the worm's and the wheel's tip
edges rounded or chamfered and the wheel's rim faces chamfered, held to what a rounding is
independently of how it is put on: the broken flank departs from the exact one at the
rounding's start with no step or kink, curves by 1/ρ across its edge (the principal
curvature of the surface, from its own jets), reaches the drop of a circle tangent to the
flank at the edge, leaves the rest of the flank exact, and a worm stays a helicoid. Lengths
in mm."""

import math

import numpy as np
import pytest
from scipy.optimize import least_squares

from toothcontact import worm_gearset
from toothcontact.case import parse_case
from toothcontact.runner import bundled_cases_dir
from toothcontact.case import load_case


@pytest.fixture(scope="module")
def saba():
    case, _ = load_case(bundled_cases_dir() / "worm_saba_set.toml")
    return case, worm_gearset.worm_set(case)


def across(flank, u, v=0.0):
    """The broken flank's normal curvature square to its u edges at (u, v) (1/mm)."""
    sample = flank.evaluate(np.atleast_1d(u), np.full(np.shape(np.atleast_1d(u)), v))
    F = np.einsum("...i,...i", sample.r_u, sample.r_v)
    G = np.einsum("...i,...i", sample.r_v, sample.r_v)
    return sample.normal_curvature(1.0, -F / G)


@pytest.mark.parametrize("member", ["worm", "wheel"])
def test_a_rounded_tip_curves_by_its_radius_across_the_edge(saba, member):
    """Over the rounding, from just past its start to the tip, the surface curves by 1/ρ
    (ρ = 0.1 normal modules by default, 0.11 mm) across the edge within 1.5 %: the turn that
    puts the drop on does not shear it (a worm's, turned along its thread, lost a quarter
    of its curvature before the slip was taken back). Before the start the flank is the
    exact one, point for point."""
    case, parts = saba
    flank = getattr(parts, member)["left"]
    tip = flank.tip
    assert tip.radius == pytest.approx(0.1 * 1.1)
    (u0, u1), _ = flank.domain
    edge = u1 if tip.toward > 0 else u0
    u = np.linspace(tip.start, edge, 9)[1:]
    curvature = across(flank, u)
    assert np.allclose(curvature, 1.0 / tip.radius, rtol=0.015)
    before = np.linspace(u0 if tip.toward > 0 else tip.start, tip.start if tip.toward > 0
                         else u1, 7)
    for v in (-1.0, 0.0, 2.0):
        exact = np.stack(flank.base.point(before, np.full_like(before, v)), -1)
        broken = np.stack(flank.point(before, np.full_like(before, v)), -1)
        assert np.abs(broken - exact).max() < 1e-12


@pytest.mark.parametrize("member", ["worm", "wheel"])
def test_the_rounding_starts_tangent_and_drops_as_its_circle(saba, member):
    """The drop along the normal starts at 0 with slope 0 (no step, no kink: one-sided
    differences of the jets' drop across the start) and reaches, at the edge, the drop of
    a circle of the relative radius tangent at the start, back = ρ·tan(θ/2) along the flank,
    θ the turn onto the tip surface; the broken edge point's distance from the exact flank
    (its nearest point, solved) matches it within a micrometre."""
    from toothcontact.surfaces.jet import Jet

    _, parts = saba
    flank = getattr(parts, member)["left"]
    tip = flank.tip
    (u0, u1), _ = flank.domain
    h = 1e-7
    U, _ = Jet.variables(np.array([tip.start + tip.toward * h, tip.start - tip.toward * h]),
                         np.zeros(2), 1)
    drop = tip.drop(U)
    assert np.abs(drop.f).max() < 1e-12 and np.abs(drop.u).max() < 1e-5
    edge = u1 if tip.toward > 0 else u0
    circle = tip.relative - math.sqrt(tip.relative**2 - tip.back**2)
    assert tip.drop(np.array(edge)) == pytest.approx(circle, rel=1e-12)
    # the material removed: the circle's drop, times the turn's share along the normal where
    # the point comes from (a little inside the edge) over its share at the edge: 1 %
    assert float(flank.normal_drop(np.array(edge), np.array(0.0))) == pytest.approx(circle, rel=0.01)
    broken = np.stack(flank.point(np.array(edge), np.array(0.0)), -1)
    nearest = least_squares(lambda uv: np.stack(flank.base.point(*uv), -1) - broken,
                            [edge, 0.0], xtol=1e-15, ftol=1e-15, gtol=1e-15)
    depth = float(np.linalg.norm(nearest.fun))
    assert depth == pytest.approx(circle, abs=1e-3)


def test_a_broken_worm_is_still_a_helicoid(saba):
    """A screw motion by φ about the worm axis (turn φ, advance p·φ) maps the broken
    flank's point at (u, v) onto its point at (u, v + φ), on the rounding too, to 1e-12 mm:
    the worm's solid is still its axial section swept along the thread."""
    _, parts = saba
    worm = parts.worm["right"]
    u = np.linspace(worm.tip.start - 0.3, worm.domain[0][1], 11)
    v = np.full_like(u, 0.2)
    phi, p = 0.37, worm.screw_parameter
    x, y, z = worm.point(u, v)
    X, Y, Z = worm.point(u, v + phi)
    c, s = math.cos(phi), math.sin(phi)
    assert np.allclose(X, c * x - s * y, atol=1e-12)
    assert np.allclose(Y, s * x + c * y, atol=1e-12)
    assert np.allclose(Z, z + p * phi, atol=1e-12)
    r, zs = worm.axial_section(9)
    back = worm.base.axial_profile(r)
    assert np.all(np.abs(zs - back)[r < worm.tip.start - 1e-9] < 1e-12)
    assert np.abs(zs - back)[-1] > 0.01      # the tip's section bends in


def raw_case(**edges):
    case, raw = load_case(bundled_cases_dir() / "worm_saba_set.toml")
    for member, spec in edges.items():
        raw[member.split(".")[0]][member.split(".")[1]] = spec
    return parse_case(raw)


def test_the_case_says_how_the_edges_are_broken():
    """'0 mm' leaves a tip sharp; a chamfer turns onto a straight chamfer at its angle (the
    drop's slope tan(angle) past the rounding of its edge); a rim chamfer breaks the
    wheel's face ends; a rounding that does not fit names its field and the limit."""
    sharp = worm_gearset.worm_set(raw_case(**{"worm.tip_edge": {"radius": "0 mm"},
                                         "wheel.tip_edge": {"radius": "0 mm"}}))
    assert sharp.worm["left"].tip is None and sharp.wheel["left"].tip is None
    assert sharp.edges["worm_tip"] is None
    chamfered = worm_gearset.worm_set(raw_case(**{
        "worm.tip_edge": {"chamfer": "0.15 mm", "angle": "20 deg", "radius": "0.05 mm"},
        "wheel.rim_chamfer": {"length": "0.4 mm", "angle": "30 deg"}}))
    tip = chamfered.worm["left"].tip
    assert tip.angle == pytest.approx(math.radians(20.0))
    from toothcontact.surfaces.jet import Jet
    (u0, u1), _ = chamfered.worm["left"].domain
    U, _ = Jet.variables(np.array([u1 - 1e-3]), np.zeros(1), 1)
    assert tip.drop(U).u[0] / tip.scale == pytest.approx(math.tan(tip.angle), rel=0.02)
    wheel = chamfered.wheel["left"]
    assert wheel.ends is not None and wheel.breaks().chamfer == pytest.approx(
        0.5 * wheel.face_width - 0.4 - 0.11 * math.tan(math.radians(15.0)))
    assert chamfered.edges["wheel_rim"]["chamfer_mm"] == pytest.approx(0.4)
    with pytest.raises(ValueError, match=r"worm\.tip_edge: .*half its depth"):
        worm_gearset.worm_set(raw_case(**{"worm.tip_edge": {"radius": "3 mm"}}))


def test_a_contact_on_the_worms_rounding_is_reported_as_such(saba):
    """The contact engine sees the worm's and the wheel's roundings as broken edges
    (Flank.breaks): where they start in each flank's own parameter, toward the tip."""
    from toothcontact.surfaces.placement import WormMesh
    from toothcontact.contact.cycle import CycleSettings, parallel_cycle
    from toothcontact.contact.edge_loads import edge_breaks
    from toothcontact.analytic.hertz import compliance

    _, parts = saba
    mesh = WormMesh(parts.wheel["left"])
    cycle = parallel_cycle(mesh, parts.worm["left"], parts.wheel["left"], 200.0,
                           compliance(206000.0, 0.3, 98000.0, 0.35),
                           CycleSettings(positions=1, grid=(11, 41), pairs=(0,)))
    breaks = edge_breaks(cycle)
    assert breaks.curved
    assert breaks.roundings["pinion"] == (parts.worm["left"].tip.start, 1.0)
    assert breaks.roundings["gear"] == (parts.wheel["left"].tip.start, -1.0)
