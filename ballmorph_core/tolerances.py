"""The tolerances several modules of the core share, named once (trimesh style).

Every other tolerance is named beside its one reader.

Lengths are relative to a *scale*: the diagonal of the bounding box of the curves involved, so
results do not depend on the drawing's units. Tolerances that are relative to the sampling
spacing ``h`` say so.
"""

import math

#: Two points closer than this (times scale) are the same point (duplicates, shared endpoints
#: after float round-off, contact of touching curves).
COINCIDENT = 1e-9

#: Stroke endpoints closer than this (times scale) count as shared (paper configuration 2).
SHARED_ENDPOINT = 1e-6

#: A spread, norm or distance of at most this (times scale) is zero: dividing by it gives a
#: ratio of round-off (``geometry.guards``: every such division takes a default instead).
DEGENERATE = COINCIDENT

#: Two curves closer than this (times scale) over a stretch of curve overlap there
#: (paper section 3.2: overlapping portions stay static).
OVERLAP = 1e-7

#: Relative slack for comparisons that only guard against floating-point round-off (monotone
#: order checks, knot spacings, boundary tests).
ROUNDOFF = 1e-12

#: A registration that moves no point by more than this (times the pair's size) is the
#: identity: no carrier motion is applied.
IDENTITY = 1e-9

#: Fits whose normalised residuals differ by less than this are equally good: the one that
#: turns least wins (a symmetric shape turned by 90 degrees never turns by round-off).
EQUAL_FIT = 1e-6

#: The floor of a divisor that is zero only for degenerate input (a length, a norm, an area, a
#: spread: ``x / max(d, TINY)``): far below anything a drawing in float64 yields, it only turns
#: 0 / 0 into 0 instead of NaN. Not a length tolerance: comparisons use the relative ones above.
TINY = 1e-300

#: Two strokes' shapes agree when the residual of their similarity fit (``sqrt(e)``, 0 for
#: similar shapes, 1 for shapes nothing alike) is at most this: a V of seven points against
#: itself slightly opened, a circle against an ellipse 1.5 x 1, a gently bent line against it
#: bent twice as much, but not a line against an arc of a quarter turn. Strokes left over pair
#: when theirs agree (however far they travel), pieces join when theirs agree with the line.
SHAPES_AGREE = 0.25

#: Stroke ends closer than this (times scale) are meant to be shared (a rope pinned at both
#: ends, redrawn a hair off its pins): a pair whose both ends are takes no carrier, and those
#: ends meet halfway (:mod:`ballmorph_core.drawing.ends`), so its in-betweens' ends stay between
#: the keys' ends and consecutive in-betweens do not cross there. Far above ``SHARED_ENDPOINT``
#: (exact sharing, round-off), far below a stroke's own length.
NEAR_SHARED_END = 5e-3

#: Two turns agree within this (radians, 10 degrees): a pair turning within it of the drawing
#: (or of its group) turns with it; a drawing or group turning less does not count as turning.
#: Shared by the stroke pairing (:mod:`ballmorph_core.drawing.pairing.groups`) and the
#: registration's carriers (:mod:`ballmorph_core.drawing.pair_morphs.riding`).
TURN_AGREE = math.radians(10.0)

#: A fitted stretch (the ratio of an affine fit's singular values, or a drawing's scale) beyond
#: ``1 / MAX_STRETCH .. MAX_STRETCH`` is degenerate: an affine fit is not kept, and a drawing's
#: motion at such a scale (its centroids coincide) says nothing of its turn.
MAX_STRETCH = 4.0
