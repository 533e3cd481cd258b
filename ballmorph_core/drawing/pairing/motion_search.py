"""The search for the keys' overall motion: starting guesses (no motion, the ink's shift, the turn
similar strokes vote for, the drawing order's motion), each alternated with the assignment."""

import numpy as np

from ...geometry.guards import least, ratio
from .certified import assign_at, padded_total
from .descriptors import complex_samples

__all__ = ["best_assignment"]


#: The drawing order's motion is a starting guess when it accounts for at least this share of
#: the spread of key B's strokes (a reordered key's accounts for about 1 / count), or when the
#: keys have fewer than MATCH_ORDER_GATE strokes.
MATCH_ORDER_EXPLAINS = 0.25
MATCH_ORDER_GATE = 64


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


#: A bounded table's step (``costs.MATCH_WHOLE_MOST``) before a guess's last is left out where
#: its costs say it totals more than this many times the best so far (a guessed turn taking a
#: drawing of look-alike strokes over itself: 3,200 of them, 42 s instead of 2). A heuristic: a
#: chain that far behind may still catch up (37 random strokes, made bounded, end at a total
#: 3 % higher); the whole-table path never leaves a chain out before its last step.
MATCH_BEHIND = 2.0


#: Alternations of (assign strokes, re-fit the keys' overall motion) per starting guess.
MATCH_MOTION_ITERATIONS = 3


def _guesses(table, key_a, key_b, motion=None):
    """Starting guesses of the keys' overall motion (complex ``a, b``), ``motion`` first."""
    guesses = [(1.0 + 0j, 0j)] if motion is None else [motion, (1.0 + 0j, 0j)]
    if key_a.valid.any() and key_b.valid.any():
        shift = complex_samples(key_b.ink_centroid() - key_a.ink_centroid())
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
    # that grew the most. Where key A's strokes share one centroid (a stroke drawn twice in
    # place) its ink has no spread: the keys' sizes say the scale.
    size = max(key_a.diagonal, key_b.diagonal)
    grow = ratio(key_b.diagonal, key_a.diagonal, least(size))
    a = ratio(key_b.ink_spread(), key_a.ink_spread(), least(size), grow) * np.exp(1j * angle)
    return complex(a), complex(complex_samples(key_b.ink_centroid()) - a * complex_samples(key_a.ink_centroid()))


def best_assignment(table, key_a, key_b, motion=None):
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
            # A bounded table's solves are the costly part at every step, where strokes crowd
            # each other (a guessed turn taking the drawing over itself): a step whose costs say
            # it totals more than MATCH_BEHIND times the best so far is left out.
            last = step == MATCH_MOTION_ITERATIONS - 1 and best is not None
            beat = best[0] if last else (MATCH_BEHIND * best[0] if table.bounded and best is not None else None)
            solved = assign_at(table, motion, beat)
            if solved is None:
                break
            rows, cols = solved
            if key_a.valid.sum() == 1 and key_b.valid.sum() == 1:  # alone in both keys: always a pair
                rows, cols = np.flatnonzero(key_a.valid), np.flatnonzero(key_b.valid)
            # (Exact costs: such a pair may cost more than the table's bounds say.)
            total = padded_total(table.costs(*motion, rows, cols), key_a.count, key_b.count)
            if best is None or total < best[0]:
                best = (total, rows, cols, motion)
            if not len(rows):
                break
            motion = table.fit_motion(rows, cols)
    return best
