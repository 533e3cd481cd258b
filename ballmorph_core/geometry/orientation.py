"""Whether a loop has an orientation of its own: a circle, a round dot or a many-sided regular
polygon fits itself turned by any angle, so nothing in it shows how it turned (it takes the turn
of what it rides: :mod:`ballmorph_core.drawing.pair_morphs.riding`)."""

import numpy as np

from .. import tolerances as tol
from .procrustes import uniform_samples

__all__ = ["NO_ORIENTATION", "ORIENTATION_SAMPLES", "orientation_free"]

#: A loop has no orientation of its own (a circle, a hand-drawn round dot, a regular polygon of
#: many sides) when turned by any angle it still fits itself within this normalised residual
#: (``1 - |<p, p_s>|^2 / |p|^4`` over every cyclic shift ``s``): a 9-gon or a circle with a 2%
#: wobble (about 7e-4) has none, an ellipse 1.1 x 1 (6e-3), a hexagon (8e-3) or a square
#: (0.05) has one.
NO_ORIENTATION = 2e-3

#: Uniform arc-length samples of a loop for the test (a hand-drawn dot's wobble is resolved).
ORIENTATION_SAMPLES = 128


def orientation_free(P, k=ORIENTATION_SAMPLES):
    """Which loops of ``P`` (Ragged) have no orientation of their own (see ``NO_ORIENTATION``):
    shape (C,) of bool, False for open strokes.

    Parameters
    ----------
    P : Ragged
    k : int
        Uniform arc-length samples per loop (on the chords).
    """
    free = np.zeros(len(P), bool)
    loops = np.flatnonzero(P.closed)
    if not len(loops):
        return free
    x = uniform_samples(P, loops, k)
    x = x - x.mean(axis=1, keepdims=True)
    norm = np.maximum(np.sum(np.abs(x) ** 2, axis=1), tol.TINY)
    spectrum = np.fft.fft(x, axis=1)
    # Autocorrelation over every shift: |<x, x_s>| is largest (norm) at s = 0.
    corr = np.abs(np.fft.ifft(np.abs(spectrum) ** 2, axis=1))
    worst = 1.0 - (corr.min(axis=1) / norm) ** 2
    free[loops] = worst <= NO_ORIENTATION
    return free
