"""Groups of strokes that move together, and the motion a stroke without an orientation rides.

A circle or a dot has no turn of its own: a tyre valve on a rolling wheel should turn with the
wheel, not with the drawing (a car body that only translates). The group a rider rides on is
the strokes enclosed by the *smallest loop that contains it* (the rim), and that loop, in both
keys (the loop's partner must contain the rider's partner). Its motion is found *jointly*, not
from any one pair (eight similar spokes pair each with its nearest neighbour: a symmetry step
off the wheel's turn; only the shorter spoke says which step is right):

- *pivot and scale*: the loop's centre in each key, the ratio of the loops' lengths;
- *turn*: the ink of the group's strokes that have an orientation (open strokes, loops that are
  not circles: never the riders, nor the loop when it is a circle; a group with none shows no
  turn, and a pupil glancing across a round eye moves straight) in polar coordinates about the
  pivot (``RADIUS_BINS`` rings x ``TURN_BINS`` angles, arc-length weighted, blurred by ``BLUR``
  bins along the angle), each ring's angular profile correlated with the other key's by FFT;
  the turn of the summed
  correlation's peak (refined between bins by a parabola). Peaks within ``EQUAL_PEAKS`` of the
  best are equally good (a symmetric wheel): the one closest to the turn the riders show about
  the pivot wins, else the smallest.

A group whose oriented strokes all lie where the drawing's motion takes them (within ``STILL``
of the loop's size) moves with the drawing: it is not searched. A group is kept when the
correlation explains the group (``GROUP_FIT``) and its turn differs from the drawing's by more
than ``tolerances.TURN_AGREE`` (otherwise the drawing's motion already is the group's:
drawings whose groups turn as they do keep their frames). Where the group's open strokes are
paired a symmetry step off its motion, they are paired again under it (the assignment of least
distance once the group's motion is applied, kept when it at least halves the pairs'
distance): the spokes then turn with the wheel.

The pair pipeline reads each pair's :class:`GroupMotion` (see
:mod:`..pair_morphs.registration`): riders take the group's turn (their own about its pivot
where that agrees with it), and the group's pairs that turn with it turn about its pivot (the
hub moves straight, as a rolling wheel's does).
"""

from dataclasses import dataclass, field

import numpy as np

from ... import tolerances as tol
from ...geometry.orientation import orientation_free
from ...geometry.procrustes import uniform_samples
from ...geometry.similarity import Similarity, as_complex
from ...geometry.spatial import box_pairs
from .assignment import solve_assignment

__all__ = ["GroupMotion", "Groups", "ride_groups", "GROUP_FIT", "EQUAL_PEAKS", "REPAIRED"]

#: Polar bins of a group's ink: rings (out to ``REACH`` times the loop's radius, the radius of a
#: circle as long as the loop; farther ink in the last ring) and angles.
RADIUS_BINS = 24
REACH = 2.0
TURN_BINS = 720
#: Gaussian blur along the angle, in bins (a hand-redrawn stroke is not exactly turned).
BLUR = 2.0
#: The normalised correlation at the group's turn must be at least this (the group moved as one).
GROUP_FIT = 0.8
#: Correlation peaks within this fraction of the best are equally good (a symmetric group).
EQUAL_PEAKS = 1e-2
#: The group's open strokes are paired again when that divides their distance (under the
#: group's motion, RMS of end-to-end samples) by at least this.
REPAIRED = 2.0
#: A group whose oriented strokes lie within this fraction of its loop's size (RMS) of where the
#: drawing's motion takes them moves with the drawing (its turn is not searched).
STILL = 0.01
#: Samples per stroke for the distances of :data:`REPAIRED` and ``STILL``, and ink samples per
#: stroke (the longest of a group).
PAIR_SAMPLES = 16
INK_SAMPLES = 512


@dataclass(frozen=True)
class GroupMotion:
    """The motion of the group a pair belongs to.

    Attributes
    ----------
    motion : Similarity
        The group's similarity, key A onto key B (drawing-plane coordinates).
    pivot : ndarray, shape (2,)
        Its centre in key A (the enclosing loop's): the group turns about it as it moves straight.
    loop : int
        The enclosing loop's stroke in key A.
    """

    motion: Similarity
    pivot: np.ndarray
    loop: int


@dataclass
class Groups:
    """What :func:`ride_groups` found.

    Attributes
    ----------
    matched : list of (int, int, bool)
        The pairs (stroke of A, stroke of B, B reversed), re-paired within groups where needed.
    members : dict of int to GroupMotion
        Index into ``matched`` -> the motion of the group the pair belongs to.
    repaired : list of (int, int)
        (enclosing loop's stroke in A, number of pairs changed) for every group re-paired.
    """

    matched: list
    members: dict = field(default_factory=dict)
    repaired: list = field(default_factory=list)


def ride_groups(rg_a, rg_b, matched, drawing, fixed=()):
    """The groups the riders of a drawing ride on (see the module docstring).

    Parameters
    ----------
    rg_a, rg_b : Ragged
        Both keys' strokes in the drawing plane.
    matched : list of (int, int, bool)
        The stroke matching's pairs.
    drawing : Similarity
        The keys' overall motion.
    fixed : collection of int
        Pairs (indices into ``matched``) never re-paired (hinted, travelled).

    Returns
    -------
    Groups
    """
    out = Groups(list(matched))
    if not matched:
        return out
    ia = np.array([i for i, _, _ in matched], np.int64)
    jb = np.array([j for _, j, _ in matched], np.int64)
    loop = rg_a.closed[ia] & rg_b.closed[jb] & (rg_a.n[ia] >= 3) & (rg_b.n[jb] >= 3)
    dot = rg_a.length[ia] <= 0.0
    free = np.zeros(len(ia), bool)
    if loop.any():
        free[loop] = orientation_free(rg_a.take(ia[loop]))
    riders = np.flatnonzero(dot | free)
    if not len(riders) or loop.sum() < 1:
        return out
    ca, cb = rg_a.centroids()[ia], rg_b.centroids()[jb]
    area = np.abs(rg_a.signed_areas()[ia])
    # Every (rider, loop) whose box holds the rider's centre, then whose loop holds it in both keys.
    loops = np.flatnonzero(loop)
    r, q = _boxes_around(ca[riders], rg_a.boxes()[ia[loops]])
    r, q = riders[r], loops[q]
    keep = (r != q) & (area[q] > area[r])
    r, q = r[keep], q[keep]
    keep = rg_a.contains(ca[r], ia[q])
    r, q = r[keep], q[keep]
    keep = rg_b.contains(cb[r], jb[q])
    r, q = r[keep], q[keep]
    enclosing = {}
    if len(r):
        order = np.lexsort((area[q], r))  # by rider, the smallest loop first
        r, q = r[order], q[order]
        first = np.r_[True, r[1:] != r[:-1]]
        for rider_k, loop_k in zip(r[first], q[first]):
            enclosing.setdefault(int(loop_k), []).append(int(rider_k))
    if not enclosing:
        return out
    rider = dot | free
    off = _off_drawing(rg_a, rg_b, matched, drawing)
    boxes = rg_a.boxes()[ia]
    loops = np.array(sorted(enclosing), np.int64)
    at, k = _boxes_around(ca, boxes[loops])  # every stroke's centre in the loops' boxes
    order = np.argsort(k, kind="stable")
    at, k = at[order], k[order]
    starts = np.searchsorted(k, np.arange(len(loops) + 1))
    for n, q in enumerate(loops):
        others = at[starts[n] : starts[n + 1]]
        others = others[others != q]
        _group(out, rg_a, rg_b, (ia, jb, ca, cb, rider, boxes[q], off, others), q, enclosing[q], drawing, set(fixed))
    return out


def _off_drawing(rg_a, rg_b, matched, drawing):
    """How far each pair's B stroke lies from where the drawing's motion takes its A stroke:
    RMS of ``PAIR_SAMPLES`` samples (loops: at the best cyclic shift), shape (len(matched),)."""
    ia = np.array([i for i, _, _ in matched], np.int64)
    jb = np.array([j for _, j, _ in matched], np.int64)
    flip = np.array([f for _, _, f in matched], bool)
    xa = drawing.a * uniform_samples(rg_a, ia, PAIR_SAMPLES) + drawing.b
    xb = uniform_samples(rg_b, jb, PAIR_SAMPLES)
    xb = np.where(flip[:, None], xb[:, ::-1], xb)
    loop = rg_a.closed[ia] & rg_b.closed[jb]
    shifts = np.arange(PAIR_SAMPLES) if loop.any() else np.zeros(1, np.int64)
    gaps = [np.sqrt(np.mean(np.abs(xa - np.roll(xb, -s, axis=1)) ** 2, axis=1)) for s in shifts]
    return np.where(loop, np.min(gaps, axis=0), gaps[0])


def _boxes_around(points, boxes):
    """Every (point, box) with the box holding the point: two index arrays (a grid's candidate
    pairs, each point a box a round-off wide, then tested)."""
    if not (len(points) and len(boxes)):
        return np.zeros(0, np.int64), np.zeros(0, np.int64)
    eps = tol.ROUNDOFF * max(float(np.abs(points).max()), float(np.abs(boxes).max()), 1.0)
    r, k = box_pairs(np.c_[points - eps, points + eps], boxes)
    inside = np.all((boxes[k, :2] <= points[r]) & (boxes[k, 2:] >= points[r]), axis=1)
    return r[inside], k[inside]


def _group(out, rg_a, rg_b, pairs, q, riders, drawing, fixed):
    """The group of loop pair ``q`` (its motion, its re-pairing), written into ``out``."""
    ia, jb, ca, cb, rider, box, off, others = pairs
    # The cheap test first, on every stroke in the loop's box (the group's oriented ones among them).
    size = float(np.max(box[2:] - box[:2]))
    if off[np.r_[q, others][~rider[np.r_[q, others]]]].max(initial=0.0) <= STILL * size:
        return
    inside = rg_a.contains(ca[others], np.full(len(others), ia[q])) & rg_b.contains(
        cb[others], np.full(len(others), jb[q])
    )
    members = np.r_[q, others[inside]]
    oriented = members[~rider[members]]
    if not len(oriented):
        return
    pivot_a, pivot_b = ca[q], cb[q]
    scale = rg_b.length[jb[q]] / max(rg_a.length[ia[q]], tol.TINY)
    unit = max(rg_a.length[ia[q]] / (2 * np.pi), tol.TINY)
    ink_a = _polar_ink(rg_a.take(ia[oriented]), pivot_a, unit)
    ink_b = _polar_ink(rg_b.take(jb[oriented]), pivot_b, unit * scale)
    corr = np.fft.ifft(np.conj(np.fft.fft(ink_a, axis=1)) * np.fft.fft(ink_b, axis=1), axis=1).real.sum(axis=0)
    norm = np.sqrt(np.sum(ink_a**2) * np.sum(ink_b**2))
    best = float(corr.max())
    if norm <= 0 or best < GROUP_FIT * norm:
        return
    shown = [complex(*(cb[r] - pivot_b)) / complex(*(ca[r] - pivot_a)) for r in riders if np.any(ca[r] != pivot_a)]
    turn = _peak_turn(corr, best, np.angle(np.mean([z / abs(z) for z in shown])) if shown else 0.0)
    if abs(np.angle(np.exp(1j * (turn - drawing.turn)))) <= tol.TURN_AGREE:
        return
    a = scale * np.exp(1j * turn)
    motion = Similarity(complex(a), complex(*pivot_b) - a * complex(*pivot_a))
    _repair(out, rg_a, rg_b, members[1:], motion, fixed, int(ia[q]))
    group = GroupMotion(motion, pivot_a.copy(), int(ia[q]))
    for k in members:
        out.members[int(k)] = group


def _polar_ink(rg, pivot, unit):
    """The strokes' ink about ``pivot`` in polar bins (radii in ``unit``), shape (RADIUS_BINS, TURN_BINS), blurred."""
    h = max(float(rg.length.max()), tol.TINY) / INK_SAMPLES
    counts = np.maximum(np.ceil(rg.length / h).astype(np.int64), 1) + 1
    samples = rg.resample(counts, smooth=False)
    z = as_complex(samples.pts - pivot) / unit
    weight = np.repeat(rg.length / counts, counts)
    weight[weight <= 0] = 1.0 / INK_SAMPLES  # a dot's ink
    r = np.minimum((np.abs(z) / REACH * RADIUS_BINS).astype(np.int64), RADIUS_BINS - 1)
    t = np.round(np.angle(z) / (2 * np.pi) * TURN_BINS).astype(np.int64) % TURN_BINS
    ink = np.zeros((RADIUS_BINS, TURN_BINS))
    np.add.at(ink, (r, t), weight)
    k = np.fft.fftfreq(TURN_BINS) * TURN_BINS
    blur = np.exp(-0.5 * (2 * np.pi * k * BLUR / TURN_BINS) ** 2)
    return np.fft.ifft(np.fft.fft(ink, axis=1) * blur, axis=1).real


def _peak_turn(corr, best, shown):
    """The turn (radians) of the correlation's peak: among peaks within ``EQUAL_PEAKS`` of the
    best, the one closest to ``shown`` (the riders' turn), refined between bins."""
    peak = (corr >= np.roll(corr, 1)) & (corr >= np.roll(corr, -1)) & (corr >= (1 - EQUAL_PEAKS) * best)
    k = np.flatnonzero(peak)
    turns = 2 * np.pi * k / TURN_BINS
    s = int(k[np.argmin(np.abs(np.angle(np.exp(1j * (turns - shown)))))])
    left, mid, right = corr[s - 1], corr[s], corr[(s + 1) % TURN_BINS]
    bend = left - 2 * mid + right
    step = 0.5 * (left - right) / bend if bend < 0 else 0.0
    return float(np.angle(np.exp(2j * np.pi * (s + step) / TURN_BINS)))


def _repair(out, rg_a, rg_b, members, motion, fixed, loop):
    """The group's open strokes paired again under its motion where that halves their distance."""
    rows = [int(k) for k in members if k not in fixed and not rg_a.closed[out.matched[k][0]]]
    rows = [k for k in rows if not rg_b.closed[out.matched[k][1]] and rg_a.length[out.matched[k][0]] > 0]
    if len(rows) < 2:
        return
    ia = np.array([out.matched[k][0] for k in rows])
    jb = np.array([out.matched[k][1] for k in rows])
    xa = motion.a * uniform_samples(rg_a, ia, PAIR_SAMPLES) + motion.b
    xb = uniform_samples(rg_b, jb, PAIR_SAMPLES)
    ahead = np.sqrt(np.mean(np.abs(xa[:, None] - xb[None]) ** 2, axis=2))
    back = np.sqrt(np.mean(np.abs(xa[:, None] - xb[None, :, ::-1]) ** 2, axis=2))
    cost = np.minimum(ahead, back)
    r, c = solve_assignment(cost)
    now, best = float(np.trace(cost)), float(cost[r, c].sum())
    if best * REPAIRED > now or np.array_equal(c[np.argsort(r)], np.arange(len(rows))):
        return
    changed = 0
    for k_row, k_col in zip(r, c):
        k = rows[k_row]
        i, j, _ = out.matched[k]
        new = int(jb[k_col])
        if new != j:
            changed += 1
            out.matched[k] = (i, new, bool(back[k_row, k_col] < ahead[k_row, k_col]))
    out.repaired.append((loop, changed))
