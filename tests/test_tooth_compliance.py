"""Tooth compliance along the face (contact.compliance): the slice against closed forms of a
uniform plate, the face coupling against the continuous Pasternak line's Green's function,
and the gear body term against its published fit."""

from __future__ import annotations

import math

import numpy as np
import pytest

from toothcontact.analytic.hats import hats
from toothcontact.analytic.stiffness import foundation_compliance, mesh_stiffness
from toothcontact.contact.compliance import ToothCompliance, cantilever
from toothcontact.contact.structure import FaceCoupling, FaceLoad, end_layer, end_layer_share
from toothcontact.rating.load_factors import face_load_factor
from toothcontact.surfaces.involute import CylindricalGear

E, NU = 206000.0, 0.3


def test_a_uniform_plate_loaded_at_its_free_edge_matches_its_closed_forms():
    """Cantilever of length H and thickness t under a transverse unit line load at the
    free edge: bending 4H³/(E't³), shear 1.2H/(Gt), no axial part; Vlasov's coupling
    length H·sqrt((2.4 - 3ν)/3) (module docstring). Tolerance 0.1 % (trapezoid rule on
    2001 points)."""
    H, t = 7.0, 5.0
    s = np.linspace(0.0, H, 2001)
    plate = cantilever(s, np.full_like(s, t / 2), H, t / 2, (0.0, -1.0), E, NU)
    E_plane, G = E / (1 - NU ** 2), E / (2 * (1 + NU))
    assert plate.bending[0, 0] == pytest.approx(4 * H ** 3 / (E_plane * t ** 3), rel=1e-3)
    assert plate.shear[0, 0] == pytest.approx(1.2 * H / (G * t), rel=1e-3)
    assert plate.axial[0, 0] == 0.0
    assert plate.coupling_length[0] == pytest.approx(H * math.sqrt((2.4 - 3 * NU) / 3),
                                                     rel=1e-3)


def test_a_uniform_plate_under_loads_along_it_deflects_as_the_beam_does():
    """Cross compliance (the profile direction) of a uniform plate, by Maxwell-Betti against
    the beam's closed forms within 0.2 %: loads at s1 = H/2 and s2 = H give
    s1²(3 s2 - s1)/(6E'I) + 1.2 s1/(Gt) both ways; a uniform line load q over the whole
    height (40 loads, the midpoint rule) moves the free edge by qH⁴/(8E'I) + 1.2 qH²/(2Gt),
    I = t³/12 per unit width."""
    H, t, q = 7.0, 5.0, 1.0
    s = np.linspace(0.0, H, 4001)
    E_plane, G, inertia = E / (1 - NU ** 2), E / (2 * (1 + NU)), t ** 3 / 12
    loads = np.array([H / 2, H])
    plate = cantilever(s, np.full_like(s, t / 2), loads, np.full(2, t / 2),
                       np.tile([0.0, -1.0], (2, 1)), E, NU)
    total = plate.bending + plate.shear + plate.axial
    cross = (H / 2) ** 2 * (3 * H - H / 2) / (6 * E_plane * inertia) + 1.2 * (H / 2) / (G * t)
    assert total[0, 1] == pytest.approx(cross, rel=2e-3)
    assert total[1, 0] == pytest.approx(total[0, 1], rel=1e-12)
    n = 40
    spots = (np.arange(n) + 0.5) * H / n
    at = np.append(spots, H)
    plate = cantilever(s, np.full_like(s, t / 2), at, np.full(n + 1, t / 2),
                       np.tile([0.0, -1.0], (n + 1, 1)), E, NU)
    edge = ((plate.bending + plate.shear)[-1, :n] * q * H / n).sum()
    exact = q * H ** 4 / (8 * E_plane * inertia) + 1.2 * q * H ** 2 / (2 * G * t)
    assert edge == pytest.approx(exact, rel=2e-3)


def test_a_load_inside_the_plate_bends_only_the_part_below_it():
    """A load at s = H/2 of a uniform plate: bending 4(H/2)³/(E't³) (the part beyond the
    load carries no moment); the coupling length grows with the unloaded part's slope."""
    H, t = 7.0, 5.0
    s = np.linspace(0.0, H, 4001)
    inside = cantilever(s, np.full_like(s, t / 2), H / 2, t / 2, (0.0, -1.0), E, NU)
    E_plane = E / (1 - NU ** 2)
    assert inside.bending[0, 0] == pytest.approx(4 * (H / 2) ** 3 / (E_plane * t ** 3),
                                                 rel=1e-3)
    at_edge = cantilever(s[s <= H / 2], np.full(int((s <= H / 2).sum()), t / 2), H / 2,
                         t / 2, (0.0, -1.0), E, NU)
    assert inside.coupling_length[0] > at_edge.coupling_length[0]


def green(z, z0, length, face):
    """The continuous Pasternak line's Green's function on [0, face], free ends."""
    low, high = min(z, z0), max(z, z0)
    return (math.cosh(low / length) * math.cosh((face - high) / length)
            / (length * math.sinh(face / length)))


@pytest.mark.parametrize("face, length", [(20.0, 2.5), (30.0, 3.2), (6.0, 3.0)])
def test_the_face_coupling_is_the_pasternak_line(face, length):
    """A unit point load at mid-face and at the face end: the discrete coupling's
    deflections against the continuous Green's function within 1 % of its peak (nodes
    length/8 apart); a uniform line load deflects every node by 1 (c = 1)."""
    nodes = int(round(face / (length / 8))) + 1
    coupling = FaceCoupling(0.0, face, length, nodes)
    z = coupling.nodes
    for at in (face / 2, 0.0):
        load = np.zeros(nodes)
        node = int(np.argmin(np.abs(z - at)))
        load[node], at = 1.0, z[node]
        w = coupling.flexibility @ load
        exact = np.array([green(zi, at, length, face) for zi in z])
        assert np.max(np.abs(w - exact)) < 0.01 * exact.max()
    uniform = coupling.flexibility @ coupling.widths
    assert np.allclose(uniform, 1.0, atol=1e-12)


def test_a_load_at_the_face_end_deflects_twice_as_far_as_in_mid_face():
    """End softening on a long face (face = 12 coupling lengths): the end's own deflection
    over mid-face's is 2·coth(L/λ)·tanh(L/2λ)... -> 2 within 0.1 %."""
    coupling = FaceCoupling(0.0, 36.0, 3.0, 289)
    end, middle = np.zeros(289), np.zeros(289)
    end[0], middle[144] = 1.0, 1.0
    ratio = (coupling.flexibility @ end)[0] / (coupling.flexibility @ middle)[144]
    exact = green(0.0, 0.0, 3.0, 36.0) / green(18.0, 18.0, 3.0, 36.0)
    assert ratio == pytest.approx(exact, rel=2e-3)
    assert exact == pytest.approx(2.0, rel=1e-3)


def test_a_coupling_fading_at_the_free_ends_softens_them_only_under_uneven_loads():
    """The end layer (Reissner's t/sqrt(10): 1.48 mm for a tooth 4.67 mm thick) on a 40 mm
    face, λ = 5.94 mm: a uniform load still deflects every node by 1; each link keeps the
    exact mean of (1 - e^(-d0/ℓ))(1 - e^(-d1/ℓ)) over it (the end link 1 - ℓ/s·(1 - e^(-s/ℓ))
    on a long face); a 1 mm patch at the end deflects 2.22 times one in mid-face (the free
    line's 1.89), converged within 1 % with the nodes half a layer apart; a load rising
    along the face (q = z/20 N/mm, c = 1) deflects the end node 2.6 % further than with
    w' = 0 (0.722 against 0.704), as the 3D FE's tooth does (benchmarks/fe_face_load.py's
    pinion: 0.731 c over the last 0.1 mm against the free line's 0.701)."""
    layer = end_layer(2.336)
    assert layer == pytest.approx(2 * 2.336 / math.sqrt(10))
    nodes = np.linspace(-20.0, 20.0, 81)
    share = end_layer_share(nodes, layer)
    step = 0.5
    assert share[0] == pytest.approx(1 - layer / step * (1 - math.exp(-step / layer)), rel=1e-9)
    assert share[0] == pytest.approx(share[-1]) and share[40] == pytest.approx(1.0, abs=1e-5)
    assert np.allclose(end_layer_share(nodes, 0.0), 1.0)

    def patch(coupling, z0, z1):
        zs = np.linspace(z0, z1, 4001)
        q = np.zeros(len(coupling.nodes))
        left, right = hats(coupling.nodes, zs)
        np.add.at(q, left, (1 - right) / len(zs))
        np.add.at(q, left + 1, right / len(zs))
        return q @ coupling.flexibility @ q

    ratios = {}
    for count in (81, 481):
        coupling = FaceCoupling(-20.0, 20.0, 5.944, count, layer)
        assert np.allclose(coupling.flexibility @ coupling.widths, 1.0, atol=1e-10)
        ratios[count] = patch(coupling, 19.0, 20.0) / patch(coupling, -0.5, 0.5)
    assert ratios[81] == pytest.approx(ratios[481], rel=0.01)
    assert ratios[481] == pytest.approx(2.22, abs=0.02)
    free = FaceCoupling(-20.0, 20.0, 5.944, 481)
    assert patch(free, 19.0, 20.0) / patch(free, -0.5, 0.5) == pytest.approx(1.89, abs=0.02)
    fading = FaceCoupling(-20.0, 20.0, 5.944, 481, layer)
    rising = [c.flexibility @ (c.widths * c.nodes / 20.0) for c in (fading, free)]
    assert rising[0][-1] == pytest.approx(0.722, abs=0.002)
    assert rising[1][-1] == pytest.approx(0.704, abs=0.002)


def test_the_gear_body_term_is_sainsots_fit():
    """Sainsot et al. (2004) at a tooth of their validity range (θ_f = 0.15 rad,
    h_fi = 2, load on the centre line's perpendicular): the bracket's terms written out by
    hand from the table's coefficients."""
    theta, h = 0.15, 2.0

    def star(A, B, C, D, E_, F):
        return A / theta ** 2 + B * h ** 2 + C * h / theta + D / theta + E_ * h + F

    L = star(-5.574e-5, -1.9986e-3, -2.3015e-4, 4.7702e-3, 0.0271, 6.8045)
    M = star(60.111e-5, 28.100e-3, -83.431e-4, -9.9256e-3, 0.1624, 0.9086)
    P = star(-50.952e-5, 185.50e-3, 0.0538e-4, 53.300e-3, 0.2895, 0.9236)
    assert foundation_compliance(3.0, 6.0, theta, h, 0.0, E) == pytest.approx(
        (L * 0.25 + M * 0.5 + P) / E, rel=1e-12)
    # the published validity range of L* (6.82-6.94): this tooth lies in it
    assert 6.82 <= L <= 6.94


def test_a_spur_tooth_is_stiffest_at_its_root_and_its_parts_are_all_positive():
    """The exact tooth's slice (z = 20, m = 3): every part positive, the total rising from
    the form circle to the tip; the coupling length of the order of the tooth height."""
    gear = CylindricalGear(20, 3.0, math.radians(20), 20.0)
    teeth = ToothCompliance(gear, E, NU)
    totals = [c.total for c in teeth.table]
    assert all(c.bending > 0 and c.shear > 0 and c.foundation > 0 and c.axial >= 0
               for c in teeth.table)
    assert np.all(np.diff(totals) > 0)
    height = gear.tip_radius - gear.root_radius_value
    assert all(0.2 * height < c.coupling_length < height for c in teeth.table)


def test_the_profile_compliance_is_a_symmetric_positive_definite_gram_matrix():
    """The exact tooth's cross compliance over the profile (z = 20, m = 3, and a ring of
    60): symmetric, positive definite, its diagonal the slices' totals, and each coupling
    below the geometric mean of the two own compliances (Cauchy-Schwarz: two loads at
    different heights bend the tooth in different shapes, which the single-shape rank-one
    coupling sqrt(c_i c_j) overstates)."""
    for gear in (CylindricalGear(20, 3.0, math.radians(20), 20.0),
                 CylindricalGear(60, 3.0, math.radians(20), 20.0, internal=True)):
        teeth = ToothCompliance(gear, E, NU)
        C = teeth.matrix
        assert np.allclose(C, C.T, rtol=1e-12, atol=0.0)
        assert np.linalg.eigvalsh(C).min() > 0
        assert np.allclose(np.diag(C), [c.total for c in teeth.table], rtol=1e-12)
        geometric = np.sqrt(np.outer(np.diag(C), np.diag(C)))
        off = ~np.eye(len(C), dtype=bool)
        assert np.all(C[off] < geometric[off])
        # far apart (form circle and tip) the difference is clear
        assert C[0, -1] < 0.95 * geometric[0, -1]


def test_iso_mesh_stiffness_and_face_load_factor():
    """ISO 6336-1:2006 §9.3.3 c_γα = c'(0.75 ε_α + 0.25) and §7.6 K_Hβ on both sides of
    K_Hβ = 2."""
    assert mesh_stiffness(14.0, 1.6) == pytest.approx(14.0 * 1.45)
    assert face_load_factor(10.0, 16.0, 320.0) == pytest.approx(1.25)
    assert face_load_factor(80.0, 16.0, 320.0) == pytest.approx(math.sqrt(8.0))
    assert face_load_factor(40.0, 16.0, 320.0) == pytest.approx(2.0)


@pytest.mark.parametrize("extent", [0.04, 2.0])
def test_the_line_load_spreads_each_cells_load_over_the_face_it_spans(extent):
    """FaceLoad.line_load (cumulative sums over the cells sorted by their start) against
    the direct sum of each cell's load times its covered share of every strip, on random
    face positions under a random pressure: cells much shorter than a strip and cells
    spanning several; to 1e-12 of the largest line load, and the line moment (each load
    times its cell's load radius) to 1e-10 of the largest (its cumulative sums are 30
    times larger: more round-off in t·S0 - S1). Strips covering every cell hold the whole
    load."""
    rng = np.random.default_rng(3)
    shape, cell = (30, 20), 0.01
    material = rng.random(shape) > 0.2
    z = rng.uniform(-6.0, 6.0, int(material.sum()))
    p = rng.random(shape) * 100.0
    order = np.argsort(z, kind="stable")
    edges = np.sort(rng.uniform(-8.0, 8.0, 15))
    radius = rng.uniform(30.0, 33.0, z.size)
    face = FaceLoad(material, order, z[order] - 0.5 * extent, extent, cell, radius[order])
    loads = p[material] * cell
    share = np.clip((edges[:, None] - z[None, :]) / extent + 0.5, 0.0, 1.0)
    for moment, weights, tolerance in ((False, loads, 1e-12), (True, loads * radius, 1e-10)):
        expected = np.diff(share @ weights) / np.diff(edges)
        found = face.line_load(p, edges, moment=moment)
        assert np.max(np.abs(found - expected)) < tolerance * np.max(np.abs(expected))
    whole = np.array([-8.0, -1.0, 0.5, 8.0])
    assert np.sum(face.line_load(p, whole) * np.diff(whole)) == pytest.approx(loads.sum(),
                                                                              rel=1e-12)
