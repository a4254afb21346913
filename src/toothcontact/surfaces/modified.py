"""A flank with its modifications applied along the normal: r = r0 - cos(beta_b)·drop·n."""

from __future__ import annotations

import math

from ..modify import FlankModifications
from .base import Flank
from .involute import InvoluteFlank


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

    def point(self, u, v):
        (x, y, z), (nx, ny, nz) = self.base.point_and_normal(u, v)
        d = -self.normal_drop(u, v)
        return x + d * nx, y + d * ny, z + d * nz

    def parameters_near(self, points):
        return self.base.parameters_near(points)
