"""The off-screen scene the pictures are drawn in: the plotter (pyvista, loaded only here),
screenshots and PNG writing, titles, legends and scale bars, cameras fitted to what they
show. Units: mm."""

from __future__ import annotations

import math
import os
import sys
import textwrap
from pathlib import Path

import numpy as np

from .. import __version__
from .scene_geometry import Patch, flank_normals

#: picture size (pixels)
from .scene_style import BACKGROUND, INK, WARNING, WINDOW

# ---------------------------------------------------------------------------------------
# plumbing


def load_pyvista():
    """pyvista, set up for off-screen rendering (imported here, never at module level)."""
    if sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
        # no X server: render through EGL (Mesa's llvmpipe without a GPU) rather than
        # trying X first
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    import pyvista

    pyvista.OFF_SCREEN = True
    return pyvista


def new_plotter(pv):
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

    from ..writing import write_atomic

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


def finish(plotter, path: Path) -> Path:
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
# text and cameras


def add_texts(plotter, title: str, legend: list[str] = (), warnings: list[str] = ()):
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


def ordinal(n: int) -> str:
    return f"{n}{'th' if 10 <= n % 100 <= 20 else {1: 'st', 2: 'nd', 3: 'rd'}.get(n % 10, 'th')}"


def picture_title(case, name: str, what: str) -> str:
    title = getattr(case, "title", "") or name
    return _wrap(f"{name}: {title}" if name and title != name else title) + "\n" + what


def flank_frame(patch: Patch):
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


def set_camera(plotter, focus: np.ndarray, direction: np.ndarray, up: np.ndarray, half: float,
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


def fit_view(points: np.ndarray, focus: np.ndarray, direction: np.ndarray, up: np.ndarray,
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


def refit_view(plotter, points: np.ndarray, box, margin: float = 1.05, rounds: int = 3):
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


def head_on_layout(plotter, points: np.ndarray, centre: np.ndarray, normal: np.ndarray,
                    up: np.ndarray, stretch: float) -> None:
    """Frame a head-on picture of a flank (its `points`, seen along `normal`, `up` up):
    fitted just under the texts (call after add_texts) with room for the colour bar and the
    mm scale bar below it, which then sit right under the flank, and the empty rest of
    the window cut off (see finish)."""
    top = min(FLANK_BOX[3], getattr(plotter, "_text_bottom", 1.0) - 0.06)  # room for "tip"
    focus, half = fit_view(points, centre, normal, up, 1.1, (FLANK_BOX[0], FLANK_BOX[1],
                                                          FLANK_BOX[2], top))
    heights = 0.5 + ((points[np.isfinite(points).all(axis=1)] - focus) @ up) / (2.0 * half)
    rise = top - heights.max()                        # a wide flank: up to the texts
    focus = focus - up * rise * 2.0 * half
    set_camera(plotter, focus, normal, up, half, parallel=True)
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
    pv = load_pyvista()
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


def add_edge_labels(plotter, edges: dict[str, np.ndarray], centre: np.ndarray, offset: float,
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


#: a flank map's ticks: at most this many per axis, none within this share of an edge's
#: length of its middle (where the edge's own name stands)
FLANK_TICKS, TICK_CLEAR = 5, 0.15


def add_flank_ticks(plotter, edges: dict[str, np.ndarray], centre: np.ndarray,
                    offset: float, warp=lambda p: p) -> None:
    """Coordinates on a head-on flank map: the face position (mm along the member's axis,
    0 at mid-face) under its form (or root) edge and the diameter (mm) beside its end B,
    at round values (matplotlib's MaxNLocator; the last with its unit), each label
    `offset` mm off the edge away from `centre`, none where the edge's own name stands.
    `edges`: the flank's edges in its member's frame (patch_boundary)."""
    from matplotlib.ticker import MaxNLocator

    bottom = next((edges[n] for n in ("form", "root") if len(edges.get(n, ())) > 1), None)
    axes = [(bottom, lambda p: p[:, 2], "{:g}"),
            (edges.get("end_B"), lambda p: 2.0 * np.hypot(p[:, 0], p[:, 1]), "d {:g}")]
    for line, coordinate, text in axes:
        if line is None or len(line) < 2:
            continue
        values = coordinate(line)
        if np.ptp(values) <= 1e-9:
            continue
        order = np.argsort(values)
        place = np.arange(len(line), dtype=float) / (len(line) - 1)   # along the edge
        ticks = [t for t in MaxNLocator(FLANK_TICKS).tick_values(values.min(), values.max())
                 if values.min() <= t <= values.max()
                 and abs(np.interp(t, values[order], place[order]) - 0.5) > TICK_CLEAR]
        for i, tick in enumerate(ticks):
            point = warp(np.array([np.interp(tick, values[order], line[order, j])
                                   for j in range(3)]))
            away = point - centre
            norm = np.linalg.norm(away)
            point = point + away / norm * offset if norm > 0 else point
            label = text.format(round(float(tick), 6)) + (" mm" if i == len(ticks) - 1 else "")
            plotter.add_point_labels(point[None], [label], font_size=12, text_color=INK,
                                     shape=None, show_points=False, always_visible=True)


#: a head-on view stretches a flank longer than this many times its depth
MAX_ASPECT = 4.0


def stretcher(patch: Patch, centre, up, across, view: str):
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


def lift_off_flank(flank, line: np.ndarray, lift: float) -> np.ndarray:
    """Points on (or near) the flank moved `lift` mm along its outward normal (so that lines
    drawn on the flank are not hidden by it)."""
    u, v = flank.parameters_near(line)
    with np.errstate(all="ignore"):
        n = flank_normals(flank, u, v)
    return line + lift * np.nan_to_num(n)


def near_patch(patch: Patch, outlines: np.ndarray) -> np.ndarray:
    """Rows whose outline lies near the shown part of the flank (all, unless it is cut)."""
    if not patch.cropped:
        return np.ones(len(outlines), bool)
    from scipy.spatial import cKDTree

    tree = cKDTree(patch.points.reshape(-1, 3))
    step = max(np.linalg.norm(np.diff(patch.points, axis=0), axis=-1).max(),
               np.linalg.norm(np.diff(patch.points, axis=1), axis=-1).max())
    d, _ = tree.query(outlines.reshape(-1, 3))
    return (d.reshape(outlines.shape[:2]) < 2.0 * step).all(axis=1)


def surface_props(**extra) -> dict:
    return dict(smooth_shading=True, specular=0.2, specular_power=20, ambient=0.25,
                diffuse=0.75, **extra)
