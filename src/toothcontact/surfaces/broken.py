"""Flanks as made: a worm's or a worm wheel's exact flank with its tip edge broken by a
rounding or a chamfer and its face ends chamfered.

No standard fixes these edges (../shared/references/worm-tip-geometry.md: drawings give a
chamfer on the worm and the wheel's rim; no typical value was found); the defaults are the
project's assumption, stated in the results (worm_gearset.worm_set).

A rounding of radius ρ tangent to the flank and to the surface across its edge (the tip
cylinder of a worm, the throat torus of a wheel), whose outward normals make the angle θ,
starts ρ·tan(θ/2) before the edge, measured on the flank square to it. As for an involute's
tip (modify.TipEdge) the rounding is the drop it cuts from the flank along the flank's
normal: a circle departing from the flank's tangent at its start, of the radius relative to
the flank's own curvature across the edge (1/(1/ρ - κ)), so that the broken surface curves
by 1/ρ across it; at the edge the drop is that circle's, and past it (where a gap field
continues a flank) it runs on at its slope there and levels off within LEVEL_OFF of its
radius: curving on, the continued surface curled away (the lines of a gap field crossing
the tip failed to meet it), and a drop growing without bound (millimetres on a field's far
samples) is no longer what the flank's normal and a line through it make of it
(field.modification_gap). On a corner sharper
than a right angle the circle runs on straight once it has turned by ROUNDING_TURN. A
chamfer of `chamfer` mm along the flank from the edge, at `angle` to the flank, turns the
rounding of its edge by that angle and runs on straight. The rounding's start, its radius and
the angle θ are taken at the edge's middle (a wheel's tip edge turns a little along the
face).

The drop δ is put on as a turn about the member's own axis (its frame's z) by
-δ/(R·c), R the point's distance from the axis and c the flank normal's share along the
turn at the edge's middle: on a worm's helicoid the drop depends on the radius alone and the
turn keeps the surface a helicoid (its axial profile moved by the drop), so the worm's solid
is still the swept axial section; on a wheel the turn moves the flank along its tooth's
thickness. Both keep the jets exact (the surfaces' derivatives are the broken surface's).
Units: mm, rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .base import Flank, FlankBreaks
from .jet import Jet, cos_sin, value, where
from .modify import EndChamfer, arc_drop, broken_edge_drop

#: past its edge a rounding's drop levels off over this share of its radius (see the module)
LEVEL_OFF = 0.25
#: a rounding of a corner sharper than a right angle (a worm wheel's tip on a steep lead,
#: its flank meeting the throat at 110 deg) is modelled up to this turn from the flank and
#: run on along its tangent to the edge: taken along the flank's normal, the circle turns
#: square to the flank before it gets there; no contact reaches that far round
ROUNDING_TURN = math.radians(60.0)


@dataclass(frozen=True)
class ProfileEdgeBreak:
    """A rounding (or a chamfer with a rounded edge) across the flank's u edge at `edge`:
    it starts at u = `start` and runs `toward` (+1: to larger u) the edge; `scale` (mm per
    unit of u) the flank's length square to the edge, `radius` the rounding's (mm),
    `relative` its radius relative to the flank's curvature across the edge (mm), `back`
    the run (mm) from its start to the edge, `angle` where the rounding runs on straight
    (rad: a chamfer's, or ROUNDING_TURN on a corner sharper than a right angle) or None,
    `bend` the flank's curvature across the edge taken back along it (1/mm), `chamfered`
    whether it is a chamfer."""

    start: float
    toward: float
    scale: float
    radius: float
    relative: float
    back: float
    angle: float | None = None
    bend: float = 0.0
    chamfered: bool = False

    @classmethod
    def across(cls, flank: Flank, edge: str, radius: float, turn: float,
               chamfer: float | None = None, angle: float | None = None) -> ProfileEdgeBreak:
        """The break of `flank`'s u edge `edge` ("u0" or "u1") by a rounding of `radius`
        (mm), the surface across the edge turned by `turn` (rad) from the flank; with
        `chamfer` (mm along the flank from the edge) and `angle` (rad), a chamfer whose edge
        is rounded by `radius`. Raises ValueError where it does not fit on the flank."""
        (u0, u1), (v0, v1) = flank.domain
        at_edge, toward = (u1, 1.0) if edge == "u1" else (u0, -1.0)

        def square(u: float) -> tuple[float, float]:
            """The flank's length per unit of u square to the edge (mm) and its curvature
            that way (1/mm, convex positive) at u, the edge's middle."""
            sample = flank.evaluate(np.array(u), np.array(0.5 * (v0 + v1)))
            r_u, r_v = sample.r_u, sample.r_v
            return (float(np.linalg.norm(np.cross(r_u, r_v)) / np.linalg.norm(r_v)),
                    float(sample.normal_curvature(1.0, -np.dot(r_u, r_v) / np.dot(r_v, r_v))))

        scale, across = square(at_edge)
        if chamfer is None:
            if not 0.0 < turn < math.pi:
                raise ValueError(f"the flank meets the surface across its edge at "
                                 f"{math.degrees(turn):.3g} deg: a rounding needs a turn "
                                 "between 0 and 180 deg")
            back = radius * math.tan(0.5 * turn)
        else:
            if not 0.0 < angle < turn:
                raise ValueError(f"angle: {math.degrees(angle):.4g} deg must be less than "
                                 f"{math.degrees(turn):.3g} deg, the turn from the flank onto "
                                 "the surface across its edge")
            back = chamfer + radius * math.tan(0.5 * angle)
        if not 1.0 / radius - across > 0.0:
            raise ValueError(f"radius: {radius:.4g} mm is flatter than the flank itself "
                             f"(its radius of curvature {1.0 / across:.4g} mm) across the edge")
        relative = 1.0 / (1.0 / radius - across)
        if chamfer is None and back > relative * math.sin(ROUNDING_TURN):
            angle = ROUNDING_TURN        # a sharp corner's rounding, run on straight
        # the flank's length per unit of u taken at the rounding's middle (it changes over
        # the flank: taken at the edge, a wheel's rounding curved 2 % off at its start)
        scale, _ = square(at_edge - 0.5 * toward * back / scale)
        start = at_edge - toward * back / scale
        depth = (u1 - u0) * scale
        if not (u0 < start < u1 and back < 0.5 * depth):
            raise ValueError(f"the edge break reaches {back:.4g} mm into the flank, more than "
                             f"half its depth {depth:.4g} mm")
        return cls(float(start), toward, scale, float(radius), float(relative), float(back),
                   angle, -across, chamfer is not None)

    @property
    def breaks(self) -> tuple[float, ...]:
        """The parameters u where the flank's curvature jumps: the start, and a chamfer's
        where its edge's rounding runs into the straight chamfer."""
        if self.angle is None:
            return (self.start,)
        return (self.start, self.start + self.toward * self.relative * math.sin(self.angle)
                / self.scale)

    def drop(self, u):
        """The material removed along the normal (mm) at u (arrays or jets)."""
        run = (u - self.start) * (self.toward * self.scale)
        beyond = value(run) > 0.0
        held = where(beyond, run, 0.0 * run)
        if self.angle is not None:
            return where(beyond, broken_edge_drop(held, self.relative, self.angle, self.bend),
                         0.0 * run)
        past = value(run) > self.back
        circle = arc_drop(where(past, 0.0 * run + self.back, held), self.relative, "circular")
        root = math.sqrt(self.relative**2 - self.back**2)
        # past the edge: on at the edge's slope, levelling off over LEVEL_OFF of the radius
        level = LEVEL_OFF * self.relative
        slope = self.back / root
        continued = (self.relative - root
                     + slope * level * (1.0 - np.exp(-where(past, run - self.back, 0.0 * run)
                                                     / level)))
        return where(beyond, where(past, continued, circle), 0.0 * run)


class BrokenEdgeFlank(Flank):
    """`base` (a worm's or a worm wheel's flank, in its member's frame: axis z) as made: its
    tip edge broken by `tip` (a ProfileEdgeBreak or None), its face ends by `ends` (an
    end chamfer along v, modify.EndChamfer, over `face_width` mm, or None). Same domain and
    edges as the base; its data (module, blank, ...) are the base's.

    The turn that puts a drop δ on moves the point along the flank too, across the edge by
    k·δ (k the turn's share across the edge per unit of normal drop, at the edge's middle):
    a rounding put on at the base's parameters would be sheared by it (a worm's, turned
    mostly along its thread, lost a quarter of its curvature). So the base is taken at
    parameters moved back by k·δ: the broken flank's (u, v) are where its point lies across
    the edges after the turn, and its drop there is the break's own (normal_drop)."""

    def __init__(self, base: Flank, tip: ProfileEdgeBreak | None = None,
                 ends: EndChamfer | None = None, face_width: float | None = None):
        self.base, self.tip, self.ends, self.face_width_broken = base, tip, ends, face_width
        self.domain, self.edges, self.orientation = base.domain, base.edges, base.orientation
        self.straight_contact_lines = base.straight_contact_lines
        (u0, u1), (v0, v1) = base.domain
        sample = base.evaluate(np.array(u1 if tip is None or tip.toward > 0 else u0),
                               np.array(0.5 * (v0 + v1)))
        x, y, _ = sample.points
        along = np.array([-y, x, 0.0]) / math.hypot(x, y)
        #: the flank normal's share along the turn about the axis at the edge's middle
        self.turn_share = float(along @ sample.normals)
        if abs(self.turn_share) < 1e-6:
            raise ValueError("the flank's normal is square to the turn about its axis: an "
                             "edge break cannot be put on as a turn")
        moved = -along / self.turn_share     # the turn's move per unit of normal drop
        r_u, r_v = sample.r_u, sample.r_v
        #: the turn's move across the edges per unit of drop, in units of u and of v
        self._slip = tuple(float(moved @ square) / float(square @ square) for square in (
            r_u - (r_u @ r_v) / (r_v @ r_v) * r_v, r_v - (r_u @ r_v) / (r_u @ r_u) * r_u))

    def __getattr__(self, name):
        if name == "base":          # not yet set (unpickling): no recursion
            raise AttributeError(name)
        return getattr(self.base, name)

    def __getstate__(self):
        return self.__dict__

    def __setstate__(self, state):
        self.__dict__.update(state)

    def _drops(self, u, v):
        """(the tip's drop, the ends' drop) in mm at (u, v); 0 where there is none."""
        tip = 0.0 * u if self.tip is None else self.tip.drop(u)
        ends = 0.0 * v if self.ends is None else self.ends.drop(v, self.face_width_broken)
        return tip, ends

    def normal_drop(self, u, v):
        """The material removed along the flank's normal (mm) at arrays of (u, v): the
        break's drop, times the turn's share along the normal there over its share at the
        edge's middle (on a wheel it changes by a few per cent along the face)."""
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        tip, ends = self._drops(u, v)
        total = np.array(tip + ends, float)
        dropped = total != 0.0
        if dropped.any():
            sample, _ = self._exact(u[dropped], v[dropped])
            x, y = sample.points[..., 0], sample.points[..., 1]
            share = (-y * sample.normals[..., 0] + x * sample.normals[..., 1]) / np.hypot(x, y)
            total[dropped] *= share / self.turn_share
        return total

    def drop_normals(self, u, v) -> np.ndarray:
        """The unit normals (..., 3) along which the drop is taken at arrays of parameters:
        the exact flank's, turned with its point."""
        sample, turn = self._exact(np.asarray(u, float), np.asarray(v, float))
        cos, sin = np.cos(turn), np.sin(turn)
        n = sample.normals
        return np.stack([n[..., 0] * cos - n[..., 1] * sin, n[..., 0] * sin + n[..., 1] * cos,
                         n[..., 2]], axis=-1)

    def _exact(self, u: np.ndarray, v: np.ndarray):
        """The exact flank evaluated (to first order) where the broken one's points at
        arrays (u, v) come from, and the turn (rad) that moves them."""
        tip, ends = self._drops(u, v)
        sample = self.base.evaluate(*self._moved_back(u, v, tip, ends), order=1)
        x, y = sample.points[..., 0], sample.points[..., 1]
        return sample, -(tip + ends) / (np.hypot(x, y) * self.turn_share)

    def point(self, u, v):
        tip, ends = self._drops(u, v)
        if not isinstance(tip + ends, Jet) and not np.any(tip + ends):
            return self.base.point(u, v)
        x, y, z = self.base.point(*self._moved_back(u, v, tip, ends))
        cos, sin = cos_sin(-(tip + ends) / (np.sqrt(x * x + y * y) * self.turn_share))
        return x * cos - y * sin, x * sin + y * cos, z

    def _moved_back(self, u, v, tip, ends):
        """The base's parameters a broken point comes from: (u, v) moved back by the turn's
        slip across the edges, held at the tip's edge (a large break, a sharp corner's run
        on straight, would take them past the flank, where a wheel's surface is not)."""
        u_back = u - self._slip[0] * tip
        if self.tip is not None:
            (u0, u1), _ = self.domain
            edge = u1 if self.tip.toward > 0 else u0
            past = (value(u_back) - edge) * self.tip.toward > 0.0
            if np.any(past):
                u_back = where(past, 0.0 * u_back + edge, u_back)
        return u_back, v - self._slip[1] * ends

    def parameters_near(self, points):
        return self.base.parameters_near(points)

    def profile_parameters(self, count: int) -> np.ndarray:
        """`count` values of u evenly over the domain and more over the tip's break, from a
        little before its start to the edge, so that a section follows its turn."""
        even = self.base.profile_parameters(count)
        if self.tip is None:
            return even
        (u0, u1), _ = self.domain
        edge = u1 if self.tip.toward > 0 else u0
        step = (edge - self.tip.start) / 7.0
        # the break at 8 points, and 3 more before its start at their spacing: a section's
        # spline then turns into it without overshooting (the curvature jumps there)
        break_points = self.tip.start + step * np.arange(-3, 8)
        even = even[(even - self.tip.start) * self.tip.toward < -3.5 * abs(step)]
        return np.unique(np.concatenate([even, break_points]))

    def breaks(self) -> FlankBreaks:
        """Where the edges are broken, in this flank's parameters."""
        face = self.face_width_broken
        return FlankBreaks(
            rounding=None if self.tip is None else (self.tip.start, self.tip.toward),
            chamfer=None if self.ends is None else self.ends.start(face),
            profile_kinks=() if self.tip is None else tuple(sorted(self.tip.breaks)),
            lead_kinks=() if self.ends is None else self.ends.breaks(face))


class BrokenWormFlank(BrokenEdgeFlank):
    """A worm's flank as made: a helicoid still (the drop depends on the radius alone, and a
    turn about the axis keeps the radius), whose axial section is the base's moved by the
    turn's axial equivalent: a turn by φ about the axis is the helicoid's shift by -p·φ
    along it (p the screw parameter)."""

    def axial_section(self, count: int) -> tuple[np.ndarray, np.ndarray]:
        """The broken flank's axial section (radii r and axial positions z, mm, in the
        half-plane y = 0, x > 0) through `count` points over the flank and seven more over
        the tip's break: the base's profile at the radius its point keeps under the turn,
        moved along the axis by the turn's equivalent."""
        u = self.profile_parameters(count)
        tip, ends = self._drops(u, 0.0 * u)
        r, _ = self._moved_back(u, 0.0 * u, tip, ends)
        return r, self.base.axial_profile(r) + self.base.screw_parameter * tip / (
            r * self.turn_share)

