"""A helical tooth's wall under its load's axial part (analytic.tooth_wall): the closed form
of a long wall in shear, the finite elements' convergence, and how the contact's operator
takes it (contact.structure.MemberLoading). Against the 3D FE of the helical reference
pair: tests/test_gear_body.py (the line on itself) and tests/test_helical_stiffness_fe.py
(the mesh stiffness)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from toothcontact.analytic.tooth_wall import ToothWall
from toothcontact.case import parse_case
from toothcontact.contact.compliance import ToothCompliance
from toothcontact.contact.structure import FaceCoupling, MemberLoading, StructureOperator
from toothcontact.gearset import gear_pair

E, NU = 206000.0, 0.3
SHEAR = E / (2.0 * (1.0 + NU))


def helical_pair(helix: str = "15 deg"):
    return gear_pair(parse_case({
        "kind": "spur", "title": "wall", "teeth": [25, 75], "module": "3 mm",
        "pressure_angle": "20 deg", "helix_angle": helix, "face_width": "20 mm",
        "load": {"tangential_load": "6000 N"}}))


def hat_mean_shear(height, half, s0, h):
    """The closed form: a load q = 1 N/mm along a long wall, spread over height by the hat
    of half-width h about s0, moves the wall by u(s) = ∫₀^min(s, s') ds/(G·t) under a load
    at s'; its mean under the same hat (mm)."""
    x = np.linspace(s0 - h, s0 + h, 1601)
    hat = 1.0 - np.abs(x - s0) / h
    hat /= hat.sum()
    t = 2.0 * np.asarray(half)
    flexibility = np.concatenate([[0.0], np.cumsum(np.diff(height) * 0.5
                                                   * (1.0 / t[1:] + 1.0 / t[:-1]))])
    F = np.interp(x, height, flexibility)
    return float(hat @ np.minimum.outer(F, F) @ hat) / SHEAR


@pytest.mark.parametrize("taper", [0.0, 0.5])
def test_a_long_wall_shears_as_its_closed_form(taper):
    """A wall 6 mm high and 120 mm long (20 heights: its middle far from the free ends),
    4 mm thick at the root and `taper` thinner at the top, a uniform axial line load at the
    middle height node: its middle moves by the pure-shear closed form within 0.3 % (0.10 %
    and 0.12 % at the default refinement; 0.004 % and 0.014 % at twice it). E and ν enter
    only as G: the plane-stress Lamé constant does not."""
    height = np.linspace(0.0, 6.0, 50)
    half = 2.0 * (1.0 - taper * height / 6.0)
    wall = ToothWall(height, half, 120.0, E, NU)
    k, step = 3, wall.face[1] - wall.face[0]
    loads = np.zeros((len(wall.heights), len(wall.face)))
    loads[k] = step
    loads[k, [0, -1]] = 0.5 * step
    u = (wall.matrix @ loads.ravel()).reshape(loads.shape)
    exact = hat_mean_shear(height, half, wall.heights[k], wall.heights[1])
    assert u[k, len(wall.face) // 2] == pytest.approx(exact, rel=0.003)


def test_the_wall_is_symmetric_positive_definite_and_converged_on_a_helical_tooth():
    """The reference pair's pinion tooth (m 3 mm, 20 mm face): the compliance matrix is
    symmetric positive definite; a line of loads running diagonally over the face at the
    flank's heights deflects by the same mean within 0.3 % at twice the default refinement
    (the reference pair's mesh stiffness moves 0.002 %)."""
    teeth = ToothCompliance(helical_pair().pinion, E, NU)
    height, half = teeth._profile
    coarse = teeth.wall
    fine = ToothWall(height, half, 20.0, E, NU, refinement=2)
    assert np.allclose(coarse.matrix, coarse.matrix.T)
    assert np.linalg.eigvalsh(coarse.matrix).min() > 0.0
    z = np.linspace(-10.0, 10.0, 41)
    radius = np.linspace(teeth.radii[5], teeth.radii[-5], 41)
    means = []
    for wall in (coarse, fine):
        nodes, weights = wall.spread(teeth.wall_heights(radius), z)
        spread = np.zeros((len(z), len(wall.matrix)))
        np.add.at(spread, (np.arange(len(z))[:, None], nodes), weights)
        means.append(float(np.mean(spread @ wall.matrix @ spread.T)))
    assert means[0] == pytest.approx(means[1], rel=0.003)


def test_only_a_helical_tooth_has_a_wall():
    """A spur tooth's loads have no axial part: no wall, the operator as before."""
    assert ToothCompliance(helical_pair("0 deg").pinion, E, NU).wall is None
    assert ToothCompliance(helical_pair().pinion, E, NU).wall is not None


def test_the_operator_adds_the_walls_compliance_along_the_loads_axial_part():
    """A contact grid's StructureOperator with the wall: still symmetric, and p·B·p grows by
    exactly sin²β_b times the wall's quadratic form of the cells' loads (N: p times the
    cells' area) spread to its nodes
    (the load's axial part, the same weights both ways)."""
    pair = helical_pair()
    teeth = ToothCompliance(pair.pinion, E, NU)
    shape = (6, 7)
    rng = np.random.default_rng(4)
    cells = shape[0] * shape[1]
    z = np.linspace(-4.0, 4.0, cells) + rng.uniform(-0.3, 0.3, cells)
    radius = rng.uniform(teeth.radii[10], teeth.radii[-10], cells)
    share = np.full(cells, math.cos(pair.pinion.base_helix_angle) ** 2)
    heights = teeth.wall_heights(radius)

    def operator(wall):
        coupling = FaceCoupling(-10.0, 10.0, 5.0, 41, 1.0)
        member = MemberLoading(z, radius, share, 0.2, teeth.radii, teeth.matrix, coupling,
                               wall=wall)
        return StructureOperator([member], shape, 0.01, np.ones(shape, bool), ((1.0, E, NU),))

    with_wall, without = operator((teeth.wall, heights)), operator(None)
    p, q = rng.uniform(0.0, 1.0, (2,) + shape)
    assert np.sum(p * with_wall(q)) == pytest.approx(np.sum(q * with_wall(p)), rel=1e-12)
    nodes, weights = teeth.wall.spread(heights, z)
    loads = np.zeros(len(teeth.wall.matrix))
    np.add.at(loads, nodes, weights * (p.ravel() * 0.01)[:, None])
    added = math.sin(pair.pinion.base_helix_angle) ** 2 * loads @ teeth.wall.matrix @ loads
    work = 0.01 * (np.sum(p * with_wall(p)) - np.sum(p * without(p)))    # loads · deflections
    assert work == pytest.approx(added, rel=1e-10)
