"""Linear interpolation (paper section 2): uniform arc-length correspondence, straight paths.

The uniform correspondence here is also the one the curvature-interpolation and
laplace-blending morphs assume (paper section 6: "a uniform arc-length sampling to produce the
same number of uniformly distributed samples on each curve").
"""

from dataclasses import dataclass

import numpy as np

from ..ballmap.topology import shared_endpoints
from ..geometry.polyline import MAX_SAMPLES, curve_length, resolve_spacing
from ..geometry.ragged import Ragged, ragged_arange
from .base import PathMorph, register
from .paths import LinearPaths

__all__ = [
    "uniform_correspondence",
    "uniform_correspondences",
    "Correspondences",
    "best_cyclic_alignment",
    "best_cyclic_alignments",
    "sample_count",
    "sample_counts",
]


def best_cyclic_alignment(p, q, reverse=None):
    """Cyclic shift and direction of q that minimise the summed squared travel to p.

    Parameters
    ----------
    p, q : ndarray, shape (K, 2)
        Two loops with the same number of samples.
    reverse : bool, optional
        Force the direction (only the shift is optimised); default: try both.

    Returns
    -------
    shift : int
    reversed_ : bool
        Sample ``i`` of p goes to sample ``(i + shift) % K`` of q (of q reversed, keeping its
        first sample, when ``reversed_``).

    Notes
    -----
    ``sum |p_i - q_(i+s)|^2 = sum |p|^2 + sum |q|^2 - 2 Re sum p_i conj(q_(i+s))``: the last sum
    is a circular cross-correlation, computed for every shift at once with the FFT. Squared
    travel stands in for travel (it has this closed form and the same optimum in practice).
    """
    shift, rev = best_cyclic_alignments(p[None], q[None], None if reverse is None else np.array([bool(reverse)]))
    return int(shift[0]), bool(rev[0])


def best_cyclic_alignments(p, q, reverse=None):
    """:func:`best_cyclic_alignment` of G loop pairs with K samples each, in one FFT per array.

    Parameters
    ----------
    p, q : ndarray, shape (G, K, 2)
    reverse : ndarray of bool, shape (G,), optional
        Force each pair's direction; default: try both.

    Returns
    -------
    shift : ndarray of int, shape (G,)
    reversed_ : ndarray of bool, shape (G,)
    """
    zp = p[..., 0] + 1j * p[..., 1]
    fp = np.conj(np.fft.fft(zp, axis=1))
    rows = np.arange(len(p))
    found = []
    for rev in (False, True):
        qq = np.concatenate([q[:, :1], q[:, :0:-1]], axis=1) if rev else q
        corr = np.fft.ifft(fp * np.fft.fft(qq[..., 0] + 1j * qq[..., 1], axis=1), axis=1).real
        shift = np.argmax(corr, axis=1)
        found.append((shift, corr[rows, shift]))
    (fwd, fwd_value), (bwd, bwd_value) = found
    # Trying both, the reversed direction wins only when strictly better.
    rev = bwd_value > fwd_value if reverse is None else np.asarray(reverse, dtype=bool)
    return np.where(rev, bwd, fwd), rev


def uniform_correspondence(P, Q, closed, count, match_orientation=False):
    """Uniform arc-length samples on both curves, aligned for loops.

    Parameters
    ----------
    P, Q : ndarray, shape (N, 2) and (M, 2)
    closed : bool
    count : int
        Samples per curve.
    match_orientation : bool
        Loops: pair the samples so both loops turn the same way (only the cyclic shift is
        optimised), as morphs interpolating turning angles need; default: the direction that
        minimises travel too.

    Returns
    -------
    p, q : ndarray, shape (K, 2)
    u_p, u_q : ndarray, shape (K,)
        Arc-length fractions along P and Q as given.

    Notes
    -----
    A stroke Q sharing P's endpoints the other way round (``Q[0]`` at ``P[-1]``) is read
    backwards, so the shared endpoints stay paired.
    """
    one = uniform_correspondences(
        Ragged.from_list([P], [closed]), Ragged.from_list([Q], [closed]), [count], match_orientation
    )
    return one.p, one.q, one.u_p, one.u_q


@dataclass
class Correspondences:
    """Uniform correspondences of a batch of curve pairs, flat (pair after pair).

    Attributes
    ----------
    offsets : ndarray of int, shape (C + 1,)
        Pair ``c`` owns samples ``offsets[c]:offsets[c + 1]``.
    p, q : ndarray, shape (K, 2)
    u_p, u_q : ndarray, shape (K,)
    """

    offsets: np.ndarray
    p: np.ndarray
    q: np.ndarray
    u_p: np.ndarray
    u_q: np.ndarray


def uniform_correspondences(P, Q, counts, match_orientation=False):
    """:func:`uniform_correspondence` of every pair of two batches at once: one resampling of
    each batch, one FFT per sample count for the loops' alignment.

    Parameters
    ----------
    P, Q : Ragged
        Curve ``c`` of each is a pair (the same closed flags).
    counts : array_like of int, shape (C,)
        Samples per curve of each pair.
    match_orientation : bool
        See :func:`uniform_correspondence`.

    Returns
    -------
    Correspondences
    """
    rp, rq = P.resample(counts), Q.resample(counts)
    closed, offsets = P.closed, rp.offsets
    owner, local = ragged_arange(rp.n)
    u = local / np.where(closed, rp.n, rp.n - 1)[owner]
    order, u_q = np.arange(len(u)), u.copy()
    for c in np.flatnonzero(~closed):
        if shared_endpoints(P.curve(c), Q.curve(c)) == "reversed":
            span = slice(offsets[c], offsets[c + 1])
            order[span], u_q[span] = order[span][::-1], 1.0 - u[span]
    loops = np.flatnonzero(closed)
    if match_orientation and len(loops):
        turned = (rp.signed_areas() > 0) != (rq.signed_areas() > 0)
    for k in np.unique(rp.n[loops]):
        group = loops[rp.n[loops] == k]
        first = offsets[group][:, None]
        rows = first + np.arange(k)
        reverse = turned[group] if match_orientation else None
        shift, rev = best_cyclic_alignments(rp.pts[rows], rq.pts[rows], reverse)
        idx = (np.arange(k) + shift[:, None]) % k
        taken = first + np.where(rev[:, None], (-idx) % k, idx)
        order[rows], u_q[rows] = taken, u[taken]
    return Correspondences(offsets, rp.pts, rq.pts[order], u, u_q)


def sample_count(P, Q, closed, spacing, sampling):
    """Samples per curve of a uniform correspondence at ``spacing`` (int).

    ``sampling`` picks whose length sets the count: ``'p'``, ``'q'``, or the longer curve for
    ``'symmetric'``. ``spacing=None`` uses :func:`~ballmorph_core.curves.default_spacing`.
    """
    spacing = resolve_spacing(P, Q, closed, spacing)
    lengths = {"p": curve_length(P, closed), "q": curve_length(Q, closed)}
    length = lengths[sampling] if sampling in lengths else max(lengths.values())
    return int(_counts(np.array([length]), spacing, np.array([closed]))[0])


def sample_counts(P, Q, spacing):
    """:func:`sample_count` of every pair of two batches at once, the longer curve setting it
    ('symmetric'), shape (C,) of int.

    Parameters
    ----------
    P, Q : Ragged
    spacing : ndarray, shape (C,)
        Each pair's spacing (checked by :func:`~.polyline.resolve_spacing`, which raises for
        a pair it would give too many samples).
    """
    for c in np.flatnonzero(~(np.maximum(P.length, Q.length) / spacing <= MAX_SAMPLES)):
        resolve_spacing(P.curve(c), Q.curve(c), bool(P.closed[c]), float(spacing[c]))
    return _counts(np.maximum(P.length, Q.length), spacing, P.closed)


def _counts(length, spacing, closed):
    """Samples at ``spacing`` along curves of ``length`` (both endpoints for open ones)."""
    return np.rint(length / spacing).astype(np.int64) + np.where(closed, 0, 1)


@register("linear-interpolation")
def build(P, Q, closed, spacing, sampling):
    """Uniform arc-length correspondence (for loops, the cyclic shift and direction that
    minimise travel) and straight trajectories. ``sampling`` picks which curve's length sets
    the sample count at ``spacing`` ('P', 'Q', or the longer for 'symmetric')."""
    p, q, u_p, u_q = uniform_correspondence(P, Q, closed, sample_count(P, Q, closed, spacing, sampling))
    return PathMorph("linear-interpolation", closed, LinearPaths(p, q), u_p, u_q)
