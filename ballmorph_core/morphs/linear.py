"""Linear interpolation (paper section 2): uniform arc-length correspondence, straight paths."""

import numpy as np

from ..curves import curve_length, default_spacing, resample
from ..trajectories import LinearPaths
from .base import PathMorph, register

__all__ = ["uniform_correspondence", "best_cyclic_alignment"]


def best_cyclic_alignment(p, q):
    """Cyclic shift and direction of q that minimise the summed squared travel to p.

    Parameters
    ----------
    p, q : ndarray, shape (K, 2)
        Two loops with the same number of samples.

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
    zp = p[:, 0] + 1j * p[:, 1]
    best = None
    for rev in (False, True):
        qq = np.concatenate([q[:1], q[:0:-1]]) if rev else q
        zq = qq[:, 0] + 1j * qq[:, 1]
        corr = np.fft.ifft(np.conj(np.fft.fft(zp)) * np.fft.fft(zq))
        shift = int(np.argmax(corr.real))
        if best is None or corr.real[shift] > best[0]:
            best = (corr.real[shift], shift, rev)
    return best[1], best[2]


def uniform_correspondence(P, Q, closed, count):
    """Uniform arc-length samples on both curves, aligned for loops.

    Returns
    -------
    p, q : ndarray, shape (K, 2)
    u_p, u_q : ndarray, shape (K,)
        Arc-length fractions along P and Q as given.
    """
    p = resample(P, closed, count=count)
    q = resample(Q, closed, count=count)
    k = len(p)
    u = np.arange(k) / (k if closed else k - 1)
    if not closed:
        return p, q, u, u.copy()
    shift, rev = best_cyclic_alignment(p, q)
    idx = (np.arange(k) + shift) % k
    if rev:
        idx = (-idx) % k
    return p, q[idx], u, u[idx]


@register("linear-interpolation")
def build(P, Q, closed, spacing, sampling):
    """Uniform arc-length correspondence (for loops, the cyclic shift and direction that
    minimise travel) and straight trajectories. ``sampling`` picks which curve's length sets
    the sample count at ``spacing`` ('P', 'Q', or the longer for 'symmetric')."""
    if spacing is None:
        spacing = default_spacing(P, Q, closed=closed)
    lengths = {"P": curve_length(P, closed), "Q": curve_length(Q, closed)}
    length = lengths[sampling] if sampling in lengths else max(lengths.values())
    count = int(round(length / spacing)) + (0 if closed else 1)
    p, q, u_p, u_q = uniform_correspondence(P, Q, closed, count)
    return PathMorph("linear-interpolation", closed, LinearPaths(p, q), u_p, u_q)
