"""Pictures of a contact analysis, rendered off-screen with pyvista (VTK): the contact
pattern on the flank as a paint pattern would show it, the pair in mesh, the pressure map.

- pattern_head_on.png / pattern_perspective.png: the pinion's flank (the worm's, the hub
  tooth's) with the ease-off coloured from 0 to the approach (the paint of a marking
  compound: the CONTACT colour at zero separation, paler up to the approach, grey beyond),
  each contact's Hertz ellipse outlined on the flank, the flank's edges drawn, and every
  edge contact (its ellipse and the edge it crosses) in the WARNING colour;
- pair.png: both bodies in mesh at one position (the teeth built here from the exact flanks,
  in numpy: no CAD kernel), the contact points and ellipses, and the misalignment, which
  may be exaggerated;
- pressure.png: the loaded contact's pressure painted on the flank, the largest over the
  mesh cycle (when the result carries `loaded`), and pressure_peak.png: the pressure of
  every pair at the position of the cycle's largest pressure.

Nothing here opens a window: pyvista.OFF_SCREEN is set, and on a Linux machine without a
display VTK is pointed at EGL. Only this module imports pyvista, and only inside functions.
PNGs are written whole or not at all (temporary file, then rename). Units: mm, µm, MPa.
"""

from __future__ import annotations

import math
import os
import sys
import textwrap
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import __version__
from .surfaces.outline import polar

#: picture size (pixels)
WINDOW = (1200, 900)
#: the paint at zero separation: where the flanks touch. Prussian blue, as marking compound.
CONTACT = "#0b3a9e"
#: the paint at the approach (the thinnest film that still marks)
PAINT_EDGE = "#a9cdf0"
#: flank without paint (separation beyond the approach)
NO_PAINT = "#9a9a9a"
#: edge contact: the same red as plots.WARNING; nothing else in a picture uses it
WARNING = "#d62728"
#: outline of a contact ellipse that stays clear of the edges
OUTLINE = "#ffffff"
#: flank edges and labels
INK = "#1a1a1a"
#: bodies: the driver (pinion, worm, hub) and the driven member (gear, wheel, sleeve)
DRIVER_BODY = "#c9ced6"
DRIVEN_BODY = "#d9c3a0"
#: pressure colour map (no red in it: red stays the warning)
PRESSURE_CMAP = "viridis"

BACKGROUND = "white"

#: the members' names by case kind; these kinds have pictures
MEMBER_NAMES = {"spur": ("pinion", "gear"), "spline": ("hub", "sleeve"), "worm": ("worm", "wheel")}
PICTURE_KINDS = tuple(MEMBER_NAMES)


# ---------------------------------------------------------------------------------------
# plumbing


def _pyvista():
    """pyvista, set up for off-screen rendering (imported here, never at module level)."""
    if sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
        # no X server: render through EGL (Mesa's llvmpipe without a GPU) rather than
        # trying X first
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    import pyvista

    pyvista.OFF_SCREEN = True
    return pyvista


def _plotter(pv):
    plotter = pv.Plotter(off_screen=True, window_size=WINDOW)
    plotter.set_background(BACKGROUND)
    plotter.enable_anti_aliasing("msaa")
    return plotter


def screenshot(plotter) -> np.ndarray:
    """The rendered picture (rows, columns, RGB) as uint8."""
    return np.asarray(plotter.screenshot(return_img=True))[..., :3]


def write_png(image: np.ndarray, path: str | Path) -> Path:
    """Write an RGB image as PNG whole or not at all (writing.write_atomic)."""
    from PIL import Image
    from PIL.PngImagePlugin import PngInfo

    from .writing import write_atomic

    info = PngInfo()
    info.add_text("Software", f"toothcontact {__version__} (pyvista)")
    return write_atomic(path, lambda handle: Image.fromarray(np.ascontiguousarray(image)).save(
        handle, format="png", pnginfo=info, compress_level=3), binary=True)


def project(plotter, points) -> np.ndarray:
    """Pixel positions (column, row; row 0 at the top of the screenshot) of scene points
    (n, 3), through the plotter's camera."""
    renderer = plotter.renderer
    height = plotter.window_size[1]
    warp = getattr(plotter, "_scene_warp", None)
    points = np.asarray(points, float).reshape(-1, 3)
    if warp is not None:
        points = warp(points)
    out = []
    for p in points:
        renderer.SetWorldPoint(*p, 1.0)
        renderer.WorldToDisplay()
        x, y, _ = renderer.GetDisplayPoint()
        out.append((x, height - 1 - y))
    return np.array(out)


def _finish(plotter, path: Path) -> Path:
    """Screenshot, close and write the picture, cut off below `plotter._keep_above` (a
    window fraction from the bottom, set by a head-on layout) where the picture ends."""
    _bar_title(plotter)
    image = screenshot(plotter)
    keep = getattr(plotter, "_keep_above", 0.0)
    plotter.close()
    if keep > 0.0:
        image = image[: int(round((1.0 - keep) * image.shape[0]))]
    return write_png(image, path)


def _bar_title(plotter) -> None:
    """The colour bar's title as a text of its own just above the bar's box, where it
    stands (VTK draws a horizontal bar's title over its tick labels)."""
    title = getattr(plotter, "_bar_title", None)
    if not title:
        return
    bar = plotter.scalar_bar
    x, y = bar.GetPosition()
    _, height = bar.GetPosition2()
    plotter.add_text(title, position=(x, y + height + 0.004), viewport=True, font_size=9,
                     color=INK)


def _wrap(text: str, width: int = 95) -> str:
    return "\n".join(textwrap.wrap(text, width)) or text


# ---------------------------------------------------------------------------------------
# geometry of the pictures (numpy only)


def _grid_surface(pv, points: np.ndarray, scalars: dict | None = None):
    """A pyvista StructuredGrid of points (nu, nv, 3), with point data (nu, nv) arrays."""
    grid = pv.StructuredGrid(points[..., 0], points[..., 1], points[..., 2])
    for name, values in (scalars or {}).items():
        grid.point_data[name] = np.asarray(values, float).ravel(order="F")
    return grid


def _polylines(pv, lines: list[np.ndarray]):
    """One PolyData of several polylines (each (n, 3))."""
    lines = [np.asarray(line, float) for line in lines if len(line) >= 2]
    if not lines:
        return None
    points = np.concatenate(lines)
    cells, start = [], 0
    for line in lines:
        cells += [len(line), *range(start, start + len(line))]
        start += len(line)
    return pv.PolyData(points, lines=np.array(cells))


def _normals(flank, u, v) -> np.ndarray:
    return flank.evaluate(np.asarray(u, float), np.asarray(v, float), order=1).normals


def _flank_points(flank, u, v) -> np.ndarray:
    return np.stack(flank.point(np.asarray(u, float), np.asarray(v, float)), axis=-1)


@dataclass(frozen=True)
class Patch:
    """The part of a member's tooth-0 flank a picture shows: the member ("pinion": the
    driver, "gear": the driven member), its flank, parameters u (nu,), v (nv,), points
    (nu, nv, 3) in the member's own frame, the least separation over the cycle (nu, nv) mm
    (NaN: no mate), and whether it is cut from a longer flank."""

    member: str
    flank: object
    u: np.ndarray
    v: np.ndarray
    points: np.ndarray
    separation: np.ndarray
    cropped: bool = False


def flank_patch(cycle, pad: int = 2) -> Patch:
    """The ease-off the cycle mapped (on the member cycle.settings.ease_off_member: the
    driver's flank, or a worm wheel's). A flank that winds round its axis (a worm thread)
    is cut to the part near the pattern (within 50 approaches), padded by `pad` grid
    lines."""
    member = cycle.settings.ease_off_member
    ease = cycle.ease_off
    flank = getattr(cycle, member)
    s = ease.separation
    if not _winds(flank):
        return Patch(member, flank, ease.u, ease.v, ease.points, s)
    near = np.isfinite(s) & (s <= 50.0 * cycle.settings.approach)
    if not near.any():
        near = np.isfinite(s)
    iu, iv = np.flatnonzero(near.any(axis=1)), np.flatnonzero(near.any(axis=0))
    su = slice(max(iu[0] - pad, 0), min(iu[-1] + pad + 1, len(ease.u)))
    sv = slice(max(iv[0] - pad, 0), min(iv[-1] + pad + 1, len(ease.v)))
    return Patch(member, flank, ease.u[su], ease.v[sv], ease.points[su, sv], s[su, sv], True)


def _winds(flank) -> bool:
    """True for a flank that turns round its axis by more than half a turn (a worm thread)."""
    (u0, u1), (v0, v1) = flank.domain
    v = np.linspace(v0, v1, 9)
    p = _flank_points(flank, np.full_like(v, 0.5 * (u0 + u1)), v)
    turn = np.unwrap(np.arctan2(p[:, 1], p[:, 0]))
    return bool(abs(turn[-1] - turn[0]) > math.pi)


def ellipse_outlines(cycle, member: str = "pinion", samples: int = 97) -> np.ndarray:
    """Each row's Hertz ellipse (semi-axis a along cycle.axis_angle from e1, b across; a
    contact line as its part in contact, about its centre) carried onto the member's tooth-0 flank along
    the common normal: (K, samples, 3) in that member's own frame. The rays march out from
    the contact point, each starting where the last one landed, so that the outline follows
    this part of the flank (as contact.ellipse does); beyond the flank's edges the outline
    runs along them, so a cut ellipse shows where it is cut and nothing is drawn off the
    flank."""
    from .contact.rays import intersect

    flank = getattr(cycle, member)
    frames = getattr(cycle, f"{member}_frames")
    planes = cycle.planes
    a = np.array([r["a_mm"] for r in cycle.rows])
    # a contact line is drawn as the line (its width is the Hertz band's, a hair)
    b = np.array([0.0 if r["contact_model"] == "line" else r["b_mm"] for r in cycle.rows])
    theta = np.linspace(0.0, 2.0 * np.pi, samples)
    da = planes.direction(np.asarray(cycle.axis_angle, float))
    db = np.cross(planes.normal, da)
    # a contact line's part in contact may lie to one side of its contact point
    centre = planes.at(*np.asarray(cycle.pattern_centre, float).T)
    direction = frames.vectors_to_local(planes.normal[:, None, :])
    u0, v0 = (np.asarray(getattr(cycle.contacts, f"{member}_{w}"), float) for w in ("u", "v"))
    u = np.repeat(u0[:, None], samples, axis=1)
    v = np.repeat(v0[:, None], samples, axis=1)
    along = a[:, None, None] * np.cos(theta)[:, None] * da[:, None, :]
    across = b[:, None, None] * np.sin(theta)[:, None] * db[:, None, :]
    with np.errstate(all="ignore"):
        for fraction in (0.25, 0.5, 0.75, 1.0):
            world = centre[:, None, :] + fraction * (along + across)
            hits = intersect(flank, frames.to_local(world), direction, u, v, iterations=40)
            ok = hits.converged & (np.abs(hits.s) < 0.5)
            u, v = np.where(ok, hits.u, u), np.where(ok, hits.v, v)
        # an ellipse larger than the flank is drawn cut at its edges: the cut runs along them
        (fu0, fu1), (fv0, fv1) = flank.domain
        u, v = np.clip(u, fu0, fu1), np.clip(v, fv0, fv1)
        on_flank = _flank_points(flank, u, v)
    in_plane = frames.to_local(centre[:, None, :] + along + across)
    return np.where(np.isfinite(on_flank).all(axis=-1)[..., None], on_flank, in_plane)


def _patch_boundary(patch: Patch, n: int = 121) -> dict[str, np.ndarray]:
    """Edges of the shown part of the flank (its own frame): the flank's own edges by name
    where the patch reaches them, and cut lines ("cut_u0", ...) elsewhere."""
    flank = patch.flank
    (fu0, fu1), (fv0, fv1) = flank.domain
    u0, u1, v0, v1 = patch.u[0], patch.u[-1], patch.v[0], patch.v[-1]
    us, vs = np.linspace(u0, u1, n), np.linspace(v0, v1, n)
    out = {}
    for key, value, own, (u, v) in (("u0", u0, fu0, (np.full(n, u0), vs)),
                                    ("u1", u1, fu1, (np.full(n, u1), vs)),
                                    ("v0", v0, fv0, (us, np.full(n, v0))),
                                    ("v1", v1, fv1, (us, np.full(n, v1)))):
        name = flank.edges[key] if math.isclose(value, own, abs_tol=1e-9) else f"cut_{key}"
        with np.errstate(all="ignore"):
            line = _flank_points(flank, u, v)
        out[name] = line[np.isfinite(line).all(axis=-1)]
    return out


def row_name(case, member: str) -> str:
    """The name the result rows give `member` ("pinion" or "gear", the contact engine's
    driver and driven member): a worm set's are the worm and the wheel."""
    from .analyses.worm import PUBLISHED_NAMES

    return PUBLISHED_NAMES.get(getattr(case, "kind", ""), {}).get(member, member)


def edge_contacts(rows: list[dict], member: str) -> dict[str, float]:
    """Edges of `member` (as the rows name it, see row_name) that a contact ellipse crosses,
    with the worst margin (mm, negative), from the rows' edge_margins_mm."""
    worst = {}
    for row in rows:
        for key, margin in (row.get("edge_margins_mm") or {}).items():
            if key.startswith(f"{member}_") and margin is not None and margin < 0:
                edge = key[len(member) + 1:]
                worst[edge] = min(float(margin), worst.get(edge, 0.0))
    return worst


def _cut_stretches(rows, member: str, edge: str, line: np.ndarray, outlines: np.ndarray,
                   tolerance: float) -> list[tuple[int, int]]:
    """Index ranges of the edge polyline `line` that the ellipses crossing `edge` cut:
    between the first and last edge points near each such outline."""
    from scipy.spatial import cKDTree

    tree = cKDTree(line)
    out = []
    for k, row in enumerate(rows):
        margin = (row.get("edge_margins_mm") or {}).get(f"{member}_{edge}")
        if margin is None or margin >= 0:
            continue
        d, i = tree.query(outlines[k])
        i = i[d < max(tolerance, -0.5 * margin)]
        if len(i):       # at least 3 % of the edge each side, so that a narrow cut shows
            grow = max(2, len(line) // 33)
            out.append((max(int(i.min()) - grow, 0), min(int(i.max()) + grow, len(line) - 1)))
    return out


def _paint_lut(pv, approach_um: float):
    """The paint colour map: CONTACT at 0, paler up to PAINT_EDGE at the approach, NO_PAINT
    above it and where no mate faces the flank."""
    from matplotlib.colors import LinearSegmentedColormap

    cmap = LinearSegmentedColormap.from_list("paint", [CONTACT, "#3f78c9", PAINT_EDGE])
    lut = pv.LookupTable(cmap=cmap, n_values=256)
    lut.scalar_range = (0.0, approach_um)
    lut.above_range_color = NO_PAINT
    lut.nan_color = NO_PAINT
    return lut


# ---------------------------------------------------------------------------------------
# bodies, built from the exact flanks (numpy), each in its member's own frame


def _arc(p: np.ndarray, q: np.ndarray, n: int) -> np.ndarray:
    """Points from p to q (same z) turning about the z axis, radius varying linearly."""
    a0, a1 = math.atan2(p[1], p[0]), math.atan2(q[1], q[0])
    a1 = a0 + (a1 - a0 + math.pi) % (2.0 * math.pi) - math.pi
    t = np.linspace(0.0, 1.0, n)
    r = (1 - t) * math.hypot(p[0], p[1]) + t * math.hypot(q[0], q[1])
    angle = (1 - t) * a0 + t * a1
    return np.column_stack([r * np.cos(angle), r * np.sin(angle), np.full(n, p[2])])


def _turn(points: np.ndarray, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return points @ np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])


def _join(parts: list[np.ndarray]) -> np.ndarray:
    """Concatenate polylines, dropping a point that repeats the previous one."""
    out = [parts[0]]
    for part in parts[1:]:
        if np.allclose(part[0], out[-1][-1], atol=1e-9):
            part = part[1:]
        out.append(part)
    return np.concatenate(out)


def _wheel_tooth_outline(minus_flank, plus_flank, z: float, nu: int) -> np.ndarray:
    """Outline of tooth 0 of a worm wheel in the plane z2 = z (as cad.wheel builds it)."""
    u = minus_flank.profile_parameters(nu)      # the other's break starts as near
    v = np.full_like(u, z)
    minus = _flank_points(minus_flank, u, v)       # tip -> root
    plus = _flank_points(plus_flank, u, v)
    pitch = 2.0 * math.pi / minus_flank.teeth
    root = 0.5 * (math.hypot(*minus[-1, :2]) + math.hypot(*plus[-1, :2]))
    after = 0.5 * (math.atan2(plus[-1, 1], plus[-1, 0]) + math.atan2(minus[-1, 1], minus[-1, 0])
                   + pitch)
    return _join([_arc(polar(root, after - pitch, z), minus[-1], 5), minus[::-1],
                  _arc(minus[0], plus[0], 9), plus, _arc(plus[-1], polar(root, after, z), 5)])


def _toothed_body(pv, outline_at, zs: np.ndarray, teeth: list[int], pitch: float,
                  total: int, rim: float):
    """A toothed body from its tooth-0 outline at each z: the teeth `teeth` (tooth numbers),
    the end faces closed down (or, for a ring, out) to the radius `rim`, and a sector's
    sides closed by radial walls. Returns a PolyData surface."""
    sections = []
    for z in zs:
        one = outline_at(float(z))
        ring = _join([_turn(one, k * pitch) for k in teeth])
        sections.append(ring)
    n = min(len(s) for s in sections)
    sections = np.stack([s[:n] for s in sections])                  # (nz, n, 3)
    whole = len(teeth) == total
    if whole:
        sections = np.concatenate([sections, sections[:, :1]], axis=1)
    side = _grid_surface(pv, np.transpose(sections, (1, 0, 2)))
    pieces = [side.extract_surface(algorithm="dataset_surface")]
    for j in (0, -1):                                               # end faces
        edge = sections[j]
        angle = np.arctan2(edge[:, 1], edge[:, 0])
        inner = np.column_stack([rim * np.cos(angle), rim * np.sin(angle), edge[:, 2]])
        pieces.append(_grid_surface(pv, np.stack([edge, inner], axis=1)).extract_surface(
            algorithm="dataset_surface"))
    if not whole:                                                   # sector walls
        for i in (0, -1):
            outer = sections[:, i]
            angle = np.arctan2(outer[:, 1], outer[:, 0])
            inner = np.column_stack([rim * np.cos(angle), rim * np.sin(angle), outer[:, 2]])
            pieces.append(_grid_surface(pv, np.stack([outer, inner], axis=1)).extract_surface(
                algorithm="dataset_surface"))
    body = pieces[0].merge(pieces[1:])
    return body.extract_surface(algorithm="dataset_surface").compute_normals(
        auto_orient_normals=False, split_vertices=True, feature_angle=40.0)


def _teeth_around(count: int, total: int) -> list[int]:
    if count >= total:
        return list(range(-(total // 2), total - total // 2))
    return list(range(-(count // 2), count - count // 2))


def cylindrical_body(pv, gear, modifications, teeth, nu: int = 24) -> dict:
    """Spur/helical gear, spline hub or sleeve bodies: for each count in `teeth` (a tuple),
    that many teeth around tooth 0 (or all). Returns {count: PolyData}."""
    from .surfaces.outline import ToothOutline

    teeth_outline = ToothOutline(gear, modifications)
    (u0, u1), _ = teeth_outline.flanks[1].domain
    u = np.linspace(u0, u1, nu)
    twist = abs(gear.twist_per_length) * gear.face_width
    nz = max(2 if modifications.empty else 9, int(math.ceil(twist / 0.02)) + 1)
    zs = np.linspace(-0.5 * gear.face_width, 0.5 * gear.face_width, nz)
    m = gear.normal_module
    rim = (gear.root_radius_value + 3.0 * m) if gear.internal else max(
        gear.root_radius_value - 2.5 * m, 0.35 * gear.root_radius_value)
    outlines = {}

    def outline(z):
        if z not in outlines:
            outlines[z] = teeth_outline.section(u, z).points(9, 5)
        return outlines[z]

    return {count: _toothed_body(pv, outline, zs, _teeth_around(count, gear.teeth),
                                 2.0 * math.pi / gear.teeth, gear.teeth, rim)
            for count in teeth}


def wheel_body(pv, left, right, teeth, nu: int = 21, sections: int = 21) -> dict:
    """Worm wheel bodies between its two flanks: for each count in `teeth` (a tuple), that
    many teeth around tooth 0. Returns {count: PolyData}."""
    from .cad.wheel import _ordered

    flanks = _ordered(left, right)
    zs = np.linspace(-0.5 * left.face_width, 0.5 * left.face_width, sections)
    rim = 0.5 * left.root_diameter - 2.0 * left.worm.axial_module
    outlines = {}

    def outline(z):
        if z not in outlines:
            outlines[z] = _wheel_tooth_outline(flanks["minus"], flanks["plus"], z, nu)
        return outlines[z]

    return {count: _toothed_body(pv, outline, zs, _teeth_around(count, left.teeth),
                                 2.0 * math.pi / left.teeth, left.teeth, rim)
            for count in teeth}


def worm_body(pv, left, right, n: int = 11, turn_points: int = 181):
    """The whole worm: its axial section (both flank profiles, tip and root lines) screwed
    about the axis (every flank is a helicoid), cut by the end planes and closed by them."""
    (rl, zl), (rr, zr) = left.axial_section(n), right.axial_section(n)
    if zl[0] > zr[0]:
        (rl, zl), (rr, zr) = (rr, zr), (rl, zl)
    px, p, length = left.axial_pitch, left.screw_parameter, left.length
    lead = abs(2.0 * math.pi * p)
    one = np.concatenate([np.column_stack([rl, zl]), np.column_stack([rr[::-1], zr[::-1]])])
    k0 = int(math.floor((-0.5 * length - lead) / px)) - 1
    k1 = int(math.ceil((0.5 * length + lead) / px)) + 1
    profile = np.concatenate([one + [0.0, k * px] for k in range(k0, k1 + 1)])  # (m, 2): r, z
    theta = np.linspace(0.0, 2.0 * math.pi, turn_points)
    R = profile[:, 0][:, None] * np.ones_like(theta)
    Z = profile[:, 1][:, None] + p * theta
    pts = np.stack([R * np.cos(theta), R * np.sin(theta), Z], axis=-1)
    surface = _grid_surface(pv, pts).extract_surface(algorithm="dataset_surface")
    surface = surface.clip(normal="z", origin=(0, 0, 0.5 * length), invert=True)
    surface = surface.clip(normal="-z", origin=(0, 0, -0.5 * length), invert=True)
    pieces = [surface.extract_surface(algorithm="dataset_surface")]
    # end faces: the radius of the section at each angle, from the axial profile
    order = np.argsort(profile[:, 1])
    zs, rs = profile[order, 1], profile[order, 0]
    for z_end in (-0.5 * length, 0.5 * length):
        radius = np.interp(z_end - p * theta, zs, rs)
        rim = np.column_stack([radius * np.cos(theta), radius * np.sin(theta),
                               np.full_like(theta, z_end)])
        centre = np.column_stack([np.zeros_like(theta), np.zeros_like(theta),
                                  np.full_like(theta, z_end)])
        pieces.append(_grid_surface(pv, np.stack([rim, centre], axis=1)).extract_surface(
            algorithm="dataset_surface"))
    body = pieces[0].merge(pieces[1:])
    return body.extract_surface(algorithm="dataset_surface").compute_normals(
        split_vertices=True, feature_angle=40.0)


@dataclass
class Members:
    """The bodies of a case, each in its own frame: the driver and the driven member as
    shown in mesh, a few teeth of each around tooth 0 for the pattern's perspective view,
    and the members' names."""

    driver: object
    driven: object
    driver_tooth: object
    driven_tooth: object
    names: tuple[str, str]

    def tooth(self, member: str):
        return self.driver_tooth if member == "pinion" else self.driven_tooth


def members(pv, kind: str, parts) -> Members | None:
    """The bodies of a spur, spline or worm case from the members its analysis generated
    (analyses.Result.parts); None for any other kind."""
    if kind == "spur":
        pair = parts
        pinion = cylindrical_body(pv, pair.pinion, pair.pinion_modifications, (7, 3))
        shown = 5 if pair.gear.internal else 7
        gear = cylindrical_body(pv, pair.gear, pair.gear_modifications, (shown, 3))
        return Members(pinion[7], gear[shown], pinion[3], gear[3], MEMBER_NAMES[kind])
    if kind == "spline":
        pair = parts
        hub = cylindrical_body(pv, pair.hub, pair.hub_modifications, (pair.hub.teeth, 3))
        sleeve = cylindrical_body(pv, pair.sleeve, pair.sleeve_modifications, (5, 3))
        return Members(hub[pair.hub.teeth], sleeve[5], hub[3], sleeve[3], MEMBER_NAMES[kind])
    if kind == "worm":
        worm = worm_body(pv, parts.worm["left"], parts.worm["right"])
        wheel = wheel_body(pv, parts.wheel["left"], parts.wheel["right"], (7, 3))
        return Members(worm, wheel[7], worm, wheel[3], MEMBER_NAMES[kind])
    return None


# ---------------------------------------------------------------------------------------
# text and cameras


def _texts(plotter, title: str, legend: list[str] = (), warnings: list[str] = ()):
    """The title at the top left; under it the legend lines, then the warnings in red."""
    line = 19

    def backed(actor):  # a white backing keeps the text legible over a body
        prop = actor.GetTextProperty()
        prop.SetBackgroundColor(1.0, 1.0, 1.0)
        prop.SetBackgroundOpacity(0.8)

    backed(plotter.add_text(title, position="upper_left", font_size=12, color=INK))
    y = WINDOW[1] - 10 - 24 * (title.count("\n") + 1) - 10
    for lines, color in ((list(legend), INK), (list(warnings), WARNING)):
        # a long line wrapped to the window's width at this font size
        lines = [part for text in lines for part in (textwrap.wrap(text, 112) or [text])]
        if not lines:
            continue
        y -= line * len(lines)
        backed(plotter.add_text("\n".join(lines), position=(8, y), font_size=10, color=color))
        y -= 6
    plotter._text_bottom = y / WINDOW[1]      # where the texts end (window fraction)


def _ordinal(n: int) -> str:
    return f"{n}{'th' if 10 <= n % 100 <= 20 else {1: 'st', 2: 'nd', 3: 'rd'}.get(n % 10, 'th')}"


def _title(case, name: str, what: str) -> str:
    title = getattr(case, "title", "") or name
    return _wrap(f"{name}: {title}" if name and title != name else title) + "\n" + what


def _flank_frame(patch: Patch):
    """Centre, outward normal, 'up' (toward the tip) and 'across' (toward end B, as seen
    from outside) of the shown part of the flank, in its member's frame."""
    flank = patch.flank
    uc, vc = 0.5 * (patch.u[0] + patch.u[-1]), 0.5 * (patch.v[0] + patch.v[-1])
    s = flank.evaluate(np.array([uc]), np.array([vc]), order=1)
    centre, normal = s.points[0], s.normals[0]
    up = s.r_u[0] / np.linalg.norm(s.r_u[0])
    if flank.edges["u0"] == "tip":            # u runs from the tip
        up = -up
    up = up - normal * np.dot(up, normal)
    up /= np.linalg.norm(up)
    return centre, normal, up, np.cross(up, normal)


def _camera(plotter, focus: np.ndarray, direction: np.ndarray, up: np.ndarray, half: float,
            parallel: bool = False, view_angle: float = 30.0):
    """Look at `focus` from along `direction`, `half` mm of the scene above and below it."""
    direction = direction / np.linalg.norm(direction)
    up = up - direction * np.dot(up, direction)
    up /= np.linalg.norm(up)
    camera = plotter.camera
    camera.view_angle = view_angle
    distance = half / math.tan(math.radians(0.5 * view_angle))
    camera.focal_point = tuple(focus)
    camera.position = tuple(focus + direction * distance)
    camera.up = tuple(up)
    if parallel:
        camera.enable_parallel_projection()
        camera.parallel_scale = half
    plotter.renderer.ResetCameraClippingRange()


def _fit(points: np.ndarray, focus: np.ndarray, direction: np.ndarray, up: np.ndarray,
         margin: float, box: tuple[float, float, float, float] = (0.0, 0.0, 1.0, 1.0)):
    """The focal point and half height (mm) that fit `points`, seen along `direction` with
    `up` up, into the part `box` = (left, bottom, right, top) of the window (fractions)."""
    direction = direction / np.linalg.norm(direction)
    up = up - direction * np.dot(up, direction)
    up /= np.linalg.norm(up)
    right = np.cross(up, direction)
    rel = points - focus
    x, y = rel @ right, rel @ up
    aspect = WINDOW[0] / WINDOW[1]
    width, height = box[2] - box[0], box[3] - box[1]
    half = max(np.ptp(y) / 2.0 / height, np.ptp(x) / 2.0 / (aspect * width)) * margin
    centre = focus + right * 0.5 * (x.max() + x.min()) + up * 0.5 * (y.max() + y.min())
    # the box's middle is off the window's middle: move the focal point the other way
    centre = centre - right * (0.5 * (box[0] + box[2]) - 0.5) * 2.0 * half * aspect \
        - up * (0.5 * (box[1] + box[3]) - 0.5) * 2.0 * half
    return centre, half


def _refit(plotter, points: np.ndarray, box, margin: float = 1.05, rounds: int = 3):
    """Perspective views: move the camera along its line of sight (and its focal point
    across it) until the projected `points` fill `box` (left, bottom, right, top fractions
    of the window)."""
    points = points[:: max(1, len(points) // 400)]
    width, height = WINDOW
    for _ in range(rounds):
        pix = project(plotter, points)
        cols, rows = pix[:, 0] / width, 1.0 - pix[:, 1] / height
        scale = max(np.ptp(cols) / (box[2] - box[0]), np.ptp(rows) / (box[3] - box[1])) * margin
        camera = plotter.camera
        focal, position = np.array(camera.focal_point), np.array(camera.position)
        direction = position - focal
        distance = np.linalg.norm(direction)
        up = np.array(camera.up)
        right = np.cross(up, direction / distance)
        # shift the focal point so the points' middle lands on the box's middle
        span = 2.0 * distance * math.tan(math.radians(0.5 * camera.view_angle))
        dx = (0.5 * (cols.max() + cols.min()) - 0.5 * (box[0] + box[2])) * span * width / height
        dy = (0.5 * (rows.max() + rows.min()) - 0.5 * (box[1] + box[3])) * span
        focal = focal + right * dx + up * dy
        camera.focal_point = tuple(focal)
        camera.position = tuple(focal + direction * scale)
        plotter.renderer.ResetCameraClippingRange()


#: where a flank goes in a picture with a title above and a colour bar below
FLANK_BOX = (0.05, 0.14, 0.95, 0.80)

#: a pattern picture outlines at most this many ellipses (every n-th of more; the edge
#: contacts always), so that many contacts do not become a tangle
MAX_OUTLINES = 15


def _head_on_layout(plotter, points: np.ndarray, centre: np.ndarray, normal: np.ndarray,
                    up: np.ndarray, stretch: float) -> None:
    """Frame a head-on picture of a flank (its `points`, seen along `normal`, `up` up):
    fitted just under the texts (call after _texts) with room for the colour bar and the
    mm scale bar below it, which then sit right under the flank, and the empty rest of
    the window cut off (see _finish)."""
    top = min(FLANK_BOX[3], getattr(plotter, "_text_bottom", 1.0) - 0.06)  # room for "tip"
    focus, half = _fit(points, centre, normal, up, 1.1, (FLANK_BOX[0], FLANK_BOX[1],
                                                          FLANK_BOX[2], top))
    heights = 0.5 + ((points[np.isfinite(points).all(axis=1)] - focus) @ up) / (2.0 * half)
    rise = top - heights.max()                        # a wide flank: up to the texts
    focus = focus - up * rise * 2.0 * half
    _camera(plotter, focus, normal, up, half, parallel=True)
    bar = max(0.035, heights.min() + rise - 0.16)     # under the edge labels
    plotter.scalar_bar.SetPosition(0.17, bar)
    _scale_bar(plotter, focus, normal, up, half, stretch, bar + 0.12)   # above the bar's title
    plotter._keep_above = max(bar - 0.03, 0.0)


def _scale_bar(plotter, focus: np.ndarray, direction: np.ndarray, up: np.ndarray,
               half: float, stretch: float = 1.0, y: float = 0.115) -> float:
    """A mm scale bar in the bottom right corner of an orthographic view (focus, looking
    along -direction, `half` mm from the middle to the top): a round length (1, 2 or 5
    × 10^k mm) near a sixth of the window's width, drawn across (along the face, which
    `stretch` leaves at scale), at the window height `y` (fraction). Returns its length
    (mm)."""
    pv = _pyvista()
    aspect = WINDOW[0] / WINDOW[1]
    width = 2.0 * half * aspect
    target = width / 6.0
    power = 10.0 ** math.floor(math.log10(target))
    length = max(m * power for m in (1.0, 2.0, 5.0) if m * power <= target)
    direction = direction / np.linalg.norm(direction)
    right = np.cross(up, direction)
    right /= np.linalg.norm(right)
    x1 = 0.95                                          # window fraction
    end = focus + right * (x1 - 0.5) * width + up * (y - 0.5) * 2.0 * half
    start = end - right * length
    tick = up * 0.008 * 2.0 * half
    ink = dict(color=INK, line_width=3, lighting=False)
    plotter.add_mesh(pv.lines_from_points(np.array([start, end])), **ink)
    for p in (start, end):
        plotter.add_mesh(pv.lines_from_points(np.array([p - tick, p + tick])), **ink)
    text = f"{length:g} mm" + (" along the face" if stretch > 1.05 else "")
    left = (x1 - length / width) * WINDOW[0]           # the label ends left of the bar
    plotter.add_text(text, position=(int(left - 12 * len(text) - 12), int(y * WINDOW[1]) - 8),
                     font_size=10, color=INK)
    return length


def _edge_labels(plotter, edges: dict[str, np.ndarray], centre: np.ndarray, offset: float,
                 bad: set, warp=lambda p: p):
    for name, line in edges.items():
        if name.startswith("cut_") or not len(line):
            continue
        line = warp(line)
        mid = line[len(line) // 2]
        away = mid - centre
        norm = np.linalg.norm(away)
        point = mid + away / norm * offset if norm > 0 else mid
        plotter.add_point_labels(point[None], [name.replace("_", " ")], font_size=15,
                                 text_color=WARNING if name in bad else INK, shape=None,
                                 show_points=False, always_visible=True)


#: a head-on view stretches a flank longer than this many times its depth
MAX_ASPECT = 4.0


def _stretcher(patch: Patch, centre, up, across, view: str):
    """For a head-on view of a long, shallow flank (a spline tooth): a map stretching scene
    points along `up` about `centre` so that the flank is at most MAX_ASPECT times longer
    than deep, and the factor (1: no stretch)."""
    pts = patch.points.reshape(-1, 3)
    pts = pts[np.isfinite(pts).all(axis=1)]
    ratio = float(np.ptp(pts @ across) / max(np.ptp(pts @ up), 1e-12))
    factor = max(1.0, ratio / MAX_ASPECT) if view == "head-on" else 1.0

    def warp(points):
        points = np.asarray(points, float)
        if factor == 1.0:
            return points
        return points + (factor - 1.0) * ((points - centre) @ up)[..., None] * up

    return warp, factor


def _lift(flank, line: np.ndarray, lift: float) -> np.ndarray:
    """Points on (or near) the flank moved `lift` mm along its outward normal (so that lines
    drawn on the flank are not hidden by it)."""
    u, v = flank.parameters_near(line)
    with np.errstate(all="ignore"):
        n = _normals(flank, u, v)
    return line + lift * np.nan_to_num(n)


def _near_patch(patch: Patch, outlines: np.ndarray) -> np.ndarray:
    """Rows whose outline lies near the shown part of the flank (all, unless it is cut)."""
    if not patch.cropped:
        return np.ones(len(outlines), bool)
    from scipy.spatial import cKDTree

    tree = cKDTree(patch.points.reshape(-1, 3))
    step = max(np.linalg.norm(np.diff(patch.points, axis=0), axis=-1).max(),
               np.linalg.norm(np.diff(patch.points, axis=1), axis=-1).max())
    d, _ = tree.query(outlines.reshape(-1, 3))
    return (d.reshape(outlines.shape[:2]) < 2.0 * step).all(axis=1)


def _surface_props(**extra) -> dict:
    return dict(smooth_shading=True, specular=0.2, specular_power=20, ambient=0.25,
                diffuse=0.75, **extra)


# ---------------------------------------------------------------------------------------
# the contact pattern


def pattern_scene(result, case=None, name: str = "", view: str = "head-on",
                  bodies: Members | None = None, patch: Patch | None = None):
    """The contact pattern on a tooth flank (the driver's; a worm set's wheel): a pyvista
    Plotter ready to screenshot. view "head-on": orthographic, along the flank's normal at
    the middle of the shown part, tip up; "perspective": from outside, the tip side and
    end A, with the member's teeth around it (`bodies`). Scene coordinates are the member's
    own frame (tooth 0)."""
    pv = _pyvista()
    cycle = result.cycle
    patch = patch or flank_patch(cycle)
    member, flank = patch.member, patch.flank
    names = MEMBER_NAMES.get(getattr(case, "kind", ""), ("pinion", "gear"))
    owner, mate = (names[0], names[1]) if member == "pinion" else (names[1], names[0])
    approach_um = 1e3 * cycle.settings.approach
    plotter = _plotter(pv)
    centre, normal, up, across = _flank_frame(patch)
    warp, stretch = _stretcher(patch, centre, up, across, view)
    plotter._scene_warp = warp
    pts = patch.points.reshape(-1, 3)
    span = float(np.ptp(pts @ across))
    lift = 2e-3 * span

    sep_um = np.where(np.isfinite(patch.separation), 1e3 * patch.separation, np.nan)
    surface = _grid_surface(pv, warp(patch.points), {"separation (µm)": sep_um})
    tooth = bodies.tooth(member) if bodies is not None else None
    if view == "perspective" and tooth is not None:
        plotter.add_mesh(tooth, color=DRIVER_BODY if member == "pinion" else DRIVEN_BODY,
                         **_surface_props())
        U, V = np.meshgrid(patch.u, patch.v, indexing="ij")
        with np.errstate(all="ignore"):
            n = np.nan_to_num(_normals(flank, U, V))
        surface.points = surface.points + 0.5 * lift * n.reshape(-1, 3, order="F")
    plotter._bar_title = (f"least separation over the mesh cycle (µm); paint where it is at "
                          f"most the approach, {approach_um:.2f} µm")
    bar = dict(title=" ", n_labels=5, fmt="%.1f", color=INK,
               position_x=0.17, position_y=0.035, width=0.62, height=0.055, title_font_size=15,
               label_font_size=14, above_label="no paint", vertical=False)
    plotter.add_mesh(surface, scalars="separation (µm)", cmap=_paint_lut(pv, approach_um),
                     clim=(0.0, approach_um), above_color=NO_PAINT, nan_color=NO_PAINT,
                     scalar_bar_args=bar, interpolate_before_map=True, **_surface_props())

    # the flank's edges; red along the stretch that each crossing ellipse cuts, where the
    # rigid pattern decides (without a loaded contact; its verdicts decide where solved)
    summary = result.sections.get("summary") or {}
    loaded = summary.get("loaded_contacts") is not None
    crossed = {} if loaded else edge_contacts(cycle.rows, row_name(case, member))
    edges = _patch_boundary(patch)
    outlines = ellipse_outlines(cycle, member)
    for edge, line in edges.items():
        if len(line) < 2:
            continue
        lifted = warp(_lift(flank, line, lift))
        plotter.add_mesh(pv.lines_from_points(lifted), color=INK, line_width=2, lighting=False)
        cut = [] if loaded else [
            lifted[i0:i1 + 1] for i0, i1 in _cut_stretches(
                cycle.rows, row_name(case, member), edge, line, outlines, 0.01 * span)]
        mesh = _polylines(pv, cut)
        if mesh is not None:
            plotter.add_mesh(mesh, color=WARNING, line_width=7, lighting=False)
    _edge_labels(plotter, edges, centre, 0.035 * span, set(crossed), warp)

    # the ellipses: every flagged contact's (the loaded contact's edge-loaded ones where it
    # was solved, else the rigid pattern's edge contacts), and of the others every n-th (at
    # most MAX_OUTLINES)
    edge_rows = np.array([bool(r.get("edge_loaded")) if loaded else bool(r["edge_contact"])
                          for r in cycle.rows])
    near = _near_patch(patch, outlines) & np.array([r.get("rigid_contact", True)
                                                    for r in cycle.rows])
    plain, cut = np.flatnonzero(~edge_rows & near), np.flatnonzero(edge_rows & near)
    every = max(1, math.ceil(len(plain) / MAX_OUTLINES), math.ceil(len(cut) / MAX_OUTLINES))
    outlined, cut_outlined = np.zeros(len(cycle.rows), bool), np.zeros(len(cycle.rows), bool)
    outlined[plain[::every]] = True
    cut_outlined[cut[::every]] = True
    if len(cut) and not loaded:      # the deepest cut is always drawn
        cut_outlined[min(cut, key=lambda k: cycle.rows[k]["edge_margin_mm"] or 0.0)] = True
    for rows, color, width, opacity in ((outlined, OUTLINE, 1.0, 0.6),
                                        (cut_outlined, WARNING, 2.0, 1.0)):
        lines = [warp(_lift(flank, outlines[k], 1.5 * lift))
                 for k in np.flatnonzero(rows & near)]
        mesh = _polylines(pv, lines)
        if mesh is not None:
            plotter.add_mesh(mesh, color=color, line_width=width, opacity=opacity,
                             lighting=False)

    positions = len({r["roll_deg"] for r in cycle.rows})
    touching = sum(r.get("rigid_contact", True) for r in cycle.rows)
    what = (f"contact pattern on the {owner}'s flank: "
            + ("looking at it head-on" if view == "head-on" else "perspective"))
    legend = [f"paint: the flank's least separation from the {mate} over the mesh cycle "
              f"({positions} positions)",
              (f"outlines: the Hertz ellipse (a contact line: the line) of each of the "
               f"{touching} contacts" if every == 1 else
               f"outlines: the Hertz ellipse (a contact line: the line) of every "
               f"{_ordinal(every)} of the {touching} contacts")
              + (" (red: edge-loaded under load)" if loaded else
                 " (red: edge contacts, the deepest cut always)")]
    if patch.cropped:
        legend.append("the part of the flank near the pattern")
    if stretch > 1.05:
        legend.append(f"NOTE: the profile direction is drawn {stretch:.1f} times its scale "
                      "(a long, shallow flank)")
    warnings = []
    if loaded and summary.get("edge_loaded_contacts"):
        of = f"of {summary['loaded_contacts']} contacts carrying load"
        if summary.get("end_loaded_contacts"):
            warnings.append(f"END LOADING (red): {summary['end_loaded_contacts']} {of}, end "
                            f"load ratio up to {summary['max_end_load_ratio']:.2f}")
        if summary.get("corner_contacts"):
            warnings.append(f"CORNER CONTACT (red): {summary['corner_contacts']} {of}, up to "
                            f"{summary['corner_contact_pressure_max_MPa']:.0f} MPa at "
                            f"{summary['corner_contact_at']}")
    if crossed:
        prefix = row_name(case, member) + "_"
        cutting = sum(any(k.startswith(prefix) and m is not None and m < 0
                          for k, m in (r.get("edge_margins_mm") or {}).items()) for r in cycle.rows)
        warnings.append(f"EDGE CONTACT (red): {cutting} contacts cross the "
                        + ", ".join(f"{e.replace('_', ' ')} ({m:+.3f} mm)" for e, m in crossed.items()))
    other = {} if loaded else edge_contacts(
        cycle.rows, row_name(case, "gear" if member == "pinion" else "pinion"))
    if other:
        warnings.append(f"and the {mate}'s " + ", ".join(
            f"{e.replace('_', ' ')} ({m:+.3f} mm)" for e, m in other.items()))
    _texts(plotter, _title(case, name, what), legend, warnings)

    # the picture holds the flank and the ellipses, these cut off at a third of the flank's
    # size beyond it (an edge contact's ellipse may reach far off the face)
    shown = outlines[near].reshape(-1, 3)
    if len(shown) and view != "head-on":
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        reach = 0.1 * (hi - lo).max()
        shown = np.clip(shown, lo - reach, hi + reach)
        pts = np.concatenate([pts, shown[np.isfinite(shown).all(axis=1)]])
    pts = warp(pts)
    if view == "head-on":
        _head_on_layout(plotter, pts, centre, normal, up, stretch)
    else:
        direction = normal + 0.5 * up - 0.8 * across
        target = pts if tooth is None or patch.cropped else np.concatenate(
            [pts, np.asarray(tooth.points)[::5]])
        focus, half = _fit(target, centre, direction, up, 1.0, FLANK_BOX)
        _camera(plotter, focus, direction, up, half)
        _refit(plotter, target, FLANK_BOX)
    return plotter


# ---------------------------------------------------------------------------------------
# the pair in mesh


def position_rows(rows: list[dict], position: int | None) -> tuple[int, list[int]]:
    """The mesh position to show (index into the sorted roll angles; default the one nearest
    roll 0) and the rows (contacts) at it."""
    rolls = sorted({r["roll_deg"] for r in rows})
    if position is None:
        position = int(np.argmin(np.abs(rolls)))
    if not -len(rolls) <= position < len(rolls):
        from .case import CaseError

        raise CaseError(f"--position: {position} is not a mesh position of the cycle "
                        f"(0 to {len(rolls) - 1})")
    roll = rolls[position]
    return position % len(rolls), [k for k, r in enumerate(rows) if r["roll_deg"] == roll]


def _nominal_mesh(case, parts):
    """The same set without misalignment (frames to measure the misalignment against), from
    the members the analysis generated."""
    from .surfaces.placement import WormMesh

    if case.kind == "spur":
        return parts.placed()
    if case.kind == "spline":
        from .gearset import GearPair

        return GearPair(parts.hub, parts.sleeve, parts.hub_modifications,
                        parts.sleeve_modifications, 0.0, case.pressure_angle).placed()
    flank = case.load.flank if getattr(case, "load", None) is not None else "left"
    return WormMesh(parts.wheel[flank])


def _rotation_power(R: np.ndarray, n: float) -> np.ndarray:
    """R^n for a rotation matrix: its axis, n times its angle."""
    from scipy.spatial.transform import Rotation

    return Rotation.from_rotvec(n * Rotation.from_matrix(R).as_rotvec()).as_matrix()


def exaggerated_frame(pinion, gear, pinion0, gear0, factor: float):
    """The driven member's frame with its misalignment relative to the driver multiplied
    by `factor`: the placed frames `pinion`, `gear` are compared with the nominal ones
    `pinion0`, `gear0` at the same roll and lag; the driver stays where it is. Frames of a
    batch of one. (A rigid motion to the power `factor`: its rotation's angle and its
    translation times `factor`, exact for the small motions of a misalignment.)"""
    from .surfaces.placement import Frame

    def relative(p, g):  # g in p's coordinates
        return p.R[0].T @ g.R[0], p.R[0].T @ (g.origin[0, 0] - p.origin[0, 0])

    R1, t1 = relative(pinion, gear)
    R0, t0 = relative(pinion0, gear0)
    dR = R1 @ R0.T
    dt = t1 - dR @ t0
    Rn = _rotation_power(dR, factor)
    R = pinion.R[0] @ (Rn @ R0)
    origin = pinion.R[0] @ (Rn @ t0 + factor * dt) + pinion.origin[0, 0]
    return Frame(R[None], origin[None, None])


def _placed(body, frame):
    out = body.copy()
    out.points = frame.to_world(np.asarray(body.points)[None])[0]
    if "Normals" in out.point_data:
        out.point_data["Normals"] = frame.vectors_to_world(
            np.asarray(body.point_data["Normals"])[None])[0]
    return out


def _misalignment_text(case) -> str:
    m = getattr(case, "misalignment", None)
    if m is None:
        return ""
    if isinstance(m, (int, float)):
        return f"misalignment {m:.3g} rad" if m else ""
    parts = []
    for key, value in m.model_dump().items():
        if isinstance(value, (int, float)) and not isinstance(value, bool) and value:
            unit = "mm" if any(w in key for w in ("distance", "shift", "mount")) else "rad"
            parts.append(f"{key.replace('_', ' ')} {value:.3g} {unit}")
    return ("misalignment: " + ", ".join(parts)) if parts else ""


def _module_of(case) -> float:
    value = getattr(case, "module_mm", None)
    if value:
        return float(value)
    worm = getattr(case, "worm", None)
    if worm is not None:
        return float(worm.axial_module or worm.normal_module or 2.0)
    return 2.0


def pair_scene(result, case, name: str = "", position: int | None = None,
               exaggerate: float = 1.0, bodies: Members | None = None):
    """Both members in mesh at one position of the cycle (the driven one see-through), the
    contact points and Hertz ellipses there, and the misalignment, multiplied by
    `exaggerate` when asked."""
    pv = _pyvista()
    cycle = result.cycle
    bodies = bodies or members(pv, case.kind, result.parts)
    index, ks = position_rows(cycle.rows, position)
    # the pairs in contact (pairs kept only for the loaded contact have no ellipse)
    ks = [j for j in ks if cycle.rows[j].get("rigid_contact", True)]
    k = max(ks, key=lambda j: cycle.rows[j]["p_max_MPa"])
    row = cycle.rows[k]
    plotter = _plotter(pv)
    pinion_frame = cycle.pinion_frames[np.array([k])]
    gear_frame = cycle.gear_frames[np.array([k])]
    if exaggerate != 1.0:
        from .surfaces.placement import Frame

        mesh0 = _nominal_mesh(case, result.parts)
        phi, delta = math.radians(row["roll_deg"]), row["transmission_error_urad"] * 1e-6
        p0 = Frame.stack([mesh0.pinion_frame(phi, row["pair"])])
        g0 = Frame.stack([mesh0.gear_frame(phi, row["pair"], delta)])
        gear_frame = exaggerated_frame(pinion_frame, gear_frame, p0, g0, exaggerate)
    driver, driven = _placed(bodies.driver, pinion_frame), _placed(bodies.driven, gear_frame)
    plotter.add_mesh(driver, color=DRIVER_BODY, **_surface_props())
    plotter.add_mesh(driven, color=DRIVEN_BODY, **_surface_props(opacity=0.35))

    m = _module_of(case)
    outlines = ellipse_outlines(cycle, "pinion")
    warn = False
    for j in ks:
        world = cycle.pinion_frames[np.array([j])].to_world(outlines[j][None])[0]
        world = world + 0.01 * m * cycle.planes.normal[j]
        bad = bool(cycle.rows[j]["edge_contact"])
        warn |= bad
        plotter.add_mesh(pv.lines_from_points(world), color=WARNING if bad else CONTACT,
                         line_width=5, lighting=False)
        plotter.add_mesh(pv.Sphere(radius=0.1 * m, center=cycle.planes.point[j]),
                         color=WARNING if bad else CONTACT, smooth_shading=True)
    names = MEMBER_NAMES.get(case.kind, ("pinion", "gear"))
    what = (f"{names[0]} and {names[1]} ({names[1]} see-through) in mesh at roll "
            f"{row['roll_deg']:.2f}°, position {index} of 0-"
            f"{len({r['roll_deg'] for r in cycle.rows}) - 1}")
    legend = [f"{len(ks)} contact(s): dot = contact point, outline = Hertz ellipse "
              f"(largest: a = {row['a_mm']:.2f} mm, b = {row['b_mm']:.3f} mm, "
              f"p = {row['p_max_MPa']:.0f} MPa)"]
    text = _misalignment_text(case)
    if text:
        legend.append(text + (f", shown ×{exaggerate:g}" if exaggerate != 1.0 else ""))
    _texts(plotter, _title(case, name, what), legend,
           ["red: edge contact"] if warn else [])
    scene = np.concatenate([np.asarray(driver.points)[::3], np.asarray(driven.points)[::3]])
    _pair_camera(plotter, case, cycle.planes.point[k], cycle.planes.normal[k],
                 pinion_frame, gear_frame, m, scene)
    return plotter


#: a helical pair's view direction: the contact normal's part to the axis's (see _pair_camera)
HELICAL_OBLIQUE = 1.6


def _pair_camera(plotter, case, focus, normal, pinion_frame, gear_frame, m: float,
                 scene: np.ndarray, oblique: float = 0.35):
    """A view of the mesh through the see-through driven member. Gears and splines: from
    the driver's end B, a little from the driven side; worm sets: along the wheel's axis,
    the worm below and the wheel above. The part of `scene` (points) within reach of the
    focus fills the window below the text."""
    axis = pinion_frame.R[0][:, 2]
    radial = focus - pinion_frame.origin[0, 0]
    radial = radial - axis * np.dot(radial, axis)
    radial /= np.linalg.norm(radial)
    if case.kind == "worm":
        wheel_axis = gear_frame.R[0][:, 2]
        # from the side of the wheel's mid-plane where the contact is: not through the worm
        offset = np.dot(focus - pinion_frame.origin[0, 0], wheel_axis)
        side = 1.0 if (offset if abs(offset) > 1e-6 else np.dot(wheel_axis, normal)) >= 0 else -1.0
        toward = 1.0 if np.dot(axis, normal) >= 0 else -1.0     # the loaded flank's side
        radial = gear_frame.origin[0, 0] - pinion_frame.origin[0, 0]   # toward the wheel
        radial = radial - axis * np.dot(radial, axis)
        radial /= np.linalg.norm(radial)
        direction = side * wheel_axis + 0.3 * radial + 0.3 * toward * axis
        reach, centre = np.inf, focus              # the whole worm and the wheel's sector
    elif case.kind == "spline":                  # the whole end view
        direction = axis + 0.3 * normal + 0.3 * radial
        reach, centre = np.inf, focus
    else:
        # a helical pair's contact lines run across the face: seen from nearer the contact
        # normal, through the driven member, they lie on the flank (from the end they are
        # edge-on)
        if getattr(case, "helix_angle", 0.0):
            oblique = max(oblique, HELICAL_OBLIQUE)
        direction = axis + oblique * normal + 0.25 * radial
        reach = 7.0 * m
        centre = focus
    near = scene[np.linalg.norm(scene - centre, axis=1) < reach]
    near = near if len(near) else scene
    box = (0.02, 0.02, 0.98, 0.86)
    target, half = _fit(near, centre, direction, radial, 1.02, box)
    _camera(plotter, target, direction, radial, half)
    _refit(plotter, near, box, margin=1.04)


# ---------------------------------------------------------------------------------------
# the loaded contact's pressure


def pressure_on_flank(cycle, loaded: list, patch: Patch, refine: int = 4):
    """The largest pressure (MPa) over the rows' loaded solutions at the points of the shown
    flank, on a grid `refine` times finer than the patch: (points (nu, nv, 3), pressure
    (nu, nv)). Each row's pressure lives on a grid of its tangent plane (field.x along e1
    turned by field.turn, field.y across it, mm from the contact point); a flank point is
    carried there by the
    row's frame and read off by bilinear interpolation where it lies within 0.05 mm of the
    plane and on both flanks' material."""
    from scipy.interpolate import RegularGridInterpolator

    flank = patch.flank
    frames = getattr(cycle, f"{patch.member}_frames")
    u = np.linspace(patch.u[0], patch.u[-1], refine * (len(patch.u) - 1) + 1)
    v = np.linspace(patch.v[0], patch.v[-1], refine * (len(patch.v) - 1) + 1)
    U, V = np.meshgrid(u, v, indexing="ij")
    with np.errstate(all="ignore"):
        local = _flank_points(flank, U, V)
    flat = np.nan_to_num(local.reshape(-1, 3), nan=1e9)
    best = np.zeros(len(flat))
    planes = cycle.planes
    for k, item in enumerate(loaded or []):
        if item is None:
            continue
        field, p = item.field, np.asarray(item.solution.pressure_MPa, float)
        world = frames[np.array([k])].to_world(flat[None])[0]
        rel = world - planes.point[k]
        e1 = math.cos(field.turn) * planes.e1[k] + math.sin(field.turn) * planes.e2[k]
        e2 = np.cross(planes.normal[k], e1)
        x, y, h = rel @ e1, rel @ e2, rel @ planes.normal[k]
        fx, fy = np.asarray(field.x, float), np.asarray(field.y, float)
        near = ((x >= fx[0]) & (x <= fx[-1]) & (y >= fy[0]) & (y <= fy[-1])
                & (np.abs(h) < 0.05))
        if not near.any():
            continue
        values = np.where(np.asarray(field.material, bool), p, 0.0)
        read = RegularGridInterpolator((fx, fy), values, bounds_error=False, fill_value=0.0)
        best[near] = np.maximum(best[near], read(np.column_stack([x[near], y[near]])))
    return local, best.reshape(U.shape)


def loaded_edges(cycle, rows: list[int] | None = None) -> dict[str, float]:
    """Edges of the loaded contacts' fields that carry load (the row's edge_loaded, or more
    than 1 % of its load in the edge strip), with the largest edge pressure (MPa), over the
    rows given (all by default). A row the solver could not answer (its keys None) flags
    nothing."""
    out = {}
    for row in (cycle.rows if rows is None else [cycle.rows[k] for k in rows]):
        flagged = row.get("edge_loaded")
        if flagged is None:
            flagged = (row.get("edge_load_fraction") or 0.0) > 0.01
        if flagged and row.get("edge_pressure_at"):
            edge = row["edge_pressure_at"]
            out[edge] = max(out.get(edge, 0.0), float(row.get("edge_pressure_MPa", 0.0)))
    return out


def peak_position(rows: list[dict]) -> float | None:
    """The roll angle (deg) of the position whose loaded contact holds the largest design
    pressure (bem_p_max_MPa); None where no contact was solved."""
    solved = [r for r in rows if r.get("bem_p_max_MPa")]
    return max(solved, key=lambda r: r["bem_p_max_MPa"])["roll_deg"] if solved else None


def pressure_scene(result, case=None, name: str = "", patch: Patch | None = None,
                   roll: float | None = None):
    """The loaded contact painted on the pattern's flank, head-on: the largest pressure at
    each point over the cycle, or (`roll`, deg) the pressure of every pair at that one
    position; the colour scale tops out at the largest design pressure of the rows shown
    (bem_p_max_MPa, which leaves out the singular cells at a sharp edge)."""
    pv = _pyvista()
    cycle = result.cycle
    patch = patch or flank_patch(cycle)
    flank = patch.flank
    shown_rows = [k for k, r in enumerate(cycle.rows) if roll is None or r["roll_deg"] == roll]
    loaded = [item if k in shown_rows else None for k, item in enumerate(result.loaded or [])]
    points, pressure = pressure_on_flank(cycle, loaded, patch)
    plotter = _plotter(pv)
    centre, normal, up, across = _flank_frame(patch)
    warp, stretch = _stretcher(patch, centre, up, across, "head-on")
    plotter._scene_warp = warp
    span = float(np.ptp(patch.points.reshape(-1, 3) @ across))
    lift = 2e-3 * span
    design = [cycle.rows[k]["bem_p_max_MPa"] for k in shown_rows
              if cycle.rows[k].get("bem_p_max_MPa")]
    top = max(design) if design else float(np.percentile(pressure[pressure > 0], 99)) \
        if (pressure > 0).any() else 1.0
    shown = np.where(pressure > 0, pressure, np.nan)
    surface = _grid_surface(pv, warp(points), {"pressure (MPa)": shown})
    plotter._bar_title = ("largest contact pressure over the mesh cycle (MPa)" if roll is None
                          else f"contact pressure at roll {roll:.2f} deg (MPa)")
    bar = dict(title=" ", n_labels=5,
               fmt="%.0f", color=INK, position_x=0.17, position_y=0.035, width=0.62,
               height=0.055, title_font_size=15, label_font_size=14, vertical=False,
               above_label="above")
    plotter.add_mesh(surface, scalars="pressure (MPa)", cmap=PRESSURE_CMAP, clim=(0.0, top),
                     nan_color=NO_PAINT, above_color="#fde725", scalar_bar_args=bar,
                     **_surface_props())
    crossed = edge_contacts([cycle.rows[k] for k in shown_rows], row_name(case, patch.member))
    edges = _patch_boundary(patch)
    for line in edges.values():
        if len(line) < 2:
            continue
        plotter.add_mesh(pv.lines_from_points(warp(_lift(flank, line, lift))), color=INK,
                         line_width=2, lighting=False)
    _edge_labels(plotter, edges, centre, 0.035 * span, set(), warp)
    names = MEMBER_NAMES.get(getattr(case, "kind", ""), ("pinion", "gear"))
    owner = names[0] if patch.member == "pinion" else names[1]
    solved = sum(item is not None for item in loaded)
    peak = max((cycle.rows[k].get("bem_raw_peak_MPa") or 0.0 for k in shown_rows), default=0.0)
    legend = [f"the largest pressure at each point over the {solved} loaded contacts of the "
              f"cycle; design peak {top:.0f} MPa" if roll is None else
              f"the {solved} loaded contact{'s' if solved != 1 else ''} at roll {roll:.2f} "
              f"deg, the position of the cycle's largest pressure: peak {top:.0f} MPa"]
    if stretch > 1.05:
        legend.append(f"NOTE: the profile direction is drawn {stretch:.1f} times its scale")
    if peak > top * 1.001:
        legend.append(f"(cells at a sharp edge reach {peak:.0f} MPa: singular, "
                      "not a design value)")
    edges_loaded = loaded_edges(cycle, shown_rows)
    warnings = []
    if edges_loaded:
        sections = {member: result.sections.get(member) or {} for member in ("pinion", "gear")}
        rounded = ({f"{m}_tip" for m, s in sections.items() if s.get("tip_edge_radius_mm")}
                   | {f"{m}_end_{end}" for m, s in sections.items() if s.get("end_chamfer_mm")
                      for end in "AB"})
        warnings.append("EDGE LOAD: " + ", ".join(
            f"{e.replace('_', ' ')} {p:.0f} MPa" + (" on its rounded edge" if e in rounded
                                                    else "")
            for e, p in edges_loaded.items())
            + (" (sharp edges averaged over the edge strip)"
               if set(edges_loaded) - rounded else ""))
    if crossed:
        warnings.append("Hertz ellipses cross the " + ", ".join(
            e.replace("_", " ") for e in crossed))
    _texts(plotter, _title(case, name, f"loaded contact on the {owner}'s flank, head-on"
                                       + ("" if roll is None else f", at roll {roll:.2f} deg")),
           legend, warnings)
    _head_on_layout(plotter, warp(patch.points.reshape(-1, 3)), centre, normal, up, stretch)
    return plotter


# ---------------------------------------------------------------------------------------
# a pair without a contact analysis


def geometry_scene(case, parts, name: str = "", bodies: Members | None = None):
    """The members of a spur, spline or worm case without a load (`parts`, as its analysis
    generated them), placed in mesh at roll 0 (nominal, no lag)."""
    pv = _pyvista()
    from .surfaces.placement import Frame

    bodies = bodies or members(pv, case.kind, parts)
    mesh = _nominal_mesh(case, parts)
    pf, gf = Frame.stack([mesh.pinion_frame(0.0)]), Frame.stack([mesh.gear_frame(0.0)])
    plotter = _plotter(pv)
    driver, driven = _placed(bodies.driver, pf), _placed(bodies.driven, gf)
    plotter.add_mesh(driver, color=DRIVER_BODY, **_surface_props())
    plotter.add_mesh(driven, color=DRIVEN_BODY, **_surface_props(opacity=0.35))
    names = MEMBER_NAMES[case.kind]
    _texts(plotter, _title(case, name, f"{names[0]} and {names[1]} ({names[1]} see-through) "
                                       "in mesh, nominal position"),
           ["geometry only: the case gives no load, so there is no contact analysis"])
    m = _module_of(case)
    if case.kind == "worm":
        focus, normal = np.array([mesh.wheel.worm.reference_radius, 0.0, 0.0]), gf.R[0][:, 2]
    else:
        pitch = parts.operating_pitch_radius if case.kind == "spur" else \
            0.5 * parts.spline.pitch_diameter
        focus, normal = np.array([pitch, 0.0, 0.0]), np.array([0.0, 1.0, 0.0])
    scene = np.concatenate([np.asarray(driver.points)[::3], np.asarray(driven.points)[::3]])
    _pair_camera(plotter, case, focus, normal, pf, gf, m, scene, oblique=0.9)
    return plotter


# ---------------------------------------------------------------------------------------
# dispatch


def pictures_for(result, case, out_dir: str | Path, name: str = "", position: int | None = None,
                 exaggerate: float = 1.0) -> list[Path]:
    """Every picture that applies to a result (analyses.Result of `case`), written into
    `out_dir`: pattern_head_on.png, pattern_perspective.png and pair.png for a contact case
    (spur, spline or worm with a load), pressure.png (the largest over the cycle) and
    pressure_peak.png (at the position of the largest pressure) when the result carries the
    loaded contact; pair.png alone for a spur, spline or worm case without a load or without
    the ease-off ([analysis] ease_off = false); [] for every other kind (analytic kinds,
    imported meshes)."""
    out = Path(out_dir)
    kind = getattr(case, "kind", None)
    cycle = getattr(result, "cycle", None)
    if cycle is None and kind not in MEMBER_NAMES:
        return []
    if cycle is not None:
        position_rows(cycle.rows, position)          # a bad position fails before any write
    pv = _pyvista()
    bodies = members(pv, kind, result.parts) if kind in MEMBER_NAMES else None
    written = []
    if cycle is None:
        written.append(_finish(geometry_scene(case, result.parts, name, bodies),
                               out / "pair.png"))
        return written
    # the pattern and the pressure are painted on the ease-off: none without it
    patch = None if cycle.ease_off is None else flank_patch(cycle)
    if patch is not None:
        for view, filename in (("head-on", "pattern_head_on.png"),
                               ("perspective", "pattern_perspective.png")):
            written.append(_finish(pattern_scene(result, case, name, view, bodies, patch),
                                   out / filename))
    if bodies is not None:
        written.append(_finish(pair_scene(result, case, name, position, exaggerate, bodies),
                               out / "pair.png"))
    if patch is not None and getattr(result, "loaded", None) and any(
            x is not None for x in result.loaded):
        written.append(_finish(pressure_scene(result, case, name, patch), out / "pressure.png"))
        roll = peak_position(cycle.rows)
        if roll is not None:
            written.append(_finish(pressure_scene(result, case, name, patch, roll),
                                   out / "pressure_peak.png"))
    return written
