"""B-spline solid of a cylindrical worm: its thread swept by the screw motion.

Every worm flank is a helicoid (see surfaces.worm): its axial profile, screwed about the
axis. The solid is built the same way: the thread's axial section (both flank profiles
interpolated through exact points from the form or root circle, tip and root lines; below a
form circle, radial lines down to the root, where the flank's model ends and the real thread
is undercut) is swept along a helix with the
Frenet trihedron, which for a helix is exactly the screw motion; the threads, whose root
faces lie on the core cylinder, are glued to it (a fusion of shapes that share faces, far
faster than a general boolean) and cut to length by the end planes. `worm_flank_deviation` measures the
faces against the exact flank.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..surfaces.worm import WormFlank
from .loft import chord_parameters, interpolated


@dataclass
class WormBody:
    """A built worm: the OCP solid and its two exact flanks (left, right)."""

    solid: object
    flanks: dict[str, WormFlank]

    @property
    def description(self) -> str:
        worm = self.flanks["left"]
        return f"{worm.starts} start(s), {worm.length:g} mm long"

    def flank_deviation(self) -> float:
        return worm_flank_deviation(self)


def build_worm(left: WormFlank, right: WormFlank, profile_points: int = 17) -> WormBody:
    """Solid worm of `left.length`, centred at z = 0, with all its starts."""
    from OCP.BOPAlgo import BOPAlgo_GlueFull
    from OCP.BRepAlgoAPI import BRepAlgoAPI_Common, BRepAlgoAPI_Fuse
    from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder
    from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt
    from OCP.TopTools import TopTools_ListOfShape

    rf, ra = left.root_diameter / 2, left.domain[0][1]
    lead, length = left.lead, left.length
    turns_before = math.ceil(0.5 * length / lead + 1.0)
    base = gp_Ax2(gp_Pnt(0, 0, -0.5 * length), gp_Dir(0, 0, 1))
    envelope = BRepPrimAPI_MakeCylinder(base, ra + left.axial_module, length).Shape()
    threads, core = TopTools_ListOfShape(), TopTools_ListOfShape()
    for start in range(left.starts):
        thread = _swept_thread(left, right, profile_points, -turns_before * lead,
                               2 * turns_before, start * 2.0 * math.pi / left.starts)
        threads.Append(_boolean(BRepAlgoAPI_Common, thread, envelope))
    core.Append(BRepPrimAPI_MakeCylinder(base, rf, length).Shape())
    fuse = BRepAlgoAPI_Fuse()
    fuse.SetArguments(core)
    fuse.SetTools(threads)
    fuse.SetGlue(BOPAlgo_GlueFull)
    fuse.SetRunParallel(True)
    fuse.Build()
    if not fuse.IsDone():
        raise RuntimeError("gluing the worm's threads to its core failed")
    return WormBody(fuse.Shape(), {"left": left, "right": right})


def _swept_thread(left: WormFlank, right: WormFlank, n: int, z0: float, turns: int, angle: float):
    """One thread: its axial section (flanks, tip line, root line on the core cylinder; radial
    lines from a form circle above the root down to it) at z0,
    a whole number of leads below the thread centred at z = 0, turned by `angle`, swept along
    `turns` turns of a helix."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeWire, BRepBuilderAPI_Transform
    from OCP.BRepOffsetAPI import BRepOffsetAPI_MakePipeShell
    from OCP.gp import gp_Ax1, gp_Dir, gp_Pnt, gp_Trsf, gp_Vec
    from OCP.TopoDS import TopoDS

    (r0, _), root = left.domain[0], left.root_diameter / 2
    (r_left, z_left), (r_right, z_right) = left.axial_section(n), right.axial_section(n)
    pts_left = np.column_stack([r_left, 0 * r_left, z_left])
    pts_right = np.column_stack([r_right, 0 * r_right, z_right])
    params = chord_parameters(pts_left[:, [0, 2]])
    line = lambda p, q: BRepBuilderAPI_MakeEdge(gp_Pnt(*map(float, p)), gp_Pnt(*map(float, q))).Edge()  # noqa: E731
    wire = BRepBuilderAPI_MakeWire()
    wire.Add(interpolated(pts_left, params))
    wire.Add(line(pts_left[-1], pts_right[-1]))
    wire.Add(interpolated(pts_right[::-1], 1.0 - params[::-1]))
    if r0 > root:  # form circle above the root: radial lines down to the core cylinder
        feet = [np.array([root, 0.0, p[0, 2]]) for p in (pts_left, pts_right)]
        wire.Add(line(pts_right[0], feet[1]))
        wire.Add(line(feet[1], feet[0]))  # the root line, on the core cylinder
        wire.Add(line(feet[0], pts_left[0]))
    else:
        wire.Add(line(pts_right[0], pts_left[0]))  # the root line, on the core cylinder
    place = gp_Trsf()
    place.SetRotation(gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), angle)
    shift = gp_Trsf()
    shift.SetTranslation(gp_Vec(0, 0, z0))
    section = TopoDS.Wire_s(BRepBuilderAPI_Transform(
        BRepBuilderAPI_Transform(wire.Wire(), place, True).Shape(), shift, True).Shape())
    pipe = BRepOffsetAPI_MakePipeShell(_helix(left.reference_radius, left.lead, z0, turns,
                                              angle, left.hand == "right"))
    pipe.SetMode(True)  # Frenet trihedron: on a helix, the screw motion itself
    pipe.Add(section, False, False)
    pipe.SetTolerance(1e-7, 1e-7, 1e-3)
    pipe.Build()
    if not pipe.IsDone():
        raise RuntimeError("the sweep of the worm thread failed")
    pipe.MakeSolid()
    return pipe.Shape()


def _helix(radius: float, lead: float, z0: float, turns: int, angle: float, right_hand: bool):
    """A helix wire on the cylinder of `radius`, starting at polar `angle` and height z0."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeWire
    from OCP.BRepLib import BRepLib
    from OCP.Geom import Geom_CylindricalSurface
    from OCP.Geom2d import Geom2d_Line
    from OCP.GeomAbs import GeomAbs_C2
    from OCP.gp import gp_Ax3, gp_Dir, gp_Dir2d, gp_Pnt, gp_Pnt2d

    surface = Geom_CylindricalSurface(gp_Ax3(gp_Pnt(0, 0, z0), gp_Dir(0, 0, 1)), radius)
    turn = 2.0 * math.pi * (1.0 if right_hand else -1.0)
    line = Geom2d_Line(gp_Pnt2d(angle, 0.0), gp_Dir2d(turn, lead))
    edge = BRepBuilderAPI_MakeEdge(line, surface, 0.0, turns * math.hypot(turn, lead)).Edge()
    BRepLib.BuildCurves3d_s(edge, 1e-9, GeomAbs_C2, 14, 2000)
    return BRepBuilderAPI_MakeWire(edge).Wire()


def _boolean(operation, a, b):
    op = operation(a, b)
    op.SetRunParallel(True)
    op.Build()
    if not op.IsDone():
        raise RuntimeError(f"{operation.__name__} failed while building the worm")
    return op.Shape()


def worm_flank_deviation(body: WormBody, nu: int = 7, nv: int = 13) -> float:
    """Largest distance (mm) from exact flank points (inside 5 % of the flank's radial span and
    10 % of its length from the edges) to the solid's boundary faces, both flanks."""
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeVertex
    from OCP.BRepExtrema import BRepExtrema_DistShapeShape
    from OCP.gp import gp_Pnt
    from OCP.TopAbs import TopAbs_SHELL
    from OCP.TopExp import TopExp_Explorer

    shell = TopExp_Explorer(body.solid, TopAbs_SHELL).Current()
    worst = 0.0
    for flank in body.flanks.values():
        (u0, u1), (v0, v1) = flank.domain
        du = 0.05 * (u1 - u0)
        u, v = np.meshgrid(np.linspace(u0 + du, u1 - du, nu), np.linspace(0.9 * v0, 0.9 * v1, nv),
                           indexing="ij")
        for p in np.stack(flank.point(u.ravel(), v.ravel()), axis=-1):
            vertex = BRepBuilderAPI_MakeVertex(gp_Pnt(*map(float, p))).Vertex()
            worst = max(worst, BRepExtrema_DistShapeShape(vertex, shell).Value())
    return worst
