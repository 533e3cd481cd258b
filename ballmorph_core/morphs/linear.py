"""Linear interpolation (paper section 2): uniform arc-length correspondence, straight paths.

The uniform correspondence here is also the one the curvature-interpolation and
laplace-blending morphs assume (paper section 6: "a uniform arc-length sampling to produce the
same number of uniformly distributed samples on each curve").
"""

import numpy as np

from ..ballmap.topology import shared_endpoints
from ..geometry.polyline import curve_length, resample, resolve_spacing, signed_area
from .base import PathMorph, register
from .paths import LinearPaths

__all__ = ["uniform_correspondence", "best_cyclic_alignment", "sample_count"]


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
    zp = p[:, 0] + 1j * p[:, 1]
    best = None
    for rev in (False, True) if reverse is None else (bool(reverse),):
        qq = np.concatenate([q[:1], q[:0:-1]]) if rev else q
        zq = qq[:, 0] + 1j * qq[:, 1]
        corr = np.fft.ifft(np.conj(np.fft.fft(zp)) * np.fft.fft(zq))
        shift = int(np.argmax(corr.real))
        if best is None or corr.real[shift] > best[0]:
            best = (corr.real[shift], shift, rev)
    return best[1], best[2]


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
    p = resample(P, closed, count=count)
    q = resample(Q, closed, count=count)
    k = len(p)
    u = np.arange(k) / (k if closed else k - 1)
    if not closed:
        if shared_endpoints(P, Q) == "reversed":
            return p, q[::-1].copy(), u, 1.0 - u
        return p, q, u, u.copy()
    reverse = (signed_area(p) > 0) != (signed_area(q) > 0) if match_orientation else None
    shift, rev = best_cyclic_alignment(p, q, reverse)
    idx = (np.arange(k) + shift) % k
    if rev:
        idx = (-idx) % k
    return p, q[idx], u, u[idx]


def sample_count(P, Q, closed, spacing, sampling):
    """Samples per curve of a uniform correspondence at ``spacing`` (int).

    ``sampling`` picks whose length sets the count: ``'p'``, ``'q'``, or the longer curve for
    ``'symmetric'``. ``spacing=None`` uses :func:`~ballmorph_core.curves.default_spacing`.
    """
    spacing = resolve_spacing(P, Q, closed, spacing)
    lengths = {"p": curve_length(P, closed), "q": curve_length(Q, closed)}
    length = lengths[sampling] if sampling in lengths else max(lengths.values())
    return int(round(length / spacing)) + (0 if closed else 1)


@register("linear-interpolation")
def build(P, Q, closed, spacing, sampling):
    """Uniform arc-length correspondence (for loops, the cyclic shift and direction that
    minimise travel) and straight trajectories. ``sampling`` picks which curve's length sets
    the sample count at ``spacing`` ('P', 'Q', or the longer for 'symmetric')."""
    p, q, u_p, u_q = uniform_correspondence(P, Q, closed, sample_count(P, Q, closed, spacing, sampling))
    return PathMorph("linear-interpolation", closed, LinearPaths(p, q), u_p, u_q)
