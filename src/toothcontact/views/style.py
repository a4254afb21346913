"""The look every figure shares (its size, resolution, colours and axes) and the one way a
figure is written: its own `Figure` on an Agg canvas (object API, no pyplot, no display, no
global pyplot state), one PNG whole or not at all (a temporary file in the same folder,
then renamed). Only the views' figure modules import matplotlib."""

from __future__ import annotations

import math
import textwrap
from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.ticker import FuncFormatter, ScalarFormatter

from .. import __version__

#: Resolution of every figure (pixels per inch); widths are 8.5 in, i.e. 1020 px.
DPI = 120
WIDTH_IN = 8.5
#: Warning colour: edge contact. No other element of a figure uses it.
WARNING = "#d62728"
#: Series colours: matplotlib's tab10 without its red and orange (kept for warnings).
SERIES = ("#1f77b4", "#2ca02c", "#9467bd", "#8c564b", "#17becf", "#7f7f7f", "#bcbd22",
          "#e377c2")
#: Crown chart: the chosen design's marker colour (used nowhere else in that chart).
DESIGN = "#ffbf00"


# ---------------------------------------------------------------------------------------
# plumbing


def figure(height_in: float) -> Figure:
    fig = Figure(figsize=(WIDTH_IN, height_in), dpi=DPI, layout="constrained")
    FigureCanvasAgg(fig)
    return fig


def save(fig: Figure, path: str | Path) -> Path:
    """Write `fig` as PNG to `path` atomically; the figure is cleared afterwards."""
    from ..writing import write_atomic

    try:
        return write_atomic(path, lambda handle: fig.savefig(
            handle, format="png", dpi=DPI,
            metadata={"Software": f"toothcontact {__version__} (matplotlib)"}), binary=True)
    finally:
        fig.clear()


def num(value) -> float:
    """A float from a result value; None, "nan", "inf" or anything non-numeric -> NaN."""
    if isinstance(value, bool) or value is None:
        return math.nan
    try:
        number = float(value)
    except (TypeError, ValueError):
        return math.nan
    return number if math.isfinite(number) else math.nan


def column(rows: list[dict], key: str) -> np.ndarray:
    return np.array([num(r.get(key)) for r in rows], dtype=float)


def title(result: dict, what: str, width: int = 80) -> str:
    name = result.get("title") or result.get("case") or ""
    return "\n".join(textwrap.wrap(f"{what}: {name}" if name else what, width))


def plain_axis(axis) -> None:
    """Tick labels without an offset or a power of ten (TE varies in its fourth digit)."""
    formatter = ScalarFormatter(useOffset=False)
    formatter.set_scientific(False)
    axis.set_major_formatter(formatter)


def plain_log(axis) -> None:
    """Log-axis labels as plain numbers, at the decades and at 2, 3 and 5 between them."""
    major = FuncFormatter(lambda v, _: f"{v:g}")

    def minor(value, _):
        mantissa = value / 10.0 ** math.floor(math.log10(value) + 1e-9)
        return f"{value:g}" if round(mantissa) in (2, 3, 5) else ""

    axis.set_major_formatter(major)
    axis.set_minor_formatter(FuncFormatter(minor))


def labelled_log_limits(ax) -> None:
    """Widen a log y axis to the labelled values (1, 2, 3, 5 per decade) just outside its
    data, so each end carries a label."""
    steps = np.array([1.0, 2.0, 3.0, 5.0, 10.0])
    lo, hi = ax.get_ylim()
    if not (lo > 0 and hi > lo):
        return

    def nice(value, below):
        decade = 10.0 ** math.floor(math.log10(value))
        marks = steps * decade
        return float(marks[marks <= value * (1 + 1e-9)].max() if below
                     else marks[marks >= value * (1 - 1e-9)].min())

    ax.set_ylim(nice(lo, True), nice(hi, False))


#: the least span of the transmission-error axis (µrad, µm): a flat curve's round-off
#: ripple is not blown up to fill the panel
TE_LEAST_SPAN = {"µrad": 2.0, "µm": 0.1}


def least_span(ax, values: np.ndarray, span: float) -> None:
    """Widen the y axis to at least `span` around the values' middle."""
    finite = values[np.isfinite(values)]
    if finite.size and np.ptp(finite) < span:
        middle = 0.5 * (finite.min() + finite.max())
        ax.set_ylim(middle - 0.5 * span, middle + 0.5 * span)


def gapped(x: np.ndarray, y: np.ndarray, step: float) -> tuple[np.ndarray, np.ndarray]:
    """Sorted by x, with a NaN inserted where consecutive x differ by more than 1.5 steps,
    so a line does not bridge positions where the series is absent."""
    order = np.argsort(x, kind="stable")
    x, y = x[order], y[order]
    if len(x) < 2 or not step > 0:
        return x, y
    breaks = np.nonzero(np.diff(x) > 1.5 * step)[0] + 1
    return np.insert(x, breaks, np.nan), np.insert(y, breaks, np.nan)
