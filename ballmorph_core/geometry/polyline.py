"""One planar polyline: validation, arc length, resampling, normals, orientation, reversal.

A curve is an ``(N, 2)`` float64 array. A loop (``closed=True``) is given without repeating its
first point; its last edge joins the last point back to the first. Functions here never mutate
their input.
"""

import numpy as np

from .. import tolerances as tol
from ..errors import InvalidCurveError
from ..options import check_positive
from .ragged import Ragged
from .vectors import unit_left

__all__ = [
    "as_curve",
    "already_clean",
    "coarsen",
    "scale_of",
    "edges",
    "edge_lengths",
    "cumulative_length",
    "curve_length",
    "locate",
    "point_at",
    "resample",
    "default_spacing",
    "default_spacings",
    "pair_scales",
    "signed_area",
    "orient_clockwise",
    "vertex_normals",
    "edge_normals",
    "turning_angles",
    "points_in_loop",
    "reverse",
    "resolve_spacing",
    "subcurve",
    "reversed_fractions",
    "reversal_order",
]

#: Default geodesic sample spacing: the median input edge length, clamped to
#: [scale / DEFAULT_SAMPLES_MAX, scale / DEFAULT_SAMPLES_MIN] where scale is the longer curve.
DEFAULT_SAMPLES_MIN = 48
DEFAULT_SAMPLES_MAX = 2000

#: Coordinates beyond this magnitude are rejected (a curve here, a drawing's strokes in
#: ``drawing.plan``): the drawing pipeline multiplies up to four lengths (the fits' products of
#: squared norms), which stay below 1e240 here, far from float64's 1.8e308. (At 1e100 they
#: overflowed; the golden drawings scaled to 1e70 give the same in-betweens.)
MAX_COORDINATE = 1e60

#: :func:`already_clean` calls a curve clean only with its points this much (relative) farther
#: apart than the duplicate tolerance: round-off never makes it disagree with :func:`as_curve`.
CLEAN_MARGIN = 1e-9

#: Most samples a spacing may put along one curve; a smaller spacing is rejected rather than
#: exhausting memory.
MAX_SAMPLES = 1_000_000

#: Input curves with more than twice this many points per sample spacing are resampled to it
#: before morphing (see curves.coarsen).
COARSEN_RATIO = 4.0


def as_curve(points, name="P", closed=False, min_points=2):
    """Validate a polyline and return a clean float64 copy.

    Consecutive duplicate points are dropped (for a loop, a last point repeating the first is
    dropped too), because a zero-length edge has no direction and no normal.

    Parameters
    ----------
    points : array_like, shape (N, 2)
        The vertices.
    name : str
        The argument's name, used in error messages.
    closed : bool
        Whether the curve is a loop.
    min_points : int
        Fewest distinct points accepted (a loop needs at least 3 whatever this says).

    Returns
    -------
    ndarray, shape (M, 2)
        A new array, ``M <= N``.

    Raises
    ------
    InvalidCurveError
        If the shape is not (N, 2), a coordinate is NaN or infinite, or too few distinct
        points remain.
    """
    try:
        arr = np.array(points, dtype=np.float64, copy=True)
    except (TypeError, ValueError) as exc:
        raise InvalidCurveError(f"{name}: cannot be read as an (N, 2) array of numbers ({exc})") from None
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise InvalidCurveError(f"{name}: expected shape (N, 2), got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        bad = int(np.flatnonzero(~np.all(np.isfinite(arr), axis=1))[0])
        raise InvalidCurveError(f"{name}: point {bad} is not finite ({arr[bad].tolist()})")
    if len(arr) == 0:
        raise InvalidCurveError(f"{name}: the curve has no points")
    if np.abs(arr).max() > MAX_COORDINATE:
        raise InvalidCurveError(
            f"{name}: coordinates up to {np.abs(arr).max():.3g} are too large (at most {MAX_COORDINATE:g}): "
            "scale the drawing down"
        )
    scale = max(float(np.ptp(arr, axis=0).max()), tol.TINY)
    step = np.linalg.norm(np.diff(arr, axis=0), axis=1)
    keep = np.concatenate([[True], step > tol.COINCIDENT * scale])
    arr = arr[keep]
    if closed and len(arr) > 1 and np.linalg.norm(arr[-1] - arr[0]) <= tol.COINCIDENT * scale:
        arr = arr[:-1]
    need = max(min_points, 3 if closed else 2)
    if len(arr) < need:
        kind = "loop" if closed else "stroke"
        raise InvalidCurveError(f"{name}: a {kind} needs at least {need} distinct points, got {len(arr)}")
    return arr


def already_clean(curves, closed):
    """Which curves :func:`as_curve` would return as they are (a float64 copy), all at once:
    finite, small enough, no consecutive duplicates (nor a loop's closing one), enough points.

    The same tests as :func:`as_curve`, with ``CLEAN_MARGIN`` to spare at the duplicate-point
    tolerance, so a curve it would clean or reject is never called clean; those (and any within
    the margin) go through :func:`as_curve` one by one.

    Parameters
    ----------
    curves : list of array_like, shape (N_i, 2)
    closed : array_like of bool, shape (C,)

    Returns
    -------
    ndarray of bool, shape (C,)
    """
    closed = np.asarray(closed, dtype=bool).reshape(-1)
    arrays = [np.asarray(c) for c in curves]
    shaped = np.array(
        [a.dtype.kind in "fiu" and a.ndim == 2 and a.shape[1:] == (2,) and len(a) >= 2 for a in arrays], dtype=bool
    )
    clean = np.zeros(len(arrays), dtype=bool)
    which = np.flatnonzero(shaped)
    if not len(which):
        return clean
    sizes = np.array([len(arrays[c]) for c in which], dtype=np.int64)
    pts = np.concatenate([arrays[c] for c in which]).astype(np.float64, copy=False)
    starts = np.concatenate([[0], np.cumsum(sizes)[:-1]])
    ends = starts + sizes - 1
    finite = np.logical_and.reduceat(np.isfinite(pts).all(axis=1), starts)
    small = np.maximum.reduceat(np.abs(np.where(np.isfinite(pts), pts, 0.0)).max(axis=1), starts) <= MAX_COORDINATE
    span = np.maximum.reduceat(pts, starts) - np.minimum.reduceat(pts, starts)
    eps = tol.COINCIDENT * np.maximum(span.max(axis=1), tol.TINY) * (1.0 + CLEAN_MARGIN)
    d = np.diff(pts, axis=0)
    step = np.sqrt(d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1])
    owner = np.repeat(np.arange(len(which)), sizes)[1:]
    inner = np.ones(len(step), dtype=bool)
    inner[starts[1:] - 1] = False  # the step from one curve to the next
    duplicate = np.bincount(owner[inner & ~(step > eps[owner])], minlength=len(which)) > 0
    loop = closed[which]
    g = pts[ends] - pts[starts]
    closing = np.sqrt(g[:, 0] * g[:, 0] + g[:, 1] * g[:, 1]) <= eps
    enough = sizes >= np.where(loop, 3, 2)
    clean[which] = finite & small & ~duplicate & ~(loop & closing) & enough
    return clean


def scale_of(*curves):
    """Diagonal of the bounding box of all given curves (the unit of relative tolerances).

    Parameters
    ----------
    *curves : ndarray, shape (N_i, 2)

    Returns
    -------
    float
        Strictly positive (1.0 for a single point).
    """
    pts = np.concatenate([np.asarray(c, dtype=np.float64).reshape(-1, 2) for c in curves])
    diag = float(np.linalg.norm(pts.max(axis=0) - pts.min(axis=0)))
    return diag if diag > 0 else 1.0


def pair_scales(*batches):
    """:func:`scale_of` of every group of curves at once: curve ``c`` of each batch, shape (C,)."""
    boxes = np.stack([b.boxes() for b in batches])
    lo, hi = boxes[:, :, :2].min(axis=0), boxes[:, :, 2:].max(axis=0)
    diag = np.linalg.norm(hi - lo, axis=1)
    return np.where(diag > 0, diag, 1.0)


def edges(curve, closed):
    """Edge vectors.

    Returns
    -------
    ndarray, shape (N - 1, 2) for a stroke, (N, 2) for a loop
        ``edges[i] = curve[i + 1] - curve[i]`` (for a loop the last edge closes it).
    """
    nxt = np.roll(curve, -1, axis=0) if closed else curve[1:]
    return nxt - (curve if closed else curve[:-1])


def edge_lengths(curve, closed):
    """Lengths of :func:`edges`, shape (E,)."""
    return np.linalg.norm(edges(curve, closed), axis=1)


def cumulative_length(curve, closed):
    """Arc length at each vertex.

    Returns
    -------
    ndarray, shape (N,) for a stroke, (N + 1,) for a loop
        Starts at 0; for a loop the last entry is the total length (back at vertex 0).
    """
    return np.concatenate([[0.0], np.cumsum(edge_lengths(curve, closed))])


def curve_length(curve, closed):
    """Total arc length (float)."""
    return float(edge_lengths(curve, closed).sum())


def locate(curve, closed, s, cum=None):
    """Edge index and fraction along it for arc-length parameters.

    Parameters
    ----------
    curve : ndarray, shape (N, 2)
    closed : bool
    s : array_like, shape (K,)
        Arc-length positions; taken modulo the length for a loop, clipped for a stroke.
    cum : ndarray, optional
        :func:`cumulative_length` if already known.

    Returns
    -------
    edge : ndarray of int, shape (K,)
    frac : ndarray of float, shape (K,)
        The point is ``curve[edge] + frac * edges[edge]``.
    """
    if cum is None:
        cum = cumulative_length(curve, closed)
    total = cum[-1]
    s = np.asarray(s, dtype=np.float64)
    s = np.mod(s, total) if closed else np.clip(s, 0.0, total)
    n_edges = len(cum) - 1
    edge = np.clip(np.searchsorted(cum, s, side="right") - 1, 0, n_edges - 1)
    length = cum[edge + 1] - cum[edge]
    frac = np.divide(s - cum[edge], length, out=np.zeros_like(s), where=length > 0)
    return edge, np.clip(frac, 0.0, 1.0)


def point_at(curve, closed, s, cum=None):
    """Points at arc-length parameters ``s``, shape (K, 2) (see :func:`locate`)."""
    edge, frac = locate(curve, closed, s, cum)
    ev = edges(curve, closed)
    return curve[edge] + frac[:, None] * ev[edge]


def resolve_spacing(P, Q, closed, spacing):
    """The sample spacing for a pair: ``spacing`` checked, or :func:`default_spacing` if None.

    Raises
    ------
    InvalidCurveError
        If ``spacing`` is not a positive finite number, or would put more than
        ``MAX_SAMPLES`` samples along either curve.
    """
    if spacing is None:
        return default_spacing(P, Q, closed=closed)
    value = check_positive("spacing", spacing)
    longest = max(curve_length(P, closed), curve_length(Q, closed))
    if longest / value > MAX_SAMPLES:
        raise InvalidCurveError(
            f"spacing={value:.3g} would put {longest / value:.3g} samples along a curve of length {longest:.3g} "
            f"(at most {MAX_SAMPLES}): use a larger spacing"
        )
    return value


def coarsen(curves, spacing=None):
    """Curves drawn far more densely than their spacing, resampled to ``COARSEN_RATIO`` points per
    spacing on their spline (the others are kept as drawn).

    A 100,000-point stroke morphed at a spacing of 1/2000 of its length gains nothing from its
    extra points but the cost of every intersection test on them.

    Parameters
    ----------
    curves : Ragged
    spacing : float, optional
        Default: each curve's own :func:`default_spacings`.

    Returns
    -------
    Ragged
        ``curves`` itself when none is that dense.
    """
    # A default spacing is at most twice the mean edge (half the edges are at least the median)
    # or length / DEFAULT_SAMPLES_MAX: a curve is that dense only with more points than this.
    if spacing is None and not np.any(curves.n > 2 * COARSEN_RATIO * DEFAULT_SAMPLES_MAX):
        return curves
    own = default_spacings(curves) if spacing is None else np.full(len(curves), float(spacing))
    wanted = np.ceil(COARSEN_RATIO * curves.length / own).astype(np.int64) + 1
    dense = curves.n > 2 * wanted
    if not dense.any():
        return curves
    pieces = [
        resample(curves.curve(c), bool(curves.closed[c]), count=int(wanted[c])) if dense[c] else curves.curve(c)
        for c in range(len(curves))
    ]
    return Ragged.from_list(pieces, curves.closed)


def default_spacing(*curves, closed=False):
    """A geodesic sample spacing suited to the curves (float).

    The median input edge length, clamped so that the longest curve gets between
    ``DEFAULT_SAMPLES_MIN`` and ``DEFAULT_SAMPLES_MAX`` samples (see
    :func:`default_spacings`, of which this is a batch of one).
    """
    return float(default_spacings(*(Ragged.from_list([c], [closed]) for c in curves))[0])


def default_spacings(*batches):
    """:func:`default_spacing` of every group of curves at once: curve ``c`` of each batch.

    Parameters
    ----------
    *batches : Ragged
        As many curves each.

    Returns
    -------
    ndarray, shape (C,)
    """
    n = len(batches[0])
    owners = [b.owner[b.nxt >= 0] for b in batches]  # each edge's curve, batch by batch
    counts = [np.bincount(owner, minlength=n) for owner in owners]
    count = sum(counts)
    widest = int(count.max(initial=0))
    if n * widest <= 2 * int(count.sum()) + 1024:
        median = _padded_medians(batches, owners, counts, widest)
    else:
        # Curves of very different sizes (a padded table would be mostly padding).
        owner = np.concatenate(owners)
        length = np.concatenate([b.length_of_edge[b.nxt >= 0] for b in batches])
        order = np.lexsort((length, owner))
        owner, length = owner[order], length[order]
        start = np.searchsorted(owner, np.arange(n + 1))
        lo = np.minimum(start[:-1] + (count - 1) // 2, len(length) - 1)
        hi = np.minimum(start[:-1] + count // 2, len(length) - 1)
        median = np.where(count > 0, 0.5 * (length[lo] + length[hi]), 0.0)
    longest = np.max([b.length for b in batches], axis=0)
    return np.clip(median, longest / DEFAULT_SAMPLES_MAX, longest / DEFAULT_SAMPLES_MIN)


def _padded_medians(batches, owners, counts, widest):
    """Median edge length of each group of curves (curve ``c`` of every batch), shape (C,)
    (0 without edges): each group's lengths are a row of a table padded with inf, and the rows
    are sorted each on its own (several times faster than one lexsort of every edge by curve).

    ``owners``: each batch's edges' curves (edges come curve after curve); ``counts``: each
    batch's edges per curve, shape (C,); ``widest``: the most edges of a group.
    """
    count = sum(counts)
    table = np.full((len(count), max(widest, 1)), np.inf)
    filled = np.zeros(len(count), dtype=np.int64)
    for b, owner, mine in zip(batches, owners, counts):
        slot = np.arange(len(owner)) - np.repeat(np.cumsum(mine) - mine, mine) + filled[owner]
        table[owner, slot] = b.length_of_edge[b.nxt >= 0]
        filled += mine
    table.sort(axis=1)
    rows = np.arange(len(count))
    lo, hi = table[rows, np.maximum(count - 1, 0) // 2], table[rows, np.minimum(count // 2, table.shape[1] - 1)]
    return np.where(count > 0, 0.5 * (lo + hi), 0.0)


def signed_area(loop):
    """Shoelace area: positive for counter-clockwise loops (float)."""
    x, y = loop[:, 0], loop[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def orient_clockwise(loop):
    """The loop traversed clockwise (the paper's convention), starting at the same vertex,
    shape (N, 2); a copy."""
    return reverse(loop, True) if signed_area(loop) > 0 else loop.copy()


def reverse(curve, closed):
    """The same curve traversed backwards; a loop keeps its first vertex. Shape (N, 2)."""
    if closed:
        return np.concatenate([curve[:1], curve[:0:-1]])
    return curve[::-1].copy()


def edge_normals(curve, closed):
    """Unit left normals of the edges (tangent turned +90 degrees), shape (E, 2)."""
    return unit_left(edges(curve, closed))


def vertex_normals(curve, closed):
    """Unit left normals at the vertices, shape (N, 2).

    As in the paper (section 5.2), the normal at a vertex is orthogonal to the chord joining its
    two neighbours; a stroke's endpoints use their single edge.
    """
    if closed:
        chord = np.roll(curve, -1, axis=0) - np.roll(curve, 1, axis=0)
    else:
        chord = np.empty_like(curve)
        chord[1:-1] = curve[2:] - curve[:-2]
        chord[0] = curve[1] - curve[0]
        chord[-1] = curve[-1] - curve[-2]
    return unit_left(chord)


def turning_angles(curve, closed):
    """Signed exterior angle at each interior vertex (counter-clockwise positive).

    Returns
    -------
    ndarray, shape (N,) for a loop, (N - 2,) for a stroke
        Angle from edge ``i - 1`` to edge ``i`` at vertex ``i``.
    """
    ev = edges(curve, closed)
    prev = np.roll(ev, 1, axis=0) if closed else ev[:-1]
    nxt = ev if closed else ev[1:]
    cross = prev[:, 0] * nxt[:, 1] - prev[:, 1] * nxt[:, 0]
    dot = np.einsum("ij,ij->i", prev, nxt)
    return np.arctan2(cross, dot)


def points_in_loop(points, loop):
    """Even-odd test: which points lie inside a loop.

    Parameters
    ----------
    points : ndarray, shape (K, 2)
    loop : ndarray, shape (N, 2)

    Returns
    -------
    ndarray of bool, shape (K,)
    """
    points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    return Ragged.from_list([loop], [True]).contains(points, np.zeros(len(points), dtype=np.int64))


def resample(curve, closed, spacing=None, count=None, smooth=True):
    """Resample at uniform arc length.

    Parameters
    ----------
    curve : ndarray, shape (N, 2)
    closed : bool
    spacing : float, optional
        Target geodesic distance between samples; the count is rounded so the spacing is uniform.
    count : int, optional
        Number of samples instead of a spacing (for a stroke, both endpoints included).
    smooth : bool
        Place samples on the centripetal Catmull-Rom spline through the vertices (default)
        rather than on the straight edges.

    Returns
    -------
    ndarray, shape (K, 2)
        For a stroke the first and last samples are the endpoints; a loop starts at vertex 0 and
        does not repeat it.
    """
    if count is None:
        if spacing is None or not spacing > 0:
            raise InvalidCurveError(f"spacing must be a positive number, got {spacing!r}")
        count = int(round(curve_length(curve, closed) / spacing)) + (0 if closed else 1)
    return Ragged.from_list([curve], [closed]).resample([count], smooth=smooth).pts


def subcurve(curve, closed, s0, s1):
    """The part of a curve between two arc-length positions, as a stroke.

    Parameters
    ----------
    curve : ndarray, shape (N, 2)
    closed : bool
    s0, s1 : float
        Start and end positions. For a loop, ``s1 < s0`` (or ``s1 > length``) wraps past the
        first vertex; ``s1 = s0 + length`` is the whole loop.

    Returns
    -------
    ndarray, shape (K, 2)
        The point at ``s0``, the vertices strictly between, the point at ``s1``.
    """
    rg = Ragged.from_list([curve], [closed])
    total = float(rg.length[0])
    if closed:
        s0 = float(np.mod(s0, total))
        s1 = float(s0 + np.mod(s1 - s0, total)) if not np.isclose(s1 - s0, total) else s0 + total
    else:
        s0, s1 = float(np.clip(s0, 0, total)), float(np.clip(s1, 0, total))
    return rg.pieces(np.zeros(1, np.int64), np.array([s0]), np.array([s1])).pts


def reversed_fractions(u, closed):
    """Arc-length fractions along a curve read backwards: ``1 - u``, for a loop ``-u mod 1``
    (it keeps its first point, see :func:`reverse`)."""
    return np.mod(-u, 1.0) if closed else 1.0 - u


def reversal_order(n, closed):
    """Indices that reverse ``n`` samples: a loop keeps its first sample (see :func:`reverse`)."""
    return np.r_[0, np.arange(n - 1, 0, -1)] if closed else np.arange(n)[::-1]
