"""Stroke matching: which stroke of one key morphs into which stroke of the other, and which way.

Two keys rarely list their strokes in the same order with the same count: the animator adds a
line, redraws an eye first, draws a loop the other way round, and between the keys the character
moves, turns and grows. Blender's own interpolation pairs strokes by index and drops the surplus;
:func:`match_strokes` keeps that pairing when it fits the drawings and otherwise solves an optimal
assignment on a cost that does not care how each stroke moved.

The cost of a pair
------------------
Every stroke is resampled to ``MATCH_SAMPLES`` points at uniform arc length (on its chords).
With complex coordinates and samples centred on their own centroid, the best similarity (turn and
scale) taking stroke ``i`` onto stroke ``j`` leaves the normalised residual

    e_ij = 1 - |<a_i, b_j>|^2 / (|a_i|^2 |b_j|^2)   (in [0, 1]: 0 when the shapes are similar),

minimised over B's direction (open strokes) or B's cyclic shift (loops, all at once by FFT). The
cost adds where the strokes lie and how their sizes differ, each relative to the strokes' *own*
sizes (``r``, the RMS distance of the samples from their centroid), once the keys' overall motion
``G`` (a similarity) is taken out:

    cost_ij = W_SHAPE sqrt(e_ij) + W_PLACE |G(c_i) - c_j| / (|G| r_i + r_j)
              + W_SCALE |log(r_j / (|G| r_i))| / log 4 + W_TURN |arg G| / pi
              (+ MATCH_CYCLIC_PENALTY if mixed).

So a stroke turned by any angle, scaled from 1/4 to 4 times or moved by a few of its own sizes
still pairs, and a small stroke is not paired with a big one across the drawing. ``G`` is found by
alternating (assign, fit ``G`` to the paired centroids) from a few starting guesses: no motion,
the shift of the keys' ink, the turn on which similar strokes' fits agree (found without pairing
them: a drawing turned far and redrawn in another order), and the drawing order's motion where
the order accounts for how the drawing moved.

Pairs near each other
---------------------
Most pairs of a drawing of many strokes could never be formed. At each motion the pairs whose
place term alone stays below ``MATCH_NEAR_COST`` are priced and solved first; the solve's dual
potentials certify it for every pair (``u_i + v_j`` at most what each pair left out costs), or
the strokes that break the certificate get all their pairs priced. Where that does not settle
a motion, every pair that may cost less than ``MATCH_MAX_COST`` is priced where those are few
(key A moved across key B), else the whole table (its open fits by matrix products, once: the
faster where most pairs may form, and the ones read from then on). Either way the assignment
is an optimal one of the whole table.

Direction
---------
An open stroke of B runs the way in which more of its ends coincide with its partner's (a
shoulder stays put); then the way that fits with the smaller residual plus
``DIRECTION_TURN (turn / pi)^2``, the turn measured from the keys' overall turn ``arg G`` (a
reading that needs a half turn more than the drawing must fit clearly better); between equal
ones, the way it was drawn. A loop of B runs the other way when its orientation (the sign of
its area) differs.

Unmatched strokes
-----------------
A pair costing ``MATCH_MAX_COST`` or more is never formed by the assignment, except that a
stroke alone in both keys always pairs. The strokes it leaves over pair when their shapes agree,
however far they travel (:mod:`.travelling`; ``Matching.travelled``); the rest stay unmatched
(they appear or disappear, see :func:`~ballmorph_core.inbetween`).
"""

from dataclasses import dataclass, field

import numpy as np

from .. import tolerances as tol
from ..errors import InvalidCurveError
from ..geometry.polyline import as_curve, curve_length, resample
from ..geometry.ragged import Ragged, budget_slices, ragged_arange
from ..geometry.spatial import box_pairs
from ..options import MATCHINGS, check_option
from .assignment import SparseCosts, solve_assignment
from .symmetry import loop_reversals, unoriented
from .travelling import pair_leftovers

__all__ = ["Matching", "match_strokes", "pair_direction"]

#: Samples per stroke in the matching descriptor.
MATCH_SAMPLES = 32
#: Weights of the cost's shape, place and scale terms, and the cost at which a pair is never
#: formed. A similar shape moved by four of its own sizes and grown three times still pairs.
W_SHAPE, W_PLACE, W_SCALE = 1.5, 0.2, 0.3
MATCH_MAX_COST = 1.5
#: Added to the cost of a pair where one stroke is cyclic and the other is not.
MATCH_CYCLIC_PENALTY = 0.1
#: 'auto' keeps the drawing order (pairing by index) when the counts agree, every index pair
#: costs less than MATCH_INDEX_MAX_COST, and the index pairing's total is within
#: MATCH_INDEX_FACTOR of the optimal assignment's.
MATCH_INDEX_MAX_COST = 0.75
MATCH_INDEX_FACTOR = 1.25
#: The drawing order's motion is a starting guess when it accounts for at least this share of
#: the spread of key B's strokes (a reordered key's accounts for about 1 / count), or when the
#: keys have fewer than MATCH_ORDER_GATE strokes.
MATCH_ORDER_EXPLAINS = 0.25
MATCH_ORDER_GATE = 64
#: A motion's assignment is first solved on the pairs whose place term alone stays below this
#: (each stroke's neighbours), and kept when its dual potentials certify it.
MATCH_NEAR_COST = 0.1
#: ... and its strokes whose potentials do not certify it get all their pairs priced, while
#: they stay within this share of the strokes (beyond, the whole table is priced).
MATCH_NEAR_SHARE = 1 / 16
#: ... and where they do not settle it, every pair that may cost less than MATCH_MAX_COST is
#: priced when those are at most this share of the table (else the whole table is, its open
#: fits by matrix products: the faster where more pairs may form).
MATCH_SPARSE_SHARE = 1 / 8
#: The turn guess: the ``TURN_VOTERS`` largest strokes of each key pair up every way, and each
#: pair whose shapes fit within ``TURN_VOTE_FIT`` (``sqrt(e)``) votes for its fit's turn (the
#: better fitting the more), in ``TURN_VOTE_BINS`` bins; the guess is tried where it turns or
#: scales by more than ``TURN_VOTE_MOVE`` (``|a - 1|``, about 6 degrees; below, alternating from
#: the ink's shift finds it).
TURN_VOTERS = 48
TURN_VOTE_FIT = 0.2
TURN_VOTE_BINS = 72
TURN_VOTE_MOVE = 0.1
#: Per pair, totals closer than this are equal (round-off of the cost evaluation).
MATCH_ROUNDOFF = 1e-6
#: Alternations of (assign strokes, re-fit the keys' overall motion) per starting guess.
MATCH_MOTION_ITERATIONS = 3
#: A direction whose fit needs a half turn must fit better than the other by this much of the
#: residual ``e`` (quadratic in the turn): a hook turned 170 degrees (``e`` 0.5 read backwards)
#: keeps its turn, an arch flipped about its chord (``e`` 0.33 read forward) is not a half turn.
DIRECTION_TURN = 0.45
#: Directions whose costs differ by less than this are equally good: the drawn one is kept.
EQUAL_FIT = 1e-4
#: Cost of each pair per half turn of the keys' overall motion: between motions that fit
#: equally (a symmetric drawing), the one that turns less.
W_TURN = 0.1
#: An end within this fraction of the strokes' sizes of its partner's end is shared: the
#: direction in which more ends are shared wins whatever the fits say (a shoulder stays put, a
#: flipped arch keeps its ends).
MATCH_SHARED_ENDS = 0.05
#: Shape term of a dot paired with a stroke (it grows out of the dot or shrinks into it).
DOT_SHAPE = 0.5
#: Two dots have no size: their distance counts relative to this fraction of the drawings' size
#: (the floor of every pair's spread, so also of tiny strokes'). In a drawing of more than
#: ``DOT_SPREAD_STROKES`` strokes the fraction shrinks with one over the square root of the
#: count: the floor stays the strokes' spacing (the size over that root; 0.05 x 20 at 400).
#: Relative to the drawing's size only, each of a thousand hatch lines would reach hundreds of
#: candidates, a share of the drawing that stays put as the count grows (quadratic matching).
DOT_SPREAD = 0.05
DOT_SPREAD_STROKES = 400

# Elements per block when a product would otherwise allocate S_a x S_b x m at once (memory only).
_CHUNK = 2_000_000


@dataclass
class Matching:
    """How the strokes of two keys are paired.

    Attributes
    ----------
    pairs : list of (int, int, bool)
        ``(i, j, reverse)``: stroke ``i`` of key A morphs into stroke ``j`` of key B, sorted by
        ``i``. ``reverse`` is True when B's stroke runs opposite to A's, so the caller reverses
        B's stroke before morphing.
    unmatched_a, unmatched_b : list of int
        Strokes with no partner, sorted.
    method : str
        ``'index'`` (paired by drawing order) or ``'assignment'`` (optimal assignment).
    reason : str
        Why, in a short sentence for the animator.
    costs : list of float
        The cost of each pair (see the module notes); ``inf`` for a pair involving a stroke
        with no points.
    motion : ndarray, shape (2,)
        The translation of the keys' overall motion (key B is about key A moved by it).
    rotation : complex
        Its turn and scale: key B is about ``rotation * z + motion`` of key A (complex ``z``).
    travelled : list of (int, int)
        The pairs ``(i, j)`` made by the drawing's motion: left over by the assignment (too far
        apart for it), paired because their shapes agree (:mod:`.travelling`).
    """

    pairs: list
    unmatched_a: list
    unmatched_b: list
    method: str
    reason: str
    costs: list = field(default_factory=list)
    motion: np.ndarray = field(default_factory=lambda: np.zeros(2))
    rotation: complex = 1.0 + 0j
    travelled: list = field(default_factory=list)


def _clean(points, name, closed):
    """Distinct points of one stroke: shape (K, 2) with K >= 2, (1, 2) for a dot, None if empty.

    A loop with fewer than three distinct points is kept as the open polyline it is.
    """
    try:
        return as_curve(points, name, closed)
    except InvalidCurveError as exc:
        error = exc
    try:
        arr = np.asarray(points, dtype=np.float64)
    except (TypeError, ValueError):
        raise error from None
    if arr.size == 0 and (arr.ndim == 1 or arr.shape[-1] == 2):
        return None
    if arr.ndim != 2 or arr.shape[1] != 2 or not np.all(np.isfinite(arr)):
        raise error
    if closed and len(arr) > 1:
        try:
            return as_curve(arr, name, False)
        except InvalidCurveError:
            pass
    return arr[:1].copy()  # every point coincides: a dot


class _Key:
    """Matching descriptors of the strokes of one key.

    Attributes
    ----------
    loop : ndarray of bool, shape (S,)
        The cyclic flags as given.
    open : ndarray, shape (S, m, 2)
        Arc-length samples along each stroke's vertices, closing edge excluded (how a loop is
        morphed when its partner is open); a dot repeats its point.
    ring : ndarray, shape (S, m, 2)
        For loops, samples around the whole loop; for open strokes the same as ``open``.
    valid : ndarray of bool, shape (S,)
        False for strokes with no points.
    length : ndarray, shape (S,)
    diagonal : float
        Bounding-box diagonal of all the key's points (0 when none).
    """

    def __init__(self, strokes, closed, name, closed_name, m):
        strokes = strokes if isinstance(strokes, Ragged) else list(strokes)
        s = len(strokes)
        closed = np.asarray(closed, dtype=bool).reshape(-1)
        if len(closed) != s:
            raise InvalidCurveError(f"{closed_name}: expected one flag per stroke ({s}), got {len(closed)}")
        self.count = s
        self.loop = closed
        self.open = np.zeros((s, m, 2))
        self.ring = np.zeros((s, m, 2))
        self.valid = np.zeros(s, bool)
        self.length = np.zeros(s)
        if self._batched(strokes, closed, m):
            return
        if isinstance(strokes, Ragged):
            strokes = [strokes.curve(i) for i in range(s)]
        lo, hi = np.full(2, np.inf), np.full(2, -np.inf)
        for i, points in enumerate(strokes):
            clean = _clean(points, f"{name}[{i}]", bool(closed[i]))
            if clean is None:
                continue
            self.valid[i] = True
            lo, hi = np.minimum(lo, clean.min(axis=0)), np.maximum(hi, clean.max(axis=0))
            if len(clean) == 1:
                self.open[i] = self.ring[i] = clean[0]
                continue
            self.open[i] = resample(clean, False, count=m, smooth=False)
            self.ring[i] = resample(clean, True, count=m, smooth=False) if closed[i] else self.open[i]
            self.length[i] = curve_length(clean, bool(closed[i]))
        self.diagonal = float(np.linalg.norm(hi - lo)) if self.valid.any() else 0.0

    def _batched(self, strokes, closed, m):
        """All descriptors at once for well-formed keys (finite points); False to go one by one."""
        given = strokes if isinstance(strokes, Ragged) else None
        flat = (given.pts, given.n, given.offsets) if given is not None else _flattened(strokes)
        if flat is None:
            return False  # the per-stroke road names the malformed stroke
        pts, sizes, offsets = flat
        if not np.all(np.isfinite(pts)):
            return False  # the per-stroke road names the bad stroke
        self.valid = sizes > 0
        if not self.valid.any():
            self.diagonal = 0.0
            return True
        # Column by column: a reduction along axis 0 of an (N, 2) array is ~25 times slower.
        x, y = pts[:, 0], pts[:, 1]
        self.diagonal = float(np.linalg.norm(np.array([x.max() - x.min(), y.max() - y.min()])))
        # A batch given read open is the one read open here (the same arithmetic on the same points).
        if given is not None and not given.closed.any():
            line = given
        else:
            line = Ragged(pts, offsets, np.zeros(len(sizes), dtype=bool))
        # Dots (one point, or all points the same) repeat their point.
        dot = self.valid & (line.length <= tol.COINCIDENT * max(self.diagonal, 1e-300))
        first = pts[np.minimum(offsets[:-1], max(len(pts) - 1, 0))]
        self.open[dot] = self.ring[dot] = first[dot][:, None, :]
        keep = np.flatnonzero(self.valid & ~dot)
        if len(keep):
            # Usually every stroke is kept: then the batch read open is ``line`` itself, and
            # read as drawn it is the same again unless a stroke is a loop.
            if len(keep) == len(sizes):
                opened = line
            else:
                owner, local = ragged_arange(sizes[keep])
                sub = np.concatenate([[0], np.cumsum(sizes[keep])])
                opened = Ragged(pts[offsets[keep][owner] + local], sub, np.zeros(len(keep), dtype=bool))
            if not closed[keep].any():
                looped = opened
            elif opened is line and given is not None and np.array_equal(given.closed, closed):
                looped = given  # the batch given, read as drawn
            else:
                looped = Ragged(opened.pts, opened.offsets, closed[keep])
            self._read(keep, opened, looped, closed[keep], m)
        return True

    def _read(self, keep, opened, looped, closed, m):
        """The descriptors of strokes ``keep`` (shape (K,)) from their batch read open and as
        drawn (Ragged, the same one when no stroke is a loop: then the ring is the open read)."""
        self.open[keep] = opened.resample(np.full(len(keep), m), smooth=False).pts.reshape(-1, m, 2)
        if looped is opened:
            self.ring[keep] = self.open[keep]
        else:
            ring = looped.resample(np.full(len(keep), m), smooth=False).pts.reshape(-1, m, 2)
            self.ring[keep] = np.where(closed[:, None, None], ring, self.open[keep])
        self.length[keep] = looped.length

    def centroids(self):
        """Sample centroid of each stroke's own descriptor (ring for loops), shape (S, 2)."""
        return np.where(self.loop[:, None], self.ring.mean(axis=1), self.open.mean(axis=1))

    def sizes(self):
        """Each stroke's own size: RMS distance of its samples from their centroid, shape (S,)
        (exactly 0 for dots, whatever the round-off of their centroid)."""
        samples = np.where(self.loop[:, None, None], self.ring, self.open)
        rms = np.sqrt(np.mean(np.sum((samples - self.centroids()[:, None]) ** 2, axis=2), axis=1))
        return np.where(self.length > 0, rms, 0.0)

    def areas(self):
        """Signed area of each loop's samples (counter-clockwise positive; 0 for strokes), shape (S,)."""
        x, y = self.ring[..., 0], self.ring[..., 1]
        area = 0.5 * np.sum(x * np.roll(y, -1, axis=1) - np.roll(x, -1, axis=1) * y, axis=1)
        return np.where(self.loop, area, 0.0)

    def _ink(self):
        """The stroke centroids with points and their weights, their lengths (the dots' equal
        where no stroke has ink): shapes (V, 2), (V,)."""
        ctr, w = self.centroids()[self.valid], self.length[self.valid]
        return ctr, (w if w.sum() > 0 else np.ones(len(ctr)))

    def ink_spread(self):
        """Weighted RMS distance of the stroke centroids from :meth:`ink_centroid`, weighted
        as there (float)."""
        ctr, w = self._ink()
        return float(np.sqrt(np.sum(w * np.sum((ctr - self.ink_centroid()) ** 2, axis=1)) / w.sum()))

    def ink_centroid(self):
        """Length-weighted mean of the stroke centroids, shape (2,) (dots weigh in if no ink)."""
        ctr, w = self._ink()
        return (w[:, None] * ctr).sum(axis=0) / w.sum()


def _flattened(strokes):
    """Points, sizes and offsets of a list of strokes, shapes (N, 2), (S,), (S + 1,); None when
    a stroke is not an array of 2D points."""
    try:
        arrays = [np.asarray(p, dtype=np.float64) for p in strokes]
    except (TypeError, ValueError):
        return None
    if any(a.ndim != 2 or a.shape[1] != 2 for a in arrays if a.size):
        return None
    arrays = [a.reshape(-1, 2) for a in arrays]
    sizes = np.array([len(a) for a in arrays], dtype=np.int64)
    pts = np.concatenate(arrays) if arrays else np.zeros((0, 2))
    return pts, sizes, np.concatenate([[0], np.cumsum(sizes)])


def _complex(samples):
    return samples[..., 0] + 1j * samples[..., 1]


def _residual(d, norms):
    """``clip(1 - |d|^2 / norms, 0, 1)`` in place from ``|d|`` (the similarity fit's residual
    from the product ``d = <a, b>`` and ``|a|^2 |b|^2``), shape of ``d``."""
    e = np.abs(d)
    np.square(e, out=e)
    e /= norms
    np.subtract(1.0, e, out=e)
    return np.clip(e, 0.0, 1.0, out=e)


def _open_shapes(a, b):
    """Residuals of open (and mixed) pairs, both directions, and the turns of the fits, for
    every pair (matrix products: the fastest where most pairs are asked for).

    Parameters
    ----------
    a, b : ndarray of complex, shape (S_a, m), (S_b, m)
        Samples centred on their own centroids.

    Returns
    -------
    e_fwd, e_rev : ndarray, shape (S_a, S_b)
    turn_fwd, turn_rev : ndarray, shape (S_a, S_b)
        The fits' turns, the angles of the products ``<a_i, b_j>`` (only the angles are
        kept: 8 bytes a pair rather than 16, which a drawing of thousands of strokes feels).
    """
    norms = np.maximum(_sq_norms(a)[:, None] * _sq_norms(b)[None, :], 1e-300)
    conj_a, out = np.conj(a), []
    for read in (b, b[:, ::-1]):
        # One direction at a time: the complex products are the largest arrays here.
        d = conj_a @ read.T
        out.append((_residual(d, norms), np.angle(d)))
        del d
    (e_f, turn_f), (e_r, turn_r) = out
    return e_f, e_r, turn_f, turn_r


def _sq_norms(a):
    """``|a_k|^2`` of samples ``a`` (complex, shape (K, m)), shape (K,)."""
    return np.sum(np.abs(a) ** 2, axis=1)


def _pair_shapes(a, b, norm_a=None, norm_b=None):
    """:func:`_open_shapes` of pairs: ``a[k]`` with ``b[k]`` (shapes (K, m), complex, centred;
    their :func:`_sq_norms`, shapes (K,), when known), each ``e_fwd, e_rev, turn_fwd,
    turn_rev`` of shape (K,). Each pair's values are its own (the same however many pairs are
    asked at once); they differ from the matrix products' by round-off (the sums are taken in
    another order)."""
    norm_a = _sq_norms(a) if norm_a is None else norm_a
    norm_b = _sq_norms(b) if norm_b is None else norm_b
    norms = np.maximum(norm_a * norm_b, 1e-300)
    conj_a, out = np.conj(a), []
    for read in (b, b[:, ::-1]):
        d = np.sum(conj_a * read, axis=1)
        out.append((_residual(d, norms), np.angle(d)))
    (e_f, turn_f), (e_r, turn_r) = out
    return e_f, e_r, turn_f, turn_r


def _shared_ends(a, b, spread):
    """How many ends pairs of open strokes share read forward and read backwards, shapes (K,).

    ``a``, ``b``: the pairs' samples, shapes (K, m, 2); ``spread``: their sizes, shape (K,).
    """

    def shared(i, j):
        d = a[:, i] - b[:, j]
        # np.linalg.norm's arithmetic (a sum of two squares), without its call.
        return (np.sqrt(d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1]) <= MATCH_SHARED_ENDS * spread).astype(int)

    return shared(0, 0) + shared(-1, -1), shared(0, -1) + shared(-1, 0)


def _dot_spread(key_a, key_b):
    """The floor of every pair's spread (see ``DOT_SPREAD``): a float."""
    strokes = max(np.count_nonzero(key_a.valid), np.count_nonzero(key_b.valid), 1)
    spacing = min(1.0, np.sqrt(DOT_SPREAD_STROKES / strokes))
    return DOT_SPREAD * spacing * max(key_a.diagonal, key_b.diagonal, 1e-300)


class _LoopFits:
    """Residuals of loop pairs over every cyclic shift of B's samples (by FFT), for any pairs.

    Parameters
    ----------
    a, b : ndarray of complex, shape (L_a, m), (L_b, m)
        Samples centred on their own centroids.
    sign_a, sign_b : ndarray, shape (L_a,), (L_b,), optional
        The loops' areas' signs: B's loop is read backwards where the two run opposite ways
        (each pair's correlation is computed once, in the direction it needs). Default: all
        read as given.

    Each pair's residual is computed on its own (its spectra, product and inverse transform
    are its own rows): the same values however many pairs are asked at once, so a table can
    fit only the pairs whose cost may matter.
    """

    def __init__(self, a, b, sign_a=None, sign_b=None):
        self._fa = np.conj(np.fft.fft(a, axis=1))
        self._na = np.sum(np.abs(a) ** 2, axis=1)
        # B read as given and backwards (the norm summed in the order it is read).
        self._fb = [np.fft.fft(v, axis=1) for v in (b, _backwards(b))]
        self._nb = [np.sum(np.abs(v) ** 2, axis=1) for v in (b, _backwards(b))]
        self._sign_a = np.ones(len(a)) if sign_a is None else sign_a
        self._sign_b = np.ones(len(b)) if sign_b is None else sign_b

    def residuals(self, i, j):
        """Residuals of pairs ``(i[k], j[k])`` (rows of ``a`` and ``b``), shape (K,)."""
        back = self._sign_a[i] * self._sign_b[j] < 0
        fb, nb = np.take(self._fb[0], j, axis=0), np.take(self._nb[0], j)
        fb[back], nb[back] = self._fb[1][j[back]], self._nb[1][j[back]]
        norms = np.maximum(np.take(self._na, i) * nb, 1e-300)
        best = np.empty(len(i))
        m = self._fa.shape[1]
        for sl in budget_slices(np.full(len(i), m), _CHUNK):
            corr = np.fft.ifft(np.take(self._fa, i[sl], axis=0) * fb[sl], axis=1)
            best[sl] = np.abs(corr).max(axis=1) ** 2
        return np.clip(1.0 - best / norms, 0.0, 1.0)


def _loop_shapes(a, b, sign_a=None, sign_b=None):
    """Residuals of every loop pair over every cyclic shift of B's samples, shape (L_a, L_b):
    the whole table of :class:`_LoopFits` (``a``, ``b`` complex and centred; with ``sign_a``,
    ``sign_b``, their areas' signs, B's loop read backwards where the two run opposite ways).
    """
    i, j = (g.ravel() for g in np.meshgrid(np.arange(len(a)), np.arange(len(b)), indexing="ij"))
    return _LoopFits(a, b, sign_a, sign_b).residuals(i, j).reshape(len(a), len(b))


def _backwards(samples):
    """Loop samples read the other way round, keeping the first (shape (..., m))."""
    return np.concatenate([samples[..., :1], samples[..., :0:-1]], axis=-1)


@dataclass
class _Priced:
    """The pairs priced at one motion of key A, and what those left out cost at least.

    Attributes
    ----------
    rows, cols : ndarray of int, shape (K,)
        Pair ``k`` is stroke ``rows[k]`` of key A with stroke ``cols[k]`` of key B.
    costs : ndarray, shape (K,)
        Exact below ``MATCH_MAX_COST``, at least that elsewhere.
    size : tuple of int
        ``(S_a, S_b)``.
    floor_a, floor_b : ndarray, shape (S_a,), (S_b,)
        A pair left out costs at least the larger of its strokes' floors, at most
        ``MATCH_MAX_COST`` (a stroke's floor is that once all its pairs are priced that may
        cost less).
    """

    rows: np.ndarray
    cols: np.ndarray
    costs: np.ndarray
    size: tuple
    floor_a: np.ndarray
    floor_b: np.ndarray

    def table(self):
        """Every pair's cost clipped at ``MATCH_MAX_COST``, those left out at that, shape
        (S_a, S_b) (:class:`~.assignment.SparseCosts`): never below the clipped costs, equal
        to them on the pairs priced."""
        return SparseCosts(self.size, self.rows, self.cols, np.minimum(self.costs, MATCH_MAX_COST), MATCH_MAX_COST)

    def cheapest(self):
        """Each stroke's cheapest pair priced, clipped at its floor: never above its cheapest
        pair's cost clipped at ``MATCH_MAX_COST``; shapes (S_a,), (S_b,)."""
        out = []
        for side, floor in ((self.rows, self.floor_a), (self.cols, self.floor_b)):
            cheapest = floor.copy()
            np.minimum.at(cheapest, side, self.costs)
            out.append(cheapest)
        return out

    def least_total(self):
        """:func:`_least_total` of the whole table, from the pairs priced and the floors
        (float): never above it, so never above any matching's total at this motion."""
        cheapest_a, cheapest_b = self.cheapest()
        return 0.5 * (float(cheapest_a.sum()) + float(cheapest_b.sum()))

    def uncertified(self, u, v):
        """The strokes whose pairs must all be priced before potentials ``u``, ``v`` (shapes
        (S_a,), (S_b,)) of a solve of :meth:`table` can certify it: masks, shapes (S_a,),
        (S_b,), none when they do.

        The solve's potentials hold on its table (``u_i + v_j`` at most each entry), so they
        hold on every pair of a stroke whose pairs are all priced: those left out cost
        ``MATCH_MAX_COST`` or more, the table's entry. Between the other strokes, a pair
        left out costs at least ``level``, and a split ``u_i <= t``, ``v_j <= level - t``
        certifies every such pair: of a few splits, the one leaving the fewest strokes over
        their bound."""
        open_a, open_b = self.floor_a < MATCH_MAX_COST, self.floor_b < MATCH_MAX_COST
        if not (open_a.any() and open_b.any()):
            return np.zeros(len(u), bool), np.zeros(len(v), bool)
        level = float(min(self.floor_a[open_a].min(), self.floor_b[open_b].min()))
        top_u, top_v = float(u[open_a].max()), float(v[open_b].max())
        best = None
        for t in (0.5 * level, level - max(top_v, 0.0), max(top_u, 0.0)):
            over = (u > t) & open_a, (v > level - t) & open_b
            if best is None or over[0].sum() + over[1].sum() < best[0].sum() + best[1].sum():
                best = over
        return best


class _CostTable:
    """Pair costs of two keys, for any overall motion (see the module notes).

    A pair's shape term (the fit of its samples, the bulk of a cost) is fitted only once a
    cost asked for may fall below ``MATCH_MAX_COST`` (the other terms alone say when it
    cannot): a pair never formed needs no exact cost. Costs come two ways: the pairs near
    each other (:meth:`priced`, each stroke's neighbours: what a drawing of many small strokes
    needs), or the whole table (:meth:`costs`; once asked for, every open pair is fitted at
    once by matrix products, the fastest where most pairs may be formed).

    Attributes
    ----------
    shape : ndarray, shape (S_a, S_b)
        ``sqrt(e_ij)``, the similarity-free shape difference; 0 where not fitted yet.
    whole : bool
        Whether the whole table's open fits are made (then they are the ones read).
    """

    def __init__(self, key_a, key_b):
        ca, cb = key_a.centroids(), key_b.centroids()
        self.ca, self.cb = _complex(ca), _complex(cb)
        self.ra, self.rb = key_a.sizes(), key_b.sizes()
        self._valid = key_a.valid, key_b.valid
        self._loop = key_a.loop, key_b.loop
        self.dot_spread = _dot_spread(key_a, key_b)
        self.prior_turn = 1.0 + 0j  # the turn motions are charged from (the hints' when given)
        self._open = key_a.open, key_b.open
        # The open reads centred: how every pair but two loops is fitted.
        self._centred = [_complex(k.open) - _complex(k.open.mean(axis=1))[:, None] for k in (key_a, key_b)]
        self._norms = [_sq_norms(c) for c in self._centred]
        dot_a, dot_b = self.ra <= 0, self.rb <= 0
        self.shape = np.zeros((key_a.count, key_b.count))
        self.shape[dot_a[:, None] != dot_b[None, :]] = DOT_SHAPE
        # A dot's shape term is fixed; every other pair's is fitted when first needed.
        self._unfitted = ~(dot_a[:, None] | dot_b[None, :])
        self.whole, self._fits, self._turns = False, None, None
        self._signs = None  # the loops' areas' signs (0 for open strokes), when both keys have loops
        la, lb = np.flatnonzero(key_a.loop), np.flatnonzero(key_b.loop)
        if la.size and lb.size:
            ra = _complex(key_a.ring[la]) - self.ca[la, None]
            rb = _complex(key_b.ring[lb]) - self.cb[lb, None]
            # A loop drawn the other way (its area's sign) is read backwards before fitting; a
            # loop whose area cannot tell (a figure eight: the sign is round-off) as drawn.
            flat_a, flat_b = unoriented(key_a.areas()[la], self.ra[la]), unoriented(key_b.areas()[lb], self.rb[lb])
            sign_a = np.where(flat_a, 0.0, np.sign(key_a.areas()[la]))
            sign_b = np.where(flat_b, 0.0, np.sign(key_b.areas()[lb]))
            self._loop_fits = _LoopFits(ra, rb, sign_a, sign_b)
            self._rings = ra, rb
            # Each stroke's row among the loops (-1 for open strokes).
            self._loop_row = np.full(key_a.count, -1), np.full(key_b.count, -1)
            self._loop_row[0][la], self._loop_row[1][lb] = np.arange(len(la)), np.arange(len(lb))
            self._signs = np.zeros(key_a.count), np.zeros(key_b.count)
            self._signs[0][la], self._signs[1][lb] = sign_a, sign_b

    def valid(self, rows, cols):
        """Whether both strokes of pairs ``(rows[k], cols[k])`` have points, shape (K,)."""
        return self._valid[0][rows] & self._valid[1][cols]

    def _fit_whole(self):
        """Fit every open (and mixed) pair at once, by matrix products (once)."""
        if self.whole:
            return
        self.whole = True
        n_a, n_b = self.shape.shape
        if self._loop[0].all() and self._loop[1].all():
            # Every pair is a loop pair: its shape is its loop fit (or a dot's), its direction
            # its loops' orientations; the open reads' fits would never be read.
            e_f = e_r = turn_f = turn_r = np.zeros((n_a, n_b))
        else:
            e_f, e_r, turn_f, turn_r = _open_shapes(*self._centred)
        self._fits, self._turns = (e_f, e_r), (turn_f, turn_r)
        loops = self._loop[0][:, None] & self._loop[1][None, :]
        shape = np.minimum(e_f, e_r)
        np.sqrt(shape, out=shape)
        # Every pair but two loops' and a dot's (its shape term is fixed).
        np.copyto(self.shape, shape, where=~(loops | (self.ra[:, None] <= 0) | (self.rb[None, :] <= 0)))
        self._unfitted &= loops

    def _pair_fits(self, rows, cols):
        """Open fits of pairs ``(rows[k], cols[k])`` (shapes (K,)): ``e_fwd, e_rev, turn_fwd,
        turn_rev``, shapes (K,), the whole table's where it is fitted."""
        if self.whole:
            return (*(e[rows, cols] for e in self._fits), *(t[rows, cols] for t in self._turns))
        (a, b), (na, nb), out = self._centred, self._norms, np.empty((4, len(rows)))
        for sl in budget_slices(np.full(len(rows), a.shape[1]), _CHUNK):
            i, j = rows[sl], cols[sl]
            out[:, sl] = _pair_shapes(np.take(a, i, axis=0), np.take(b, j, axis=0), na[i], nb[j])
        return tuple(out)

    def _fit(self, rows, cols):
        """Fit the pairs ``(rows[k], cols[k])`` (shapes (K,)) not fitted yet: two loops by their
        loop fit, any other pair by its open reads."""
        todo = self._unfitted[rows, cols]
        if not todo.any():
            return
        rows, cols = rows[todo], cols[todo]
        loops = self._loop[0][rows] & self._loop[1][cols]
        e = np.empty(len(rows))
        if loops.any():
            e[loops] = self._loop_fits.residuals(self._loop_row[0][rows[loops]], self._loop_row[1][cols[loops]])
        if not loops.all():
            e_f, e_r = self._pair_fits(rows[~loops], cols[~loops])[:2]
            e[~loops] = np.minimum(e_f, e_r)
        self.shape[rows, cols] = np.sqrt(e)
        self._unfitted[rows, cols] = False

    def shapes(self, rows, cols):
        """``sqrt(e)`` of pairs ``(rows[k], cols[k])`` (shapes (K,)), fitted where not yet, shape (K,)."""
        self._fit(rows, cols)
        return self.shape[rows, cols]

    def unplaced_costs(self, a, rows, cols):
        """Costs of pairs ``(rows[k], cols[k])`` (shapes (K,)) without the place and turn terms,
        sizes compared at the scale of ``a`` (complex), shape (K,): how well their shapes agree
        wherever they are (:mod:`.travelling`)."""
        return self._costs(a, 0j, rows, cols, placed=False)

    def directions(self, turn, rows, cols):
        """Whether B's stroke runs opposite to A's in pairs ``(rows[k], cols[k])`` (shapes (K,)),
        given the drawing's turn (radians), shape (K,): the direction sharing more ends; then the
        better fit, a turn away from the drawing's counting against it; then the drawn direction
        (always, next to a dot)."""
        e_f, e_r, *turns = self._pair_fits(rows, cols)
        away = [np.angle(np.exp(1j * (t - turn))) / np.pi for t in turns]
        cost_f, cost_r = e_f + DIRECTION_TURN * away[0] ** 2, e_r + DIRECTION_TURN * away[1] ** 2
        reverse = cost_r < cost_f - EQUAL_FIT
        open_a, open_b = self._open
        shared_f, shared_r = _shared_ends(open_a[rows], open_b[cols], self.ra[rows] + self.rb[cols])
        reverse = np.where(shared_f > shared_r, False, np.where(shared_r > shared_f, True, reverse))
        if self._signs is not None:
            sign_a, sign_b = self._signs[0][rows], self._signs[1][cols]
            loops = self._loop[0][rows] & self._loop[1][cols]
            reverse[loops] = (sign_a * sign_b < 0)[loops]
            # Where an area cannot tell (a zero sign), the smallest turn the fits allow does.
            flat = loops & ((sign_a == 0) | (sign_b == 0))
            if flat.any():
                i, j = self._loop_row[0][rows[flat]], self._loop_row[1][cols[flat]]
                ring_a, ring_b = self._rings
                reverse[flat] = loop_reversals(ring_a[i], ring_b[j], turn, DIRECTION_TURN, EQUAL_FIT)
        # A dot has no direction: its partner keeps the one it was drawn in.
        return reverse & (self.ra[rows] > 0) & (self.rb[cols] > 0)

    def near(self, a, b, level=MATCH_MAX_COST, only_a=None, only_b=None):
        """The pairs whose place term alone stays below the cost ``level`` with key A moved by
        ``z -> a z + b`` (complex), and perhaps a few more: ``rows, cols``, shapes (K,), sorted
        by row then column. Only the strokes of masks ``only_a``, ``only_b`` (shapes (S_a,),
        (S_b,)) when given; strokes with no points are left out (their pairs cost inf).

        The place term is at least ``level`` once the centroids are ``level / W_PLACE`` spreads
        apart, and a pair's spread ``max(|a| r_i + r_j, dot_spread)`` is at most the sum of the
        strokes' halves ``max(|a| r_i, dot_spread / 2) + max(r_j, dot_spread / 2)``: boxes of
        those half-widths (grown by margins far above the round-off) around the moved
        centroids of A and the centroids of B overlap for every pair that may cost less."""
        moved = a * self.ca + b
        ia, ib = (np.flatnonzero(v if k is None else v & k) for v, k in zip(self._valid, (only_a, only_b)))
        za, zb = moved[ia], self.cb[ib]
        scale, half_dot, reach = max(abs(a), 1e-300), 0.5 * self.dot_spread, level / W_PLACE * (1.0 + 1e-6)
        # Round-off of the centroids' coordinates, far below any half-width that matters.
        slack = 1e-12 * max(np.abs(za).max(initial=0.0), np.abs(zb).max(initial=0.0))
        half_a = reach * np.maximum(scale * self.ra[ia], half_dot) + slack
        half_b = reach * np.maximum(self.rb[ib], half_dot) + slack
        boxes = [(z.real - h, z.imag - h, z.real + h, z.imag + h) for z, h in ((za, half_a), (zb, half_b))]
        i, j = box_pairs(*boxes)
        return ia[i], ib[j]

    def priced(self, a, b, level, pairs=None):
        """The pairs that may cost less than ``level`` (at most ``MATCH_MAX_COST``) with key A
        moved by ``z -> a z + b`` (complex), and their costs (:class:`_Priced`); ``pairs``:
        those pairs, ``(rows, cols)`` as :meth:`near` gives them, when already found."""
        level = min(level, MATCH_MAX_COST)
        rows, cols = self.near(a, b, level) if pairs is None else pairs
        floors = np.full(len(self.ra), level), np.full(len(self.rb), level)
        return _Priced(rows, cols, self.costs(a, b, rows, cols, exact=False), self.shape.shape, *floors)

    def widened(self, priced, a, b, wide_a, wide_b):
        """``priced`` (at motion ``z -> a z + b``) and every pair of the strokes of masks
        ``wide_a``, ``wide_b`` (shapes (S_a,), (S_b,)) that may cost less than
        ``MATCH_MAX_COST`` (:class:`_Priced`)."""
        n_b = len(self.rb)
        runs = self.near(a, b, only_a=wide_a), self.near(a, b, only_b=wide_b)
        code = np.concatenate([i * n_b + j for i, j in runs])
        code = np.setdiff1d(code, priced.rows * n_b + priced.cols)
        rows, cols = code // n_b, code % n_b
        return _Priced(
            np.concatenate([priced.rows, rows]),
            np.concatenate([priced.cols, cols]),
            np.concatenate([priced.costs, self.costs(a, b, rows, cols, exact=False)]),
            priced.size,
            np.where(wide_a, MATCH_MAX_COST, priced.floor_a),
            np.where(wide_b, MATCH_MAX_COST, priced.floor_b),
        )

    def costs(self, a, b, rows=None, cols=None, exact=True):
        """Pair costs with key A moved by ``z -> a z + b`` (complex), shape (S_a, S_b): exact
        where below ``MATCH_MAX_COST``, elsewhere at least that (those of pairs not fitted,
        bounds from the other terms); with ``rows`` and ``cols`` (shapes (K,)) the costs of
        pairs ``(rows[k], cols[k])`` only, shape (K,), exact (or, with ``exact`` False, as
        the whole table's). Elementwise: a pair's cost is the same whichever pairs are asked,
        once the whole table's open fits are made (:meth:`_fit_whole`, which the whole table
        makes).

        A cost with its shape term left out is a bound of the cost: the term is not negative
        and every rounded sum after it grows with it."""
        if rows is not None and exact:
            self._fit(rows, cols)
            return self._costs(a, b, rows, cols)
        if rows is None:
            self._fit_whole()
        c = self._costs(a, b, rows, cols)
        # The pairs whose bound may fall below the limit: fitted, then priced exactly.
        may = (self._unfitted if rows is None else self._unfitted[rows, cols]) & (c < MATCH_MAX_COST)
        if may.any():
            fit = np.nonzero(may) if rows is None else (rows[may], cols[may])
            self._fit(*fit)
            c[may] = self._costs(a, b, *fit)
        return c

    def _costs(self, a, b, rows=None, cols=None, placed=True):
        """:meth:`costs` from the shape terms as they are (fitted or not); without the place and
        turn terms unless ``placed``."""
        scale = max(abs(a), 1e-300)
        moved = a * self.ca + b
        if rows is None:
            ra, rb, za, zb = self.ra[:, None], self.rb[None, :], moved[:, None], self.cb[None, :]
            shape = self.shape
            (loop_a, loop_b), (valid_a, valid_b) = ((f[0][:, None], f[1][None, :]) for f in (self._loop, self._valid))
        else:
            ra, rb, za, zb = self.ra[rows], self.rb[cols], moved[rows], self.cb[cols]
            shape = self.shape[rows, cols]
            (loop_a, loop_b), (valid_a, valid_b) = ((f[0][rows], f[1][cols]) for f in (self._loop, self._valid))
        mixed, valid = loop_a != loop_b, valid_a & valid_b
        # The terms of the module notes, each full-size result worked on in place (the same
        # operations in the same order as the plain formula: a drawing of thousands of strokes
        # holds three (S_a, S_b) arrays here instead of a dozen).
        near = scale * ra
        spread = np.add(near, rb)
        np.maximum(spread, self.dot_spread, out=spread)
        place = np.abs(za - zb)
        place /= spread
        size = np.divide(np.maximum(rb, 1e-300), np.maximum(near, 1e-300), out=spread)  # the ratio
        np.log(size, out=size)
        np.abs(size, out=size)
        size /= np.log(4.0)
        np.copyto(size, 0.0, where=~((ra > 0) & (rb > 0)))
        c = np.multiply(shape, W_SHAPE)
        if placed:
            place *= W_PLACE
            c += place
        size *= W_SCALE
        c += size
        # + MATCH_CYCLIC_PENALTY * mixed: the others add 0.0, which leaves these sums of terms
        # that are not negative as they are.
        np.add(c, MATCH_CYCLIC_PENALTY, out=c, where=mixed)
        if placed:
            c += W_TURN * abs(np.angle(a * np.conj(self.prior_turn))) / np.pi
        np.copyto(c, np.inf, where=~valid)
        return c

    def fit_motion(self, rows, cols):
        """Least-squares similarity of the paired centroids (weighted by size): ``(a, b)`` complex."""
        keep = self.valid(rows, cols)
        rows, cols = rows[keep], cols[keep]
        if not len(rows):
            return 1.0 + 0j, 0j
        w = np.maximum(self.ra[rows] + self.rb[cols], 1e-300)
        za, zb = self.ca[rows], self.cb[cols]
        ma, mb = np.sum(w * za) / w.sum(), np.sum(w * zb) / w.sum()
        if len(rows) < 2:
            return 1.0 + 0j, mb - ma
        da, db = za - ma, zb - mb
        norm = np.sum(w * np.abs(da) ** 2)
        a = np.sum(w * np.conj(da) * db) / norm if norm > 0 else 1.0 + 0j
        return a, mb - a * ma

    def explained(self, rows, cols, motion):
        """The share of the spread of B's paired centroids that ``motion`` (complex ``a, b``)
        accounts for: 1 - (weighted squared misses of A's moved centroids) / (weighted squared
        distances of B's from their mean), weighted as :meth:`fit_motion`; 1 when they do not
        spread (float)."""
        keep = self.valid(rows, cols)
        rows, cols = rows[keep], cols[keep]
        w = np.maximum(self.ra[rows] + self.rb[cols], 1e-300)
        zb = self.cb[cols]
        spread = np.sum(w * np.abs(zb - np.sum(w * zb) / max(w.sum(), 1e-300)) ** 2)
        if not spread > 0:
            return 1.0
        return 1.0 - float(np.sum(w * np.abs(motion[0] * self.ca[rows] + motion[1] - zb) ** 2) / spread)


def _assign_within(costs):
    """Optimal pairs among those cheaper than MATCH_MAX_COST (rows, cols, each shape (K,))."""
    if not np.any(costs < MATCH_MAX_COST):
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    rows, cols = solve_assignment(np.minimum(costs, MATCH_MAX_COST))
    keep = costs[rows, cols] < MATCH_MAX_COST
    return rows[keep], cols[keep]


def _assign_at(table, motion, beat=None):
    """Optimal pairs among those cheaper than MATCH_MAX_COST with key A moved by ``motion``
    (complex ``a, b``): rows, cols, each shape (K,); None when no matching at this motion
    totals less than ``beat`` (float).

    The pairs near each other are tried first (:func:`_assign_near`); where they do not settle
    the motion, the whole table is priced.
    """
    solved = _assign_near(table, motion, beat)
    if solved is not _UNSETTLED:
        return solved
    costs = table.costs(*motion)
    if beat is not None and _least_total(costs) >= beat:
        return None
    return _assign_within(costs)


#: What :func:`_assign_near` returns when the pairs near each other do not settle a motion.
_UNSETTLED = object()


def _assign_near(table, motion, beat=None):
    """:func:`_assign_at` from the pairs near each other, or ``_UNSETTLED`` (the whole table is needed).

    The pairs whose place term alone stays below ``MATCH_NEAR_COST`` are priced, and their
    solve is the solve on every pair when its dual potentials certify it: ``u_i + v_j`` at
    most what each pair left out costs (:func:`~.assignment.solve_assignment`), so a solve on
    every pair would find nothing cheaper. The strokes whose potentials could break that get
    all their pairs priced, and the solve is made again: while they stay within
    ``MATCH_NEAR_SHARE`` of the strokes (beyond, each stroke's pairs are most of the table).
    Where the pairs near each other do not settle the motion: :func:`_assign_every`.
    """
    priced = table.priced(*motion, MATCH_NEAR_COST)
    most = MATCH_NEAR_SHARE * (len(priced.floor_a) + len(priced.floor_b))
    # A stroke of the smaller key (the solve's rows, whose potentials are at least their
    # pair's cost) with no pair priced below the floor breaks the certificate: where many
    # do, most pairs are needed anyway.
    cheapest = priced.cheapest()[0 if len(priced.floor_a) <= len(priced.floor_b) else 1]
    if np.count_nonzero(cheapest >= MATCH_NEAR_COST) <= most:
        solved = _settle(table, motion, priced, beat, most)
        if solved is not _UNSETTLED:
            return solved
    return _assign_every(table, motion, beat, len(priced.rows))


def _settle(table, motion, priced, beat, most):
    """The solve of the pairs ``priced`` (:class:`_Priced`) at ``motion``, widened until its
    dual potentials certify it (see :func:`_assign_near`): rows, cols; None when no matching
    totals less than ``beat``; ``_UNSETTLED`` when more than ``most`` strokes would need all
    their pairs priced, or when none priced may form while others left out still may."""
    while True:
        if beat is not None and priced.least_total() >= beat:
            return None
        if not np.any(priced.costs < MATCH_MAX_COST):
            # Every pair that may form is priced (each left out has a stroke whose floor is
            # the limit) and none does: no pair.
            if np.all(priced.floor_a >= MATCH_MAX_COST) or np.all(priced.floor_b >= MATCH_MAX_COST):
                return np.zeros(0, np.int64), np.zeros(0, np.int64)
            return _UNSETTLED
        clipped = priced.table()
        rows, cols, u, v = solve_assignment(clipped, duals=True)
        wide_a, wide_b = priced.uncertified(u, v)
        if not (wide_a.any() or wide_b.any()):
            keep = clipped.at(rows, cols) < MATCH_MAX_COST
            return rows[keep], cols[keep]
        # Strokes already widened keep their pairs: only the new ones are searched.
        full = np.count_nonzero(priced.floor_a >= MATCH_MAX_COST) + np.count_nonzero(priced.floor_b >= MATCH_MAX_COST)
        if full + np.count_nonzero(wide_a) + np.count_nonzero(wide_b) > most:
            return _UNSETTLED
        priced = table.widened(priced, *motion, wide_a, wide_b)


def _assign_every(table, motion, beat=None, near=0):
    """:func:`_assign_at` from every pair that may cost less than ``MATCH_MAX_COST`` (the
    others would be clipped to it: the solve is the whole table's, certified at once), where
    those are at most ``MATCH_SPARSE_SHARE`` of the table; else ``_UNSETTLED``. At a motion
    that takes the strokes far from their partners (a drawing moved across itself), few pairs
    may form.

    ``near`` (int): how many pairs :func:`_assign_near` found within ``MATCH_NEAR_COST``. A
    stroke's reach grows with the level, the pairs within it with its square: where that many
    would be most of the table, they are not listed (the benchmark's 400 open strokes: 96,000
    pairs, 47 ms to list, then priced whole anyway).
    """
    limit = MATCH_SPARSE_SHARE * len(table.ra) * len(table.rb)
    if near * (MATCH_MAX_COST / MATCH_NEAR_COST) ** 2 > limit:
        return _UNSETTLED
    rows, cols = table.near(*motion)
    if len(rows) > limit:
        return _UNSETTLED
    return _settle(table, motion, table.priced(*motion, MATCH_MAX_COST, (rows, cols)), beat, 0)


def _padded_total(pair_costs, n_a, n_b):
    """Total of a matching with every unmatched stroke paying MATCH_MAX_COST / 2 (float)."""
    unmatched = n_a + n_b - 2 * len(pair_costs)
    return float(np.sum(pair_costs)) + 0.5 * MATCH_MAX_COST * unmatched


def _least_total(costs):
    """No matching at this motion totals less (float) than this (``costs`` the table, shape
    (S_a, S_b)): a pair's cost is split half to each of its strokes and an unmatched stroke
    pays MATCH_MAX_COST / 2, so each stroke pays at least half its cheapest pair, or that.
    (The table bounds the exact costs from below, and so does this the exact total.)"""
    # The least of each row and column, then clipped: the same values as the least of the
    # clipped table, without a copy of the (S_a, S_b) table.
    rows, cols = costs.min(axis=1, initial=MATCH_MAX_COST), costs.min(axis=0, initial=MATCH_MAX_COST)
    return 0.5 * (float(rows.sum()) + float(cols.sum()))


def _guesses(table, key_a, key_b, motion=None):
    """Starting guesses of the keys' overall motion (complex ``a, b``), ``motion`` first."""
    guesses = [(1.0 + 0j, 0j)] if motion is None else [motion, (1.0 + 0j, 0j)]
    if key_a.valid.any() and key_b.valid.any():
        shift = _complex(key_b.ink_centroid() - key_a.ink_centroid())
        guesses.append((1.0 + 0j, complex(shift)))
        turned = _turn_guess(table, key_a, key_b)
        if turned is not None and abs(turned[0] - 1.0) > TURN_VOTE_MOVE:
            guesses.append(turned)
        if key_a.count == key_b.count:
            # The drawing order's motion, where the order says how the drawing moved: the
            # motion fitted to a reordered key crowds key A together and leads nowhere (from
            # there each solve is a table of near-ties, the costliest there is). A few strokes'
            # order accounts for much by chance, and their solves cost little: always tried.
            index = np.arange(key_a.count)
            order = table.fit_motion(index, index)
            if key_a.count < MATCH_ORDER_GATE or table.explained(index, index, order) >= MATCH_ORDER_EXPLAINS:
                guesses.append(order)
    return guesses


def _turn_guess(table, key_a, key_b):
    """The keys' overall motion from the turn that similar strokes' fits agree on, found
    without pairing them (see ``TURN_VOTERS``): complex ``(a, b)``, scaled as the keys' ink
    spreads, the shift taking key A's ink centroid onto key B's; None where no pair votes.

    A drawing turned a quarter turn and redrawn in another order, or with a stroke more: no
    other guess turns, and alternating from them rarely finds the turn.
    """
    voters = []
    for size, valid in ((table.ra, key_a.valid), (table.rb, key_b.valid)):
        index = np.flatnonzero(valid & (size > 0))
        voters.append(index[np.argsort(-size[index], kind="stable")][:TURN_VOTERS])
    rows, cols = np.repeat(voters[0], len(voters[1])), np.tile(voters[1], len(voters[0]))
    if not len(rows):
        return None
    e_f, e_r, turn_f, turn_r = table._pair_fits(rows, cols)
    reverse = e_r < e_f
    fit, turn = np.sqrt(np.where(reverse, e_r, e_f)), np.where(reverse, turn_r, turn_f)
    weight = np.clip(1.0 - fit / TURN_VOTE_FIT, 0.0, None)
    if not np.any(weight > 0):
        return None
    bins = np.floor((turn + np.pi) / (2 * np.pi) * TURN_VOTE_BINS).astype(np.int64) % TURN_VOTE_BINS
    votes = np.bincount(bins, weight, TURN_VOTE_BINS)
    votes = votes + 0.5 * (np.roll(votes, 1) + np.roll(votes, -1))
    off = np.abs((bins - int(np.argmax(votes)) + TURN_VOTE_BINS // 2) % TURN_VOTE_BINS - TURN_VOTE_BINS // 2)
    peak = (off <= 1) & (weight > 0)
    w = weight[peak]
    angle = np.angle(np.sum(w * np.exp(1j * turn[peak])))
    # The scale of the whole ink, not the voters': the largest strokes of key B are the ones
    # that grew the most.
    a = key_b.ink_spread() / max(key_a.ink_spread(), 1e-300) * np.exp(1j * angle)
    return complex(a), complex(_complex(key_b.ink_centroid()) - a * _complex(key_a.ink_centroid()))


def _best_assignment(table, key_a, key_b, motion=None):
    """Alternate assignment and motion fit from each starting guess; keep the cheapest.

    Returns
    -------
    total : float
    rows, cols : ndarray of int
    motion : tuple of complex
    """
    best, tried = None, []
    for motion in _guesses(table, key_a, key_b, motion):  # noqa: B020 (the guess starts the list)
        for step in range(MATCH_MOTION_ITERATIONS):
            # A motion already evaluated (the previous pairs refit to the same motion, or another
            # guess led here) would give the same assignment: this guess has converged.
            if any(abs(motion[0] - a) + abs(motion[1] - b) <= MATCH_ROUNDOFF for a, b in tried):
                break
            tried.append(motion)
            # The guess's last motion only counts if it beats the best so far (no refit follows
            # it), and its costs may say it cannot: then its solve, the costly part where
            # strokes look alike, is left out. (Earlier in a chain it may not be: a chain that
            # starts far behind often ends ahead, e.g. from a turned drawing.)
            last = step == MATCH_MOTION_ITERATIONS - 1 and best is not None
            solved = _assign_at(table, motion, best[0] if last else None)
            if solved is None:
                break
            rows, cols = solved
            if key_a.valid.sum() == 1 and key_b.valid.sum() == 1:  # alone in both keys: always a pair
                rows, cols = np.flatnonzero(key_a.valid), np.flatnonzero(key_b.valid)
            # (Exact costs: such a pair may cost more than the table's bounds say.)
            total = _padded_total(table.costs(*motion, rows, cols), key_a.count, key_b.count)
            if best is None or total < best[0]:
                best = (total, rows, cols, motion)
            if not len(rows):
                break
            motion = table.fit_motion(rows, cols)
    return best


def _matching(key_a, key_b, table, rows, cols, motion, method, reason):
    costs = table.costs(*motion, rows, cols)
    order = np.argsort(rows, kind="stable")
    rows, cols, costs = rows[order], cols[order], costs[order]
    reverse = table.directions(float(np.angle(motion[0])), rows, cols) & table.valid(rows, cols)
    return Matching(
        pairs=[(int(i), int(j), bool(flip)) for i, j, flip in zip(rows, cols, reverse)],
        unmatched_a=sorted(set(range(key_a.count)) - {int(i) for i in rows}),
        unmatched_b=sorted(set(range(key_b.count)) - {int(j) for j in cols}),
        method=method,
        reason=reason,
        costs=[float(c) for c in costs],
        motion=np.array([motion[1].real, motion[1].imag]),
        rotation=complex(motion[0]),
    )


def pair_direction(stroke_a, stroke_b, closed_a, closed_b, turn=0.0):
    """Whether the second stroke should run the other way to morph into the first (bool), by
    the rules of :func:`match_strokes` (a pair the caller formed, e.g. by hints)."""
    key_a = _Key([stroke_a], [closed_a], "stroke_a", "closed_a", MATCH_SAMPLES)
    key_b = _Key([stroke_b], [closed_b], "stroke_b", "closed_b", MATCH_SAMPLES)
    first = np.zeros(1, np.int64)
    return bool(_CostTable(key_a, key_b).directions(turn, first, first)[0])


def match_strokes(strokes_a, strokes_b, closed_a, closed_b, mode="auto", motion=None):
    """Pair the strokes of two keys.

    Parameters
    ----------
    strokes_a, strokes_b : sequence of array_like, each shape (n_i, 2), or Ragged
        The strokes of each key in the drawing plane, in drawing order. A stroke may have one
        point, repeated points or no point at all; a stroke with no point is never paired by
        'auto'. A Ragged (its closed flags those of ``closed_a``, ``closed_b``) is read as it is.
    closed_a, closed_b : array_like of bool, shape (S_a,), (S_b,)
        Cyclic flags.
    mode : {'auto', 'index'}
        'index' pairs stroke ``i`` with stroke ``i`` for ``i < min(S_a, S_b)`` (what Blender's
        interpolation does) and leaves the extra strokes unmatched. 'auto' does the same when
        the counts agree and the drawing order fits (every index pair costs less than
        ``MATCH_INDEX_MAX_COST`` and their total is within ``MATCH_INDEX_FACTOR`` of the
        optimal assignment's), which keeps the animator's order when it is right; otherwise it
        returns the optimal assignment, where no pair costs ``MATCH_MAX_COST`` or more.
        Either way each pair's direction is chosen (see the module notes).
    motion : (complex, complex), optional
        A guess of the keys' overall motion ``z -> a z + b`` tried first, its turn the one
        motions are charged from (the animator's hints say how the drawing moves).

    Returns
    -------
    Matching

    Raises
    ------
    InvalidCurveError
        For a malformed stroke (named ``strokes_a[i]``), flags of the wrong length, or an
        unknown ``mode``.

    Examples
    --------
    >>> import numpy as np
    >>> line = np.array([[0.0, 0.0], [1.0, 0.0]])
    >>> hook = np.array([[0.0, 1.0], [0.5, 1.5], [1.0, 1.0]])
    >>> m = match_strokes([line, hook], [hook[::-1], line], [False, False], [False, False])
    >>> m.pairs, m.method
    ([(0, 1, False), (1, 0, True)], 'assignment')
    """
    mode = check_option("mode", mode, MATCHINGS)
    key_a = _Key(strokes_a, closed_a, "strokes_a", "closed_a", MATCH_SAMPLES)
    key_b = _Key(strokes_b, closed_b, "strokes_b", "closed_b", MATCH_SAMPLES)
    table = _CostTable(key_a, key_b)
    if motion is not None and abs(motion[0]) > 0:
        table.prior_turn = motion[0] / abs(motion[0])
    n_a, n_b = key_a.count, key_b.count
    index = np.arange(min(n_a, n_b))
    if mode == "index":
        extra = f"; {abs(n_a - n_b)} extra stroke(s) of key {'A' if n_a > n_b else 'B'} unmatched" if n_a != n_b else ""
        motion = table.fit_motion(index, index)
        return _matching(
            key_a, key_b, table, index, index, motion, "index", f"paired by drawing order (mode 'index'){extra}"
        )
    if n_a == n_b == 0:
        return _matching(key_a, key_b, table, index, index, (1.0 + 0j, 0j), "index", "neither key has strokes")
    total, rows, cols, motion = _best_assignment(table, key_a, key_b, motion)
    rows, cols, travelled = _with_travellers(key_a, key_b, table, rows, cols, motion)
    if n_a != n_b:
        reason = f"stroke counts differ ({n_a} vs {n_b}): optimal assignment"
        matching = _matching(key_a, key_b, table, rows, cols, motion, "assignment", reason)
    else:
        matching = _order_or_assignment(key_a, key_b, table, total, rows, cols, motion)
    # (The drawing order, when kept, may not be the pairs travelling made.)
    matching.travelled = sorted(set(travelled) & {(i, j) for i, j, _ in matching.pairs})
    return matching


def _with_travellers(key_a, key_b, table, rows, cols, motion):
    """The assignment's pairs and those :func:`.travelling.pair_leftovers` makes of the strokes it
    leaves over: rows, cols (shapes (K,)), and the new pairs (list of (int, int))."""
    left_a = np.setdiff1d(np.flatnonzero(key_a.valid), rows)
    left_b = np.setdiff1d(np.flatnonzero(key_b.valid), cols)
    new_a, new_b = pair_leftovers(table, motion, left_a, left_b, key_a.count == key_b.count)
    travelled = list(zip(new_a.tolist(), new_b.tolist()))
    return np.concatenate([rows, new_a]).astype(np.int64), np.concatenate([cols, new_b]).astype(np.int64), travelled


def _order_or_assignment(key_a, key_b, table, total, rows, cols, motion):
    """Equal counts: the drawing order when it fits (see :func:`match_strokes`), else the assignment."""
    n_a, n_b = key_a.count, key_b.count
    index = np.arange(n_a)
    index_motion = table.fit_motion(index, index)
    if len(rows) == n_a and np.array_equal(np.sort(rows), index) and np.array_equal(cols[np.argsort(rows)], index):
        # The optimal assignment is the drawing order itself: keep it, however far strokes moved.
        reason = "same stroke count and the optimal assignment is the drawing order"
        return _matching(key_a, key_b, table, index, index, motion, "index", reason)
    index_costs = table.costs(*index_motion, index, index)
    worst = int(np.argmax(index_costs))
    index_total = _padded_total(index_costs, n_a, n_b)
    if index_costs[worst] >= MATCH_INDEX_MAX_COST:
        reason = (
            f"drawing order does not fit: stroke {worst} -> {worst} costs {index_costs[worst]:.3g} "
            f"(limit {MATCH_INDEX_MAX_COST:g}): optimal assignment"
        )
    elif index_total > MATCH_INDEX_FACTOR * total + MATCH_ROUNDOFF * n_a:
        reason = (
            f"drawing order costs {index_total:.3g} against {total:.3g} for the optimal assignment "
            f"(limit {MATCH_INDEX_FACTOR:g} times): optimal assignment"
        )
    else:
        reason = "same stroke count and the drawing order fits"
        return _matching(key_a, key_b, table, index, index, index_motion, "index", reason)
    return _matching(key_a, key_b, table, rows, cols, motion, "assignment", reason)
