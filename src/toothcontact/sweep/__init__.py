"""Sweeps over a base case: grids of varied inputs and tolerance samples (spec: the sweep
file's schema; sampling: the validated sample cases, the same for the same seed)."""
