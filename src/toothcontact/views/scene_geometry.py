"""The geometry the 3D pictures show, from the analysis's exact flanks and results (numpy
only, testable without VTK): the flank patch the contact runs on, its edges, the rigid
ellipses' outlines, the bodies' tooth surfaces in their members' frames, and the loaded
pressure laid on the flank. Units: mm, MPa."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..surfaces.outline import polar

#: picture size (pixels)
from .scene_style import CONTACT, MEMBER_NAMES, NO_PAINT, PAINT_EDGE

# ---------------------------------------------------------------------------------------
# geometry of the pictures (numpy only)


def grid_surface(pv, points: np.ndarray, scalars: dict | None = None):
    """A pyvista StructuredGrid of points (nu, nv, 3), with point data (nu, nv) arrays."""
    grid = pv.StructuredGrid(points[..., 0], points[..., 1], points[..., 2])
    for name, values in (scalars or {}).items():
        grid.point_data[name] = np.asarray(values, float).ravel(order="F")
    return grid


def polyline_mesh(pv, lines: list[np.ndarray]):
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


def flank_normals(flank, u, v) -> np.ndarray:
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
    from ..contact.rays import intersect

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


def patch_boundary(patch: Patch, n: int = 121) -> dict[str, np.ndarray]:
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
    from ..analyses.worm import PUBLISHED_NAMES

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


def cut_stretches(rows, member: str, edge: str, line: np.ndarray, outlines: np.ndarray,
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


def paint_lut(pv, approach_um: float):
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
    side = grid_surface(pv, np.transpose(sections, (1, 0, 2)))
    pieces = [side.extract_surface(algorithm="dataset_surface")]
    for j in (0, -1):                                               # end faces
        edge = sections[j]
        angle = np.arctan2(edge[:, 1], edge[:, 0])
        inner = np.column_stack([rim * np.cos(angle), rim * np.sin(angle), edge[:, 2]])
        pieces.append(grid_surface(pv, np.stack([edge, inner], axis=1)).extract_surface(
            algorithm="dataset_surface"))
    if not whole:                                                   # sector walls
        for i in (0, -1):
            outer = sections[:, i]
            angle = np.arctan2(outer[:, 1], outer[:, 0])
            inner = np.column_stack([rim * np.cos(angle), rim * np.sin(angle), outer[:, 2]])
            pieces.append(grid_surface(pv, np.stack([outer, inner], axis=1)).extract_surface(
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
    from ..surfaces.outline import ToothOutline

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
    from ..cad.wheel import _ordered

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
    surface = grid_surface(pv, pts).extract_surface(algorithm="dataset_surface")
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
        pieces.append(grid_surface(pv, np.stack([rim, centre], axis=1)).extract_surface(
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
