"""Exact tooth flanks as parametric surfaces r(u, v) (DESIGN.md principle 1)."""
