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
#: ``NONLOCAL_RELATIVE`` of the disk's radius plus ``NONLOCAL_PENETRATION`` dense spacings.
#: Shrinking the searched disk keeps the tree from refining the band where the curves hug the
#: disk near its contacts (5x faster on 4000-vertex loops); what it can miss is a distant part
#: of a curve grazing a disk by less than that: a slight bifurcation whose in-betweens overlap
#: by less than 5 % of the local gap.
LOCAL_WINDOW = 4
NONLOCAL_RELATIVE = 0.05
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
ARC_TABLE_SAMPLES = 16

#: Strokes whose points lie farther than this (times scale) from the fitted drawing plane are
#: reported as non-planar.
PLANARITY = 1e-3

#: Stroke matching (ballmorph_core.matching). Costs are root-mean-square distances between
#: corresponding arc-length samples of two strokes, once the keys' overall motion is removed,
#: relative to the drawing size (the smaller of the two keys' bounding-box diagonals).
#: Samples per stroke in the matching descriptor.
MATCH_SAMPLES = 32
#: A pair costing this much or more is never formed: both strokes stay unmatched (they appear
#: or disappear) rather than morphing across the drawing. Equivalent to padding the
#: assignment with dummy partners costing half of this each.
MATCH_MAX_COST = 0.5
#: Added to the cost of a pair where one stroke is cyclic and the other is not.
MATCH_CYCLIC_PENALTY = 0.1
#: 'AUTO' keeps the drawing order (pairing by index) when the counts agree, every index pair
#: costs less than MATCH_INDEX_MAX_COST, and the index pairing's total is within
#: MATCH_INDEX_FACTOR of the optimal assignment's.
MATCH_INDEX_MAX_COST = 0.25
MATCH_INDEX_FACTOR = 1.25
#: Per pair, totals closer than this are equal (round-off of the Gram-matrix cost evaluation).
MATCH_ROUNDOFF = 1e-6
#: Alternations of (assign strokes, re-fit the keys' overall translation) per starting guess.
MATCH_MOTION_ITERATIONS = 3

#: Default number of time steps ``T`` (``eps = 1 / T``) at which the quality measures sample a
#: morph (paper section 6).
MEASURE_STEPS = 40

#: Default sample count of the quality measures along the longer curve (their geodesic spacing
#: is its length over this), independent of how densely the input was drawn.
MEASURE_SAMPLES = 200

#: Acceleration measure: a local frame triangle (sample, neighbour now, neighbour next) whose
#: sine of its angle at the sample is below this is degenerate (the neighbour does not move, or
#: moves along the edge) and gives no barycentric coordinates.
DEGENERATE_FRAME = 1e-6

#: Comparison morphs (ballmorph_core.morphs.closest, curvature, laplace, heat).
#: Closest projection: consecutive samples whose closest points step backwards along the other
#: curve by more than this many sample spacings make the projection non-monotone.
PROJECTION_REVERSAL = 0.01
#: Closest projection: a vertex of the other curve passed over between two consecutive samples'
#: closest points lying farther than both samples' distances by this many sample spacings means
#: the closest point jumped (a point in between has two closest projections). A continuous
#: projection passes over vertices only O(h^2 curvature) farther.
PROJECTION_BULGE = 0.25
#: At most this many places are listed in an incompatibility message.
DEFECTS_LISTED = 3
#: Closest projection: three dense vertices with |2 cross| below this times their squared span
#: are straight: the foot on the chord is kept instead of the foot on their circle.
PROJECTION_STRAIGHT = 1e-9

#: Composite ball-morph: incompatible stretches separated by at most this many good dense
#: samples are bridged as one (a notch's walls and lips are one feature).
COMPOSITE_MERGE_GAP = 6

#: Curvature interpolation: an edge's closure weight L_AB is at least this fraction of the mean
#: edge length (Sederberg's L_tol), so edges whose length does not change still take a share.
CURVATURE_LENGTH_FLOOR = 1e-3
#: Heat propagation: default grid cells along the longer side of the pair's bounding box, and
#: stored levels per trajectory (frames interpolate linearly between levels).
HEAT_GRID = 256
HEAT_LEVELS = 64
#: Heat propagation: empty cells around the curves' bounding box (room for the extension past
#: the curves), and how many node layers the field is extended by past the first ghost layer.
HEAT_GRID_PAD = 6
HEAT_EXTENSION_LAYERS = 3
#: Heat propagation: the solve starts from the solution on a grid half as fine, recursively
#: down to this many cells (the smallest grid accepted).
HEAT_COARSEST_GRID = 16
#: Heat propagation: conjugate gradients stop at this relative residual, or after this many
#: iterations per grid cell along the longer side.
HEAT_CG_RTOL = 1e-9
HEAT_CG_MAX_ITER_PER_CELL = 8
#: Heat propagation: a curve cutting a grid edge closer than this fraction of the edge to a node
#: is put at this fraction (keeps the Dirichlet weight 1/theta finite).
HEAT_MIN_THETA = 1e-3
#: Heat propagation: a gradient smaller than this (times 1 / extent of the pair) is a stall.
HEAT_MIN_GRADIENT = 1e-6
#: Heat propagation: a tracing step longer than this fraction of the pair's extent is a failure.
HEAT_MAX_STEP = 0.25
#: Heat propagation: a traced path ending farther than this many cells from the other curve
#: failed; samples closer than HEAT_THIN_GAP cells to the other curve are not traced. Both move
#: straight to their closest point instead.
HEAT_END_MISS_CELLS = 2.0
HEAT_THIN_GAP = 1.5

#: Loop registration: a fitted rotation costs this times (angle / pi)^2 of the normalised
#: residual, so shapes that merely change proportions (squash and stretch, apple to pear) are
#: not turned to fit better; a shape that really turned still is (its unrotated residual is
#: larger than the penalty).
ROTATION_PENALTY = 1.0

#: Relative slack for comparisons that only guard against floating-point round-off (monotone
#: order checks, knot spacings, boundary tests).
ROUNDOFF = 1e-12

#: A registration that moves no point by more than this (times the pair's size) is the
#: identity: no carrier motion is applied.
IDENTITY = 1e-9

#: A fitted drawing plane within this (1 - |cos|) of a world axis plane is taken as that plane,
#: so a drawing on Blender's front canvas maps to plain (x, z) coordinates.
PLANE_AXIS = 1e-6

#: Most (sample, edge) candidate pairs evaluated at once by the ball-map's searches: bounds
#: their temporary arrays (about 0.2 KB per pair) without slowing them down noticeably.
CANDIDATE_BUDGET = 500_000

#: The fast path ball-maps its lenses in batches of about this many input points: one batch
#: for a typical drawing, several for a huge one, which bounds the ball-map's temporaries.
BALLMAP_BATCH_POINTS = 60_000

#: Coordinates beyond this magnitude are rejected: their squares (lengths, disk radii)
#: would overflow float64.
MAX_COORDINATE = 1e150

#: Most samples a spacing may put along one curve; a smaller spacing is rejected rather than
#: exhausting memory.
MAX_SAMPLES = 1_000_000

#: The ball-map redoes at most this many failed samples per direction with an unwindowed
#: search (each costs a pass over the whole other curve); a pair with more failures is plainly
#: not b-compatible and is reported as it is.
REPAIR_LIMIT = 2048

#: Input curves with more than twice this many points per sample spacing are resampled to it
#: before morphing (see curves.coarsen).
COARSEN_RATIO = 4.0
