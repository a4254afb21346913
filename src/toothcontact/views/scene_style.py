"""The look of the off-screen 3D pictures: window size, colours, the members' names by kind
(and so the kinds that have pictures)."""

from __future__ import annotations

#: picture size (pixels)



WINDOW = (1200, 900)
#: the paint at zero separation: where the flanks touch. Prussian blue, as marking compound.
CONTACT = "#0b3a9e"
#: the paint at the approach (the thinnest film that still marks)
PAINT_EDGE = "#a9cdf0"
#: flank without paint (separation beyond the approach)
NO_PAINT = "#9a9a9a"
#: edge contact: the same red as style.WARNING; nothing else in a picture uses it
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
