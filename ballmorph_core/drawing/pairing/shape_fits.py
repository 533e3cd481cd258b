"""Shape fits of stroke pairs: the normalised residual of the best similarity taking one
stroke's samples onto another's, over B's direction (open strokes) or B's cyclic shift (loops,
by FFT), and shared ends (see :mod:`.matching`)."""

import numpy as np

from ... import tolerances as tol
from ...geometry.ragged import budget_slices

__all__ = ["open_shapes", "sq_norms", "pair_shapes", "shared_ends", "LoopFits"]


#: An end within this fraction of the strokes' sizes of its partner's end is shared: the
#: direction in which more ends are shared wins whatever the fits say (a shoulder stays put, a
#: flipped arch keeps its ends).
MATCH_SHARED_ENDS = 0.05


# Elements per block when a product would otherwise allocate S_a x S_b x m at once (memory only).
CHUNK = 2_000_000


def _residual(d, norms):
    """``clip(1 - |d|^2 / norms, 0, 1)`` in place from ``|d|`` (the similarity fit's residual
    from the product ``d = <a, b>`` and ``|a|^2 |b|^2``), shape of ``d``."""
    e = np.abs(d)
    np.square(e, out=e)
    e /= norms
    np.subtract(1.0, e, out=e)
    return np.clip(e, 0.0, 1.0, out=e)


def open_shapes(a, b):
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
    norms = np.maximum(sq_norms(a)[:, None] * sq_norms(b)[None, :], tol.TINY)
    conj_a, out = np.conj(a), []
    for read in (b, b[:, ::-1]):
        # One direction at a time: the complex products are the largest arrays here.
        d = conj_a @ read.T
        out.append((_residual(d, norms), np.angle(d)))
        del d
    (e_f, turn_f), (e_r, turn_r) = out
    return e_f, e_r, turn_f, turn_r


def sq_norms(a):
    """``|a_k|^2`` of samples ``a`` (complex, shape (K, m)), shape (K,)."""
    return np.sum(np.abs(a) ** 2, axis=1)


def pair_shapes(a, b, norm_a=None, norm_b=None):
    """:func:`open_shapes` of pairs: ``a[k]`` with ``b[k]`` (shapes (K, m), complex, centred;
    their :func:`sq_norms`, shapes (K,), when known), each ``e_fwd, e_rev, turn_fwd,
    turn_rev`` of shape (K,). Each pair's values are its own (the same however many pairs are
    asked at once); they differ from the matrix products' by round-off (the sums are taken in
    another order)."""
    norm_a = sq_norms(a) if norm_a is None else norm_a
    norm_b = sq_norms(b) if norm_b is None else norm_b
    norms = np.maximum(norm_a * norm_b, tol.TINY)
    conj_a, out = np.conj(a), []
    for read in (b, b[:, ::-1]):
        d = np.sum(conj_a * read, axis=1)
        out.append((_residual(d, norms), np.angle(d)))
    (e_f, turn_f), (e_r, turn_r) = out
    return e_f, e_r, turn_f, turn_r


def shared_ends(a, b, spread):
    """How many ends pairs of open strokes share read forward and read backwards, shapes (K,).

    ``a``, ``b``: the pairs' samples, shapes (K, m, 2); ``spread``: their sizes, shape (K,).
    """

    def shared(i, j):
        d = a[:, i] - b[:, j]
        # np.linalg.norm's arithmetic (a sum of two squares), without its call.
        return (np.sqrt(d[:, 0] * d[:, 0] + d[:, 1] * d[:, 1]) <= MATCH_SHARED_ENDS * spread).astype(int)

    return shared(0, 0) + shared(-1, -1), shared(0, -1) + shared(-1, 0)


class LoopFits:
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
        norms = np.maximum(np.take(self._na, i) * nb, tol.TINY)
        best = np.empty(len(i))
        m = self._fa.shape[1]
        for sl in budget_slices(np.full(len(i), m), CHUNK):
            corr = np.fft.ifft(np.take(self._fa, i[sl], axis=0) * fb[sl], axis=1)
            best[sl] = np.abs(corr).max(axis=1) ** 2
        return np.clip(1.0 - best / norms, 0.0, 1.0)


def _loop_shapes(a, b, sign_a=None, sign_b=None):
    """Residuals of every loop pair over every cyclic shift of B's samples, shape (L_a, L_b):
    the whole table of :class:`LoopFits` (``a``, ``b`` complex and centred; with ``sign_a``,
    ``sign_b``, their areas' signs, B's loop read backwards where the two run opposite ways).
    """
    i, j = (g.ravel() for g in np.meshgrid(np.arange(len(a)), np.arange(len(b)), indexing="ij"))
    return LoopFits(a, b, sign_a, sign_b).residuals(i, j).reshape(len(a), len(b))


def _backwards(samples):
    """Loop samples read the other way round, keeping the first (shape (..., m))."""
    return np.concatenate([samples[..., :1], samples[..., :0:-1]], axis=-1)
