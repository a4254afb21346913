"""A flank with its modifications applied along the normal: r = r0 - cos(beta_b)·drop·n."""

from __future__ import annotations

import math

import numpy as np

from .base import Flank, FlankBreaks
from .involute import InvoluteFlank
from .modify import FlankModifications


class ModifiedFlank(Flank):
    """An involute flank displaced by `FlankModifications` (same parameters and domain)."""

    def __init__(self, base: InvoluteFlank, modifications: FlankModifications):
        self.base, self.modifications = base, modifications
        self.domain, self.edges, self.orientation = base.domain, base.edges, base.orientation
        self.straight_contact_lines = base.straight_contact_lines
        self._normal_factor = math.cos(base.gear.base_helix_angle)

    def drop(self, u, v):
        """Transverse drop (mm) at (u, v): the sum of the modifications."""
        b = self.base
        return self.modifications.drop(v, b.gear.base_radius * u, b.gear.face_width,
                                       b.form_roll, b.tip_roll)

    def normal_drop(self, u, v):
        """The material removed along the flank's normal (mm) at (u, v)."""
        return self._normal_factor * self.drop(u, v)

    def drop_normals(self, u, v):
        """The unit normals (..., 3) along which the drop is taken: the involute's."""
        _, normal = self.base.point_and_normal(np.asarray(u, float), np.asarray(v, float))
        return np.stack(np.broadcast_arrays(*normal), axis=-1)

    def point(self, u, v):
        (x, y, z), (nx, ny, nz) = self.base.point_and_normal(u, v)
        d = -self.normal_drop(u, v)
        return x + d * nx, y + d * ny, z + d * nz

    def parameters_near(self, points):
        return self.base.parameters_near(points)

    def breaks(self) -> FlankBreaks:
        """Where the tip edge is broken, the end chamfers start and the modifications bend
        the flank, in its parameters (roll angle u, face position v)."""
        mods, gear = self.modifications, self.base.gear
        edge = mods.tip_edge
        rounding = None
        if edge is not None:
            rounding = (edge.start / gear.base_radius,
                        1.0 if self.base.tip_roll >= edge.start else -1.0)
        chamfer = None if mods.end_chamfer is None else mods.end_chamfer.start(gear.face_width)
        return FlankBreaks(rounding, chamfer,
                           tuple(sorted(b / gear.base_radius for b in mods.profile_breaks)),
                           mods.lead_breaks(gear.face_width))
