"""Gear ratings from the loaded contact: root stress, allowable stresses and safety factors."""
