"""Hat functions (linear interpolation weights) on equally spaced nodes: how a load at a
point is shared between its two nearest nodes, and how a field on the nodes is read there."""

from __future__ import annotations

import numpy as np


def hats(nodes: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The hat functions on the increasing, equally spaced `nodes` at `values`: each value's
    left node (int) and the share (0..1) its right neighbour takes; the left one takes the
    rest. Values beyond the nodes go to the end nodes."""
    n = len(nodes)
    t = np.clip((np.asarray(values, float) - nodes[0]) / (nodes[-1] - nodes[0]) * (n - 1),
                0.0, n - 1)
    left = np.minimum(np.floor(t).astype(int), n - 2)
    return left, t - left


def grid_hats(rows: np.ndarray, columns: np.ndarray, at_rows: np.ndarray, at_columns: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray]:
    """The two-way hat functions of the grid `rows` × `columns` (equally spaced nodes each)
    at the points (at_rows, at_columns): each point's four nodes (row-major index in the
    grid, (points, 4)) and its weights on them ((points, 4), summing to 1)."""
    up, up_share = hats(rows, at_rows)
    along, along_share = hats(columns, at_columns)
    nodes = np.stack([r * len(columns) + k for r in (up, up + 1) for k in (along, along + 1)],
                     axis=-1)
    weights = np.stack([wr * wk for wr in (1.0 - up_share, up_share)
                        for wk in (1.0 - along_share, along_share)], axis=-1)
    return nodes, weights
