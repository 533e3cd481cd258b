"""Every numeric tolerance of the core, named once (trimesh style).

Lengths are relative to a *scale*: the diagonal of the bounding box of the curves involved, so
results do not depend on the drawing's units. Tolerances that are relative to the sampling
spacing ``h`` say so.
"""

#: Two points closer than this (times scale) are the same point (duplicates, shared endpoints
#: after float round-off, contact of touching curves).
COINCIDENT = 1e-9

#: Stroke endpoints closer than this (times scale) count as shared (paper configuration 2).
SHARED_ENDPOINT = 1e-6

#: Two curves closer than this (times scale) over a stretch of curve overlap there
#: (paper section 3.2: overlapping portions stay static).
OVERLAP = 1e-7

#: ``1 - n_P . N_Q`` below this means the edge faces the same way as the normal at p:
#: the tangent disk would be infinite (paper section 5.2, the parallel singular case).
PARALLEL = 1e-12

#: Slack, as a fraction of the edge length, when deciding that a contact lies on an edge.
ON_EDGE = 1e-9

#: A maximal disk may be entered by the curves by this fraction of the sample spacing before
#: the pair counts as not b-compatible. Polylines are never exactly b-compatible (paper
#: section 4): this is the discretisation slack.
DISK_PENETRATION = 0.05

#: Disk-emptiness check: vertices within this many dense samples of a disk's contact points
#: are checked against ``DISK_PENETRATION``; farther ones (another part of a curve reaching
#: into the disk) are found by a k-d tree search that ignores penetrations shallower than
#: ``NONLOCAL_PENETRATION`` sample spacings, which keeps that search fast.
LOCAL_WINDOW = 16
NONLOCAL_PENETRATION = 1.0

#: In symmetric sampling, the forward (P -> Q) and backward (Q -> P) maps may disagree by this
#: many dense spacings before the pair counts as not b-compatible there (a disk touching a curve
#: at two places makes them disagree by much more).
MAP_DISAGREEMENT = 1.0

#: Default geodesic sample spacing: the median input edge length, clamped to
#: [scale / DEFAULT_SAMPLES_MAX, scale / DEFAULT_SAMPLES_MIN] where scale is the longer curve.
DEFAULT_SAMPLES_MIN = 48
DEFAULT_SAMPLES_MAX = 2000

#: Interpolating subdivision steps are applied until no edge is longer than this many sample
#: spacings (so coarse, hand-placed polylines become smooth before the PLC ball-map).
SUBDIVIDE_EDGE_RATIO = 4.0

#: At most this many subdivision steps (each doubles the vertex count).
SUBDIVIDE_MAX_STEPS = 4

#: Points along each trajectory used to tabulate arc length for uniform-speed traversal.
ARC_TABLE_SAMPLES = 64

#: Strokes whose points lie farther than this (times scale) from the fitted drawing plane are
#: reported as non-planar.
PLANARITY = 1e-3
