"""Where lines meet a flank (contact/rays.py): a caller that takes only the hits inside the
flank's domain (the separation of the rigid search) abandons the rays that cycle."""

import math

import numpy as np

from toothcontact import gearset
from toothcontact.surfaces.placement import Misalignment
from toothcontact.case import parse_case
from toothcontact.contact import rays

CASE = {"kind": "spur", "teeth": [20, 60], "module": "3 mm", "pressure_angle": "20 deg",
        "face_width": "20 mm", "gear": {"crown": {"radius": "3000 mm"}},
        "load": {"tangential_load": "8000 N"}}


def whole_grid_rays(helix_deg: float = 0.0, slope: float = 0.0):
    """The rigid search's first ray solve (contact/cycle.parallel_cycle, search.separation):
    the normals of a 41 × 41 grid of pinion flank points at 7 positions of three tooth pairs,
    onto the gear flank, in its frame: (gear flank, points, directions, u0, v0)."""
    pair = gearset.gear_pair(parse_case({**CASE, "helix_angle": f"{helix_deg} deg"}))
    mesh = pair.placed(Misalignment(slope=slope))
    pinion = gearset.working_flank(pair.pinion, pair.pinion_modifications, 1)
    gear = gearset.working_flank(pair.gear, pair.gear_modifications, mesh.gear_side)
    u, v = pinion.grid(41, 41)
    sample = pinion.evaluate(u.ravel(), v.ravel(), order=1)
    pitch = mesh.driver_pitch
    points, normals = [], []
    for phi in np.linspace(-0.5 * pitch, 0.5 * pitch, 7):
        for j in (-1, 0, 1):
            pf, gf = mesh.pinion_frame(phi, j), mesh.gear_frame(phi, j, 0.0)
            points.append(gf.to_local(pf.to_world(sample.points)))
            normals.append(gf.vectors_to_local(pf.vectors_to_world(sample.normals)))
    points, normals = np.concatenate(points), np.concatenate(normals)
    return (gear, points, normals) + gear.parameters_near(points)


class Counting:
    """A flank that counts the ray steps taken on it (points evaluated)."""

    def __init__(self, flank):
        self.flank, self.steps = flank, 0
        self.domain, self.orientation = flank.domain, flank.orientation

    def tangents(self, u, v):
        self.steps += np.size(u)
        return self.flank.tangents(u, v)


def test_the_hits_inside_the_flank_are_the_same_when_cycling_rays_are_abandoned():
    for helix, slope in ((0.0, 0.0), (0.0, 1e-3), (20.0, -5e-4)):
        gear, points, normals, u0, v0 = whole_grid_rays(helix, slope)
        every, inside = Counting(gear), Counting(gear)
        full = rays.intersect(every, points, normals, u0, v0)
        kept = rays.intersect(inside, points, normals, u0, v0, inside_only=True)
        assert full.inside.sum() > 0.2 * full.inside.size      # the lines that meet the flank
        assert np.array_equal(kept.inside, full.inside)
        on = full.inside
        for name in ("u", "v", "s", "normal"):
            assert np.array_equal(getattr(kept, name)[on], getattr(full, name)[on]), name
        # the lines that miss it cycled on for most of the 30 steps allowed; abandoned after
        # STALL_STEPS without halving their residual, the solve takes about half the steps
        # (0.47-0.49 on these three; STALL_STEPS = 1 loses hits inside, 2 and up do not)
        assert not full.converged.all()
        assert inside.steps < 0.6 * every.steps, (inside.steps, every.steps)


def test_a_line_that_misses_the_flank_stops_after_the_stall_steps():
    gear, points, normals, u0, v0 = whole_grid_rays()
    full = rays.intersect(gear, points, normals, u0, v0)
    missing = np.flatnonzero(~full.converged)[:50]
    counted = Counting(gear)
    hits = rays.intersect(counted, points[missing], normals[missing], u0[missing], v0[missing],
                          inside_only=True)
    assert not hits.converged.any() and not hits.inside.any()
    # each abandoned no later than when it last halved its residual plus STALL_STEPS
    assert counted.steps < 30 * len(missing)
    assert math.isfinite(float(np.nanmax(np.abs(hits.u))))
