"""The one similarity fit of the core: complex Procrustes between sampled curves.

Samples are complex numbers ``x + iy``; a similarity is ``z -> a z + b`` (``a`` turns and
scales). For samples ``p`` and ``q`` centred on the points the fit turns about, the
least-squares ``a`` taking ``p`` onto ``q`` is ``<p, q> / <p, p>``; for loops, every cyclic
shift of ``q`` at once comes from one cross-correlation by FFT. Registration, exact fits, hints,
the matching's shape fits and the comparison morphs' start alignment all fit this way.
"""

import numpy as np

from .similarity import as_complex

__all__ = ["cyclic_correlation", "similarity_fit", "similarity_fits", "uniform_samples"]


def uniform_samples(rg, index, k):
    """The samples the fits take: ``k`` uniform arc-length samples (on the chords) of the curves
    ``index`` of ``rg`` (Ragged), complex, shape (len(index), k)."""
    # Every curve, in order (all loops of a drawing of loops): no copy of the batch first.
    whole = len(index) == len(rg) and np.array_equal(index, np.arange(len(rg)))
    sub = rg if whole else rg.take(index)
    return as_complex(sub.resample(np.full(len(index), k), smooth=False).pts).reshape(len(index), k)


def cyclic_correlation(p, q):
    """Every cyclic shift's correlation of samples, by FFT along the last axis.

    Parameters
    ----------
    p, q : ndarray of complex, shape (..., n)

    Returns
    -------
    ndarray of complex, shape (..., n)
        ``corr[..., k] = sum_i conj(p[..., i]) q[..., (i + k) % n]``.

    Examples
    --------
    >>> p = np.array([1, 2j, -1, 0.5])
    >>> int(np.argmax(np.abs(cyclic_correlation(p, np.roll(p, -1)))))  # q[i] = p[i + 1]: shift 3
    3
    """
    return np.fft.ifft(np.conj(np.fft.fft(p, axis=-1)) * np.fft.fft(q, axis=-1), axis=-1)


def similarity_fit(za, zb, ca=None, cb=None):
    """Least-squares similarity taking samples ``za`` onto ``zb`` (one pair).

    Parameters
    ----------
    za, zb : ndarray of complex, shape (n,)
    ca, cb : complex, optional
        The points the fit turns and scales about, and where it takes it (default: the
        samples' centroids).

    Returns
    -------
    a, b : complex
        ``z -> a z + b``; ``a`` is 1 when ``za`` has no extent.

    Examples
    --------
    >>> za = np.array([0, 1, 1j])
    >>> a, b = similarity_fit(za, 2j * za + 3)
    >>> complex(np.round(a, 12)), complex(np.round(b, 12))
    (2j, (3+0j))
    """
    ca = za.mean() if ca is None else ca
    cb = zb.mean() if cb is None else cb
    pa, pb = za - ca, zb - cb
    norm = float(np.vdot(pa, pa).real)
    a = complex(np.vdot(pa, pb) / norm) if norm > 0 else 1.0 + 0j
    return a, cb - a * ca


def similarity_fits(p, q):
    """Least-squares complex factors of many centred sample rows: ``a p ~ q`` row by row.

    Parameters
    ----------
    p, q : ndarray of complex, shape (L, n)
        Samples centred on the points each fit turns about.

    Returns
    -------
    a : ndarray of complex, shape (L,)
        1 where a row of ``p`` has no extent.
    norm_p : ndarray, shape (L,)
        ``<p, p>`` per row.
    """
    norm_p = np.sum(np.abs(p) ** 2, axis=1)
    dot = np.sum(np.conj(p) * q, axis=1)
    return np.where(norm_p > 0, dot / np.where(norm_p > 0, norm_p, 1.0), 1.0), norm_p
