"""Exact tooth flanks as parametric surfaces r(u, v) (docs/DESIGN.md principle 1)."""
